/* SPDX-License-Identifier: GPL-3.0-or-later */
/* loadtest: quasi-static loading of a pack along a path of wall displacements, one TSV row per
 * increment (physics.md §8; the path grammar is in loadpath.h and loadtest(1)). */
#include "base/cli.h"
#include "base/fileio.h"
#include "qs/friction.h"
#include "qs/loadpath.h"
#include "qs/minopts.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_STEPS 100	/* a segment's stop when no stop is given at all */

/* The options; the table below points into it. */
static struct opts {
	struct load_params lp;
	struct path_defaults def;
	struct path_limits lim;
	const char *path, *axis, *rule;
	double mu, wall_mu;
	long nsub;
	int allow_limit;
} o = {
	.def = {1e-4, 0, NAN, NAN, 2},
	.lim = {100000, 0.05},
	.path = "uniaxial", .axis = "z", .rule = "return-map",
	.mu = NAN, .wall_mu = NAN,
	.nsub = 1,
};

static struct cli_opt opt_table[] = {
	{"path", 'p', CLI_STRING, &o.path, "SPEC", "loading path: uniaxial, isotropic, triaxial, polyaxial, probe, or segments 'A; B' (see loadtest(1))", NULL},
	{"strain-step", 'd', CLI_DOUBLE, &o.def.step, "D", "strain per increment (negative: unloading)", NULL},
	{"steps", 'n', CLI_LONG, &o.def.steps, "N", "stop after N increments; 0: none (default: 100 when no stop is given at all, else 0)", NULL},
	{"to-stress", 's', CLI_DOUBLE, &o.def.to_stress, "PA", "stop when sigma_c reaches PA", "Pa"},
	{"to-strain", 'e', CLI_DOUBLE, &o.def.to_strain, "E", "stop when the axial strain reaches E", NULL},
	{"axis", 'a', CLI_STRING, &o.axis, "x|y|z", "axis of uniaxial and triaxial paths", NULL},
	{"mu", 'm', CLI_DOUBLE, &o.mu, "M", "grain-grain friction (default: the pack's; 0: frictionless)", NULL},
	{"wall-mu", 0, CLI_DOUBLE, &o.wall_mu, "M", "grain-wall friction (default: the pack's, or --mu when given)", NULL},
	QS_LOAD_OPTS(o.lp, o.rule, o.nsub),
	{"max-steps", 0, CLI_LONG, &o.lim.max_steps, "N", "limit on the increments of one segment", NULL},
	{"max-strain", 0, CLI_DOUBLE, &o.lim.max_strain, "E", "limit on |strain| along any axis", NULL},
	{"allow-limit", 0, CLI_FLAG, &o.allow_limit, NULL, "write -o and exit 0 even if a limit stopped the test", NULL},
	QS_MIN_OPTS(o.lp.min),
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"loadtest", "[options] [FILE]",
	"Load a pack quasi-statically along a path of wall displacements; a TSV row per increment on stdout, the final pack to -o.",
	opt_table, 1,
};

struct out_ctx {
	const struct pack *p;	/* for the header, printed with the first row */
	const struct load_path *path;
	long rows;
	size_t grains;
	int seg;		/* segment of the last row, and its increments so far */
	long seg_inc;
	double sig0, eps0[3];	/* sigma_c and the strains where the segment began (its target's start) */
	double last_sig, last_eps[3];
};

static void print_header(const struct pack *p, const struct load_path *path);

static int
on_row(int seg, const struct load_row *row, void *vctx)
{
	struct out_ctx *c = vctx;

	if (c->rows == 0)	/* only now: a test that cannot start (its stop passed) writes nothing */
		print_header(c->p, c->path);
	/* sig_lat: the lateral axes of the row's own segment (the first one for the start row) */
	load_table_row(stdout, row, c->path->seg[seg < 0 ? 0 : seg].axis, 0, 0, 0);
	fflush(stdout);	/* a curve can be followed (tail -f, a pipe) while it grows */
	c->rows++;
	if (seg != c->seg) {
		c->seg = seg;
		c->seg_inc = 0;
		c->sig0 = c->rows > 1 ? c->last_sig : row->sigma_c;
		memcpy(c->eps0, c->rows > 1 ? c->last_eps : row->eps, sizeof c->eps0);
		cli_progress_frac(NAN);	/* the ETA of each segment from its own start */
	}
	c->last_sig = row->sigma_c;
	memcpy(c->last_eps, row->eps, sizeof c->last_eps);
	if (seg >= 0) {
		const struct path_seg *sg = &c->path->seg[seg];
		char goal[64] = "";
		c->seg_inc++;
		/* the share of the segment's stop: its increments, or the way from the segment's
		 * start to its stress or strain (the first stop that is set, as loadpath takes them) */
		if (sg->steps > 0) {
			snprintf(goal, sizeof goal, " of %ld", sg->steps);
			cli_progress_frac((double)c->seg_inc / (double)sg->steps);
		} else if (!isnan(sg->to_stress)) {
			snprintf(goal, sizeof goal, " (to sigma_c %.4g Pa)", sg->to_stress);
			cli_progress_frac((row->sigma_c - c->sig0) / (sg->to_stress - c->sig0));
		} else if (!isnan(sg->to_strain)) {
			snprintf(goal, sizeof goal, " (to strain %.4g)", sg->to_strain);
			cli_progress_frac((row->eps[sg->axis] - c->eps0[sg->axis]) / (sg->to_strain - c->eps0[sg->axis]));
		}
		cli_progress("segment %d of %zu (%s), increment %ld%s, %zu grains: sigma_c %.4g Pa  sliding %.4f  iter %ld  residual %.2e",
		    seg + 1, c->path->n, path_kind_name(sg->kind), c->seg_inc, goal, c->grains, row->sigma_c,
		    row->sliding_ratio, row->iterations, row->res_max);
		cli_progress_stage("segment %d increment %ld", seg + 1, c->seg_inc + 1);
	}
	return ferror(stdout) ? 1 : 0;
}

static void
print_header(const struct pack *p, const struct load_path *path)
{
	size_t k;

	printf("## qusgm loadtest %s\n", QUSGM_VERSION);
	printf("## path:");
	for (k = 0; k < path->n; k++) {
		const struct path_seg *sg = &path->seg[k];
		printf("%s %s ratio=%g:%g:%g step=%g", k ? ";" : "", path_kind_name(sg->kind), sg->ratio[0], sg->ratio[1],
		    sg->ratio[2], sg->step);
		if (sg->hold)
			printf(" hold=%g", sg->hold == 1 ? sg->hold_stress : -1.0);
		if (sg->steps)
			printf(" steps=%ld", sg->steps);
		if (!isnan(sg->to_stress))
			printf(" to-stress=%g", sg->to_stress);
		if (!isnan(sg->to_strain))
			printf(" to-strain=%g", sg->to_strain);
	}
	printf("\n## equilibrium: residual <= %g (largest per-grain max(|F_i|, |M_i|/R_i) / largest contact force on i, "
	       "floored at %g x the mean contact force)",
	    o.lp.min.tol, o.lp.min.tol_floor);
	if (o.lp.min.eps1 > 0)
		printf(" or eps1 %g", o.lp.min.eps1);
	if (o.lp.min.eps2 > 0)
		printf(" or eps2 %g", o.lp.min.eps2);
	printf("; method %s; max-iter %ld\n", o.lp.min.method->name, o.lp.min.max_iter);
	if (o.lp.friction)
		printf("## friction: mu %g, wall_mu %g, rule %s\n", p->mu, p->wall_mu, fr_rule_name(o.lp.rule));
	else
		printf("## friction: none (mu 0)\n");
	printf("## stress: sig_* from the normal forces on the walls, sig_lw_* volume-averaged (Love-Weber), "
	       "sig_lat the mean of the two axes lateral to each segment's axis\n");
	load_table_header(stdout, 0);
}

/* Every option is checked before the path, so that the path is parsed with valid defaults. */
static void
parse_args(int argc, char **argv, struct cli_state *st, struct load_path *path)
{
	load_params_default(&o.lp);
	cli_output_help("write the final pack to FILE (atomically; .gz compresses); the table always goes to stdout");
	qs_min_opts_init();
	cli_parse(&tool, argc, argv, st);
	qs_min_opts_check(&o.lp.min);
	if (path_parse_axis(o.axis, &o.def.axis))
		cli_usage_error("--axis: must be x, y or z");
	if (!(o.def.step != 0 && fabs(o.def.step) <= 0.01))
		cli_usage_error("--strain-step: must be nonzero, |D| <= 0.01");
	if (o.def.steps < 0)
		cli_usage_error("--steps: must be positive");
	if (!isnan(o.def.to_stress) && !(o.def.to_stress > 0))
		cli_usage_error("--to-stress: must be positive");
	qs_load_opts_check(&o.lp, o.rule, o.nsub, o.mu, o.wall_mu);
	if (o.lim.max_steps < 1 || !(o.lim.max_strain > 0 && o.lim.max_strain <= 0.5))
		cli_usage_error("--max-steps must be positive and --max-strain in (0, 0.5]");
	if (!isnan(o.def.to_strain) && !(fabs(o.def.to_strain) <= 0.5))
		cli_usage_error("--to-strain: must be in [-0.5, 0.5]");
	{	/* before any work: -o writable (it may be the input: the pack updated in place), and
		 * not the table's standard output */
		struct file_role r[] = {{st->output, "-o", FILE_UPDATE}, {"-", "the table", FILE_OUT}, {st->input, "the input", FILE_IN}};
		if (file_roles_check(r, 3))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
	/* no stop anywhere (a bare loadtest in a pipe): 100 increments, 1 % strain at the
	 * default step, about 9 -> 18 MPa on the default pack after frictionalize */
	if (o.def.steps == 0 && isnan(o.def.to_stress) && isnan(o.def.to_strain))
		o.def.steps = DEFAULT_STEPS;
	if (path_parse(o.path, &o.def, path))
		cli_usage_error("--path: %s", msg_geterr());
	cli_usage_done();
}

/* A test continued from a pack that loadtest wrote numbers its increments on. */
static void
continue_increments(struct loader *L, const struct pack *p, const char *in)
{
	const char *done = pack_get_meta(p, "increments");
	char *end;

	if (!done)
		return;
	L->inc = strtol(done, &end, 10);
	if (*end || L->inc < 0)
		msg_die(EXIT_DATA, "%s: meta increments: '%s' is not a count", in, done);
}

/* The table on stdout as the path runs; the pack keeps the count of increments for a
 * continuation.  Returns path_run's code. */
static int
run_test(struct pack *p, const struct load_path *path, const char *in, struct out_ctx *oc)
{
	struct loader L;
	char buf[32];
	int r;

	if (loader_open(&L, p, &o.lp))
		msg_die_err(EXIT_DATA);
	continue_increments(&L, p, in);
	oc->p = p;
	r = path_run(&L, path, &o.lim, on_row, oc);
	cli_progress_end();
	snprintf(buf, sizeof buf, "%ld", L.inc);
	pack_set_meta(p, "increments", buf);
	loader_close(&L);
	return r;
}

/* A limit that stopped the test fails it unless --allow-limit; the rows written so far stay
 * on stdout either way. */
static void
check_stop(int r, const struct cli_state *st)
{
	if (r == 3)
		msg_die(EXIT_DATA, "writing the table failed");
	if (r < 0 || (r > 0 && !o.allow_limit)) {
		if (r > 0)
			msg_die(EXIT_DATA, "%s; the rows computed so far are kept%s", msg_geterr(),
			    st->output ? ", the pack is not written (--allow-limit writes it)" : "");
		msg_die_err(EXIT_DATA);
	}
	if (r > 0)
		msg_warn("%s (kept: --allow-limit)", msg_geterr());
	if (fflush(stdout) || ferror(stdout))
		msg_die(EXIT_DATA, "writing the table failed");
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct load_path path;
	struct out_ctx oc = {NULL, &path, 0, 0, -1, 0, 0, {0, 0, 0}, 0, {0, 0, 0}};
	struct pack p;
	const char *in;
	size_t stale;
	int r;

	msg_init(argv[0]);
	parse_args(argc, argv, &st, &path);
	in = file_display_name(st.input);
	/* a fault of the pack is named by the input; a read error names its place itself */
	if ((r = path_read_pack(st.input, tool.name, &p, &stale)))
		msg_die(EXIT_DATA, "%s%s%s", r > 0 ? in : "", r > 0 ? ": " : "", msg_geterr());
	if (stale)
		msg_warn("%s: %zu history lines name grains that do not touch: dropped", in, stale);
	oc.grains = p.n;
	o.lp.friction = path_set_friction(&p, o.mu, o.wall_mu);
	check_stop(run_test(&p, &path, in, &oc), &st);
	if (st.output) {
		if (pack_write_tool(&p, &tool, &st))
			msg_die_err(EXIT_DATA);
	}
	msg_info(1, "%ld rows", oc.rows);
	pack_free(&p);
	return 0;
}
