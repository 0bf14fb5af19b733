/* loadtest: quasi-static loading of a pack along a path of wall displacements, one TSV row per
 * increment (physics.md §8; the path grammar is in loadpath.h and loadtest(1)). */
#include "base/cli.h"
#include "qs/friction.h"
#include "qs/loadpath.h"
#include "analysis/measure.h"
#include "qs/minopts.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct load_params lp;
static struct path_defaults def = {1e-4, 0, NAN, NAN, 2};
static struct path_limits lim = {100000, 0.05};
#define DEFAULT_STEPS 100	/* a segment's stop when no stop is given at all */

static const char *path_arg = "uniaxial", *axis_arg = "z", *rule_arg = "return-map";
static double mu = NAN, wall_mu = NAN;
static long nsub = 1;
static int allow_limit;

static struct cli_opt opts[] = {
	{"path", 'p', CLI_STRING, &path_arg, "SPEC", "loading path: uniaxial, isotropic, triaxial, polyaxial, or segments 'A; B' (see loadtest(1))", NULL},
	{"strain-step", 'd', CLI_DOUBLE, &def.step, "D", "strain per increment (negative: unloading)", NULL},
	{"steps", 'n', CLI_LONG, &def.steps, "N", "stop after N increments (100 when no stop is given at all)", NULL},
	{"to-stress", 's', CLI_DOUBLE, &def.to_stress, "PA", "stop when sigma_c reaches PA", "Pa"},
	{"to-strain", 'e', CLI_DOUBLE, &def.to_strain, "E", "stop when the axial strain reaches E", NULL},
	{"axis", 'a', CLI_STRING, &axis_arg, "x|y|z", "axis of uniaxial and triaxial paths", NULL},
	{"mu", 'm', CLI_DOUBLE, &mu, "M", "grain-grain friction (default: the pack's; 0: frictionless)", NULL},
	{"wall-mu", 0, CLI_DOUBLE, &wall_mu, "M", "grain-wall friction (default: the pack's, or --mu when given)", NULL},
	{"rule", 0, CLI_STRING, &rule_arg, "NAME", "sliding rule: return-map (exact potential) or paper (F (6)-(7b))", NULL},
	{"sub-increments", 0, CLI_LONG, &nsub, "N", "sub-increments per increment (affine guess each)", NULL},
	{"k-inc", 0, CLI_LONG, &lp.k_inc, "N", "minimiser iterations between sub-increments", NULL},
	{"skin", 0, CLI_DOUBLE, &lp.skin, "RATIO", "Verlet skin / smallest radius", NULL},
	{"max-steps", 0, CLI_LONG, &lim.max_steps, "N", "limit on the increments of one segment", NULL},
	{"max-strain", 0, CLI_DOUBLE, &lim.max_strain, "E", "limit on |strain| along any axis", NULL},
	{"allow-limit", 0, CLI_FLAG, &allow_limit, NULL, "write -o and exit 0 even if a limit stopped the test", NULL},
	QS_MIN_OPTS(lp.min),
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"loadtest", "[options] [FILE]",
	"Load a pack quasi-statically along a path of wall displacements; a TSV row per increment on stdout, the final pack to -o.",
	opts, 1,
};

struct out_ctx {
	const struct load_path *path;
	long rows;
	size_t grains;
	int seg;		/* segment of the last row, and its increments so far */
	long seg_inc;
};

static int
on_row(int seg, const struct load_row *row, void *vctx)
{
	struct out_ctx *c = vctx;

	/* sig_lat: the lateral axes of the row's own segment (the first one for the start row) */
	load_table_row(stdout, row, c->path->seg[seg < 0 ? 0 : seg].axis, 0, 0, 0);
	fflush(stdout);	/* a curve can be followed (tail -f, a pipe) while it grows */
	c->rows++;
	if (seg != c->seg) {
		c->seg = seg;
		c->seg_inc = 0;
	}
	if (seg >= 0) {
		const struct path_seg *sg = &c->path->seg[seg];
		char goal[64] = "";
		c->seg_inc++;
		if (sg->steps > 0)
			snprintf(goal, sizeof goal, " of %ld", sg->steps);
		else if (!isnan(sg->to_stress))
			snprintf(goal, sizeof goal, " (to sigma_c %.4g Pa)", sg->to_stress);
		else if (!isnan(sg->to_strain))
			snprintf(goal, sizeof goal, " (to strain %.4g)", sg->to_strain);
		cli_progress("%zu grains  segment %d of %zu (%s)  increment %ld%s  sigma_c %.4g Pa  sliding %.4f  iter %ld  residual %.2e",
		    c->grains, seg + 1, c->path->n, path_kind_name(sg->kind), c->seg_inc, goal, row->sigma_c,
		    row->sliding_ratio, row->iterations, row->res_max);
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
	    lp.min.tol, lp.min.tol_floor);
	if (lp.min.eps1 > 0)
		printf(" or eps1 %g", lp.min.eps1);
	if (lp.min.eps2 > 0)
		printf(" or eps2 %g", lp.min.eps2);
	printf("; method %s; max-iter %ld\n", qs_method_name(lp.min.method), lp.min.max_iter);
	if (lp.friction)
		printf("## friction: mu %g, wall_mu %g, rule %s\n", p->mu, p->wall_mu, fr_rule_name(lp.rule));
	else
		printf("## friction: none (mu 0)\n");
	printf("## stress: sig_* from the normal forces on the walls, sig_lw_* volume-averaged (Love-Weber), "
	       "sig_lat the mean of the two axes lateral to each segment's axis\n");
	load_table_header(stdout, 0);
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct out_ctx oc = {NULL, 0, 0, -1, 0};
	struct load_path path;
	struct loader L;
	struct pack p;
	const char *in;
	char *hist;
	int r;

	msg_init(argv[0]);
	load_params_default(&lp);
	cli_parse(&tool, argc, argv, &st);
	qs_min_opts_check(&lp.min);
	if (strlen(axis_arg) != 1 || axis_arg[0] < 'x' || axis_arg[0] > 'z')
		cli_usage_error("--axis: must be x, y or z");
	if (!(def.step != 0 && fabs(def.step) <= 0.01))
		cli_usage_error("--strain-step: must be nonzero, |D| <= 0.01");
	if (def.steps < 0)
		cli_usage_error("--steps: must be positive");
	if (!isnan(def.to_stress) && !(def.to_stress > 0))
		cli_usage_error("--to-stress: must be positive");
	if (!isnan(mu) && !(mu >= 0 && mu <= 10))
		cli_usage_error("--mu: must be in [0, 10]");
	if (!isnan(wall_mu) && !(wall_mu >= 0 && wall_mu <= 10))
		cli_usage_error("--wall-mu: must be in [0, 10]");
	if (fr_rule_parse(rule_arg, &lp.rule))
		cli_usage_error("--rule: must be return-map or paper");
	if (nsub < 1 || nsub > 1000 || lp.k_inc < 1)
		cli_usage_error("--sub-increments (<= 1000) and --k-inc must be positive");
	if (!(lp.skin > 0 && lp.skin <= 2))
		cli_usage_error("--skin: must be in (0, 2]");
	if (lim.max_steps < 1 || !(lim.max_strain > 0 && lim.max_strain <= 0.5))
		cli_usage_error("--max-steps must be positive and --max-strain in (0, 0.5]");
	if (!isnan(def.to_strain) && !(fabs(def.to_strain) <= 0.5))
		cli_usage_error("--to-strain: must be in [-0.5, 0.5]");
	cli_usage_done();	/* the path is parsed only with valid defaults */
	/* no stop anywhere (a bare loadtest in a pipe): 100 increments, 1 % strain at the
	 * default step, about 9 -> 18 MPa on the default pack after frictionalize */
	if (def.steps == 0 && isnan(def.to_stress) && isnan(def.to_strain))
		def.steps = DEFAULT_STEPS;
	def.axis = axis_arg[0] - 'x';
	if (path_parse(path_arg, &def, &path))
		cli_usage_error("--path: %s", msg_geterr());
	cli_usage_done();
	oc.path = &path;
	lp.nsub = (int)nsub;

	in = st.input && strcmp(st.input, "-") ? st.input : "<stdin>";
	if (pack_read_path(st.input, &p))
		msg_die_err(EXIT_DATA);
	oc.grains = p.n;
	if (p.n < 5)
		msg_die(EXIT_DATA, "%s: %zu grains: loadtest needs at least 5", in, p.n);
	if (!p.has_refbox)
		msg_die(EXIT_DATA, "%s: no reference box: densify the pack first", in);
	if (fr_check_history(&p))
		msg_die(EXIT_DATA, "%s: %s", in, msg_geterr());
	{
		struct geo_contacts gc;
		struct pack_measures m;
		contacts_init(&gc);
		if (measure_pack(&p, &gc, &m))
			msg_die_err(EXIT_DATA);
		contacts_free(&gc);
		if (m.stale_history)
			msg_warn("%s: %zu history lines name grains that do not touch: dropped", in, m.stale_history);
	}
	if (!isnan(mu)) {
		p.mu = mu;
		p.wall_mu = isnan(wall_mu) ? mu : wall_mu;
	} else if (!isnan(wall_mu))
		p.wall_mu = wall_mu;
	lp.friction = p.mu > 0 || p.wall_mu > 0;
	if (!lp.friction)
		p.mu = p.wall_mu = 0;

	if (loader_open(&L, &p, &lp))
		msg_die_err(EXIT_DATA);
	/* a test continued from a pack that loadtest wrote numbers its increments on */
	if (pack_get_meta(&p, "increments")) {
		char *end;
		L.inc = strtol(pack_get_meta(&p, "increments"), &end, 10);
		if (*end || L.inc < 0)
			msg_die(EXIT_DATA, "%s: meta increments: '%s' is not a count", in, pack_get_meta(&p, "increments"));
	}
	print_header(&p, &path);
	r = path_run(&L, &path, &lim, on_row, &oc);
	cli_progress_end();
	{
		char buf[32];
		snprintf(buf, sizeof buf, "%ld", L.inc);
		pack_set_meta(&p, "increments", buf);
	}
	loader_close(&L);
	if (r == 3)
		msg_die(EXIT_DATA, "writing the table failed");
	if (r < 0 || (r > 0 && !allow_limit)) {
		if (r > 0)
			msg_die(EXIT_DATA, "%s; the rows computed so far are kept%s", msg_geterr(),
			    st.output ? ", the pack is not written (--allow-limit writes it)" : "");
		msg_die_err(EXIT_DATA);
	}
	if (r > 0)
		msg_warn("%s (kept: --allow-limit)", msg_geterr());
	if (fflush(stdout) || ferror(stdout))
		msg_die(EXIT_DATA, "writing the table failed");
	if (st.output) {
		hist = cli_history_line(&tool, &st);
		pack_add_history(&p, hist);
		free(hist);
		if (pack_write_path(&p, st.output))
			msg_die_err(EXIT_DATA);
	}
	msg_info(1, "%ld rows", oc.rows);
	pack_free(&p);
	return 0;
}
