/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_shape: the table of the shapes (pack/shape.h), walked row by row, so that a new row is
 * tested without an edit here.  (a) The table itself: kinds in order, names unique and found
 * by shape_find; (b) each row's volume, principal moments and bounding radius against a
 * reference where this file has one for the kind's name (a sphere: 4/3 pi r^3, 2/5 m r^2, r;
 * a spheroplate: slices of the rounded square integrated across its thickness, an
 * independent route to shape.c's polynomials, and r + L / sqrt 2), and for every row their
 * scaling (r, L) -> (s r, s L) as s^3, s^5, s and the bounds the extent and the bounding
 * radius put on the volume; (c) each kind written in a pack and read back. */
#include "unit.h"
#include "base/msg.h"
#include "pack/pack.h"
#include "pack/packio.h"
#include "pack/shape.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A side the row accepts: 0 where it takes one (a sphere), else r (a core as wide as the
 * spheroradius). */
static double
some_side(const struct shape_ops *sh, double r)
{
	return sh->side_ok(0) ? 0 : r;
}

/* The rounded square of core half side a swept by a disc of radius rho: its area and polar
 * moment about its centre (central square, four edge rectangles, four corner quarter discs). */
static void
rounded_square(double a, double rho, double *A, double *J)
{
	double L = 2 * a, quarter = M_PI * rho * rho / 4;

	*A = L * L + 4 * L * rho + M_PI * rho * rho;
	*J = L * L * L * L / 6 + 4 * (L * (pow(a + rho, 3) - a * a * a) / 3 + rho * L * L * L / 12) +
	    4 * (2 * a * a * quarter + 4 * a * rho * rho * rho / 3 + M_PI * rho * rho * rho * rho / 8);
}

/* A spheroplate of spheroradius r and side L by slices z = r sin t, t in [-pi/2, pi/2]
 * (Simpson's rule): V = int A, I_normal = int J, I_inplane = int (J / 2 + z^2 A). */
static void
plate_by_slices(double r, double L, double *V, double *In, double *Ip)
{
	const int n = 2000;
	int k;

	*V = *In = *Ip = 0;
	for (k = 0; k <= n; k++) {
		double t = -M_PI / 2 + M_PI * k / n, z = r * sin(t), dz = r * cos(t) * M_PI / n, A, J;
		double w = (k == 0 || k == n) ? 1.0 / 3 : (k % 2 ? 4.0 / 3 : 2.0 / 3);

		rounded_square(L / 2, sqrt(fmax(r * r - z * z, 0)), &A, &J);
		*V += w * dz * A;
		*In += w * dz * J;
		*Ip += w * dz * (J / 2 + z * z * A);
	}
}

/* The reference of the kind named name at (r, L): 1 with V, I_normal / rho, I_inplane / rho
 * and the bounding radius set, 0 when this file has none for it. */
static int
reference(const char *name, double r, double L, double *V, double *In, double *Ip, double *rb)
{
	if (strcmp(name, "sphere") == 0) {
		*V = 4.0 / 3 * M_PI * r * r * r;
		*In = *Ip = 0.4 * *V * r * r;	/* 2/5 m r^2 over the density */
		*rb = r;
		return 1;
	}
	if (strcmp(name, "spheroplate") == 0) {
		plate_by_slices(r, L, V, In, Ip);
		*rb = r + L / M_SQRT2;
		return 1;
	}
	return 0;
}

static void
test_table(void)
{
	int k, j;
	char names[256];

	for (k = 0; k < SHAPE_NKINDS; k++) {
		const struct shape_ops *sh = shape_table[k];

		CHECK(sh->kind == (enum shape_kind)k && shape_of((enum shape_kind)k) == sh, "table: row %d is kind %d", k, k);
		CHECK(sh->name && *sh->name && !strchr(sh->name, ' ') && shape_find(sh->name) == sh,
		    "table: '%s' is a name shape_find finds", sh->name);
		for (j = 0; j < k; j++)
			CHECK(strcmp(sh->name, shape_table[j]->name) != 0, "table: '%s' once", sh->name);
	}
	CHECK(shape_table[0]->kind == SHAPE_SPHERE && !shape_table[0]->oriented, "table: the first row is the sphere");
	CHECK(shape_find("cube") == NULL, "table: shape_find of no kind is NULL");
	CHECK(shape_kind_of_side(0) == SHAPE_SPHERE && shape_kind_of_side(1e-5) == SHAPE_SPHEROPLATE,
	    "table: a pack without a shape column: side 0 a sphere, side > 0 a spheroplate");
	shape_names(names, sizeof names);
	CHECK(strncmp(names, "sphere, spheroplate", 19) == 0, "table: shape_names '%s'", names);
}

static void
test_row(const struct shape_ops *sh, double r)
{
	double L = some_side(sh, r), V, In, Ip, rb, V2, In2, Ip2, half[3], want[4];
	char what[128];

	snprintf(what, sizeof what, "%s r %g L %g", sh->name, r, L);
	CHECK(sh->side_ok(L) && !sh->side_ok(-r) && !sh->side_ok(NAN), "%s: side_ok takes L, refuses -r and NaN", what);
	V = sh->volume(r, L);
	sh->inertia(r, L, &In, &Ip);
	rb = sh->bounding_radius(r, L);
	sh->extent(r, L, half);
	CHECK(V > 0 && In > 0 && Ip > 0 && rb >= r, "%s: volume, moments positive, bounding radius at least r", what);
	CHECK(V <= 8 * half[0] * half[1] * half[2] * (1 + 1e-15) && V <= 4.0 / 3 * M_PI * rb * rb * rb * (1 + 1e-15) &&
	    rb * rb <= (half[0] * half[0] + half[1] * half[1] + half[2] * half[2]) * (1 + 1e-15),
	    "%s: the extent's box and the bounding sphere hold the volume", what);
	V2 = sh->volume(2 * r, 2 * L);
	sh->inertia(2 * r, 2 * L, &In2, &Ip2);
	CHECK(unit_close(V2, 8 * V, 1e-14, 0) && unit_close(In2, 32 * In, 1e-14, 0) && unit_close(Ip2, 32 * Ip, 1e-14, 0) &&
	    unit_close(sh->bounding_radius(2 * r, 2 * L), 2 * rb, 1e-15, 0), "%s: scales as s^3, s^5, s", what);
	if (!reference(sh->name, r, L, &want[0], &want[1], &want[2], &want[3])) {
		CHECK(1, "%s: no reference here (the generic checks only)", what);
		return;
	}
	CHECK_CLOSE(V, want[0], 1e-12, what);
	CHECK_CLOSE(In, want[1], 1e-12, what);
	CHECK_CLOSE(Ip, want[2], 1e-12, what);
	CHECK_CLOSE(rb, want[3], 1e-15, what);
}

/* The spheroplate's polynomials at other aspect ratios, against the slices. */
static void
test_plate_aspects(void)
{
	const double Ls[] = {1e-3, 0.3, 1, 4, 50};
	size_t k;

	for (k = 0; k < sizeof Ls / sizeof *Ls; k++) {
		double V, In, Ip, want[4];
		char what[96];

		V = shape_spheroplate.volume(1, Ls[k]);
		shape_spheroplate.inertia(1, Ls[k], &In, &Ip);
		reference("spheroplate", 1, Ls[k], &want[0], &want[1], &want[2], &want[3]);
		snprintf(what, sizeof what, "spheroplate r 1 L %g: V, I_normal, I_inplane", Ls[k]);
		CHECK(unit_close(V, want[0], 1e-12, 0) && unit_close(In, want[1], 1e-12, 0) && unit_close(Ip, want[2], 1e-12, 0),
		    "%s (%.17g %.17g %.17g vs %.17g %.17g %.17g)", what, V, In, Ip, want[0], want[1], want[2]);
	}
}

/* One grain of each kind, written and read back: the same kinds. */
static void
test_round_trip(const char *path)
{
	struct pack p, q;
	const double qid[4] = {1, 0, 0, 0};
	int k, same = 1;

	pack_init(&p);
	p.box[3] = p.box[4] = p.box[5] = 1e-3;
	p.wall_E = 7e12, p.wall_nu = 0.3, p.mu = p.wall_mu = 0.3;
	CHECK(pack_set_shapes(&p) == 0, "round trip: shape columns");
	for (k = 0; k < SHAPE_NKINDS; k++) {
		const double x[3] = {1e-4 * (k + 1), 5e-4, 5e-4}, r = 2e-5;

		pack_add_grain(&p, k + 1, x, r, 7e10, 0.2, 2500);
		pack_set_grain_shape(&p, (size_t)k, some_side(shape_table[k], r), qid);
		pack_set_grain_kind(&p, (size_t)k, (enum shape_kind)k);
	}
	CHECK(pack_validate(&p) == 0, "round trip: the pack is valid (%s)", msg_geterr());
	CHECK(pack_write_path(&p, path) == 0 && pack_read_path(path, &q) == 0, "round trip: written and read (%s)",
	    msg_geterr());
	for (k = 0; k < SHAPE_NKINDS && q.n == p.n; k++)
		same &= pack_grain_shape(&q, (size_t)k) == (enum shape_kind)k;
	CHECK(q.n == p.n && same, "round trip: every kind of the table read back");
	pack_free(&p);
	pack_free(&q);
}

int
main(void)
{
	char dir[] = "/tmp/qusgm-test-shape.XXXXXX", path[128];
	int k;

	test_table();
	for (k = 0; k < SHAPE_NKINDS; k++) {
		test_row(shape_table[k], 1);
		test_row(shape_table[k], 3e-5);
	}
	test_plate_aspects();
	if (!mkdtemp(dir)) {
		CHECK(0, "mkdtemp");
		return unit_summary();
	}
	snprintf(path, sizeof path, "%s/kinds.pack", dir);
	test_round_trip(path);
	unlink(path);
	rmdir(dir);
	return unit_summary();
}
