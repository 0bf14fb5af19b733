/* SPDX-License-Identifier: GPL-3.0-or-later */
/* shape: spheroplate geometry in closed form, and the table of the shapes (see shape.h). */
#include "pack/shape.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const char *const shape_radius_names[2] = {"edge", "corner"};

double
shape_plate_side(double R, double eta, enum shape_radius conv)
{
	return (conv == SHAPE_R_CORNER ? M_SQRT2 : 2.0) * eta * R;
}

double
shape_spheroradius(double R, double eta)
{
	return (1 - eta) * R;
}

double
shape_outer_radius(double r, double L, enum shape_radius conv)
{
	return r + (conv == SHAPE_R_CORNER ? L / M_SQRT2 : L / 2);
}

double
shape_platyness(double r, double L, enum shape_radius conv)
{
	double R = shape_outer_radius(r, L, conv);

	return (R - r) / R;
}

double
shape_bounding_radius(double r, double L)
{
	return r + L / M_SQRT2;
}

double
shape_volume(double r, double L)
{
	return 2 * r * L * L + 2 * M_PI * r * r * L + 4.0 / 3.0 * M_PI * r * r * r;
}

void
shape_inertia(double r, double L, double *Inormal, double *Iinplane)
{
	double r2 = r * r, r3 = r2 * r, r4 = r3 * r, r5 = r4 * r, L2 = L * L, L3 = L2 * L, L4 = L3 * L;

	*Inormal = r * L4 / 3 + (2 * M_PI / 3) * r2 * L3 + (8.0 / 3 + 2 * M_PI / 3) * r3 * L2 + (1.5 * M_PI) * r4 * L +
	    (8 * M_PI / 15) * r5;
	*Iinplane = r * L4 / 6 + (M_PI / 3) * r2 * L3 + (2 + M_PI / 3) * r3 * L2 + (1.25 * M_PI) * r4 * L +
	    (8 * M_PI / 15) * r5;
}

/* ---- the table ---- */

/* A sphere of radius r (L is 0): the spheroplate's closed forms at L = 0, written so that they
 * give their bytes (4/3 pi r^3, 8 pi/15 r^5 over the density, that is 2/5 m r^2). */
static double
sphere_volume(double r, double L)
{
	(void)L;
	return 4.0 / 3.0 * M_PI * r * r * r;
}

static void
sphere_inertia(double r, double L, double *Inormal, double *Iinplane)
{
	double r2 = r * r, r3 = r2 * r, r4 = r3 * r, r5 = r4 * r;

	(void)L;
	*Inormal = *Iinplane = (8 * M_PI / 15) * r5;
}

static double
sphere_bounding_radius(double r, double L)
{
	(void)L;
	return r;
}

static void
sphere_extent(double r, double L, double half[3])
{
	(void)L;
	half[0] = half[1] = half[2] = r;
}

static int
sphere_side_ok(double L)
{
	return L == 0;
}

const struct shape_ops shape_sphere = {
	.name = "sphere", .kind = SHAPE_SPHERE, .oriented = 0, .lammps_type = 2,
	.volume = sphere_volume, .inertia = sphere_inertia, .bounding_radius = sphere_bounding_radius,
	.extent = sphere_extent, .side_ok = sphere_side_ok,
};

static void
plate_extent(double r, double L, double half[3])
{
	half[0] = half[1] = L / 2 + r;
	half[2] = r;
}

static int
plate_side_ok(double L)
{
	return isfinite(L) && L > 0;
}

const struct shape_ops shape_spheroplate = {
	.name = "spheroplate", .kind = SHAPE_SPHEROPLATE, .oriented = 1, .lammps_type = 1,
	.volume = shape_volume, .inertia = shape_inertia, .bounding_radius = shape_bounding_radius,
	.extent = plate_extent, .side_ok = plate_side_ok,
};

#define SHAPE_ROW(K, id) &shape_##id,
const struct shape_ops *const shape_table[SHAPE_NKINDS] = {SHAPES(SHAPE_ROW)};
#undef SHAPE_ROW

const struct shape_ops *
shape_of(enum shape_kind k)
{
	return shape_table[k];
}

const struct shape_ops *
shape_find(const char *name)
{
	int k;

	for (k = 0; k < SHAPE_NKINDS; k++)
		if (strcmp(name, shape_table[k]->name) == 0)
			return shape_table[k];
	return NULL;
}

enum shape_kind
shape_kind_of_side(double L)
{
	return L > 0 ? SHAPE_SPHEROPLATE : SHAPE_SPHERE;
}

void
shape_names(char *buf, size_t size)
{
	size_t len = 0;
	int k;

	if (size)
		buf[0] = 0;
	for (k = 0; k < SHAPE_NKINDS && len < size; k++)
		len += (size_t)snprintf(buf + len, size - len, "%s%s", k ? ", " : "", shape_table[k]->name);
}
