/* SPDX-License-Identifier: GPL-3.0-or-later */
/* platecontact: the cost of the spheroplate element contacts (contact/plate.h) against libccd.
 *
 * usage: platecontact [PAIRS]
 *
 * At platyness 0.14, 0.5 and 0.8 (outer radius 1, SHAPE_R_EDGE): PAIRS (default 2000) pairs
 * of random orientations (gsl_rng_mt19937, seed 1), b's centre along a random direction where
 * the cores are r_i + r_j - delta apart, delta uniform in [0, 0.02): the near contacts of a
 * dense pack.  Each method then sweeps the pairs until 0.4 s have passed
 * (CLOCK_MONOTONIC): plate_interaction (gap 0), plate_core_distance, and libccd's
 * ccdMPRPenetration and ccdGJKPenetration (GJK + EPA) on the same spheroplates, with libccd's
 * default tolerances (1e-4, absolute: here 1e-4 R) and with tolerances of 1e-8 R (EPA stops
 * early on the rounded shapes under the default and underestimates most depths).  One TSV row
 * per method and platyness: microseconds per call, element contacts per interaction
 * (plate_interaction), and for libccd the fraction of pairs whose depth is off r_i + r_j - d
 * by more than 10 %. */
#include "base/quat.h"
#include "contact/plate.h"
#include "pack/shape.h"

#include <ccd/ccd.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include "../unit/plate_place.h"

enum { M_PLATE, M_DIST, M_MPR, M_GJK, M_MPR_TIGHT, M_GJK_TIGHT, NMETHODS };

static const char *const method_names[NMETHODS] = {"plate_interaction", "plate_core_distance",
    "ccdMPRPenetration/default", "ccdGJKPenetration/default", "ccdMPRPenetration/1e-8", "ccdGJKPenetration/1e-8"};

struct bpair {
	struct plate_body a, b;
	double h;	/* r_i + r_j - d */
};

static void
body_random(gsl_rng *rng, double eta, struct plate_body *b)
{
	double q[4];

	quat_from_uniform(gsl_rng_uniform(rng), gsl_rng_uniform(rng), gsl_rng_uniform(rng), q);
	quat_to_matrix(q, b->R);
	memset(b->x, 0, sizeof b->x);
	b->half = shape_plate_side(1, eta, SHAPE_R_EDGE) / 2;
	b->r = shape_spheroradius(1, eta);
}

static void
pairs_make(gsl_rng *rng, double eta, struct bpair *p, int n)
{
	int i;

	for (i = 0; i < n; i++) {
		double z = 2 * gsl_rng_uniform(rng) - 1, ph = 2 * M_PI * gsl_rng_uniform(rng), s = sqrt(1 - z * z);
		double dir[3] = {s * cos(ph), s * sin(ph), z};
		body_random(rng, eta, &p[i].a);
		body_random(rng, eta, &p[i].b);
		plate_place(&p[i].a, &p[i].b, dir, p[i].a.r + p[i].b.r - 0.02 * gsl_rng_uniform(rng));
		p[i].h = p[i].a.r + p[i].b.r - plate_core_distance(&p[i].a, &p[i].b, NULL, NULL);
	}
}

static void
support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *v)
{
	const struct plate_body *b = obj;
	double du = 0, dv = 0, n = sqrt(dir->v[0] * dir->v[0] + dir->v[1] * dir->v[1] + dir->v[2] * dir->v[2]);
	int k;

	for (k = 0; k < 3; k++)
		du += dir->v[k] * b->R[3 * k], dv += dir->v[k] * b->R[3 * k + 1];
	du = du >= 0 ? b->half : -b->half;
	dv = dv >= 0 ? b->half : -b->half;
	for (k = 0; k < 3; k++)
		v->v[k] = b->x[k] + du * b->R[3 * k] + dv * b->R[3 * k + 1] + (n > 0 ? b->r * dir->v[k] / n : 0);
}

static void
centre(const void *obj, ccd_vec3_t *c)
{
	memcpy(c->v, ((const struct plate_body *)obj)->x, sizeof c->v);
}

/* One call of method m on pair p: the depth (or the element count for plate_interaction). */
static double
call(int m, const struct bpair *p, const ccd_t ccd[2])
{
	struct plate_interaction I;
	ccd_vec3_t dir, pos;
	double depth = -1;

	switch (m) {
	case M_PLATE:
		return plate_interaction(&p->a, &p->b, 0, &I);
	case M_DIST:
		return plate_core_distance(&p->a, &p->b, NULL, NULL);
	case M_MPR:
	case M_MPR_TIGHT:
		return ccdMPRPenetration(&p->a, &p->b, &ccd[m == M_MPR_TIGHT], &depth, &dir, &pos) == 0 ? depth : -1;
	default:
		return ccdGJKPenetration(&p->a, &p->b, &ccd[m == M_GJK_TIGHT], &depth, &dir, &pos) == 0 ? depth : -1;
	}
}

static volatile double sink;	/* keeps the timed calls from being optimised away */

static void
run(int m, double eta, const struct bpair *p, int n, const ccd_t ccd[2])
{
	double t0, dt, first = 0, off = 0;
	long calls = 0;
	int i;

	for (i = 0; i < n; i++) {
		double v = call(m, &p[i], ccd);
		first += v;
		off += !(fabs(v - p[i].h) <= 0.1 * p[i].h);
	}
	t0 = bench_now();
	do {
		for (i = 0; i < n; i++)
			sink += call(m, &p[i], ccd);
		calls += n;
	} while ((dt = bench_now() - t0) < 0.4);
	printf("%s\t%.2f\t%d\t%.3f\t", method_names[m], eta, n, 1e6 * dt / calls);
	if (m == M_PLATE)
		printf("%.3f\t-\n", first / n);
	else if (m == M_DIST)
		printf("-\t-\n");
	else
		printf("-\t%.3f\n", off / n);
}

int
main(int argc, char **argv)
{
	static const double etas[3] = {0.14, 0.5, 0.8};
	int n = argc > 1 ? atoi(argv[1]) : 2000, ie, m;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct bpair *p = malloc((size_t)(n > 0 ? n : 1) * sizeof *p);
	ccd_t ccd[2];

	if (!rng || !p || n <= 0) {
		fprintf(stderr, "platecontact: usage: platecontact [PAIRS > 0]\n");
		return 2;
	}
	gsl_rng_set(rng, 1);
	for (m = 0; m < 2; m++) {
		CCD_INIT(&ccd[m]);
		ccd[m].support1 = ccd[m].support2 = support;
		ccd[m].center1 = ccd[m].center2 = centre;
	}
	ccd[1].mpr_tolerance = ccd[1].epa_tolerance = 1e-8;
	ccd[1].dist_tolerance = 1e-10;
	printf("# method\teta\tpairs\tus_per_call\telements_per_interaction\tdepth_off_10pct\n");
	for (ie = 0; ie < 3; ie++) {
		pairs_make(rng, etas[ie], p, n);
		for (m = 0; m < NMETHODS; m++)
			run(m, etas[ie], p, n, ccd);
		fflush(stdout);
	}
	free(p);
	gsl_rng_free(rng);
	return 0;
}
