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

/* The options, and what their text parses into; the table below points into it. */
static struct opts {
	long ngrains, seed, max_steps;
	const char *psd_spec, *material_name, *aspect_spec;
	double wall_E, wall_nu, mu, wall_mu;
	double dem_mu, overlap, damping, phi0, rest_tol;
	struct psd psd;
	struct material mat;
	double aspect[3];
} o = {
	.ngrains = 2740, .seed = 1, .max_steps = 2000000,
	.psd_spec = "uniform:7e-5,1.3e-4", .material_name = "glass", .aspect_spec = "1,1,1",
	.wall_E = 0, .wall_nu = 0.495, .mu = 0.3, .wall_mu = -1,
	.dem_mu = 0.5, .overlap = 1e-4, .damping = 0.7, .phi0 = 0.3, .rest_tol = 2e-2,
};

static struct cli_opt opt_table[] = {
	{"grains", 'n', CLI_LONG, &o.ngrains, "N", "number of grains", NULL},
	{"seed", 's', CLI_LONG, &o.seed, "S", "seed of the random generator (GSL mt19937)", NULL},
	{"psd", 0, CLI_STRING, &o.psd_spec, "SPEC", "radius distribution: uniform:RMIN,RMAX | lognormal:MEDIAN,SIGMA[,RMIN,RMAX] | table:FILE", "m"},
	{"material", 'm', CLI_STRING, &o.material_name, "NAME", "grain material: glass, quartz, hydrate, or a preset file", NULL},
	{"aspect", 0, CLI_STRING, &o.aspect_spec, "AX,AY,AZ", "box side ratios", NULL},
	{"wall-E", 0, CLI_DOUBLE, &o.wall_E, "PA", "Young's modulus of the walls (0: 100 x the material's)", "Pa"},
	{"wall-nu", 0, CLI_DOUBLE, &o.wall_nu, "NU", "Poisson ratio of the walls", NULL},
	{"friction", 0, CLI_DOUBLE, &o.mu, "MU", "grain-grain friction coefficient recorded in the pack", NULL},
	{"wall-friction", 0, CLI_DOUBLE, &o.wall_mu, "MU", "grain-wall friction coefficient (negative: same as --friction)", NULL},
	{"dem-friction", 0, CLI_DOUBLE, &o.dem_mu, "MU", "friction during the DEM compaction (higher: looser pack)", NULL},
	{"overlap", 0, CLI_DOUBLE, &o.overlap, "RATIO", "target mean overlap / radius when the DEM pack is at rest", NULL},
	{"damping", 0, CLI_DOUBLE, &o.damping, "ALPHA", "Cundall local damping of the DEM (0..1)", NULL},
	{"phi0", 0, CLI_DOUBLE, &o.phi0, "PHI", "packing fraction of the initial random placement", NULL},
	{"rest-tol", 0, CLI_DOUBLE, &o.rest_tol, "RATIO", "at rest when mean |net force| / mean contact force is below this", NULL},
	{"max-steps", 0, CLI_LONG, &o.max_steps, "N", "DEM step limit", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"packgen", "[options]",
	"Make a loose random pack of polydisperse elastic spheres in a box by DEM compaction (writes a qusgm pack).",
	opt_table, 0,
};

static void
progress(const struct dem_status *s, void *ctx)
{
	(void)ctx;
	cli_progress("stage %d step %ld  packing %.4f  stress/target %.3g  coordination %.2f  unbalanced %.2e",
	    s->stage, s->step, s->phi, s->p_ratio, s->coordination, s->unbalanced);
}

static void
parse_args(int argc, char **argv, struct cli_state *st)
{
	char extra[16];

	cli_parse(&tool, argc, argv, st);
	if (o.ngrains < 1 || o.ngrains > 100000000L)
		cli_usage_error("--grains: %ld is not in [1, 1e8]", o.ngrains);
	if (o.seed < 0)
		cli_usage_error("--seed: must be non-negative");
	if (psd_parse(o.psd_spec, &o.psd))
		cli_usage_error("%s", msg_geterr());
	if (material_lookup(o.material_name, &o.mat))
		cli_usage_error("--material: %s", msg_geterr());
	if (sscanf(o.aspect_spec, "%lf,%lf,%lf%15s", &o.aspect[0], &o.aspect[1], &o.aspect[2], extra) != 3 ||
	    !(o.aspect[0] > 0 && o.aspect[1] > 0 && o.aspect[2] > 0) || !isfinite(o.aspect[0] * o.aspect[1] * o.aspect[2]))
		cli_usage_error("--aspect: expected three positive numbers AX,AY,AZ, got '%s'", o.aspect_spec);
	if (o.wall_E < 0)
		cli_usage_error("--wall-E: must be positive (or 0 for 100 x E)");
	if (!(o.wall_nu > -1 && o.wall_nu < 0.5))
		cli_usage_error("--wall-nu: must be in (-1, 0.5)");
	if (o.mu < 0)
		cli_usage_error("--friction: must be non-negative");
	if (o.dem_mu < 0)
		cli_usage_error("--dem-friction: must be non-negative");
	if (!(o.overlap > 0 && o.overlap <= 1e-2))
		cli_usage_error("--overlap: must be in (0, 0.01]");
	if (!(o.damping >= 0 && o.damping < 1))
		cli_usage_error("--damping: must be in [0, 1)");
	if (!(o.phi0 > 0 && o.phi0 <= 0.35))
		cli_usage_error("--phi0: must be in (0, 0.35]");
	if (!(o.rest_tol > 0))
		cli_usage_error("--rest-tol: must be positive");
	if (o.max_steps < 1)
		cli_usage_error("--max-steps: must be positive");
	cli_usage_done();
	if (o.wall_E == 0)
		o.wall_E = 100 * o.mat.E;
	if (o.wall_mu < 0)
		o.wall_mu = o.mu;
}

/* The grains' radii and elastic constants, drawn in id order so that a seed fixes the pack;
 * the DEM places them. */
static void
draw_grains(struct pack *p, gsl_rng *rng)
{
	long k;

	pack_init(p);
	if (pack_reserve(p, (size_t)o.ngrains))
		msg_die_err(EXIT_DATA);
	for (k = 0; k < o.ngrains; k++) {
		double x[3] = {0, 0, 0}, r = psd_draw(&o.psd, rng), E, nu;
		material_sample(&o.mat, rng, &E, &nu);
		pack_add_grain(p, k + 1, x, r, E, nu, o.mat.rho);
	}
}

static void
compact(struct pack *p, gsl_rng *rng)
{
	struct dem_params dp;
	struct dem_status ds;

	dem_params_default(&dp);
	dp.mu = o.dem_mu;
	dp.overlap = o.overlap;
	dp.damping = o.damping;
	dp.phi0 = o.phi0;
	dp.rest_tol = o.rest_tol;
	dp.max_steps = o.max_steps;
	memcpy(dp.aspect, o.aspect, sizeof o.aspect);
	if (dem_loose_pack(p, &dp, rng, progress, NULL, &ds)) {
		/* name the option (a few grains fill a box of a few diameters: they need a lower one) */
		if (strncmp(msg_geterr(), "cannot place grain", 18) == 0)
			msg_die(EXIT_DATA, "%s (--phi0, now %g)", msg_geterr(), o.phi0);
		msg_die_err(EXIT_DATA);
	}
	cli_progress_end();
	msg_info(1, "at rest after %ld steps: packing %.4f, coordination %.3f, largest overlap/r %.2e",
	    ds.step, ds.phi, ds.coordination, ds.max_overlap);
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct pack p;
	gsl_rng *rng;

	msg_init(argv[0]);
	parse_args(argc, argv, &st);
	rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, (unsigned long)o.seed);
	draw_grains(&p, rng);
	compact(&p, rng);
	p.wall_E = o.wall_E;
	p.wall_nu = o.wall_nu;
	p.mu = o.mu;
	p.wall_mu = o.wall_mu;
	pack_set_meta(&p, "material", o.mat.name);
	if (pack_validate(&p) || pack_write_tool(&p, &tool, &st))
		msg_die_err(EXIT_DATA);
	pack_free(&p);
	psd_free(&o.psd);
	gsl_rng_free(rng);
	return 0;
}
