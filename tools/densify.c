/* SPDX-License-Identifier: GPL-3.0-or-later */
/* densify: frictionless isotropic compaction of a loose pack to a confining stress. */
#include "base/cli.h"
#include "base/fileio.h"
#include "contact/hertz.h"
#include "qs/densify.h"
#include "qs/minopts.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/packio.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* The options; the table below points into it. */
static struct opts {
	struct densify_params dp;
	const char *log, *checkpoint;
	double time_limit;
	int allow_limit, full_steps;
	long min_coord, nsub;
} o = {
	.min_coord = 4, .nsub = 1,
};

static struct cli_opt opt_table[] = {
	{"stress", 'p', CLI_DOUBLE, &o.dp.stress, "PA", "target confining stress sigma_c = tr(sigma)/3", "Pa"},
	{"log", 'l', CLI_STRING, &o.log, "FILE", "write a TSV row per stage to FILE", NULL},
	{"onset", 0, CLI_DOUBLE, &o.dp.onset, "PA", "stress that marks the reference box for strains; 0: 1e5, or --stress/10 if lower", "Pa"},
	{"stress-tol", 0, CLI_DOUBLE, &o.dp.stress_tol, "RATIO", "relative tolerance on the final sigma_c", NULL},
	{"strain-step", 0, CLI_DOUBLE, &o.dp.strain_step, "EPS", "largest isotropic strain per step", NULL},
	{"max-growth", 0, CLI_DOUBLE, &o.dp.max_growth, "RATIO", "largest growth of a radius per round / radius", NULL},
	{"grow-tol", 0, CLI_DOUBLE, &o.dp.grow_tol, "RATIO", "residual target of growth rounds and of compaction steps that move the box or grow grains", NULL},
	{"grow-max-iter", 0, CLI_LONG, &o.dp.grow_max_iter, "N", "iteration limit of those rounds and steps (reaching it is not an error)", NULL},
	{"release-after", 0, CLI_LONG, &o.dp.release_after, "N", "iterations between releases of grains with 1-3 contacts; 0: never", NULL},
	{"full-steps", 0, CLI_FLAG, &o.full_steps, NULL, "every compaction step to the full tolerance (not only the last)", NULL},
	{"min-coord", 0, CLI_LONG, &o.min_coord, "N", "grains with fewer contacts (grains and walls) are expanded", NULL},
	{"max-rounds", 0, CLI_LONG, &o.dp.max_rounds, "N", "limit on growth rounds and on compaction steps", NULL},
	{"sub-increments", 0, CLI_LONG, &o.nsub, "N", "sub-increments per strain step (affine guess each)", NULL},
	{"k-inc", 0, CLI_LONG, &o.dp.k_inc, "N", "minimiser iterations between sub-increments", NULL},
	{"skin", 0, CLI_DOUBLE, &o.dp.skin, "RATIO", "Verlet skin / smallest radius", NULL},
	{"checkpoint", 0, CLI_STRING, &o.checkpoint, "FILE", "save the state to FILE after every stage; go on from FILE if it exists", NULL},
	{"time-limit", 0, CLI_DOUBLE, &o.time_limit, "S", "with --checkpoint: stop (exit 75) before a stage would end past S seconds; 0: none", "s"},
	{"allow-limit", 0, CLI_FLAG, &o.allow_limit, NULL, "write the pack even if a minimisation hit --max-iter (exit 0)", NULL},
	QS_MIN_OPTS(o.dp.min),
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"densify", "[options] [FILE]",
	"Frictionless isotropic compaction: expand grains with fewer than 4 contacts, shrink, minimise; then compress to --stress.",
	opt_table, 1,
};

/* The log, and the checkpoint: its file, the rows so far (a memory stream), what identifies
 * the run (options and input), the clock. */
struct log_ctx {
	struct file_out *log;	/* --log, or NULL */
	FILE *rows;
	char *rowbuf;
	size_t rowlen;
	const char *ckpath;
	char *run;
	double longest;		/* the longest stage so far, in any call (s) */
	double last;		/* when the last checkpoint was written, in this call (s) */
	double before;		/* the wall time of the earlier calls (s) */
	long calls;		/* this call's number */
};

/* The tool's own checkpoint line: the clock, which is not part of the state (the run goes
 * on the same whatever it says): the longest stage, the wall time of the calls, their count. */
#define CK_CLOCK "densify-clock"


static void
on_stage(const struct densify_stage *st, void *vctx)
{
	struct log_ctx *c = vctx;

	double elapsed = floor((c->before + cli_elapsed()) * 1e3 + 0.5) / 1e3;

	if (c->log) {
		densify_log_row(c->log->fp, st, elapsed);
		file_out_flush(c->log);	/* the log is followed (tail -f) and kept as it runs */
	}
	if (c->rows)
		densify_log_row(c->rows, st, elapsed);
	/* the target: sigma_c from the onset up to --stress, on a log scale (compaction steps are
	 * steps in strain, and the stress grows as its 3/2 power) */
	if (st->sigma_c > o.dp.onset && strcmp(st->stage, "compact") == 0)
		cli_progress_frac(log(st->sigma_c / o.dp.onset) / log(o.dp.stress / o.dp.onset));
	cli_progress("%s %ld: sigma_c %.4g Pa  porosity %.4f  Z %.3f  under4 %zu  growth %.2e  iter %ld  residual %.2e",
	    st->stage, st->round, st->sigma_c, st->porosity, st->coordination, st->under4, st->growth,
	    st->iterations, st->res_max);
}

/* After every stage: the pack and the state to the checkpoint file (atomically), and, with
 * --time-limit, stop when the next stage, taken as long as the longest so far in any call
 * and followed by a checkpoint as long as this one, would end past it.  A stage cannot be
 * cut short: its minimiser's state is not saved, so each call runs at least one. */
static int
on_checkpoint(const struct pack *p, const struct densify_resume *at, void *vctx)
{
	struct log_ctx *c = vctx;
	double now = cli_elapsed(), wrote;
	char clock[96];

	c->longest = fmax(c->longest, now - c->last);
	snprintf(clock, sizeof clock, "%.3f %.3f %ld", c->longest, c->before + now, c->calls);
	if (fflush(c->rows) || densify_resume_put((struct pack *)p, at, c->run, c->rowbuf) ||
	    pack_set_meta((struct pack *)p, CK_CLOCK, clock) || pack_write_path(p, c->ckpath))
		return -1;
	wrote = cli_elapsed();
	c->last = wrote;
	return o.time_limit > 0 && wrote + c->longest + (wrote - now) > o.time_limit;
}

/* What a checkpoint must match to be gone on from: the options that change the result, and
 * the input's grains (a CRC-32 of their ids, centres and radii). */
static char *
run_identity(const struct pack *p)
{
	/* what only decides where output goes, when to stop, or whether a run at its limit is
	 * kept, is left out: a run stopped by --time-limit may be finished without it */
	static const char *const skip[] = {"log", "checkpoint", "time-limit", "allow-limit", NULL};
	char input[64];

	pack_checksum(p, input, sizeof input);
	return cli_run_identity(&tool, skip, input);
}

/* An existing checkpoint of this run replaces the input: 1 when there was one. */
static int
resume_from(const char *path, struct pack *p, struct densify_resume *at, struct log_ctx *c)
{
	struct pack q;
	char *run, *rows;
	int r;

	if (access(path, F_OK) != 0) {
		if (errno != ENOENT)
			msg_die(EXIT_DATA, "%s: %s", path, strerror(errno));
		return 0;
	}
	if (pack_read_path(path, &q))
		msg_die_err(EXIT_DATA);
	if ((r = densify_resume_get(&q, at, &run, &rows)) != 0)
		msg_die(EXIT_DATA, "%s: %s", path, r > 0 ? "not a densify checkpoint (no meta densify-checkpoint)" : msg_geterr());
	if (strcmp(run, c->run) != 0 || q.n != p->n)
		msg_die(EXIT_DATA, "%s: the checkpoint of another run (other options or another input): remove it to start afresh",
		    path);
	if (densify_resume_check_input(p, &o.dp, at))
		msg_die(EXIT_DATA, "%s: %s", path, msg_geterr());
	if (pack_get_meta(&q, CK_CLOCK)) {
		int end = -1;
		const char *cl = pack_get_meta(&q, CK_CLOCK);
		if (sscanf(cl, "%lg %lg %ld %n", &c->longest, &c->before, &c->calls, &end) != 3 || end < 0 || cl[end] ||
		    !(c->longest >= 0 && c->longest < 1e12) || !(c->before >= 0 && c->before < 1e12) || c->calls < 1)
			msg_die(EXIT_DATA, "%s: meta %s: malformed", path, CK_CLOCK);
		pack_unset_meta(&q, CK_CLOCK);
	}
	c->calls++;
	if (c->log && (fputs(rows, c->log->fp) < 0 || file_out_flush(c->log))) {	/* the rows so far, kept from now on */
		errno = c->log->err;
		msg_die(EXIT_DATA, "%s: write error:", o.log);
	}
	fputs(rows, c->rows);
	msg_info(1, "going on from %s, after %s %ld", path, at->st.stage, at->round);
	free(run), free(rows);
	pack_free(p);
	*p = q;
	return 1;
}

/* The directory a file is to be written in exists and is writable (a usage error otherwise). */
static void
check_dir(const char *path, const char *opt)
{
	struct file_role r = {path, opt, 1};

	if (file_roles_check(&r, 1))
		cli_usage_error("%s", msg_geterr());
}

static void
parse_args(int argc, char **argv, struct cli_state *st)
{
	densify_params_default(&o.dp);
	qs_min_opts_init();
	cli_parse(&tool, argc, argv, st);
	qs_min_opts_check(&o.dp.min);
	if (!(o.dp.stress > 0))
		cli_usage_error("--stress: must be positive");
	if (!(o.dp.onset >= 0))
		cli_usage_error("--onset: must be positive (or 0 for the default)");
	if (!(o.dp.stress_tol > 0 && o.dp.stress_tol < 0.5))
		cli_usage_error("--stress-tol: must be in (0, 0.5)");
	if (!(o.dp.strain_step > 0 && o.dp.strain_step <= 0.05))
		cli_usage_error("--strain-step: must be in (0, 0.05]");
	if (o.dp.grow_max_iter < 1 || o.dp.grow_max_iter > 100000000)
		cli_usage_error("--grow-max-iter: must be in 1..1e8");
	if (o.dp.release_after < 0 || o.dp.release_after > 100000000)
		cli_usage_error("--release-after: must be in 0..1e8");
	if (!(o.dp.grow_tol > 0 && o.dp.grow_tol < 1))
		cli_usage_error("--grow-tol: must be in (0, 1)");
	if (!(o.dp.max_growth > 0 && o.dp.max_growth <= 0.5))
		cli_usage_error("--max-growth: must be in (0, 0.5]");
	if (o.min_coord < 0 || o.min_coord > 4)
		cli_usage_error("--min-coord: must be in [0, 4]");
	if (o.dp.max_rounds < 1 || o.nsub < 1 || o.nsub > 1000 || o.dp.k_inc < 1)
		cli_usage_error("--max-rounds, --sub-increments (<= 1000) and --k-inc must be positive");
	if (!(o.dp.skin > 0 && o.dp.skin <= 2))
		cli_usage_error("--skin: must be in (0, 2]");
	if (!(o.time_limit >= 0) || !isfinite(o.time_limit))
		cli_usage_error("--time-limit: must be a number of seconds, 0 or more");
	if (o.time_limit > 0 && !o.checkpoint)
		cli_usage_error("--time-limit needs --checkpoint (where the state goes)");
	/* the finished run removes the checkpoint: never the pack or the log just written, nor
	 * the input; and it is read back, so not standard output */
	if (o.checkpoint && (strcmp(o.checkpoint, "-") == 0 || file_same(o.checkpoint, st->output, 1) ||
	                        file_same(o.checkpoint, o.log, 0) || file_same(o.checkpoint, st->input, 0)))
		cli_usage_error("--checkpoint: '%s' is standard output, the input, the output or the log; give it a file of its own",
		    o.checkpoint);
	/* a run of hours must not find out at its end that it cannot write */
	if (o.checkpoint)
		check_dir(o.checkpoint, "--checkpoint");
	{	/* nor the log or the pack over the other, nor the log over the input, even through
		 * a symbolic link (--log X -o X kept the log as X and lost the pack); the pack may
		 * replace the input (read whole, then renamed over it) */
		struct file_role r[] = {{st->output ? st->output : "-", "-o", FILE_UPDATE}, {o.log, "--log", FILE_LOG}, {st->input, "the input", FILE_IN}};
		if (file_roles_check(r, 3))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
	o.dp.loose_steps = !o.full_steps;
	if (o.dp.onset == 0)
		o.dp.onset = densify_onset_default(o.dp.stress);	/* the history line records the value used */
	o.dp.min_coord = (unsigned)o.min_coord;
	o.dp.nsub = (int)o.nsub;
}

static void
read_pack(const char *input, struct pack *p)
{
	size_t i;
	int a;

	const char *name = file_display_name(input);

	if (pack_read_path(input, p))
		msg_die_err(EXIT_DATA);
	if (pack_require_spheres(p, "densify"))
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	if (!contact_law_of_pack(p))	/* densify runs any law of the table (qs/functional.c) */
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	if (p->n < 5)
		msg_die(EXIT_DATA, "%s: %zu grains: densify needs at least 5", name, p->n);
	for (a = 0; a < 3; a++)
		for (i = 0; i < p->n; i++)
			if (pack_box_length(p->box, a) < 2 * p->r[i])
				msg_die(EXIT_DATA, "the box is thinner than grain %ld along %c", p->id[i], 'x' + a);
}

/* --stress within the law's range (Hertz: small strains, hertz_stress_in_range), and not too far below the
 * moduli; checked here, where the pack is known. */
static void
check_stress(const struct pack *p)
{
	double Emean = 0;
	size_t i;

	for (i = 0; i < p->n; i++)
		Emean += p->E[i] / p->n;
	const struct contact_law *law = contact_law_of_pack(p);

	if (law->stress_in_range(law, p, o.dp.stress))
		msg_die(EXIT_USAGE, "--stress %s", msg_geterr());
	/* a target this far below the moduli is no jammed pack the minimisers can resolve:
	 * --stress 1e-300 ran 74 s before failing */
	if (o.dp.stress < 1e-12 * Emean)
		msg_die(EXIT_USAGE, "--stress %g Pa is below 1e-12 E of the grains (1e-12 E = %g Pa)",
		    o.dp.stress, 1e-12 * Emean);
	if (o.dp.stress <= o.dp.onset)
		msg_die(EXIT_USAGE, "--stress %g Pa must exceed --onset %g Pa", o.dp.stress, o.dp.onset);
}

/* A minimisation at its limit fails the run unless --allow-limit; a failed run keeps its log
 * (closed, with every row so far) and writes no pack. */
static void
check_stop(int r, struct file_out *logout, const struct densify_stage *last, const char *name)
{
	if (r < 0 || (r == 1 && !o.allow_limit)) {
		if (o.log)
			file_out_abort(logout);
		if (r == 1)
			msg_die(EXIT_DATA, "%s: %s; rerun with a larger --max-iter, or --allow-limit to keep the pack", name,
			    msg_geterr());
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	}
	/* never a pack that does not carry what it claims: the end conditions, checked on the
	 * final state itself (densify_run loops until they hold; this guards that loop) */
	if (r == 0 && (!isfinite(last->sigma_c) || last->under_min > 0 || !isfinite(last->res_max) ||
	        fabs(last->sigma_c / o.dp.stress - 1) > o.dp.stress_tol)) {
		if (o.log)
			file_out_abort(logout);
		msg_die(EXIT_DATA, "the final state fails the end conditions: sigma_c %g Pa (target %g, "
		    "--stress-tol %g), %zu grains under %u contacts, residual %g", last->sigma_c, o.dp.stress,
		    o.dp.stress_tol, last->under_min, o.dp.min_coord, last->res_max);
	}
	if (r == 1)
		msg_warn("%s (kept: --allow-limit)", msg_geterr());
	msg_info(1, "sigma_c %.6g Pa, porosity %.4f, coordination %.3f, under4 %zu, residual %.2e", last->sigma_c,
	    last->porosity, last->coordination, last->under4, last->res_max);
}

/* The header flushed at once: a log that cannot be written (--log /dev/full) fails the run
 * before it starts. */
static void
open_log(struct file_out *logout, struct log_ctx *lc)
{
	if (file_log_open(logout, o.log))
		msg_die_err(EXIT_DATA);
	lc->log = logout;
	densify_log_header(logout->fp);
	if (file_out_flush(logout)) {
		errno = logout->err;
		file_out_abort(logout);
		msg_die(EXIT_DATA, "%s: write error:", o.log);
	}
}

/* Returns whether the run goes on from the checkpoint (which then holds the state in p and at). */
static int
start_checkpoint(struct pack *p, struct densify_resume *at, struct log_ctx *lc)
{
	if (!(lc->rows = open_memstream(&lc->rowbuf, &lc->rowlen)))
		msg_die(EXIT_DATA, "out of memory");
	lc->ckpath = o.checkpoint;
	lc->calls = 1;
	lc->run = run_identity(p);
	return resume_from(o.checkpoint, p, at, lc);
}

/* The time limit: neither a pack nor a log; the checkpoint is where the same command goes on. */
static int
stop_at_limit(struct file_out *logout, struct log_ctx *lc, const struct densify_stage *last, struct pack *p)
{
	if (o.log)
		file_out_abort(logout);
	msg_info(0, "stopped after %s %ld at the time limit (%.0f s); the same command goes on from %s", last->stage,
	    last->round, cli_elapsed(), o.checkpoint);
	fclose(lc->rows);
	free(lc->rowbuf), free(lc->run);
	pack_free(p);
	return EXIT_STOPPED;
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct file_out logout = {0};
	struct log_ctx lc = {NULL};
	struct densify_stage last;
	struct densify_resume at;
	struct pack p;
	char buf[40], ckname[4096];
	int r, resumed = 0;

	msg_init(argv[0]);
	parse_args(argc, argv, &st);
	read_pack(st.input, &p);
	check_stress(&p);
	if (o.log)
		open_log(&logout, &lc);
	if (o.checkpoint)
		resumed = start_checkpoint(&p, &at, &lc);
	lc.last = cli_elapsed();	/* the first stage's time does not count the reading */
	r = densify_run_resumable(&p, &o.dp, on_stage, &lc, o.checkpoint ? on_checkpoint : NULL, resumed ? &at : NULL,
	    &last);
	cli_progress_end();
	if (r == 2)
		return stop_at_limit(&logout, &lc, &last, &p);
	/* a resumed run's state is the checkpoint's */
	if (resumed && (size_t)snprintf(ckname, sizeof ckname, "%s (resumed)", o.checkpoint) >= sizeof ckname)
		strcpy(ckname, "the checkpoint");
	check_stop(r, &logout, &last, resumed ? ckname : file_display_name(st.input));
	densify_resume_clear(&p);
	pack_unset_meta(&p, CK_CLOCK);
	if (o.checkpoint)
		msg_info(1, "%.0f s of wall time in %ld call%s", lc.before + cli_elapsed(), lc.calls, lc.calls == 1 ? "" : "s");
	num_format(buf, last.sigma_c);
	pack_set_meta(&p, "sigma_c0", buf);
	if (pack_write_tool_with(&p, &tool, &st, o.log ? &logout : NULL))	/* the log closed with it: a log that failed writes no pack */
		msg_die_err(EXIT_DATA);
	/* the run is done: a rerun starts afresh (never the pack or the log just written, even
	 * if a name the checks above could not see through leads there) */
	if (o.checkpoint && !file_same(o.checkpoint, st.output, 0) && !file_same(o.checkpoint, o.log, 0) &&
	    unlink(o.checkpoint) != 0 && errno != ENOENT)
		msg_warn("%s: %s (the checkpoint of a finished run)", o.checkpoint, strerror(errno));
	if (lc.rows)
		fclose(lc.rows);
	free(lc.rowbuf), free(lc.run);
	pack_free(&p);
	return 0;
}
