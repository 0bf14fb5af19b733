/* SPDX-License-Identifier: GPL-3.0-or-later */
/* shape: spheroplate geometry in closed form (see shape.h). */
#include "pack/shape.h"

#include <math.h>

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
