/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_plate: the spheroplate element contacts (contact/plate.h).  (a) The cores' distance
 * against a reference written here: a grid on one square with the exact point-square distance
 * to the other, and a nested golden-section search of that convex function; (b) every
 * element's overlap against the true distance of the two elements it names, h_max against the
 * reference; (c) the symmetry i <-> j; (d) element contacts per interaction on random and on
 * near-parallel stacked near-contact pairs, and on set configurations (stacks, crossed edges,
 * line contacts, corners); (e) the sphere limit; (f) walls; (g) periodic images; (h) libccd's
 * MPR as an independent estimate of the depth and as the fallback for intersecting cores.
 *
 * Shapes: outer radius R = 1 and platyness eta under SHAPE_R_EDGE (half side eta, spheroradius
 * 1 - eta); orientations from quat_from_uniform with gsl_rng_mt19937 and fixed seeds. */
#include "unit.h"
#include "base/quat.h"
#include "contact/narrow.h"
#include "contact/plate.h"
#include "pack/shape.h"

#include <ccd/ccd.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <string.h>
#include "plate_place.h"

static const double etas[3] = {0.14, 0.5, 0.8};

static void
body_make(struct plate_body *b, const double x[3], const double q[4], double half, double r)
{
	double qq[4] = {q[0], q[1], q[2], q[3]};

	quat_normalize(qq);
	memcpy(b->x, x, sizeof b->x);
	quat_to_matrix(qq, b->R);
	b->half = half;
	b->r = r;
}

static void
body_random(gsl_rng *rng, double eta, const double x[3], struct plate_body *b)
{
	double q[4];

	quat_from_uniform(gsl_rng_uniform(rng), gsl_rng_uniform(rng), gsl_rng_uniform(rng), q);
	body_make(b, x, q, shape_plate_side(1, eta, SHAPE_R_EDGE) / 2, shape_spheroradius(1, eta));
}

static void
unit_random(gsl_rng *rng, double u[3])
{
	double z = 2 * gsl_rng_uniform(rng) - 1, ph = 2 * M_PI * gsl_rng_uniform(rng), s = sqrt(1 - z * z);

	u[0] = s * cos(ph), u[1] = s * sin(ph), u[2] = z;
}

/* Two spheres (frames the lab's): a of radius 0.5-1.5 at the origin, b of radius 0.5-1.5 at
 * 1.2-2 from it in a random direction; e = x_a - x_b into e, |e| returned. */
static double
sphere_pair_random(gsl_rng *rng, struct plate_body *a, struct plate_body *b, double e[3])
{
	static const double id[4] = {1, 0, 0, 0}, xa[3] = {0, 0, 0};
	double dir[3], xb[3];
	int k;

	unit_random(rng, dir);
	for (k = 0; k < 3; k++)
		xb[k] = (1.2 + 0.8 * gsl_rng_uniform(rng)) * dir[k];
	body_make(a, xa, id, 0, 0.5 + gsl_rng_uniform(rng));
	body_make(b, xb, id, 0, 0.5 + gsl_rng_uniform(rng));
	for (k = 0; k < 3; k++)
		e[k] = a->x[k] - b->x[k];
	return sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
}

static double
dist3(const double a[3], const double b[3])
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* ---- the reference ---- */

static void
ref_at(const struct plate_body *b, double s, double t, double p[3])
{
	int k;

	for (k = 0; k < 3; k++)
		p[k] = b->x[k] + s * b->R[3 * k] + t * b->R[3 * k + 1];
}

static double
clamp(double x, double h)
{
	return x < -h ? -h : x > h ? h : x;
}

/* The distance from p to b's square: the in-plane coordinates clamped. */
static double
ref_point_square(const struct plate_body *b, const double p[3])
{
	double s = 0, t = 0, q[3];
	int k;

	for (k = 0; k < 3; k++) {
		s += (p[k] - b->x[k]) * b->R[3 * k];
		t += (p[k] - b->x[k]) * b->R[3 * k + 1];
	}
	ref_at(b, clamp(s, b->half), clamp(t, b->half), q);
	return dist3(p, q);
}

struct ref_ctx {
	const struct plate_body *a, *b;
	double s;
};

static double
ref_f(const struct ref_ctx *c, double s, double t)
{
	double p[3];

	ref_at(c->a, s, t, p);
	return ref_point_square(c->b, p);
}

/* Golden section for min over t in [-h, h] (outer = 0) or min over s of that (outer = 1): the
 * distance to a convex set is convex along the affine square, and so is its partial minimum. */
static double
ref_golden(struct ref_ctx *c, int outer)
{
	const double g = (sqrt(5) - 1) / 2;
	double h = c->a->half, lo = -h, hi = h, x1, x2, f1, f2;
	int it;

	x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
	f1 = outer ? (c->s = x1, ref_golden(c, 0)) : ref_f(c, c->s, x1);
	f2 = outer ? (c->s = x2, ref_golden(c, 0)) : ref_f(c, c->s, x2);
	for (it = 0; it < 75; it++) {
		if (f1 <= f2) {
			hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo);
			f1 = outer ? (c->s = x1, ref_golden(c, 0)) : ref_f(c, c->s, x1);
		} else {
			lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo);
			f2 = outer ? (c->s = x2, ref_golden(c, 0)) : ref_f(c, c->s, x2);
		}
	}
	return fmin(f1, f2);
}

static double
ref_distance(const struct plate_body *a, const struct plate_body *b)
{
	struct ref_ctx c = {a, b, 0};

	if (a->half == 0)
		return ref_point_square(b, a->x);
	return ref_golden(&c, 1);
}

/* The least distance to b over an n x n grid on a's square. */
static double
grid_distance(const struct plate_body *a, const struct plate_body *b, int n)
{
	struct ref_ctx c = {a, b, 0};
	double best = INFINITY, h = a->half;
	int i, j;

	for (i = 0; i < n; i++)
		for (j = 0; j < n; j++)
			best = fmin(best, ref_f(&c, -h + 2 * h * i / (n - 1), -h + 2 * h * j / (n - 1)));
	return best;
}

/* A random pair at platyness eta whose cores are `target` apart. */
static void
pair_random(gsl_rng *rng, double eta, double target, struct plate_body *a, struct plate_body *b)
{
	static const double o[3] = {0.3, -0.2, 0.1};
	double dir[3];

	body_random(rng, eta, o, a);
	body_random(rng, eta, o, b);
	unit_random(rng, dir);
	plate_place(a, b, dir, target);
}

/* A near-parallel stack: b is a turned about a's normal by a random angle and tilted by up to
 * 0.01 rad (or by nothing, a third of the time: exact ties), moved in a's plane by up to a
 * side and along its normal to a core distance of `target`. */
static void
pair_stacked(gsl_rng *rng, double eta, double target, struct plate_body *a, struct plate_body *b)
{
	static const double o[3] = {0.3, -0.2, 0.1};
	double ang = 2 * M_PI * gsl_rng_uniform(rng), tl = gsl_rng_uniform(rng) < 1.0 / 3 ? 0 : 0.01 * gsl_rng_uniform(rng);
	double ax = 2 * M_PI * gsl_rng_uniform(rng), qa[4], qt[4], qs[4], qb[4], dir[3], u[2];
	int k;

	quat_from_uniform(gsl_rng_uniform(rng), gsl_rng_uniform(rng), gsl_rng_uniform(rng), qa);
	qt[0] = cos(tl / 2), qt[1] = sin(tl / 2) * cos(ax), qt[2] = sin(tl / 2) * sin(ax), qt[3] = 0;
	qs[0] = cos(ang / 2), qs[1] = qs[2] = 0, qs[3] = sin(ang / 2);
	quat_mul(qt, qs, qb);
	quat_mul(qa, qb, qt);
	body_make(a, o, qa, shape_plate_side(1, eta, SHAPE_R_EDGE) / 2, shape_spheroradius(1, eta));
	body_make(b, o, qt, a->half, a->r);
	u[0] = (2 * gsl_rng_uniform(rng) - 1) * a->half, u[1] = (2 * gsl_rng_uniform(rng) - 1) * a->half;
	for (k = 0; k < 3; k++)
		dir[k] = a->R[3 * k + 2] + u[0] * a->R[3 * k] + u[1] * a->R[3 * k + 1];
	{
		double n = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
		for (k = 0; k < 3; k++)
			dir[k] /= n;
	}
	plate_place(a, b, dir, target);
}

/* ---- (a) the cores' distance ---- */

static void
test_core_distance(void)
{
	const int npairs = 200, ngrid = 41;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	int ie;

	gsl_rng_set(rng, 1);
	for (ie = 0; ie < 3; ie++) {
		double eta = etas[ie], h = shape_plate_side(1, eta, SHAPE_R_EDGE) / 2, sp = 2 * h / (ngrid - 1);
		double err_ref = 0, grid_over = 0, grid_under = 0, pt_err = 0, on_err = 0;
		int i, k, nzero = 0, zero_bad = 0;
		for (i = 0; i < npairs; i++) {
			struct plate_body a, b;
			double pa[3], pb[3], d, dr, dg;
			if (i % 4 == 0) {	/* centres at random distances: many intersecting cores */
				double dir[3], s = gsl_rng_uniform(rng) * (2 * M_SQRT2 * h + 0.3);
				pair_random(rng, eta, 1, &a, &b);
				unit_random(rng, dir);
				for (k = 0; k < 3; k++)
					b.x[k] = a.x[k] + s * dir[k];
			} else {
				pair_random(rng, eta, 2 * (1 - eta) * (0.6 + 0.8 * gsl_rng_uniform(rng)), &a, &b);
			}
			d = plate_core_distance(&a, &b, pa, pb);
			dr = ref_distance(&a, &b);
			dg = grid_distance(&a, &b, ngrid);
			err_ref = fmax(err_ref, fabs(d - dr));
			grid_over = fmax(grid_over, dg - d);
			grid_under = fmax(grid_under, d - dg);
			pt_err = fmax(pt_err, fabs(dist3(pa, pb) - d));
			on_err = fmax(on_err, fmax(ref_point_square(&a, pa), ref_point_square(&b, pb)));
			if (d == 0)
				nzero++;
			zero_bad += (d == 0) != (dr < 1e-12);
		}
		/* The golden sections shrink each interval by 0.618^75 ~ 2e-16: with a 1-Lipschitz
		 * function the reference is within round-off (1e-15) of the minimum, so 1e-12 leaves
		 * only the search's own rounding. */
		CHECK(err_ref < 1e-12, "core distance eta %.2f: %d pairs (%d intersecting), max |d - golden section| %.2e",
		    eta, npairs, nzero, err_ref);
		/* A grid of spacing sp on a's square holds a point within sp/sqrt2 of the closest point
		 * of a, and the distance to b is 1-Lipschitz: the grid is above d by at most sp/sqrt2,
		 * and never below it. */
		CHECK(grid_over <= sp / M_SQRT2 + 1e-12 && grid_under < 1e-12,
		    "core distance eta %.2f: grid minus d in [%.2e, %.2e], bound sp/sqrt2 = %.2e", eta, -grid_under,
		    grid_over, sp / M_SQRT2);
		CHECK(pt_err < 1e-12 && on_err < 1e-12,
		    "core distance eta %.2f: closest points |pa - pb| - d %.2e, off their squares %.2e", eta, pt_err, on_err);
		CHECK(zero_bad == 0, "core distance eta %.2f: d == 0 exactly when the reference is 0 (%d disagree)", eta,
		    zero_bad);
	}
	gsl_rng_free(rng);
}

/* ---- (b) the elements' distances ---- */

enum { F_FACE, F_EDGE, F_VERTEX };

static void
corner(const struct plate_body *b, int k, double p[3])
{
	static const double cs[4] = {-1, 1, 1, -1}, ct[4] = {-1, -1, 1, 1};

	ref_at(b, cs[k] * b->half, ct[k] * b->half, p);
}

static double
point_segment(const double p[3], const double a[3], const double b[3])
{
	double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, l2 = 0, t = 0, q[3];
	int k;

	for (k = 0; k < 3; k++) {
		l2 += ab[k] * ab[k];
		t += (p[k] - a[k]) * ab[k];
	}
	t = l2 > 0 ? fmin(1, fmax(0, t / l2)) : 0;
	for (k = 0; k < 3; k++)
		q[k] = a[k] + t * ab[k];
	return dist3(p, q);
}

static double
segment_at(const double a0[3], const double a1[3], const double b0[3], const double b1[3], double x)
{
	double p[3];
	int k;

	for (k = 0; k < 3; k++)
		p[k] = a0[k] + x * (a1[k] - a0[k]);
	return point_segment(p, b0, b1);
}

/* Segment-segment distance by golden section along the first (the distance to a segment is
 * convex along the other), ends included. */
static double
segment_segment(const double a0[3], const double a1[3], const double b0[3], const double b1[3])
{
	const double g = (sqrt(5) - 1) / 2;
	double lo = 0, hi = 1, x1 = 1 - g, x2 = g, f1, f2;
	int it;

	f1 = segment_at(a0, a1, b0, b1, x1), f2 = segment_at(a0, a1, b0, b1, x2);
	for (it = 0; it < 80; it++) {
		if (f1 <= f2)
			hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = segment_at(a0, a1, b0, b1, x1);
		else
			lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = segment_at(a0, a1, b0, b1, x2);
	}
	return fmin(fmin(f1, f2), fmin(point_segment(a0, b0, b1), point_segment(a1, b0, b1)));
}

/* The feature of b of type `type` that p lies on (within tol): a corner, an edge (two corners)
 * or the face.  Returns the number of points naming it (1, 2, or 0 for the face), -1 if none. */
static int
feature_find(const struct plate_body *b, int type, const double p[3], double f[2][3])
{
	double best = INFINITY, c0[3], c1[3];
	int k, n = -1;

	if (type == F_FACE)
		return ref_point_square(b, p) < 1e-9 ? 0 : -1;
	for (k = 0; k < 4; k++) {
		double e;
		corner(b, k, c0);
		corner(b, (k + 1) % 4, c1);
		e = type == F_VERTEX || b->half == 0 ? dist3(p, c0) : point_segment(p, c0, c1);
		if (e < best && e < 1e-9) {
			best = e, n = type == F_VERTEX || b->half == 0 ? 1 : 2;
			memcpy(f[0], c0, sizeof c0);
			memcpy(f[1], c1, sizeof c1);
		}
	}
	return n;
}

static void
kind_types(int kind, int *ti, int *tj)
{
	static const int tab[6][2] = {{F_VERTEX, F_VERTEX}, {F_VERTEX, F_EDGE}, {F_EDGE, F_VERTEX},
	    {F_VERTEX, F_FACE}, {F_FACE, F_VERTEX}, {F_EDGE, F_EDGE}};

	*ti = tab[kind][0], *tj = tab[kind][1];
}

/* The true distance between the two elements of e, or -1 if its points are not on them. */
static double
element_distance(const struct plate_body *a, const struct plate_body *b, const struct plate_element *e)
{
	double fa[2][3], fb[2][3];
	int ti, tj, na, nb;

	if (e->kind > PLATE_EDGE_EDGE)
		return -1;
	kind_types(e->kind, &ti, &tj);
	na = feature_find(a, ti, e->pi, fa);
	nb = feature_find(b, tj, e->pj, fb);
	if (na < 0 || nb < 0)
		return -1;
	if (na == 1 && nb == 1)
		return dist3(fa[0], fb[0]);
	if (na == 1)
		return nb == 2 ? point_segment(fa[0], fb[0], fb[1]) : ref_point_square(b, fa[0]);
	if (nb == 1)
		return na == 2 ? point_segment(fb[0], fa[0], fa[1]) : ref_point_square(a, fb[0]);
	return segment_segment(fa[0], fa[1], fb[0], fb[1]);
}

static void
test_elements(void)
{
	const int npairs = 300;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	int ie;

	gsl_rng_set(rng, 2);
	for (ie = 0; ie < 3; ie++) {
		double eta = etas[ie], rr = 2 * (1 - eta), dk_err = 0, hmax_err = 0, pt_err = 0, sep_err = 0;
		int i, bad = 0, empty = 0, total = 0, nglobal = 0;
		for (i = 0; i < npairs; i++) {
			struct plate_body a, b;
			struct plate_interaction I;
			double gap = i % 2 ? 0 : 0.05, d, hmax = -INFINITY;
			int j;
			(i % 3 ? pair_random : pair_stacked)(rng, eta, rr * (1 - 0.2 * gsl_rng_uniform(rng)), &a, &b);
			plate_interaction(&a, &b, gap, &I);
			d = ref_distance(&a, &b);
			empty += I.m == 0;
			for (j = 0; j < I.m; j++) {
				const struct plate_element *e = &I.e[j];
				double dk = a.r + b.r - e->h, dt = element_distance(&a, &b, e), sep = 0;
				int k;
				for (k = 0; k < 3; k++)
					sep += I.n[k] * (e->pi[k] - e->pj[k]);
				bad += dt < 0 || !(e->h > -gap);
				if (dt >= 0)
					dk_err = fmax(dk_err, fabs(dk - dt));
				pt_err = fmax(pt_err, fabs(dist3(e->pi, e->pj) - dk));
				sep_err = fmax(sep_err, d - sep);
				hmax = fmax(hmax, e->h);
				nglobal += fabs(dk - d) < 1e-9;
			}
			total += I.m;
			hmax_err = fmax(hmax_err, fabs(hmax - (a.r + b.r - d)));
		}
		/* dk and the elements' distance are both exact formulas (up to round-off, 1e-15) or a
		 * converged golden section (1e-15): 1e-9 is the library's own tie tolerance. */
		CHECK(bad == 0 && dk_err < 1e-9 && pt_err < 1e-12,
		    "elements eta %.2f: %d elements of %d pairs on the elements they name (%d not), max |d_k - true| %.2e, "
		    "||pi - pj| - d_k| %.2e", eta, total, npairs, bad, dk_err, pt_err);
		CHECK(empty == 0 && hmax_err < 1e-9 && nglobal >= npairs,
		    "elements eta %.2f: every touching pair has elements (%d without), h_max = r_i + r_j - d to %.2e", eta,
		    empty, hmax_err);
		/* n separates the cores, so every pair of their points is at least d apart along n. */
		CHECK(sep_err < 1e-12, "elements eta %.2f: n.(pi - pj) >= d for every element (worst %.2e below)", eta,
		    sep_err);
	}
	gsl_rng_free(rng);
}

/* ---- (c) symmetry ---- */

static int
mirror_kind(int k)
{
	static const int m[] = {PLATE_VERTEX_VERTEX, PLATE_EDGE_VERTEX, PLATE_VERTEX_EDGE, PLATE_FACE_VERTEX,
	    PLATE_VERTEX_FACE, PLATE_EDGE_EDGE, PLATE_CORE_OVERLAP, PLATE_SPHERE};

	return m[k];
}

/* Do I(a, b) and J(b, a) hold the same elements, mirrored? */
static int
mirrored(const struct plate_interaction *I, const struct plate_interaction *J, double tol)
{
	int used[PLATE_MAX_ELEMENTS] = {0}, i, j, k;

	if (I->m != J->m)
		return 0;
	for (k = 0; k < 3; k++)
		if (fabs(I->n[k] + J->n[k]) > tol)
			return 0;
	for (i = 0; i < I->m; i++) {
		for (j = 0; j < J->m; j++)
			if (!used[j] && fabs(I->e[i].h - J->e[j].h) <= tol && dist3(I->e[i].pi, J->e[j].pj) <= tol &&
			    dist3(I->e[i].pj, J->e[j].pi) <= tol && dist3(I->e[i].p, J->e[j].p) <= tol &&
			    J->e[j].kind == mirror_kind(I->e[i].kind))
				break;
		if (j == J->m)
			return 0;
		used[j] = 1;
	}
	return 1;
}

static void
test_symmetry(void)
{
	const int npairs = 300;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	int ie;

	gsl_rng_set(rng, 3);
	for (ie = 0; ie < 3; ie++) {
		double eta = etas[ie], rr = 2 * (1 - eta);
		int i, bad = 0, total = 0;
		for (i = 0; i < npairs; i++) {
			struct plate_body a, b;
			struct plate_interaction I, J;
			(i % 3 ? pair_random : pair_stacked)(rng, eta, rr * (1 - 0.2 * gsl_rng_uniform(rng)), &a, &b);
			plate_interaction(&a, &b, 0.05, &I);
			plate_interaction(&b, &a, 0.05, &J);
			bad += !mirrored(&I, &J, 1e-9);
			total += I.m;
		}
		/* The two calls work from different centres: round-off 1e-15, ties at 1e-9. */
		CHECK(bad == 0, "symmetry eta %.2f: (i,j) and (j,i) give the same %d elements, opposite normals (%d pairs differ)",
		    eta, total, bad);
	}
	gsl_rng_free(rng);
}

/* ---- (d) counts ---- */

static double
count_mean(double eta, int npairs, unsigned long seed, int stacked, int kinds[8])
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	double rr = 2 * (1 - eta);
	long total = 0;
	int i, j;

	gsl_rng_set(rng, seed);
	memset(kinds, 0, 8 * sizeof *kinds);
	for (i = 0; i < npairs; i++) {
		struct plate_body a, b;
		struct plate_interaction I;
		(stacked ? pair_stacked : pair_random)(rng, eta, rr - 0.02 * gsl_rng_uniform(rng), &a, &b);
		plate_interaction(&a, &b, 0, &I);
		total += I.m;
		for (j = 0; j < I.m; j++)
			kinds[I.e[j].kind]++;
	}
	gsl_rng_free(rng);
	return (double)total / npairs;
}

/* The pair a at the origin (rotation qa), b at x (rotation qb), eta 0.14. */
static int
count_config(const double qa[4], const double qb[4], const double x[3], int *kinds, double *hmin, double *hmax)
{
	static const double o[3] = {0, 0, 0};
	double half = shape_plate_side(1, 0.14, SHAPE_R_EDGE) / 2, r = shape_spheroradius(1, 0.14);
	struct plate_body a, b;
	struct plate_interaction I;
	int j;

	body_make(&a, o, qa, half, r);
	body_make(&b, x, qb, half, r);
	plate_interaction(&a, &b, 0, &I);
	*kinds = 0, *hmin = INFINITY, *hmax = -INFINITY;
	for (j = 0; j < I.m; j++) {
		*kinds |= 1 << I.e[j].kind;
		*hmin = fmin(*hmin, I.e[j].h), *hmax = fmax(*hmax, I.e[j].h);
	}
	return I.m;
}

static void
test_counts(void)
{
	static const char *names[8] = {"VV", "VE", "EV", "VF", "FV", "EE", "core", "sphere"};
	double h = 0.14, r = 0.86, s45 = sqrt(0.5), del = 0.01, hmin, hmax;
	double id[4] = {1, 0, 0, 0}, z45[4] = {cos(M_PI / 8), 0, 0, sin(M_PI / 8)};
	double x45[4] = {cos(M_PI / 8), sin(M_PI / 8), 0, 0}, y45[4] = {cos(M_PI / 8), 0, sin(M_PI / 8), 0};
	double tilt[4] = {cos(0.025), sin(0.025), 0, 0};
	int ie, kinds[8], m, km;

	for (ie = 0; ie < 3; ie++) {
		int k, st;
		for (st = 0; st < 2; st++) {
			double mean = count_mean(etas[ie], 1000, 4, st, kinds);
			char line[160];
			int len = 0;
			for (k = 0; k < 8; k++)
				if (kinds[k])
					len += snprintf(line + len, sizeof line - len, " %s %.3f", names[k], kinds[k] / 1000.0);
			CHECK(ie > 0 || st || mean < 2.5, "counts eta %.2f: %.3f element contacts per interaction on 1000 %s pairs "
			    "overlapping by up to 0.02 R (per kind:%s)%s", etas[ie], mean, st ? "near-parallel stacked" : "random",
			    line, ie || st ? "" : ", below 2.5");
		}
	}
	/* Identical plates stacked face to face: their 4 corners, vertex-vertex. */
	m = count_config(id, id, (double[3]){0, 0, -(2 * r - del)}, &km, &hmin, &hmax);
	CHECK(m == 4 && km == 1 << PLATE_VERTEX_VERTEX && fabs(hmin - del) < 1e-12 && fabs(hmax - del) < 1e-12,
	    "counts: stacked plates give 4 vertex-vertex elements of h = %g (%d, h %.15g..%.15g)", del, m, hmin, hmax);
	/* Turned by 45 degrees: the octagon's 8 corners, all crossings. */
	m = count_config(id, z45, (double[3]){0, 0, -(2 * r - del)}, &km, &hmin, &hmax);
	CHECK(m == 8 && km == 1 << PLATE_EDGE_EDGE && fabs(hmin - del) < 1e-12,
	    "counts: a stack turned by 45 degrees gives the octagon's 8 edge-edge elements (%d)", m);
	/* Shifted along x: the overlap rectangle's 4 corners, not the 4 corners that stick out. */
	m = count_config(id, id, (double[3]){0.3 * h, 0, -(2 * r - del)}, &km, &hmin, &hmax);
	CHECK(m == 4 && km == (1 << PLATE_VERTEX_EDGE | 1 << PLATE_EDGE_VERTEX) && fabs(hmin - del) < 1e-12,
	    "counts: a stack shifted by 0.3 half gives the overlap's 4 corners (%d)", m);
	/* One turned by 0.05 rad about x: still 4 (a's corners over b), h from del down. */
	m = count_config(tilt, id, (double[3]){0, 0, -(h * sin(0.05) + 2 * r - 2 * del)}, &km, &hmin, &hmax);
	CHECK(m == 4 && fabs(hmax - 2 * del) < 1e-12 && fabs(hmin - (2 * del - 2 * h * sin(0.05))) < 1e-12,
	    "counts: a stack tilted by 0.05 rad gives 4 elements (%d, h %.6f..%.6f)", m, hmin, hmax);
	/* Crossed edges: a turned 45 degrees about x (lowest edge along x at y = z = -half/sqrt2),
	 * b about y (highest edge along y at x = -half/sqrt2 from its centre) right under it,
	 * their middles on one vertical. */
	m = count_config(x45, y45, (double[3]){h * s45, -h * s45, -(2 * h * s45 + 2 * r - del)}, &km, &hmin, &hmax);
	CHECK(m == 1 && km == 1 << PLATE_EDGE_EDGE && fabs(hmax - del) < 1e-12,
	    "counts: crossed edges give 1 edge-edge element (%d, kinds %#x, h %.6f)", m, km, hmax);
	/* Coplanar, side by side along x and offset along y: a line contact, its 2 ends. */
	m = count_config(id, id, (double[3]){2 * h + 2 * r - del, 0.5 * h, 0}, &km, &hmin, &hmax);
	CHECK(m == 2 && fabs(hmin - del) < 1e-12 && fabs(hmax - del) < 1e-12,
	    "counts: coplanar plates edge to edge give the 2 ends of the line contact (%d)", m);
	/* ... and a turned slightly in their plane: still 2, of different depths (the far end
	 * 0.02 * 1.5 half less deep). */
	m = count_config((double[4]){cos(0.01), 0, 0, sin(0.01)}, id, (double[3]){2 * h + 2 * r - del, 0.5 * h, 0}, &km,
	    &hmin, &hmax);
	CHECK(m == 2 && hmin < hmax - 1e-4, "counts: edge to edge turned by 0.02 rad gives 2 ends (%d, h %.6f..%.6f)", m,
	    hmin, hmax);
	/* a standing on its edge on b's face (b turned 45 degrees so that a's corners, at
	 * (+-half, -0.3 half) from b's centre, are inside it): 2 vertex-face. */
	{
		double q[4] = {cos(M_PI / 4), sin(M_PI / 4), 0, 0};
		m = count_config(q, z45, (double[3]){0, 0.3 * h, -(h + 2 * r - del)}, &km, &hmin, &hmax);
		CHECK(m == 2 && km == 1 << PLATE_VERTEX_FACE && fabs(hmin - del) < 1e-12,
		    "counts: a plate standing on its edge on a face gives 2 vertex-face (%d, kinds %#x)", m, km);
	}
	/* Corner to corner along the diagonal. */
	m = count_config(id, id, (double[3]){2 * h + (2 * r - del) / sqrt(3), 2 * h + (2 * r - del) / sqrt(3),
	    (2 * r - del) / sqrt(3)}, &km, &hmin, &hmax);
	CHECK(m == 1 && km == 1 << PLATE_VERTEX_VERTEX && fabs(hmax - del) < 1e-12,
	    "counts: corner to corner gives 1 vertex-vertex (%d, kinds %#x)", m, km);
}

/* ---- (e) the sphere limit ---- */

static void
test_sphere_limit(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	double err_tiny = 0, n_tiny = 0, mixed = 0, core0 = 0;
	int i, exact = 1, tiny_ok = 1;

	gsl_rng_set(rng, 5);
	for (i = 0; i < 200; i++) {
		struct plate_body a, b, at, bt;
		struct plate_interaction I, T;
		double xa[3] = {0, 0, 0}, xb[3], e[3], d, h, n[3];
		int k;

		d = sphere_pair_random(rng, &a, &b, e);
		memcpy(xb, b.x, sizeof xb);
		h = a.r + b.r - d;
		for (k = 0; k < 3; k++)
			n[k] = e[k] / d;
		/* two cores of side 0 by the rules for cores (the table gives two spheres to
		 * sphere.c, test_narrow_table): the sphere's element to round-off at unit size */
		plate_interaction(&a, &b, 1, &I);
		exact &= I.m == 1;
		core0 = fmax(core0, fmax(fabs(I.e[0].h - h), fabs(I.d - d)));
		for (k = 0; k < 3; k++)
			core0 = fmax(core0, fabs(I.n[k] - n[k]));
		/* Half 1e-9 and random turns: the cores lie within sqrt2 half of the centres, so h
		 * moves by at most sqrt2 (half_i + half_j) and n by that over d. */
		body_random(rng, 0, xa, &at);
		body_random(rng, 0, xb, &bt);
		at.half = bt.half = 1e-9, at.r = a.r, bt.r = b.r;
		plate_interaction(&at, &bt, 1, &T);
		tiny_ok &= T.m >= 1;
		for (k = 0; k < T.m; k++)
			err_tiny = fmax(err_tiny, fabs(T.e[k].h - h));
		for (k = 0; k < 3; k++)
			n_tiny = fmax(n_tiny, fabs(T.n[k] - n[k]));
		/* A plate against a sphere: one element, the sphere's centre against the square. */
		body_random(rng, 0.5, xa, &at);
		plate_interaction(&at, &b, 10, &T);
		tiny_ok &= T.m == 1;
		mixed = fmax(mixed, fabs(T.e[0].h - (at.r + b.r - ref_point_square(&at, b.x))));
	}
	/* h, d and n are O(1): a few roundings of the centres' difference and its norm */
	CHECK(exact && core0 < 1e-15 * 8, "sphere limit: half 0 gives the sphere-sphere element (h, d, n) to %.2e "
	    "(200 pairs; 8 ulp of 1 allowed)", core0);
	CHECK(tiny_ok && err_tiny <= 2 * M_SQRT2 * 1e-9 && n_tiny <= 2 * M_SQRT2 * 1e-9 / 1.2,
	    "sphere limit: half 1e-9 matches sphere-sphere to %.2e in h, %.2e in n (bound 2.8e-9)", err_tiny, n_tiny);
	CHECK(mixed < 1e-12, "sphere limit: plate against sphere gives r_i + r_j - |centre - square| to %.2e", mixed);
	gsl_rng_free(rng);
}

/* ---- (f) walls ---- */

static void
test_wall(void)
{
	double h = 0.14, r = 0.86, del = 0.01, s45 = sqrt(0.5), w0[3] = {0, 0, -1}, wn[3] = {0, 0, 1};
	double id[4] = {1, 0, 0, 0}, x45[4] = {cos(M_PI / 8), sin(M_PI / 8), 0, 0}, c[4], y30[4] = {cos(0.3), 0, sin(0.3), 0};
	double xc[3];
	struct plate_body a;
	struct plate_interaction I;
	int k, ok;

	body_make(&a, (double[3]){0.2, 0.1, -1 + r - del}, id, h, r);
	plate_wall_interaction(&a, w0, wn, 0, &I);
	ok = I.m == 4;
	for (k = 0; k < I.m; k++)
		ok &= fabs(I.e[k].h - del) < 1e-12 && I.e[k].kind == PLATE_VERTEX_FACE && fabs(I.e[k].pj[2] + 1) < 1e-15 &&
		    fabs(I.e[k].p[2] - (-1 + (r - del) / 2 - r / 2)) < 1e-12;
	CHECK(ok && I.n[2] == 1, "wall: face down gives 4 corners of h = %g (%d)", del, I.m);
	body_make(&a, (double[3]){0, 0, -1 + h * s45 + r - del}, x45, h, r);
	plate_wall_interaction(&a, w0, wn, 0, &I);
	ok = I.m == 2;
	for (k = 0; k < I.m; k++)
		ok &= fabs(I.e[k].h - del) < 1e-12;
	CHECK(ok, "wall: on an edge gives 2 corners of h = %g (%d)", del, I.m);
	quat_mul(y30, x45, c);
	quat_normalize(c);
	body_make(&a, (double[3]){0, 0, 0}, c, h, r);
	{
		double lo = INFINITY;
		for (k = 0; k < 4; k++) {
			double s = k % 3 ? h : -h, t = k < 2 ? -h : h;
			lo = fmin(lo, s * a.R[6] + t * a.R[7]);
		}
		xc[0] = 0, xc[1] = 0, xc[2] = -1 - lo + r - del;
	}
	body_make(&a, xc, c, h, r);
	plate_wall_interaction(&a, w0, wn, 0, &I);
	CHECK(I.m == 1 && fabs(I.e[0].h - del) < 1e-12 && fabs(I.d - (r - del)) < 1e-12,
	    "wall: on a corner gives 1 corner of h = %g (%d)", del, I.m);
	body_make(&a, (double[3]){0, 0, -1 + r - del}, id, 0, r);
	plate_wall_interaction(&a, w0, wn, 0, &I);
	CHECK(I.m == 1 && I.e[0].kind == PLATE_SPHERE && fabs(I.e[0].h - del) < 1e-12,
	    "wall: a sphere gives its centre, h = %g (%d)", del, I.m);
}

/* ---- (g) periodic images ---- */

static void
test_periodic(void)
{
	const double L = 7.3;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	double worst = 0;
	int ie, i, bad = 0, total = 0;

	gsl_rng_set(rng, 6);
	for (ie = 0; ie < 3; ie++)
		for (i = 0; i < 100; i++) {
			struct plate_body a, b, ai, bi;
			struct plate_interaction I, J;
			double rr = 2 * (1 - etas[ie]);
			int j, k;
			pair_random(rng, etas[ie], rr * (1 - 0.2 * gsl_rng_uniform(rng)), &a, &b);
			/* a near the box's upper x face, b wrapped to its lower one; the caller passes
			 * b's image b + L.  The reference is the same pair at the lower face. */
			ai = a, bi = b;
			ai.x[0] += L - 1.5, bi.x[0] += L - 1.5;
			b.x[0] = bi.x[0] - L;
			bi.x[0] = b.x[0] + L;
			a.x[0] = ai.x[0] - L;
			plate_interaction(&ai, &bi, 0.05, &I);
			plate_interaction(&a, &b, 0.05, &J);
			bad += I.m != J.m;
			for (j = 0; j < I.m && j < J.m; j++) {
				for (k = 0; k < 3; k++) {
					J.e[j].pi[k] += k == 0 ? L : 0;
					J.e[j].pj[k] += k == 0 ? L : 0;
					J.e[j].p[k] += k == 0 ? L : 0;
				}
				worst = fmax(worst, fmax(fabs(I.e[j].h - J.e[j].h),
				    fmax(dist3(I.e[j].pi, J.e[j].pi), fmax(dist3(I.e[j].pj, J.e[j].pj), dist3(I.e[j].p, J.e[j].p)))));
				bad += I.e[j].kind != J.e[j].kind;
			}
			total += I.m;
		}
	/* The two differ by the rounding of the centres at the box's size: ulp(7.3) ~ 1e-15. */
	CHECK(bad == 0 && worst < 1e-12,
	    "periodic: the image b + L gives the %d elements of the pair at the other face, shifted (worst %.2e)", total,
	    worst);
	gsl_rng_free(rng);
}

/* ---- (i) the table of shape pairs (narrow.h) ---- */

static void
test_narrow_table(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	double mixed = 0, wall_err = 0;
	int a, b, i, filled = 1, exact = 1, kinds_ok = 1, wall_same = 1;

	for (a = 0; a < SHAPE_NKINDS; a++) {
		filled &= narrow_wall_of((enum shape_kind)a) != NULL;
		for (b = 0; b < SHAPE_NKINDS; b++) {
			const struct narrow_pair *np = narrow_pair_of((enum shape_kind)a, (enum shape_kind)b);
			filled &= np->interaction && np->cached && (np->bounds_exact || np->gap_bound);
		}
	}
	CHECK(filled, "narrow table: every pair of the %d kinds and every kind on a wall has its functions", SHAPE_NKINDS);
	CHECK(narrow_pair_of(SHAPE_SPHERE, SHAPE_SPHERE)->bounds_exact &&
	    !narrow_pair_of(SHAPE_SPHERE, SHAPE_SPHEROPLATE)->bounds_exact &&
	    !narrow_pair_of(SHAPE_SPHEROPLATE, SHAPE_SPHEROPLATE)->bounds_exact,
	    "narrow table: only two spheres are their bounding spheres");
	gsl_rng_set(rng, 9);
	for (i = 0; i < 200; i++) {
		const struct narrow_pair *ss = narrow_pair_of(SHAPE_SPHERE, SHAPE_SPHERE);
		const struct narrow_pair *ps = narrow_pair_of(SHAPE_SPHEROPLATE, SHAPE_SPHERE);
		const struct narrow_pair *sp = narrow_pair_of(SHAPE_SPHERE, SHAPE_SPHEROPLATE);
		struct plate_body s1, s2, pl;
		struct plate_interaction I, J, W1, W2;
		double x0[3] = {0, 0, 0}, e[3], d, w0[3] = {0, 0, -1}, wn[3] = {0, 0, 1};
		unsigned word = 7;
		int k, m;

		d = sphere_pair_random(rng, &s1, &s2, e);
		/* two spheres: the closed form to the bit, cached or not, and no cache kept */
		m = ss->interaction(&s1, &s2, 1, &I);
		exact &= m == 1 && I.e[0].kind == PLATE_SPHERE && I.e[0].h == s1.r + s2.r - d && I.d == d;
		for (k = 0; k < 3; k++)
			exact &= I.n[k] == e[k] / d;
		if (I.e[0].h > 0) {
			m = ss->cached(&s1, &s2, 0.1, &word, 0, &J);
			exact &= m == 1 && word == 0 && J.e[0].h == I.e[0].h;
		}
		/* a plate and a sphere, both orders: r_i + r_j - |centre - square|, opposite normals */
		body_random(rng, 0.5, x0, &pl);
		m = ps->interaction(&pl, &s2, 10, &I);
		kinds_ok &= m == 1 && sp->interaction(&s2, &pl, 10, &J) == 1;
		mixed = fmax(mixed, fabs(I.e[0].h - (pl.r + s2.r - ref_point_square(&pl, s2.x))));
		mixed = fmax(mixed, fabs(J.e[0].h - I.e[0].h));
		for (k = 0; k < 3; k++)
			mixed = fmax(mixed, fabs(I.n[k] + J.n[k]));
		/* a sphere on a wall: h = r - signed distance, and what the plate rules give a core
		 * of side 0, to the bit (the bytes of sphere packs before the table) */
		s1.x[2] = -1 + s1.r * (2 * gsl_rng_uniform(rng));
		narrow_wall_of(SHAPE_SPHERE)(&s1, w0, wn, 1, &W1);
		plate_wall_interaction(&s1, w0, wn, 1, &W2);
		wall_err = fmax(wall_err, fabs(W1.e[0].h - (s1.r - (s1.x[2] + 1))));
		wall_same &= W1.m == W2.m && W1.d == W2.d && (W1.m == 0 || (W1.e[0].h == W2.e[0].h &&
		    !memcmp(W1.e[0].p, W2.e[0].p, sizeof W1.e[0].p) && !memcmp(W1.e[0].pj, W2.e[0].pj, sizeof W1.e[0].pj) &&
		    W1.e[0].kind == W2.e[0].kind));
	}
	CHECK(exact, "narrow table: two spheres give h = r_i + r_j - d and n along x_i - x_j to the bit (200 pairs)");
	CHECK(kinds_ok && mixed < 1e-12, "narrow table: plate-sphere and sphere-plate agree with the reference (%.2e)",
	    mixed);
	CHECK(wall_same && wall_err < 1e-15, "narrow table: a sphere on a wall, h = r - distance (%.2e), the plate "
	    "rules' element to the bit", wall_err);
	gsl_rng_free(rng);
}

/* ---- (h) libccd ---- */

static void
ccd_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *v)
{
	const struct plate_body *b = obj;
	double du = 0, dv = 0, n = sqrt(dir->v[0] * dir->v[0] + dir->v[1] * dir->v[1] + dir->v[2] * dir->v[2]), p[3];
	int k;

	for (k = 0; k < 3; k++)
		du += dir->v[k] * b->R[3 * k], dv += dir->v[k] * b->R[3 * k + 1];
	ref_at(b, du >= 0 ? b->half : -b->half, dv >= 0 ? b->half : -b->half, p);
	for (k = 0; k < 3; k++)
		v->v[k] = p[k] + (n > 0 ? b->r * dir->v[k] / n : 0);
}

static void
ccd_centre(const void *obj, ccd_vec3_t *c)
{
	const struct plate_body *b = obj;

	memcpy(c->v, b->x, sizeof c->v);
}

static int
mpr(const struct plate_body *a, const struct plate_body *b, double *depth, double dir[3])
{
	ccd_vec3_t d, pos;
	ccd_t ccd;
	int rc;

	CCD_INIT(&ccd);
	ccd.support1 = ccd.support2 = ccd_support;
	ccd.center1 = ccd.center2 = ccd_centre;
	ccd.mpr_tolerance = 1e-10;
	ccd.max_iterations = 500;
	rc = ccdMPRPenetration(a, b, &ccd, depth, &d, &pos);
	memcpy(dir, d.v, 3 * sizeof *dir);
	return rc;
}

static void
test_libccd(void)
{
	const int npairs = 300;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	double id[4] = {1, 0, 0, 0}, yq[4] = {cos(M_PI / 4), 0, sin(M_PI / 4), 0}, h = 0.14, r = 0.86;
	struct plate_body a, b;
	struct plate_interaction I;
	int i, ie, close3 = 0, fails = 0, ok = 1;

	gsl_rng_set(rng, 7);
	for (ie = 0; ie < 3; ie++) {
		double rr = 2 * (1 - etas[ie]);
		close3 = fails = 0;
		for (i = 0; i < npairs; i++) {
			double depth, dir[3], hh;
			pair_random(rng, etas[ie], rr - rr / 2 * (0.05 + 0.15 * gsl_rng_uniform(rng)), &a, &b);
			hh = a.r + b.r - plate_core_distance(&a, &b, NULL, NULL);
			if (mpr(&a, &b, &depth, dir) != 0) {
				fails++;
				continue;
			}
			close3 += fabs(depth - hh) <= 0.03 * hh;
		}
		/* The true penetration depth of the two spheroplates is r_i + r_j - d (cores apart);
		 * MPR measures along its final portal's normal, not the least translation, so it is
		 * an estimate.  At eta = 0.14 the shapes are nearly spheres and it should agree
		 * within 3 % for nearly all pairs (100 % when this was written; 90 % required); at
		 * 0.5 and 0.8 the fraction is printed only (physics.md §12: MPR misjudges flat ones). */
		CHECK(fails == 0 && (ie > 0 || close3 >= 0.9 * npairs),
		    "libccd: MPR depth within 3%% of r_i + r_j - d for %.1f%% of %d pairs at eta %.2f overlapping by "
		    "0.05-0.2 r%s", 100.0 * close3 / npairs, npairs, etas[ie], ie ? "" : " (90% required)");
	}

	/* Intersecting cores: b vertical (normal along x) through a, shifted by -0.5 half along x.
	 * The least push is along x, 0.5 half + 2 r. */
	body_make(&a, (double[3]){0, 0, 0}, id, h, r);
	body_make(&b, (double[3]){-0.5 * h, 0, 0}, yq, h, r);
	plate_interaction(&a, &b, 0, &I);
	{
		double nn = sqrt(I.n[0] * I.n[0] + I.n[1] * I.n[1] + I.n[2] * I.n[2]);
		CHECK(I.m == 1 && I.d == 0 && I.e[0].kind == PLATE_CORE_OVERLAP && fabs(nn - 1) < 1e-12 && I.n[0] > 0.99 &&
		    fabs(I.e[0].h - (0.5 * h + 2 * r)) < 0.01 * (0.5 * h + 2 * r),
		    "libccd fallback: crossed cores give one element, h %.6f (expected %.6f), n (%.4f %.4f %.4f)",
		    I.m ? I.e[0].h : 0, 0.5 * h + 2 * r, I.n[0], I.n[1], I.n[2]);
	}
	for (ie = 0; ie < 3; ie++)
		for (i = 0; i < 100; i++) {
			double dir[3], s, nn, nd = 0;
			int k;
			pair_random(rng, etas[ie], 1, &a, &b);
			unit_random(rng, dir);
			s = gsl_rng_uniform(rng) * 0.5 * a.half;
			for (k = 0; k < 3; k++)
				b.x[k] = a.x[k] + s * dir[k];
			if (plate_core_distance(&a, &b, NULL, NULL) > 0)
				continue;
			plate_interaction(&a, &b, 0, &I);
			nn = sqrt(I.n[0] * I.n[0] + I.n[1] * I.n[1] + I.n[2] * I.n[2]);
			for (k = 0; k < 3; k++)
				nd += I.n[k] * (a.x[k] - b.x[k]);
			ok &= I.m == 1 && I.e[0].kind == PLATE_CORE_OVERLAP && I.e[0].h > a.r + b.r - 1e-6 &&
			    fabs(nn - 1) < 1e-12 && (s == 0 || nd > 0);
		}
	CHECK(ok, "libccd fallback: intersecting cores at each eta give h >= r_i + r_j and a unit n from j to i");
	gsl_rng_free(rng);
}

/* The separating-axis shortcut of plate_interaction never drops a touching pair: on random
 * and stacked pairs whose cores are 0 to 2 (r_i + r_j) apart, a pair is told apart (m = 0) only
 * when its true core distance is at least r_i + r_j, and the bound it reports then is below
 * the true distance (rounding: 1e-12 of the size). */
static void
test_shortcut(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	int k, i, dropped = 0, bad_bound = 0, apart = 0;

	gsl_rng_set(rng, 11);
	for (k = 0; k < 3; k++)
		for (i = 0; i < 2000; i++) {
			struct plate_body a, b;
			struct plate_interaction it;
			double rr, t, d;

			body_random(rng, etas[k], (const double[3]){0, 0, 0}, &a);
			rr = 2 * a.r;
			t = 2 * rr * gsl_rng_uniform(rng);
			if (i % 2)
				pair_random(rng, etas[k], t, &a, &b);
			else
				pair_stacked(rng, etas[k], t, &a, &b);
			d = plate_core_distance(&a, &b, NULL, NULL);
			if (plate_interaction(&a, &b, 0, &it) == 0) {
				apart++;
				dropped += d < a.r + b.r - 1e-12;
				bad_bound += it.d > d + 1e-12 * (a.half + b.half + a.r);
			}
		}
	CHECK(dropped == 0 && bad_bound == 0 && apart > 1000,
	    "shortcut: no touching pair dropped (%d), no bound above the distance (%d), over %d pairs apart", dropped,
	    bad_bound, apart);
	gsl_rng_free(rng);
}

/* ---- (i) the cached narrow phase ---- */

/* b moved rigidly so that no point of its core moves by more than lim: a translation of up
 * to lim / 2 and a turn about a random axis whose corner displacement 2 sin(th / 2) half
 * sqrt 2 is up to lim / 2. */
static void
body_nudge(gsl_rng *rng, struct plate_body *b, double lim)
{
	double u[3], t = 0.5 * lim * gsl_rng_uniform(rng), arm = b->half * M_SQRT2, th, q[4], R[9], Rn[9];
	int k, i, j;

	unit_random(rng, u);
	for (k = 0; k < 3; k++)
		b->x[k] += t * u[k];
	if (arm <= 0)
		return;
	th = 2 * asin(fmin(1, 0.5 * lim * gsl_rng_uniform(rng) / (2 * arm)));
	unit_random(rng, u);
	q[0] = cos(th / 2), q[1] = sin(th / 2) * u[0], q[2] = sin(th / 2) * u[1], q[3] = sin(th / 2) * u[2];
	quat_to_matrix(q, R);
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			Rn[3 * i + j] = R[3 * i] * b->R[j] + R[3 * i + 1] * b->R[3 + j] + R[3 * i + 2] * b->R[6 + j];
	memcpy(b->R, Rn, sizeof Rn);
}

/* The same interaction to the bit: the count, and with elements the normal and every
 * element (with none, plate_interaction's d and n are not defined alike). */
static int
same_interaction(const struct plate_interaction *x, const struct plate_interaction *y)
{
	int k;

	if (x->m != y->m)
		return 0;
	if (x->m == 0)
		return 1;
	if (memcmp(x->n, y->n, sizeof x->n) || memcmp(&x->d, &y->d, sizeof x->d))
		return 0;
	for (k = 0; k < x->m; k++)
		if (memcmp(&x->e[k].h, &y->e[k].h, sizeof x->e[k].h) || memcmp(x->e[k].pi, y->e[k].pi, sizeof x->e[k].pi) ||
		    memcmp(x->e[k].pj, y->e[k].pj, sizeof x->e[k].pj) || memcmp(x->e[k].p, y->e[k].p, sizeof x->e[k].p) ||
		    x->e[k].kind != y->e[k].kind)
			return 0;
	return 1;
}

/* plate_interaction_cached gives plate_interaction's elements to the bit after any motion
 * within its margin: pairs random and near-parallel stacked (where the edge pairs and rule 3
 * matter), plates and a sphere against a plate, from apart by 1.5 margins to overlapping by
 * a tenth of r (the cores crossing too), each cache made at one state and used at 20 others
 * (each body moved by up to half the margin); and the cache word is honest: every feature
 * it leaves out is farther than r_a + r_b + margin at the state it was made. */
static void
test_cached(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	double margin = 0.1;
	long compared = 0, touching = 0, differ = 0, built_differ = 0, crossing = 0;
	int k, i, s, sphere;

	gsl_rng_set(rng, 12);
	for (k = 0; k < 3; k++)
		for (sphere = 0; sphere < 2; sphere++)
			for (i = 0; i < 600; i++) {
				struct plate_body a, b, a1, b1;
				struct plate_interaction ref, got;
				unsigned cache;
				double t;

				body_random(rng, etas[k], (const double[3]){0, 0, 0}, &a);
				/* core distance from r_a + r_b + 1.5 margin down to 0 (cores touching), and a
				 * few crossing (a tenth of the stacked pairs start at distance 0 and move) */
				t = (2 * a.r + 1.5 * margin) * gsl_rng_uniform(rng);
				if (i % 10 == 0)
					t = 0;
				if (sphere) {
					double dir[3];
					b = a;
					b.half = 0;
					unit_random(rng, dir);
					plate_place(&a, &b, dir, t);
				} else if (i % 2) {
					pair_random(rng, etas[k], t, &a, &b);
				} else {
					pair_stacked(rng, etas[k], t, &a, &b);
				}
				plate_interaction(&a, &b, 0, &ref);
				plate_interaction_cached(&a, &b, margin, &cache, 1, &got);
				built_differ += !same_interaction(&ref, &got);
				crossing += t == 0;
				for (s = 0; s < 20; s++) {
					a1 = a, b1 = b;
					body_nudge(rng, &a1, 0.5 * margin);
					body_nudge(rng, &b1, 0.5 * margin);
					plate_interaction(&a1, &b1, 0, &ref);
					plate_interaction_cached(&a1, &b1, margin, &cache, 0, &got);
					compared++;
					touching += ref.m > 0;
					differ += !same_interaction(&ref, &got);
				}
			}
	CHECK(built_differ == 0 && differ == 0 && touching > compared / 4 && crossing > 0,
	    "cached narrow phase: the same elements to the bit as plate_interaction when the cache is made (%ld differ) "
	    "and at %ld states within the margin, %ld of them touching (%ld differ)", built_differ, compared, touching,
	    differ);
	gsl_rng_free(rng);
}

int
main(void)
{
	test_cached();
	test_shortcut();
	test_core_distance();
	test_elements();
	test_symmetry();
	test_counts();
	test_sphere_limit();
	test_wall();
	test_periodic();
	test_libccd();
	test_narrow_table();
	return unit_summary();
}
