/* SPDX-License-Identifier: GPL-3.0-or-later */
/* packgen: a loose, irregular pack of polydisperse elastic spheres in a box, or a static pack
 * of monodisperse spheroplates (--shape spheroplate: the platy-particle paper's samples). */
#include "base/cli.h"
#include "base/fileio.h"
#include "dem/dem.h"
#include "dem/platepack.h"
#include "pack/hydrate.h"
#include "pack/material.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/pack.h"
#include "pack/packio.h"
#include "pack/psd.h"
#include "pack/shape.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The options, and what their text parses into; the table below points into it. */
static struct opts {
	long ngrains, seed, max_steps;
	const char *psd_spec, *material_name, *aspect_spec;
	const char *shape_name, *plate_radius_name, *periodic_spec;
	double wall_E, wall_nu, mu, wall_mu;
	double dem_mu, dem_wall_mu, jitter, overlap, damping, phi0, rest_tol;
	double eta, spheroradius, kn, kt, restitution, sigma0, kappa, density, hydrate_volume;
	struct psd psd;
	struct material mat, hydrate;
	double aspect[3];
	int plates, periodic[3];
	enum shape_radius conv;
} o = {
	.ngrains = 2740, .seed = 1, .max_steps = 2000000,
	.psd_spec = "uniform:7e-5,1.3e-4", .material_name = "glass", .aspect_spec = "1,1,1",
	.shape_name = "sphere", .plate_radius_name = "edge", .periodic_spec = "none",
	.wall_E = 0, .wall_nu = 0.495, .mu = NAN, .wall_mu = -1,
	.dem_mu = NAN, .dem_wall_mu = NAN, .jitter = NAN, .overlap = 1e-4, .damping = NAN, .phi0 = 0.3, .rest_tol = NAN,
	.eta = 0.5, .spheroradius = 3e-8, .kn = 1.5e3, .kt = 1.5e3, .restitution = 0.6, .sigma0 = NAN, .kappa = NAN,
	.density = NAN, .hydrate_volume = 0,
};

static struct cli_opt opt_table[] = {
	{"grains", 'n', CLI_LONG, &o.ngrains, "N", "number of grains", NULL},
	{"seed", 's', CLI_LONG, &o.seed, "S", "seed of the random generator (GSL mt19937)", NULL},
	{"psd", 0, CLI_STRING, &o.psd_spec, "SPEC", "radius distribution: uniform:RMIN,RMAX | lognormal:MEDIAN,SIGMA[,RMIN,RMAX] | table:FILE", "m"},
	{"material", 'm', CLI_STRING, &o.material_name, "NAME", "grain material: glass, quartz, hydrate, or a preset file", NULL},
	{"hydrate-volume", 0, CLI_DOUBLE, &o.hydrate_volume, "F", "spheres: make the smallest grains hydrate (phase column; the hydrate preset's E, nu, rho) until they hold the fraction F of the grain volume, in [0, 1); 0: none, no phase column", NULL},
	{"aspect", 0, CLI_STRING, &o.aspect_spec, "AX,AY,AZ", "box side ratios", NULL},
	{"wall-E", 0, CLI_DOUBLE, &o.wall_E, "PA", "Young's modulus of the walls (0: 100 x the material's)", "Pa"},
	{"wall-nu", 0, CLI_DOUBLE, &o.wall_nu, "NU", "Poisson ratio of the walls", NULL},
	{"friction", 0, CLI_DOUBLE, &o.mu, "MU", "grain-grain friction coefficient recorded in the pack (default: 0.3 spheres, 0.58 spheroplates)", NULL},
	{"wall-friction", 0, CLI_DOUBLE, &o.wall_mu, "MU", "grain-wall friction coefficient (negative: same as --friction)", NULL},
	{"dem-friction", 0, CLI_DOUBLE, &o.dem_mu, "MU", "friction during the DEM compaction, higher: looser pack (default: 0.5 spheres, 0.58 spheroplates)", NULL},
	{"dem-wall-friction", 0, CLI_DOUBLE, &o.dem_wall_mu, "MU", "grain-wall friction during the compaction of spheroplates (default 0: frictionless walls, so the pack's own stress is the isotropic target; spheres use --dem-friction)", NULL},
	{"overlap", 0, CLI_DOUBLE, &o.overlap, "RATIO", "spheres: target mean overlap / radius when the DEM pack is at rest", NULL},
	{"damping", 0, CLI_DOUBLE, &o.damping, "ALPHA", "Cundall local damping of the DEM, 0..1 (default: 0.7 spheres, 0.3 spheroplates)", NULL},
	{"phi0", 0, CLI_DOUBLE, &o.phi0, "PHI", "spheres: packing fraction of the initial random placement", NULL},
	{"rest-tol", 0, CLI_DOUBLE, &o.rest_tol, "RATIO", "at rest when mean |net force| / mean contact force is below this (default: 0.02 spheres, 0.001 spheroplates)", NULL},
	{"shape", 0, CLI_STRING, &o.shape_name, "SHAPE", "grain shape: sphere | spheroplate", NULL},
	{"jitter", 0, CLI_DOUBLE, &o.jitter, "F", "spheroplates: move each grain off its grid node by up to F of the room its cell leaves, in [0, 1] (default: 1 for spheres, --platyness 0, where turning does nothing; 0 for plates, the paper's nodes)", NULL},
	{"platyness", 0, CLI_DOUBLE, &o.eta, "ETA", "spheroplates: platyness (R - r)/R in [0, 1); 0 makes spheres by the plate engine", NULL},
	{"spheroradius", 0, CLI_DOUBLE, &o.spheroradius, "R", "spheroplates: spheroradius r", "m"},
	{"plate-radius", 0, CLI_STRING, &o.plate_radius_name, "CONV", "spheroplates: the outer radius R reaches the core's edge (side 2(R-r)) or corner (sqrt2 (R-r))", NULL},
	{"kn", 0, CLI_DOUBLE, &o.kn, "K", "spheroplates: normal contact stiffness", "N/m"},
	{"kt", 0, CLI_DOUBLE, &o.kt, "K", "spheroplates: tangential contact stiffness", "N/m"},
	{"restitution", 0, CLI_DOUBLE, &o.restitution, "E", "spheroplates: restitution coefficient of a binary collision, [0.21, 1]", NULL},
	{"stress", 0, CLI_DOUBLE, &o.sigma0, "PA", "spheroplates: isotropic compaction stress sigma0 (default: kappa = kn/(sigma0 r) = 1e4)", "Pa"},
	{"kappa", 0, CLI_DOUBLE, &o.kappa, "K", "spheroplates: ... or the stiffness number kappa = kn/(sigma0 r), r the spheroradius", NULL},
	{"density", 0, CLI_DOUBLE, &o.density, "RHO", "grain density (default: the material's for spheres, 2700 for spheroplates)", "kg/m^3"},
	{"periodic", 0, CLI_STRING, &o.periodic_spec, "AXES", "spheroplates: after compaction, replace the walls of these axes (e.g. xz) by periodic boundaries, or none", NULL},
	{"max-steps", 0, CLI_LONG, &o.max_steps, "N", "DEM step limit", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"packgen", "[options]",
	"Make a loose random pack of polydisperse elastic spheres in a box by DEM compaction, or a static pack of spheroplates (writes a qusgm pack).",
	opt_table, 0,
};

/* The share of the rest criterion reached in a stage: the unbalanced force's way, on a log
 * scale, from the stage's first report down to --rest-tol. */
static void
rest_frac(int stage, double unbalanced)
{
	static int st;
	static double first;

	if (stage != st || !(first > 0 && isfinite(first))) {	/* no contacts yet: inf */
		st = stage;
		first = unbalanced;
		cli_progress_frac(NAN);
	}
	if (unbalanced > 0 && first > o.rest_tol)
		cli_progress_frac(log(first / unbalanced) / log(first / o.rest_tol));
}

static void
progress(const struct dem_status *s, void *ctx)
{
	(void)ctx;
	cli_progress_stage("stage %d", s->stage);
	rest_frac(s->stage, s->unbalanced);
	cli_progress("stage %d step %ld  packing %.4f  stress/target %.3g  coordination %.2f  unbalanced %.2e",
	    s->stage, s->step, s->phi, s->p_ratio, s->coordination, s->unbalanced);
}

static void
plate_progress(const struct platepack_status *s, void *ctx)
{
	(void)ctx;
	cli_progress_stage("stage %d", s->stage);
	rest_frac(s->stage, s->unbalanced);
	cli_progress("stage %d step %ld  packing %.4f  stress/target %.3g  interactions/grain %.2f  elements/interaction %.2f  unbalanced %.2e",
	    s->stage, s->step, s->phi, s->p_ratio, s->z, s->elements, s->unbalanced);
}

/* The per-shape defaults of the options that have two (NAN: not given). */
static void
shape_defaults(void)
{
	if (isnan(o.mu))
		o.mu = o.plates ? 0.58 : 0.3;
	if (isnan(o.dem_mu))
		o.dem_mu = o.plates ? 0.58 : 0.5;
	if (isnan(o.jitter))
		o.jitter = o.plates && o.eta == 0 ? 1 : 0;
	if (isnan(o.dem_wall_mu))
		o.dem_wall_mu = o.plates ? 0 : o.dem_mu;
	if (isnan(o.damping))
		o.damping = o.plates ? 0.3 : 0.7;
	if (isnan(o.rest_tol))
		o.rest_tol = o.plates ? 1e-3 : 2e-2;
	if (isnan(o.density))
		o.density = o.plates ? 2700 : o.mat.rho;
	if (isnan(o.sigma0))
		o.sigma0 = o.kn / ((isnan(o.kappa) ? 1e4 : o.kappa) * o.spheroradius);
	o.kappa = NAN;	/* recorded as the --stress it gave (and meta kappa): the resolved options, given back, repeat the run */
}

/* --periodic: 'none' or a set of axis letters, not all three (the walls of one axis load the
 * pack). */
static void
parse_periodic(void)
{
	const char *c;

	if (strcmp(o.periodic_spec, "none") == 0)
		return;
	for (c = o.periodic_spec; *c; c++) {
		int a = *c == 'x' ? 0 : *c == 'y' ? 1 : *c == 'z' ? 2 : -1;
		if (a < 0 || o.periodic[a]) {	/* cli_usage_error reports and returns */
			cli_usage_error("--periodic: expected 'none' or distinct axes among x, y, z (e.g. xz), got '%s'",
			    o.periodic_spec);
			return;
		}
		o.periodic[a] = 1;
	}
	if (o.periodic[0] && o.periodic[1] && o.periodic[2])
		cli_usage_error("--periodic: one axis must keep its walls, which load the pack");
	if (!*o.periodic_spec)
		cli_usage_error("--periodic: expected 'none' or axes among x, y, z");
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
	    !(o.aspect[0] > 0 && o.aspect[1] > 0 && o.aspect[2] > 0) || !isnormal(o.aspect[0] * o.aspect[1] * o.aspect[2]))
		cli_usage_error("--aspect: expected three positive numbers AX,AY,AZ, got '%s'", o.aspect_spec);
	if (o.wall_E < 0)
		cli_usage_error("--wall-E: must be positive (or 0 for 100 x E)");
	else if (o.wall_E != 0 && !(o.wall_E >= PACK_E_MIN && o.wall_E <= PACK_WALL_E_MAX))
		cli_usage_error("--wall-E: %g Pa is outside [%g, %g] Pa (or 0 for 100 x E)", o.wall_E, PACK_E_MIN, PACK_WALL_E_MAX);
	if (!(o.wall_nu > -1 && o.wall_nu < 0.5))
		cli_usage_error("--wall-nu: must be in (-1, 0.5)");
	if (strcmp(o.shape_name, "sphere") == 0)
		o.plates = 0;
	else if (strcmp(o.shape_name, "spheroplate") == 0)
		o.plates = 1;
	else
		cli_usage_error("--shape: expected sphere or spheroplate, got '%s'", o.shape_name);
	if (strcmp(o.plate_radius_name, "edge") == 0)
		o.conv = SHAPE_R_EDGE;
	else if (strcmp(o.plate_radius_name, "corner") == 0)
		o.conv = SHAPE_R_CORNER;
	else
		cli_usage_error("--plate-radius: expected edge or corner, got '%s'", o.plate_radius_name);
	if (!(o.eta >= 0 && o.eta < 1))
		cli_usage_error("--platyness: must be in [0, 1), got %g", o.eta);
	if (!(o.spheroradius >= 1e-10 && o.spheroradius <= 1))
		cli_usage_error("--spheroradius: must be in [1e-10, 1] m, got %g", o.spheroradius);
	if (!(o.kn > 0 && isfinite(o.kn)) || !(o.kt >= 0 && isfinite(o.kt)))
		cli_usage_error("--kn must be positive and --kt non-negative");
	if (!(o.restitution >= 0.21 && o.restitution <= 1))
		cli_usage_error("--restitution: must be in [0.21, 1] (a linear dashpot returns no less than exp(-pi/2))");
	if (!isnan(o.sigma0) && !(o.sigma0 > 0 && isfinite(o.sigma0)))
		cli_usage_error("--stress: must be positive");
	if (!isnan(o.kappa) && !(o.kappa >= 10 && o.kappa <= 1e9))
		cli_usage_error("--kappa: must be in [10, 1e9] (the paper's rigid limit is kappa >= 1e3)");
	if (!isnan(o.kappa) && !isnan(o.sigma0))
		cli_usage_error("--stress and --kappa: give one");
	/* the stiffness number kn / (sigma0 r) the compaction runs at: in --kappa's range, and
	 * sigma0 in [1e-3 Pa, 10 GPa] (the grains would be crushed long before); outside them
	 * the compaction ran for 15-26 s or more and failed without naming an option, or wrote
	 * a pack of no sense */
	if (o.plates && o.spheroradius >= 1e-10 && o.spheroradius <= 1 && o.kn > 0 && isfinite(o.kn)) {
		double s0 = !isnan(o.sigma0) ? o.sigma0 : o.kn / ((isnan(o.kappa) ? 1e4 : o.kappa) * o.spheroradius);
		double k = o.kn / (s0 * o.spheroradius);

		if (isnan(o.kappa) && !isnan(o.sigma0) && o.sigma0 > 0 && !(k >= 10 && k <= 1e9))
			cli_usage_error("--kn %g N/m and --stress %g Pa: the stiffness number kn / (sigma0 r) = %g (r = --spheroradius %g m) "
			    "must be in [10, 1e9], the range of --kappa", o.kn, o.sigma0, k, o.spheroradius);
		else if (!isnan(o.sigma0) && o.sigma0 > 0 && !(o.sigma0 >= 1e-3 && o.sigma0 <= 1e10))
			cli_usage_error("--stress: %g Pa is outside [1e-3 Pa, 10 GPa]", o.sigma0);
		else if (isnan(o.sigma0) && !(s0 >= 1e-3 && s0 <= 1e10))
			cli_usage_error("--kn %g N/m: the compaction stress kn / (kappa r) = %g Pa it gives is outside [1e-3 Pa, 10 GPa]",
			    o.kn, s0);
	}
	if (!isnan(o.density) && !(o.density > 0 && isfinite(o.density)))
		cli_usage_error("--density: must be positive");
	parse_periodic();
	if (!o.plates && o.periodic_spec && strcmp(o.periodic_spec, "none") != 0)
		cli_usage_error("--periodic: only with --shape spheroplate");
	/* [0, 10], the range of every tool's --mu */
	if (!isnan(o.mu) && !(o.mu >= 0 && o.mu <= 10))
		cli_usage_error("--friction: must be in [0, 10]");
	if (!(o.wall_mu <= 10))
		cli_usage_error("--wall-friction: must be at most 10 (negative: the same as --friction)");
	if (!isnan(o.dem_mu) && !(o.dem_mu >= 0 && o.dem_mu <= 10))
		cli_usage_error("--dem-friction: must be in [0, 10]");
	if (!isnan(o.jitter) && !o.plates && o.jitter != 0)
		cli_usage_error("--jitter: only with --shape spheroplate (spheres are placed at random)");
	else if (!isnan(o.jitter) && !(o.jitter >= 0 && o.jitter <= 1))
		cli_usage_error("--jitter: must be in [0, 1]");
	/* for spheres only the values the sphere path has, so that a history line's resolved
	 * options can be given back */
	if (!isnan(o.dem_wall_mu) && !o.plates && o.dem_wall_mu != (isnan(o.dem_mu) ? 0.5 : o.dem_mu))
		cli_usage_error("--dem-wall-friction: only with --shape spheroplate (the sphere DEM uses --dem-friction at the walls)");
	else if (!isnan(o.dem_wall_mu) && !(o.dem_wall_mu >= 0 && o.dem_wall_mu <= 10))
		cli_usage_error("--dem-wall-friction: must be in [0, 10]");
	if (!(o.overlap > 0 && o.overlap <= 1e-2))
		cli_usage_error("--overlap: must be in (0, 0.01]");
	if (!isnan(o.damping) && !(o.damping >= 0 && o.damping < 1))
		cli_usage_error("--damping: must be in [0, 1)");
	if (!(o.phi0 > 0 && o.phi0 <= 0.35))
		cli_usage_error("--phi0: must be in (0, 0.35]");
	if (!isnan(o.rest_tol) && !(o.rest_tol > 0))
		cli_usage_error("--rest-tol: must be positive");
	if (o.max_steps < 1)
		cli_usage_error("--max-steps: must be positive");
	if (!(o.hydrate_volume >= 0 && o.hydrate_volume < 1))
		cli_usage_error("--hydrate-volume: must be in [0, 1) (the hydrate's fraction of the grain volume), got %g", o.hydrate_volume);
	else if (o.hydrate_volume > 0 && o.plates)
		cli_usage_error("--hydrate-volume: spheres only (not with --shape spheroplate)");
	if (material_lookup("hydrate", &o.hydrate))
		cli_usage_error("%s", msg_geterr());
	{	/* before the compaction (hours at 1e6 grains): -o writable, and not a file read */
		struct file_role r[] = {{st->output ? st->output : "-", "-o", 1},
		    {strncmp(o.psd_spec, "table:", 6) == 0 ? o.psd_spec + 6 : NULL, "the --psd table", 0},
		    {material_is_file(o.material_name) ? o.material_name : NULL, "the --material file", 0}};
		if (file_roles_check(r, 3))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
	shape_defaults();
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
	if (o.plates && pack_set_shapes(p))
		msg_die_err(EXIT_DATA);
	for (k = 0; k < o.ngrains; k++) {
		double x[3] = {0, 0, 0}, r = o.plates ? o.spheroradius : psd_draw(&o.psd, rng), E, nu;
		material_sample(&o.mat, rng, &E, &nu);
		pack_add_grain(p, k + 1, x, r, E, nu, o.density);
	}
}

/* The box the sphere DEM starts from (dem_loose_pack: the grains' volume over --phi0, in the
 * proportions of --aspect) must hold the largest grain across every axis; --aspect 1e300,1,1
 * made it 1e-100 m thin and ended in "the time step is too long" with a stress of -nan. */
static void
check_aspect(const struct pack *p)
{
	double vol = 0, rmax = 0, L0;
	size_t i;
	int a;

	if (o.plates)	/* the plates' grid does not use --aspect */
		return;
	for (i = 0; i < p->n; i++) {
		vol += 4.0 / 3.0 * M_PI * p->r[i] * p->r[i] * p->r[i];
		rmax = fmax(rmax, p->r[i]);
	}
	L0 = cbrt(vol / o.phi0 / (o.aspect[0] * o.aspect[1] * o.aspect[2]));
	for (a = 0; a < 3; a++)
		if (!(L0 * o.aspect[a] >= 2 * rmax))
			msg_die(EXIT_USAGE, "--aspect %s: the starting box would be %g m along %c, less than the largest grain's diameter %g m: each side must hold it (fewer extreme ratios, more grains or a lower --phi0)",
			    o.aspect_spec, L0 * o.aspect[a], 'x' + a, 2 * rmax);
}

/* --hydrate-volume: the smallest grains become hydrate (pack/hydrate.h), before the DEM
 * places them, so that its renumbering carries the tag; F = 0 leaves the pack as without
 * the option (no phase column, no draw). */
static void
tag_hydrate(struct pack *p, gsl_rng *rng)
{
	size_t n;
	double reached;

	if (o.hydrate_volume == 0)
		return;
	if (pack_tag_hydrate(p, o.hydrate_volume, &o.hydrate, rng, &n, &reached))
		msg_die_err(EXIT_DATA);
	msg_info(1, "%zu hydrate grains of %zu, %.6g of the grain volume (--hydrate-volume %g)", n, p->n, reached,
	    o.hydrate_volume);
}

static void
set_meta_number(struct pack *p, const char *key, double v)
{
	char buf[40];

	num_format(buf, v);
	if (pack_set_meta(p, key, buf))
		msg_die_err(EXIT_DATA);
}

/* Monodisperse spheroplates (P §II C): side from the platyness under the --plate-radius
 * reading, the grid of spacing 2 sqrt(2) R, the compaction and the periodic switch of
 * platepack.h.  The pack records the contact law in its meta lines. */
static void
compact_plates(struct pack *p, gsl_rng *rng)
{
	struct platepack_params pp;
	struct platepack_status st;
	double R = o.spheroradius / (1 - o.eta), L = shape_plate_side(R, o.eta, o.conv), q[4] = {1, 0, 0, 0};
	size_t i;

	for (i = 0; i < p->n; i++)
		pack_set_grain_shape(p, i, L, q);
	platepack_params_default(&pp);
	pp.dyn.kn = o.kn, pp.dyn.kt = o.kt;
	pp.dyn.mu = o.dem_mu, pp.dyn.wall_mu = o.dem_wall_mu;
	pp.dyn.restitution = o.restitution;
	pp.dyn.damping = o.damping;
	pp.spacing = 2 * M_SQRT2 * R;
	pp.jitter = o.jitter;
	pp.sigma0 = o.sigma0;
	pp.rest_tol = o.rest_tol;
	pp.max_steps = o.max_steps;
	memcpy(pp.periodic, o.periodic, sizeof o.periodic);
	if (platepack_make(p, &pp, rng, plate_progress, NULL, &st))
		msg_die_err(EXIT_DATA);
	cli_progress_end();
	msg_info(1, "at rest after %ld steps (stage %d): packing %.4f, %.3f interactions per grain, %.3f elements per interaction",
	    st.step, st.stage, st.phi, st.z, st.elements);
	msg_info(1, "eta %g, mu %g during compaction (%g at the walls, %g recorded), e %g, kappa %.4g, inertial number at full rate %.3g",
	    o.eta, o.dem_mu, o.dem_wall_mu, o.mu, o.restitution, st.kappa, st.inertial);
	pack_set_meta(p, "plate-radius", shape_radius_names[o.conv]);
	pack_set_meta(p, "contact-law", "linear");
	set_meta_number(p, "platyness", o.eta);
	set_meta_number(p, "kn", o.kn);
	set_meta_number(p, "kt", o.kt);
	set_meta_number(p, "restitution", o.restitution);
	set_meta_number(p, "sigma0", o.sigma0);
	set_meta_number(p, "kappa", st.kappa);
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
	check_aspect(&p);
	tag_hydrate(&p, rng);
	if (o.plates)
		compact_plates(&p, rng);
	else
		compact(&p, rng);
	p.wall_E = o.wall_E;
	p.wall_nu = o.wall_nu;
	p.mu = o.mu;
	p.wall_mu = o.wall_mu;
	pack_set_meta(&p, "material", o.mat.name);
	if (o.hydrate_volume > 0) {
		set_meta_number(&p, "hydrate-volume", o.hydrate_volume);
		pack_set_meta(&p, "hydrate-material", o.hydrate.name);
	}
	if (pack_validate(&p) || pack_write_tool(&p, &tool, &st))
		msg_die_err(EXIT_DATA);
	pack_free(&p);
	psd_free(&o.psd);
	gsl_rng_free(rng);
	return 0;
}
