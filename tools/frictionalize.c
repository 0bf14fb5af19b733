/* frictionalize: switch Mindlin-Deresiewicz friction on by uniaxial loading until the sliding
 * ratio saturates (phase (b), physics.md §9). */
#include "base/cli.h"
#include "base/fileio.h"
#include "qs/friction.h"
#include "qs/frictionalize.h"
#include "analysis/measure.h"
#include "qs/minopts.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/packio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct fric_params fp;
static const char *log_path, *axis_arg = "z", *rule_arg = "return-map", *until_arg = "sliding";
static double mu = NAN, wall_mu = NAN;
static long nsub = 1;
static int allow_limit;

static struct cli_opt opts[] = {
	{"mu", 'm', CLI_DOUBLE, &mu, "M", "grain-grain friction coefficient (default: the pack's, 0.3 from packgen)", NULL},
	{"wall-mu", 0, CLI_DOUBLE, &wall_mu, "M", "grain-wall friction coefficient (default: --mu when given, else the pack's)", NULL},
	{"strain-step", 'd', CLI_DOUBLE, &fp.strain_step, "EPS", "uniaxial compression per increment", NULL},
	{"axis", 'a', CLI_STRING, &axis_arg, "x|y|z", "loading axis", NULL},
	{"log", 'l', CLI_STRING, &log_path, "FILE", "write a TSV row per increment to FILE", NULL},
	{"until", 0, CLI_STRING, &until_arg, "WHAT", "stop when the sliding ratio saturates (sliding) or G passes its minimum (shear)", NULL},
	{"window", 0, CLI_LONG, &fp.window, "K", "saturation: the mean of the last K increments (sliding ratio, or G) ...", NULL},
	{"sat-tol", 0, CLI_DOUBLE, &fp.sat_tol, "D", "... sliding: differs from the mean of the K before by less than D times itself", NULL},
	{"window-overlap", 0, CLI_DOUBLE, &fp.window_overlap, "F", "... the window covering at least F x the mean overlap / radius in strain (0: K only)", NULL},
	{"min-inc", 0, CLI_LONG, &fp.min_inc, "N", "at least N increments", NULL},
	{"max-inc", 0, CLI_LONG, &fp.max_inc, "N", "at most N increments (not saturated: an error)", NULL},
	{"rule", 0, CLI_STRING, &rule_arg, "NAME", "sliding rule: return-map (exact potential) or paper (F (6)-(7b))", NULL},
	{"sub-increments", 0, CLI_LONG, &nsub, "N", "sub-increments per increment (affine guess each)", NULL},
	{"k-inc", 0, CLI_LONG, &fp.lp.k_inc, "N", "minimiser iterations between sub-increments", NULL},
	{"skin", 0, CLI_DOUBLE, &fp.lp.skin, "RATIO", "Verlet skin / smallest radius", NULL},
	{"allow-limit", 0, CLI_FLAG, &allow_limit, NULL, "write the pack even if not saturated or a minimisation hit --max-iter", NULL},
	QS_MIN_OPTS(fp.lp.min),
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"frictionalize", "[options] [FILE]",
	"Switch friction on: uniaxial strain increments with Mindlin-Deresiewicz contacts until the sliding ratio saturates.",
	opts, 1,
};

struct log_ctx {
	FILE *fp;
	int axis;
	size_t grains;
};

static void
on_row(const struct load_row *row, const struct hooke *hk, void *vctx)
{
	struct log_ctx *c = vctx;

	if (c->fp) {
		load_table_row(c->fp, row, c->axis, 1, hk->K, hk->G);
		fflush(c->fp);
	}
	cli_progress("%zu grains  increment %ld (at most %ld)  sigma_c %.4g Pa  sliding %.4f  K %.3g  G %.3g  iter %ld  residual %.2e",
	    c->grains, row->inc, fp.max_inc, row->sigma_c, row->sliding_ratio, hk->K, hk->G, row->iterations, row->res_max);
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct file_out logout = {0};
	struct log_ctx lc = {NULL, 2, 0};
	struct load_row last;
	struct pack p;
	char *hist;
	int r;

	msg_init(argv[0]);
	fric_params_default(&fp);
	cli_parse(&tool, argc, argv, &st);
	qs_min_opts_check(&fp.lp.min);
	if (!(isnan(mu) || (mu >= 0 && mu <= 10)) || !(isnan(wall_mu) || (wall_mu >= 0 && wall_mu <= 10)))
		cli_usage_error("--mu and --wall-mu: must be in [0, 10]");
	if (!(fp.strain_step > 0 && fp.strain_step <= 0.01))
		cli_usage_error("--strain-step: must be in (0, 0.01]");
	if (strlen(axis_arg) != 1 || axis_arg[0] < 'x' || axis_arg[0] > 'z')
		cli_usage_error("--axis: must be x, y or z");
	if (fr_rule_parse(rule_arg, &fp.lp.rule))
		cli_usage_error("--rule: must be return-map or paper");
	if (fp.window < 2 || fp.min_inc < 1 || fp.max_inc < 1 || fp.max_inc > 100000)
		cli_usage_error("--window (>= 2), --min-inc and --max-inc (<= 100000) must be positive");
	if (strcmp(until_arg, "sliding") == 0)
		fp.until = FRIC_UNTIL_SLIDING;
	else if (strcmp(until_arg, "shear") == 0)
		fp.until = FRIC_UNTIL_SHEAR;
	else
		cli_usage_error("--until: must be sliding or shear");
	if (!(fp.window_overlap >= 0 && fp.window_overlap <= 100))
		cli_usage_error("--window-overlap: must be in [0, 100]");
	if (fp.min_inc > fp.max_inc || fp.window > fp.max_inc)
		cli_usage_error("--window and --min-inc must not exceed --max-inc");
	if (!(fp.sat_tol > 0 && fp.sat_tol < 1))
		cli_usage_error("--sat-tol: must be in (0, 1)");
	if (nsub < 1 || nsub > 1000 || fp.lp.k_inc < 1)
		cli_usage_error("--sub-increments (<= 1000) and --k-inc must be positive");
	if (!(fp.lp.skin > 0 && fp.lp.skin <= 2))
		cli_usage_error("--skin: must be in (0, 2]");
	cli_usage_done();
	fp.axis = lc.axis = axis_arg[0] - 'x';
	fp.lp.nsub = (int)nsub;
	fp.lp.friction = 1;

	if (pack_read_path(st.input, &p))
		msg_die_err(EXIT_DATA);
	lc.grains = p.n;
	if (p.n < 5)
		msg_die(EXIT_DATA, "%s: %zu grains: frictionalize needs at least 5", st.input ? st.input : "<stdin>", p.n);
	if (!p.has_refbox)
		msg_die(EXIT_DATA, "%s: no reference box: densify the pack first", st.input ? st.input : "<stdin>");
	/* History written by a tool satisfies the sliding limit of the pack's own coefficients:
	 * a line far above it is corrupt, not something to repair silently. */
	if (fr_check_history(&p))
		msg_die(EXIT_DATA, "%s: %s", st.input ? st.input : "<stdin>", msg_geterr());
	{
		struct geo_contacts gc;
		struct pack_measures m;
		contacts_init(&gc);
		if (measure_pack(&p, &gc, &m))
			msg_die_err(EXIT_DATA);
		contacts_free(&gc);
		if (m.stale_history)
			msg_warn("%s: %zu history lines name grains that do not touch: dropped",
			    st.input ? st.input : "<stdin>", m.stale_history);
	}
	if (isnan(wall_mu))
		wall_mu = isnan(mu) ? p.wall_mu : mu;
	if (isnan(mu))
		mu = p.mu;
	p.mu = mu;
	p.wall_mu = wall_mu;
	if (mu == 0 && wall_mu == 0)
		msg_warn("%s: friction coefficients 0 (grain-grain and wall): nothing can slide; give --mu", st.input ? st.input : "<stdin>");
	{
		long w = fric_window(&p, &fp);
		if (w > fp.max_inc)
			msg_die(EXIT_DATA, "%s: the saturation window is %ld increments (--window-overlap %g of this pack's overlaps): more than --max-inc %ld",
			    st.input ? st.input : "<stdin>", w, fp.window_overlap, fp.max_inc);
		msg_info(1, "mu %g, wall_mu %g; saturation window %ld increments of %g", mu, wall_mu, w, fp.strain_step);
	}
	if (log_path) {
		if (file_out_open(&logout, log_path))
			msg_die_err(EXIT_DATA);
		lc.fp = logout.fp;
		load_table_header(lc.fp, 1);
	}
	r = frictionalize_run(&p, &fp, on_row, &lc, &last);
	cli_progress_end();
	if (r < 0 || (r > 0 && !allow_limit)) {
		if (log_path)
			file_out_abort(&logout);
		if (r > 0)
			msg_die(EXIT_DATA, "%s; --allow-limit keeps the pack", msg_geterr());
		msg_die_err(EXIT_DATA);
	}
	if (r > 0)
		msg_warn("%s (kept: --allow-limit)", msg_geterr());
	msg_info(1, "%ld increments: sigma_c %.6g Pa, sliding ratio %.4f, residual %.2e", last.inc, last.sigma_c,
	    last.sliding_ratio, last.res_max);
	hist = cli_history_line(&tool, &st);
	pack_add_history(&p, hist);
	free(hist);
	if (pack_write_path(&p, st.output))
		msg_die_err(EXIT_DATA);
	if (log_path && file_out_commit(&logout))
		msg_die_err(EXIT_DATA);
	pack_free(&p);
	return 0;
}
