/* SPDX-License-Identifier: GPL-3.0-or-later */
/* frictionalize: switch Mindlin-Deresiewicz friction on by uniaxial loading until the sliding
 * ratio saturates (phase (b), physics.md §9). */
#include "base/cli.h"
#include "base/fileio.h"
#include "qs/friction.h"
#include "qs/frictionalize.h"
#include "qs/loadpath.h"
#include "qs/minopts.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/packio.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The options; the table below points into it. */
static struct opts {
	struct fric_params fp;
	const char *log, *axis, *rule, *until;
	double mu, wall_mu;
	long nsub;
	int allow_limit;
} o = {
	.axis = "z", .rule = "return-map", .until = "sliding",
	.mu = NAN, .wall_mu = NAN,
	.nsub = 1,
};

static struct cli_opt opt_table[] = {
	{"mu", 'm', CLI_DOUBLE, &o.mu, "M", "grain-grain friction coefficient (default: the pack's, 0.3 from packgen)", NULL},
	{"wall-mu", 0, CLI_DOUBLE, &o.wall_mu, "M", "grain-wall friction coefficient (default: --mu when given, else the pack's)", NULL},
	{"strain-step", 'd', CLI_DOUBLE, &o.fp.strain_step, "EPS", "uniaxial compression per increment", NULL},
	{"axis", 'a', CLI_STRING, &o.axis, "x|y|z", "loading axis", NULL},
	{"log", 'l', CLI_STRING, &o.log, "FILE", "write a TSV row per increment to FILE", NULL},
	{"until", 0, CLI_STRING, &o.until, "WHAT", "stop when the sliding ratio saturates (sliding) or G passes its minimum (shear)", NULL},
	{"window", 0, CLI_LONG, &o.fp.window, "K", "saturation: the mean of the last K increments (sliding ratio, or G) ...", NULL},
	{"sat-tol", 0, CLI_DOUBLE, &o.fp.sat_tol, "D", "... sliding: differs from the mean of the K before by less than D times itself", NULL},
	{"window-overlap", 0, CLI_DOUBLE, &o.fp.window_overlap, "F", "... the window covering at least F x the mean overlap / radius in strain (0: K only)", NULL},
	{"min-inc", 0, CLI_LONG, &o.fp.min_inc, "N", "at least N increments", NULL},
	{"max-inc", 0, CLI_LONG, &o.fp.max_inc, "N", "at most N increments (not saturated: an error)", NULL},
	QS_LOAD_OPTS(o.fp.lp, o.rule, o.nsub),
	{"allow-limit", 0, CLI_FLAG, &o.allow_limit, NULL, "write the pack even if not saturated or a minimisation hit --max-iter", NULL},
	QS_MIN_OPTS(o.fp.lp.min),
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"frictionalize", "[options] [FILE]",
	"Switch friction on: uniaxial strain increments with Mindlin-Deresiewicz contacts until the sliding ratio saturates.",
	opt_table, 1,
};

struct log_ctx {
	struct file_out *log;	/* --log, or NULL */
	int axis;
	size_t grains;
};

static void
on_row(const struct load_row *row, const struct hooke *hk, void *vctx)
{
	struct log_ctx *c = vctx;

	if (c->log) {
		load_log_row(c->log->fp, row, c->axis, hk->K, hk->G, cli_elapsed());
		file_out_flush(c->log);	/* the log is followed (tail -f) and kept as it runs */
	}
	/* no target: the run ends when the sliding ratio saturates, which no count foretells */
	cli_progress("increment %ld (at most %ld), %zu grains: sigma_c %.4g Pa  sliding %.4f  K %.3g  G %.3g  iter %ld  residual %.2e",
	    row->inc, o.fp.max_inc, c->grains, row->sigma_c, row->sliding_ratio, hk->K, hk->G, row->iterations, row->res_max);
	cli_progress_stage("increment %ld", row->inc + 1);
}

static void
parse_args(int argc, char **argv, struct cli_state *st)
{
	fric_params_default(&o.fp);
	qs_min_opts_init();
	cli_parse(&tool, argc, argv, st);
	qs_min_opts_check(&o.fp.lp.min);
	qs_load_opts_check(&o.fp.lp, o.rule, o.nsub, o.mu, o.wall_mu);
	if (!(o.fp.strain_step > 0 && o.fp.strain_step <= 0.01))
		cli_usage_error("--strain-step: must be in (0, 0.01]");
	if (path_parse_axis(o.axis, &o.fp.axis))
		cli_usage_error("--axis: must be x, y or z");
	if (o.fp.window < 2 || o.fp.min_inc < 1 || o.fp.max_inc < 1 || o.fp.max_inc > 100000)
		cli_usage_error("--window (>= 2), --min-inc and --max-inc (<= 100000) must be positive");
	if (strcmp(o.until, "sliding") == 0)
		o.fp.until = FRIC_UNTIL_SLIDING;
	else if (strcmp(o.until, "shear") == 0)
		o.fp.until = FRIC_UNTIL_SHEAR;
	else
		cli_usage_error("--until: must be sliding or shear");
	if (!(o.fp.window_overlap >= 0 && o.fp.window_overlap <= 100))
		cli_usage_error("--window-overlap: must be in [0, 100]");
	if (o.fp.min_inc > o.fp.max_inc || o.fp.window > o.fp.max_inc)
		cli_usage_error("--window and --min-inc must not exceed --max-inc");
	if (!(o.fp.sat_tol > 0 && o.fp.sat_tol < 1))
		cli_usage_error("--sat-tol: must be in (0, 1)");
	{	/* before any work: the pack and the log writable, neither over the other nor the log
		 * over the input (the pack may update it in place) */
		struct file_role r[] = {{st->output ? st->output : "-", "-o", FILE_UPDATE}, {o.log, "--log", FILE_LOG}, {st->input, "the input", FILE_IN}};
		if (file_roles_check(r, 3))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
	o.fp.lp.friction = 1;
}

/* --mu alone sets the wall's coefficient too. */
static void
set_friction(struct pack *p, const char *in)
{
	if (isnan(o.wall_mu))
		o.wall_mu = isnan(o.mu) ? p->wall_mu : o.mu;
	if (isnan(o.mu))
		o.mu = p->mu;
	p->mu = o.mu;
	p->wall_mu = o.wall_mu;
	if (o.mu == 0 && o.wall_mu == 0)
		msg_warn("%s: friction coefficients 0 (grain-grain and wall): nothing can slide; give --mu", in);
}

/* The window depends on the pack's overlaps, so only now can it be checked against --max-inc. */
static void
check_window(const struct pack *p, const char *in)
{
	long w = fric_window(p, &o.fp);

	if (w > o.fp.max_inc)
		msg_die(EXIT_DATA, "%s: the saturation window is %ld increments (--window-overlap %g of this pack's overlaps): more than --max-inc %ld",
		    in, w, o.fp.window_overlap, o.fp.max_inc);
	msg_info(1, "mu %g, wall_mu %g; saturation window %ld increments of %g", o.mu, o.wall_mu, w, o.fp.strain_step);
}

/* Not saturated, or a minimisation at its limit, fails the run unless --allow-limit; a failed
 * run keeps its log (closed, with every row so far) and writes no pack. */
static void
check_stop(int r, struct file_out *logout, const struct load_row *last)
{
	if (r < 0 || (r > 0 && !o.allow_limit)) {
		if (o.log)
			file_out_abort(logout);
		if (r > 0)
			msg_die(EXIT_DATA, "%s; --allow-limit keeps the pack", msg_geterr());
		msg_die_err(EXIT_DATA);
	}
	if (r > 0)
		msg_warn("%s (kept: --allow-limit)", msg_geterr());
	msg_info(1, "%ld increments: sigma_c %.6g Pa, sliding ratio %.4f, residual %.2e", last->inc, last->sigma_c,
	    last->sliding_ratio, last->res_max);
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct file_out logout = {0};
	struct log_ctx lc = {NULL, 2, 0};
	struct load_row last;
	struct pack p;
	const char *in;
	size_t stale;
	int r;

	msg_init(argv[0]);
	parse_args(argc, argv, &st);
	in = file_display_name(st.input);
	/* a fault of the pack is named by the input; a read error names its place itself */
	if ((r = path_read_pack(st.input, tool.name, &p, &stale)))
		msg_die(EXIT_DATA, "%s%s%s", r > 0 ? in : "", r > 0 ? ": " : "", msg_geterr());
	if (stale)
		msg_warn("%s: %zu history lines name grains that do not touch: dropped", in, stale);
	lc.axis = o.fp.axis;
	lc.grains = p.n;
	set_friction(&p, in);
	check_window(&p, in);
	if (o.log) {
		/* the header flushed at once: a log that cannot be written (--log /dev/full) fails
		 * the run before it starts */
		if (file_log_open(&logout, o.log))
			msg_die_err(EXIT_DATA);
		lc.log = &logout;
		load_log_header(logout.fp);
		if (file_out_flush(&logout)) {
			errno = logout.err;
			file_out_abort(&logout);
			msg_die(EXIT_DATA, "%s: write error:", o.log);
		}
	}
	r = frictionalize_run(&p, &o.fp, on_row, &lc, &last);
	cli_progress_end();
	check_stop(r, &logout, &last);
	if (pack_write_tool_with(&p, &tool, &st, o.log ? &logout : NULL))	/* the log closed with it: a log that failed writes no pack */
		msg_die_err(EXIT_DATA);
	pack_free(&p);
	return 0;
}
