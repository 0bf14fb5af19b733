/* packgen: a loose, irregular pack of polydisperse elastic spheres in a box. */
#include "base/cli.h"
#include "dem/dem.h"
#include "pack/material.h"
#include "base/msg.h"
#include "pack/pack.h"
#include "pack/packio.h"
#include "pack/psd.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static long ngrains = 2740, seed = 1, max_steps = 2000000;
static const char *psd_spec = "uniform:7e-5,1.3e-4", *material_name = "glass", *aspect_spec = "1,1,1";
static double wall_E = 0, wall_nu = 0.495, mu = 0.3, wall_mu = -1;
static double dem_mu = 0.5, overlap = 1e-4, damping = 0.7, phi0 = 0.3, rest_tol = 2e-2;

static struct cli_opt opts[] = {
	{"grains", 'n', CLI_LONG, &ngrains, "N", "number of grains", NULL},
	{"seed", 's', CLI_LONG, &seed, "S", "seed of the random generator (GSL mt19937)", NULL},
	{"psd", 0, CLI_STRING, &psd_spec, "SPEC", "radius distribution: uniform:RMIN,RMAX | lognormal:MEDIAN,SIGMA[,RMIN,RMAX] | table:FILE", "m"},
	{"material", 'm', CLI_STRING, &material_name, "NAME", "grain material: glass, quartz, hydrate, or a preset file", NULL},
	{"aspect", 0, CLI_STRING, &aspect_spec, "AX,AY,AZ", "box side ratios", NULL},
	{"wall-E", 0, CLI_DOUBLE, &wall_E, "PA", "Young's modulus of the walls (0: 100 x the material's)", "Pa"},
	{"wall-nu", 0, CLI_DOUBLE, &wall_nu, "NU", "Poisson ratio of the walls", NULL},
	{"friction", 0, CLI_DOUBLE, &mu, "MU", "grain-grain friction coefficient recorded in the pack", NULL},
	{"wall-friction", 0, CLI_DOUBLE, &wall_mu, "MU", "grain-wall friction coefficient (negative: same as --friction)", NULL},
	{"dem-friction", 0, CLI_DOUBLE, &dem_mu, "MU", "friction during the DEM compaction (higher: looser pack)", NULL},
	{"overlap", 0, CLI_DOUBLE, &overlap, "RATIO", "target mean overlap / radius when the DEM pack is at rest", NULL},
	{"damping", 0, CLI_DOUBLE, &damping, "ALPHA", "Cundall local damping of the DEM (0..1)", NULL},
	{"phi0", 0, CLI_DOUBLE, &phi0, "PHI", "packing fraction of the initial random placement", NULL},
	{"rest-tol", 0, CLI_DOUBLE, &rest_tol, "RATIO", "at rest when mean |net force| / mean contact force is below this", NULL},
	{"max-steps", 0, CLI_LONG, &max_steps, "N", "DEM step limit", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"packgen", "[options]",
	"Make a loose random pack of polydisperse elastic spheres in a box by DEM compaction (writes a qusgm pack).",
	opts, 0,
};

static void
progress(const struct dem_status *s, void *ctx)
{
	(void)ctx;
	cli_progress("stage %d step %ld  packing %.4f  stress/target %.3g  coordination %.2f  unbalanced %.2e",
	    s->stage, s->step, s->phi, s->p_ratio, s->coordination, s->unbalanced);
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct material mat;
	struct psd psd;
	struct dem_params dp;
	struct dem_status ds;
	struct pack p;
	gsl_rng *rng;
	double aspect[3];
	char *hist, extra[16];
	long k;

	msg_init(argv[0]);
	cli_parse(&tool, argc, argv, &st);
	if (ngrains < 1 || ngrains > 100000000L)
		cli_usage_error("--grains: %ld is not in [1, 1e8]", ngrains);
	if (seed < 0)
		cli_usage_error("--seed: must be non-negative");
	if (psd_parse(psd_spec, &psd))
		cli_usage_error("%s", msg_geterr());
	if (material_lookup(material_name, &mat))
		cli_usage_error("--material: %s", msg_geterr());
	if (sscanf(aspect_spec, "%lf,%lf,%lf%15s", &aspect[0], &aspect[1], &aspect[2], extra) != 3 ||
	    !(aspect[0] > 0 && aspect[1] > 0 && aspect[2] > 0) || !isfinite(aspect[0] * aspect[1] * aspect[2]))
		cli_usage_error("--aspect: expected three positive numbers AX,AY,AZ, got '%s'", aspect_spec);
	if (wall_E < 0)
		cli_usage_error("--wall-E: must be positive (or 0 for 100 x E)");
	if (!(wall_nu > -1 && wall_nu < 0.5))
		cli_usage_error("--wall-nu: must be in (-1, 0.5)");
	if (mu < 0)
		cli_usage_error("--friction: must be non-negative");
	if (dem_mu < 0)
		cli_usage_error("--dem-friction: must be non-negative");
	if (!(overlap > 0 && overlap <= 1e-2))
		cli_usage_error("--overlap: must be in (0, 0.01]");
	if (!(damping >= 0 && damping < 1))
		cli_usage_error("--damping: must be in [0, 1)");
	if (!(phi0 > 0 && phi0 <= 0.35))
		cli_usage_error("--phi0: must be in (0, 0.35]");
	if (!(rest_tol > 0))
		cli_usage_error("--rest-tol: must be positive");
	if (max_steps < 1)
		cli_usage_error("--max-steps: must be positive");
	cli_usage_done();
	if (wall_E == 0)
		wall_E = 100 * mat.E;
	if (wall_mu < 0)
		wall_mu = mu;

	rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, (unsigned long)seed);
	pack_init(&p);
	if (pack_reserve(&p, (size_t)ngrains))
		msg_die_err(EXIT_DATA);
	for (k = 0; k < ngrains; k++) {
		double x[3] = {0, 0, 0}, r = psd_draw(&psd, rng), E, nu;
		material_sample(&mat, rng, &E, &nu);
		pack_add_grain(&p, k + 1, x, r, E, nu, mat.rho);
	}
	dem_params_default(&dp);
	dp.mu = dem_mu;
	dp.overlap = overlap;
	dp.damping = damping;
	dp.phi0 = phi0;
	dp.rest_tol = rest_tol;
	dp.max_steps = max_steps;
	memcpy(dp.aspect, aspect, sizeof aspect);
	if (dem_loose_pack(&p, &dp, rng, progress, NULL, &ds))
		msg_die_err(EXIT_DATA);
	cli_progress_end();
	msg_info(1, "at rest after %ld steps: packing %.4f, coordination %.3f, largest overlap/r %.2e",
	    ds.step, ds.phi, ds.coordination, ds.max_overlap);
	p.wall_E = wall_E;
	p.wall_nu = wall_nu;
	p.mu = mu;
	p.wall_mu = wall_mu;
	pack_set_meta(&p, "material", mat.name);
	hist = cli_history_line(&tool, &st);
	pack_add_history(&p, hist);
	free(hist);
	if (pack_validate(&p) || pack_write_path(&p, st.output))
		msg_die_err(EXIT_DATA);
	pack_free(&p);
	psd_free(&psd);
	gsl_rng_free(rng);
	return 0;
}
