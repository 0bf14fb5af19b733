/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_dem: packgen's sphere DEM (lib/dem/dem.c): a small pack comes to rest at the target
 * overlap with every grain inside the box and no pair overlapping by more than the servo
 * allows; the pair forces in lanes give the bytes of one pair at a time, on one thread and on
 * two; a time step far beyond the stability limit is caught as a divergence (one clear error,
 * well before the step limit) instead of stepping NaNs to max_steps.  Blocks of 16 grains
 * (QUSGM_PAR_BLOCK, base/par.h) put the 300 grains on the threads' path.  The sanitizer build
 * runs 150 grains (ten blocks, five a thread): its four runs to rest took 45 s of CPU at 300;
 * the bounds below hold for a loose pack of either size. */
#include "unit.h"
#include "dem/dem.h"
#include "base/msg.h"
#include "base/par.h"
#include "pack/pack.h"

#include <gsl/gsl_rng.h>
#include <stdlib.h>
#include <string.h>

#define NGRAINS (UNIT_SANITIZED ? 150 : 300)

/* NGRAINS grains with radii uniform in [0.7, 1.3] mm (the default psd's spread), glass. */
static void
grains(struct pack *p, gsl_rng *rng)
{
	size_t k;

	pack_init(p);
	pack_reserve(p, NGRAINS);
	for (k = 0; k < NGRAINS; k++) {
		double x[3] = {0, 0, 0};
		pack_add_grain(p, (long)k + 1, x, 1e-3 * (0.7 + 0.6 * gsl_rng_uniform(rng)), 7e10, 0.2, 2500);
	}
}

static void
test_rest(void)
{
	struct dem_params dp;
	struct dem_status st;
	struct pack p;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	size_t i, outside = 0;
	int a, rc;

	gsl_rng_set(rng, 3);
	grains(&p, rng);
	dem_params_default(&dp);
	rc = dem_loose_pack(&p, &dp, rng, NULL, NULL, &st);
	CHECK(rc == 0 && st.at_rest, "dem: %d grains come to rest (%s; %ld steps)", NGRAINS, rc ? msg_geterr() : "ok",
	    st.step);
	for (i = 0; i < p.n; i++)
		for (a = 0; a < 3; a++)
			outside += p.x[3 * i + a] < p.box[a] || p.x[3 * i + a] > p.box[a + 3];
	CHECK(outside == 0, "dem: every centre inside the box (%zu outside)", outside);
	/* the servo holds the mean overlap near 1e-4 of a radius; ten times the largest seen at
	 * 2740 to 1e5 grains (5e-4 to 8e-4, bench/packgen-scaling.md) would be a broken servo */
	CHECK(st.max_overlap > 0 && st.max_overlap < 1e-2, "dem: largest overlap/r %.3g in (0, 1e-2)", st.max_overlap);
	CHECK(st.coordination > 1 && st.coordination < 6, "dem: a loose pack's coordination %.3g in (1, 6)", st.coordination);
	pack_free(&p);
	gsl_rng_free(rng);
}

/* The pair forces two at a time in lanes (dem_params.pair_lanes, the default) against one at a
 * time, and in lanes on two threads (where the pairs that cross to the other thread's grains
 * come from records, and the waiting pair is added before them): a DEM run amplifies a
 * difference in the last bit of one force into different positions within a few hundred
 * steps, so the same packs and step counts say the same arithmetic in the same order. */
static void
test_lanes(void)
{
	static const char *const what[3] = {"lanes", "one pair at a time", "lanes on 2 threads"};
	struct pack p[3];
	struct dem_status st[3];
	int k, rc[3];

	for (k = 0; k < 3; k++) {
		struct dem_params dp;
		gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);

		gsl_rng_set(rng, 5);
		grains(&p[k], rng);
		dem_params_default(&dp);
		dp.pair_lanes = k != 1;
		par_set_threads(k == 2 ? 2 : 1);
		rc[k] = dem_loose_pack(&p[k], &dp, rng, NULL, NULL, &st[k]);
		gsl_rng_free(rng);
	}
	par_set_threads(0);
	for (k = 1; k < 3; k++)
		CHECK(rc[0] == 0 && rc[k] == 0 && st[0].step == st[k].step && p[0].n == p[k].n &&
		    memcmp(p[0].x, p[k].x, 3 * p[0].n * sizeof *p[0].x) == 0 &&
		    memcmp(p[0].box, p[k].box, sizeof p[0].box) == 0,
		    "dem: %s gives the bytes of %s (%ld and %ld steps)", what[k], what[0], st[k].step, st[0].step);
	for (k = 0; k < 3; k++)
		pack_free(&p[k]);
}

static void
test_divergence(void)
{
	struct dem_params dp;
	struct dem_status st;
	struct pack p;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	int rc;

	gsl_rng_set(rng, 3);
	grains(&p, rng);
	dem_params_default(&dp);
	dp.dt_safety = 5;	/* explicit integration of a spring is unstable beyond 2 sqrt(m/k) */
	rc = dem_loose_pack(&p, &dp, rng, NULL, NULL, &st);
	CHECK(rc != 0 && strstr(msg_geterr(), "diverged") != NULL, "dem: a step of 5 sqrt(m/k) diverges with a clear error (%s)",
	    rc ? msg_geterr() : "came to rest");
	CHECK(rc != 0 && st.step < dp.max_steps / 10, "dem: the divergence stops the run early (step %ld of %ld)", st.step,
	    dp.max_steps);
	pack_free(&p);
	gsl_rng_free(rng);
}

int
main(void)
{
	setenv("QUSGM_PAR_BLOCK", "16", 1);	/* before any use of base/par.h */
	test_rest();
	test_lanes();
	test_divergence();
	return unit_summary();
}
