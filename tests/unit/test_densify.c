/* test_densify: densify_run's end conditions with the release of unbraced grains done both
 * ways, restarting the minimiser after each release (the default) and keeping its memory
 * (release_keep, through qs_minimizer_moved): from the same loose pack, each run ends at the
 * target stress within stress_tol, with every grain at 4 contacts or more, and at the
 * residual tolerance; releases every 50 iterations make sure both paths are taken. */
#include "qs/densify.h"
#include "unit.h"
#include "unit_pack.h"

#include <gsl/gsl_randist.h>
#include <string.h>

static void
run(const struct pack *loose, int keep)
{
	struct pack p;
	struct densify_params dp;
	struct densify_stage last;
	size_t i;
	int r;

	pack_init(&p);
	for (i = 0; i < loose->n; i++)
		pack_add_grain(&p, loose->id[i], loose->x + 3 * i, loose->r[i], loose->E[i], loose->nu[i], loose->rho[i]);
	memcpy(p.box, loose->box, sizeof p.box);
	p.wall_E = loose->wall_E, p.wall_nu = loose->wall_nu;
	densify_params_default(&dp);
	dp.stress = 1e6;
	dp.release_after = 50;
	dp.release_keep = keep;
	r = densify_run(&p, &dp, NULL, NULL, &last);
	CHECK(r == 0, "%s: densify_run ends without error or limit (%d)", keep ? "keep" : "restart", r);
	CHECK(fabs(last.sigma_c / dp.stress - 1) <= dp.stress_tol, "%s: sigma_c %.6g Pa within %.3g of the target",
	    keep ? "keep" : "restart", last.sigma_c, dp.stress_tol);
	CHECK(last.under4 == 0, "%s: no grain under 4 contacts (%zu)", keep ? "keep" : "restart", last.under4);
	CHECK(last.res_max <= dp.min.tol, "%s: the last equilibrium at the tolerance (residual %.3g)",
	    keep ? "keep" : "restart", last.res_max);
	pack_free(&p);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct pack loose;

	gsl_rng_set(rng, 5);
	random_pack(&loose, rng, 250, 1e-4, 0.5, 0.001);
	run(&loose, 0);
	run(&loose, 1);
	pack_free(&loose);
	gsl_rng_free(rng);
	return unit_summary();
}
