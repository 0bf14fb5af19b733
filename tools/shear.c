/* SPDX-License-Identifier: GPL-3.0-or-later */
/* shear: simple shear of a pack of spheres or spheroplates between glued walls at constant
 * normal stress, the platy-particle paper's test (dem/plateshear.h), under the pack's contact
 * law or the one --law names (contact/law.h). */
#include "base/cli.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "base/table.h"
#include "base/fileio.h"
#include "base/lines.h"
#include "contact/law.h"
#include "dem/plateshear.h"
#include "pack/pack.h"
#include "pack/packio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <errno.h>
#include <unistd.h>
#include <zlib.h>

#define MAX_SNAPSHOTS 64

static struct opts {
	struct shear_params sp;
	double kn, kt, restitution, mu, wall_mu, kappa;
	const char *law;	/* --law, or NULL: the pack's */
	double Estar, kappa_run;	/* Hertz: the mean grains' E*, and the run's kappa (the header) */
	const char *profile, *snapshots, *prefix, *checkpoint;
	double time_limit, checkpoint_every;
	double snap[MAX_SNAPSHOTS];
	int nsnap;
	long bins;
} o = {
	.bins = 20,
	.kappa = NAN, .kn = NAN, .kt = NAN, .restitution = NAN, .mu = NAN, .wall_mu = NAN,
	.prefix = "shear",
	.checkpoint_every = NAN,	/* 600 s, set once it is known whether it was given */
};

static struct cli_opt opt_table[] = {
	{"strain", 'g', CLI_DOUBLE, &o.sp.strain, "GAMMA", "shear strain x_w / y_w to reach", NULL},
	{"stress", 's', CLI_DOUBLE, &o.sp.sigma_w, "PA", "normal stress on the top wall (default: the pack's meta sigma0)", "Pa"},
	{"kappa", 0, CLI_DOUBLE, &o.kappa, "K", "... or the stiffness number: linear law k_n / (sigma_w r), r the mean spheroradius; Hertz-Mindlin (E* / sigma_w)^(2/3), E* of two mean grains (default: --stress)", NULL},
	{"inertial", 'I', CLI_DOUBLE, &o.sp.inertial, "I", "inertial number gamma_dot r sqrt(rho / sigma_w): sets the wall's velocity (default 1e-3)", NULL},
	{"velocity", 0, CLI_DOUBLE, &o.sp.velocity, "M/S", "... or the wall's velocity v_w outright (default: set by --inertial)", "m/s"},
	{"every", 0, CLI_DOUBLE, &o.sp.every, "DGAMMA", "a row every DGAMMA of strain, each the mean over its steps", NULL},
	{"profile", 0, CLI_STRING, &o.profile, "FILE", "write the velocity profile <v_x>(y)/v_w to FILE (TSV)", NULL},
	{"profile-from", 0, CLI_DOUBLE, &o.sp.profile_from, "GAMMA", "average the profile from this strain on (default: 0.6 x --strain)", NULL},
	{"profile-bins", 0, CLI_LONG, &o.bins, "N", "bins of y / y_w in the profile", NULL},
	{"snapshots", 0, CLI_STRING, &o.snapshots, "G1,G2,...", "write the pack at these strains, to PREFIX-G.pack", NULL},
	{"snapshot-prefix", 0, CLI_STRING, &o.prefix, "PREFIX", "file name prefix of the snapshots", NULL},
	{"law", 0, CLI_STRING, &o.law, "NAME", NULL, NULL},	/* its help from the table: parse_args */
	{"kn", 0, CLI_DOUBLE, &o.kn, "N/M", "linear law: normal stiffness of an element contact (default: the pack's meta kn)", "N/m"},
	{"kt", 0, CLI_DOUBLE, &o.kt, "N/M", "linear law: tangential stiffness (default: the pack's meta kt, else --kn)", "N/m"},
	{"restitution", 0, CLI_DOUBLE, &o.restitution, "E", "restitution coefficient, [0.21, 1] (default: the pack's meta, else 0.6)", NULL},
	{"friction", 0, CLI_DOUBLE, &o.mu, "MU", "grain-grain friction coefficient (default: the pack's)", NULL},
	{"wall-friction", 0, CLI_DOUBLE, &o.wall_mu, "MU", "friction of free grains on the walls (default: the pack's)", NULL},
	{"max-steps", 0, CLI_LONG, &o.sp.max_steps, "N", "give up after N steps", NULL},
	{"relax-tol", 0, CLI_DOUBLE, &o.sp.relax_tol, "TOL", "before the strain, relax at sigma_w until the unbalanced force is below TOL of the mean interaction force; 0: no relaxation", NULL},
	{"start-strain", 0, CLI_DOUBLE, &o.sp.start_strain, "GAMMA", "damp the top wall's normal motion up to this strain; 0: never", NULL},
	{"checkpoint", 0, CLI_STRING, &o.checkpoint, "FILE", "save the run's state to FILE as it goes; go on from FILE if it exists", NULL},
	{"checkpoint-every", 0, CLI_DOUBLE, &o.checkpoint_every, "S", "with --checkpoint: save at the first row S seconds after the last save, 0: at every row (default 600)", "s"},
	{"time-limit", 0, CLI_DOUBLE, &o.time_limit, "S", "with --checkpoint: stop (exit 75) at the last row before S seconds; 0: none", "s"},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"shear", "[options] [FILE]",
	"Simple shear of a pack of spheres or spheroplates between glued walls at constant normal stress, under the pack's contact law (Hertz-Mindlin or linear): a TSV time series of stress ratio, q/p, packing fraction, coordination.",
	opt_table, 1,
};

static void
parse_snapshots(void)
{
	const char *s = o.snapshots;
	char *end;

	if (!s || !*s)
		return;
	for (;;) {
		double g = strtod(s, &end);

		if (end == s || !(g > 0 && isfinite(g))) {
			cli_usage_error("--snapshots: expected positive strains separated by commas, got '%s'", o.snapshots);
			return;
		}
		if (o.nsnap == MAX_SNAPSHOTS) {
			cli_usage_error("--snapshots: at most %d", MAX_SNAPSHOTS);
			return;
		}
		o.snap[o.nsnap++] = g;
		if (*end == 0)
			break;
		if (*end != ',') {
			cli_usage_error("--snapshots: expected positive strains separated by commas, got '%s'", o.snapshots);
			return;
		}
		s = end + 1;
	}
}

/* Before the run (hours for a large pack): -o, the profile and the snapshots can be written,
 * none over another or over the input, and none on the table's standard output (--profile
 * nodir/p.prof failed only after the whole run). */
static void
check_files(const struct cli_state *st)
{
	static char snap[MAX_SNAPSHOTS][4096];
	struct file_role r[5 + MAX_SNAPSHOTS] = {{st->output, "-o", FILE_UPDATE}, {o.profile, "--profile", 1}, {"-", "the table", 1},
	    {st->input, "the input", 0}, {o.checkpoint, "--checkpoint", 1}};
	char g[40];
	int k;

	for (k = 0; k < o.nsnap; k++) {	/* the names on_row writes */
		num_format(g, o.snap[k]);
		snprintf(snap[k], sizeof snap[k], "%s-%s.pack", o.prefix, g);
		r[5 + k].path = snap[k];
		r[5 + k].what = "a snapshot (--snapshot-prefix)";
		r[5 + k].output = 1;
	}
	/* the checkpoint is read back: not standard output */
	if (o.checkpoint && strcmp(o.checkpoint, "-") == 0)
		cli_usage_error("--checkpoint: give it a file of its own, not standard output");
	if (file_roles_check(r, 5 + o.nsnap))
		cli_usage_error("%s", msg_geterr());
}

static void
parse_args(int argc, char **argv, struct cli_state *st)
{
	int k;

	shear_params_default(&o.sp);
	o.sp.profile_from = NAN;
	o.sp.inertial = NAN;
	cli_output_help("write the final pack to FILE (atomically; .gz compresses); the table always goes to stdout");
	{
		static char law_help[512];
		struct cli_opt *opt;

		contact_law_option_help(law_help, sizeof law_help);
		for (opt = opt_table; opt->name; opt++)
			if (!strcmp(opt->name, "law"))
				opt->help = law_help;
	}
	cli_parse(&tool, argc, argv, st);
	if (!(o.sp.strain > 0 && o.sp.strain <= 100))
		cli_usage_error("--strain: must be in (0, 100]");
	if (!(o.sp.sigma_w == 0 || (o.sp.sigma_w > 0 && isfinite(o.sp.sigma_w))))
		cli_usage_error("--stress: must be positive");
	if (!isnan(o.sp.inertial) && !(o.sp.inertial > 0 && o.sp.inertial <= 0.1))
		cli_usage_error("--inertial: must be in (0, 0.1] (the quasi-static regime is I << 1)");
	if (!(o.sp.velocity >= 0 && isfinite(o.sp.velocity)))
		cli_usage_error("--velocity: must be positive");
	if (!isnan(o.sp.inertial) && o.sp.velocity > 0)
		cli_usage_error("--inertial and --velocity: give one");
	if (!isnan(o.kappa) && !(o.kappa > 0 && isfinite(o.kappa)))
		cli_usage_error("--kappa: must be positive");
	if (!isnan(o.kappa) && o.sp.sigma_w > 0)
		cli_usage_error("--stress and --kappa: give one");
	if (o.law && !contact_law_choose(NULL, o.law))
		cli_usage_error("--law: %s", msg_geterr());
	if (!(o.sp.every > 0 && o.sp.every <= o.sp.strain))
		cli_usage_error("--every: must be in (0, --strain]");
	if (!isnan(o.sp.profile_from) && !(o.sp.profile_from >= 0))
		cli_usage_error("--profile-from: must be non-negative");
	if (o.bins < 2 || o.bins > 10000)
		cli_usage_error("--profile-bins: must be in [2, 10000]");
	if (!isnan(o.kn) && !(o.kn > 0 && isfinite(o.kn)))
		cli_usage_error("--kn: must be positive");
	if (!isnan(o.kt) && !(o.kt >= 0 && isfinite(o.kt)))
		cli_usage_error("--kt: must be non-negative");
	if (!isnan(o.restitution) && !(o.restitution >= 0.21 && o.restitution <= 1))
		cli_usage_error("--restitution: must be in [0.21, 1]");
	if ((!isnan(o.mu) && !(o.mu >= 0 && o.mu <= 10)) || (!isnan(o.wall_mu) && !(o.wall_mu >= 0 && o.wall_mu <= 10)))
		cli_usage_error("--friction and --wall-friction: must be in [0, 10]");
	if (o.sp.max_steps < 1)
		cli_usage_error("--max-steps: must be positive");
	if (!(o.sp.relax_tol >= 0 && o.sp.relax_tol < 1))
		cli_usage_error("--relax-tol: must be in [0, 1)");
	if (!(o.sp.start_strain >= 0 && o.sp.start_strain <= 100))
		cli_usage_error("--start-strain: must be in [0, 100]");
	if (!(o.time_limit >= 0 && isfinite(o.time_limit)))
		cli_usage_error("--time-limit: must be a number of seconds, 0 or more");
	if (!isnan(o.checkpoint_every) && !(o.checkpoint_every >= 0 && isfinite(o.checkpoint_every)))
		cli_usage_error("--checkpoint-every: must be a number of seconds, 0 or more");
	if (!isnan(o.checkpoint_every) && !o.checkpoint)
		cli_usage_error("--checkpoint-every needs --checkpoint (where the state goes)");
	if (!isnan(o.sp.profile_from) && o.sp.profile_from >= o.sp.strain && o.sp.strain > 0)
		cli_usage_error("--profile-from: %g is not below --strain %g (the profile would have no sample)", o.sp.profile_from,
		    o.sp.strain);
	if (o.time_limit > 0 && !o.checkpoint)
		cli_usage_error("--time-limit needs --checkpoint (where the state goes)");
	parse_snapshots();
	for (k = 0; k < o.nsnap; k++)
		if (o.sp.strain > 0 && o.snap[k] > o.sp.strain) {
			cli_usage_error("--snapshots: %g is beyond --strain %g (the run never reaches it)", o.snap[k], o.sp.strain);
			break;
		}
	check_files(st);
	cli_usage_done();
	if (isnan(o.checkpoint_every))
		o.checkpoint_every = 600;
	o.sp.profile_bins = (int)o.bins;
	if (isnan(o.sp.inertial))
		o.sp.inertial = 1e-3;
	/* the steady state of P: the last 40 % of the strain */
	if (isnan(o.sp.profile_from))
		o.sp.profile_from = 0.6 * o.sp.strain;
}

/* The contact law and its constants (plateshear_choose_law): --law, else the pack's; the
 * output pack and the snapshots record them.  Hertz: the mean grains' E* and the run's kappa
 * for the header. */
static void
set_law(struct pack *p, const char *in)
{
	struct shear_law_choice ch = {o.law, o.kn, o.kt, o.restitution, o.mu, o.wall_mu, o.kappa};
	const struct contact_law *law;
	int r = plateshear_choose_law(p, &ch, &o.sp, &law);

	if (r)
		msg_die(r == -2 ? EXIT_USAGE : EXIT_DATA, "%s: %s", in, msg_geterr());
	o.kn = o.sp.dyn.kn, o.kt = o.sp.dyn.kt, o.restitution = o.sp.dyn.restitution;
	o.mu = o.sp.dyn.mu, o.wall_mu = o.sp.dyn.wall_mu;
	if (law->stiffness == LAW_MODULI) {
		o.Estar = engine_mean_Estar(p);
		o.kappa_run = engine_kappa(p, &o.sp.dyn, o.sp.sigma_w);
	}
}

/* The run: its table so far (also kept in a memory stream for the checkpoint, whose next
 * call prints it again, so that its standard output is the whole table), the snapshots, the
 * checkpoint's clock. */
struct run_ctx {
	struct pack *p;
	const struct shear_result *res;
	const struct cli_state *st;
	int next_snap;
	time_t start;
	long rows;
	FILE *table;
	char *tablebuf;
	size_t tablelen;
	char *run;		/* what a checkpoint must match (cli_run_identity) */
	double last_row, last_save, longest, longest_save;	/* s since the start (cli_elapsed); the longest row and save in any call */
	double before;		/* the wall time of the earlier calls (s) */
	long calls;
	double gamma;		/* the last row's strain */
	int replay;		/* going on from a checkpoint: its table is printed before the next row */
};

/* The checkpoint's first lines (then plateshear_state_write's, then the checksum line
 * "checksum crc32 X", X zlib's CRC-32 of every byte before it).  Version 1 had no checksum:
 * it is refused, with a word to start afresh. */
#define CK_MAGIC "qusgm-shear-checkpoint 2"
#define CK_MAGIC_1 "qusgm-shear-checkpoint 1"

static const struct table_col cols[] = {
	{"step", NULL}, {"time", "s"}, {"gamma", NULL}, {"tau_sigma", NULL}, {"sigma_ratio", NULL}, {"qp", NULL},
	{"p", "Pa"}, {"q", "Pa"}, {"sig_xx", "Pa"}, {"sig_yy", "Pa"}, {"sig_zz", "Pa"}, {"sig_xy", "Pa"},
	{"sig_xz", "Pa"}, {"sig_yz", "Pa"}, {"phi", NULL}, {"Z", NULL}, {"elements", NULL}, {"height", "m"},
};
#define NCOLS ((int)(sizeof cols / sizeof cols[0]))

static void
print_header(FILE *fp, double inertial)
{
	fprintf(fp, "## qusgm shear %s: simple shear along x, walls on y (the bottom fixed, the top at sigma_w), x and z periodic\n",
	    QUSGM_VERSION);
	if (o.sp.dyn.law->stiffness == LAW_SPRING)
		fprintf(fp, "## sigma_w %g Pa, I %g, mu %g, wall mu %g, %s law, kn %g N/m, kt %g N/m, e %g; each row the mean over its steps; "
		       "sig_* the pair stress of P eq. 7, q/p in the xy plane\n",
		    o.sp.sigma_w, inertial, o.mu, o.wall_mu, o.sp.dyn.law->name, o.kn, o.kt, o.restitution);
	else
		fprintf(fp, "## sigma_w %g Pa, I %g, mu %g, wall mu %g, %s law, E* %g Pa, kappa (E*/sigma_w)^(2/3) %g, kt/kn %g, e %g; "
		       "each row the mean over its steps; sig_* the pair stress of P eq. 7, q/p in the xy plane\n",
		    o.sp.sigma_w, inertial, o.mu, o.wall_mu, o.sp.dyn.law->name, o.Estar, o.kappa_run, o.sp.dyn.kt / o.sp.dyn.kn,
		    o.restitution);
	table_header(fp, cols, NCOLS);
}


/* A snapshot: the state as a pack, with its strain in meta shear_gamma and this run's
 * history line, to PREFIX-G.pack (atomically). */
static int
write_snapshot(struct run_ctx *c, struct engine *d, double gamma, const char *path)
{
	char buf[40];
	struct cli_state st = *c->st;
	int r;

	if (plateshear_snapshot(d, c->p))
		return -1;
	num_format(buf, gamma);
	if (pack_set_meta(c->p, "shear_gamma", buf))
		return -1;
	st.output = path;
	r = pack_write_tool(c->p, &tool, &st);
	/* the history line belongs to this file only */
	free(c->p->history[--c->p->nhist]);
	return r;
}

static void write_profile(const double *mean, const double *n, double to, struct file_out *out);

static int
on_row(const struct shear_row *row, struct engine *d, void *vc)
{
	struct run_ctx *c = vc;
	double v[NCOLS] = {(double)row->step, row->time, row->gamma, row->tau_ratio, row->sigma_ratio, row->qp, row->p,
	    row->q, row->sig[0], row->sig[1], row->sig[2], row->sig[3], row->sig[4], row->sig[5], row->phi, row->z,
	    row->elements, row->height};

	if (c->replay) {	/* only now that the state read back: a bad checkpoint writes nothing */
		fflush(c->table);
		fwrite(c->tablebuf, 1, c->tablelen, stdout);
		c->replay = 0;
	}
	if (c->rows == 0) {	/* only now: a run that fails to start writes nothing */
		print_header(stdout, c->res->inertial);	/* the run's, also under --velocity */
		if (c->table)
			print_header(c->table, c->res->inertial);
	}
	table_row(stdout, v, NCOLS);
	fflush(stdout);	/* a series can be followed while it grows */
	if (c->table)
		table_row(c->table, v, NCOLS);
	c->rows++;
	c->gamma = row->gamma;
	while (c->next_snap < o.nsnap && row->gamma >= o.snap[c->next_snap]) {
		char path[4096], g[40];

		num_format(g, o.snap[c->next_snap]);
		snprintf(path, sizeof path, "%s-%s.pack", o.prefix, g);
		if (write_snapshot(c, d, row->gamma, path))
			return -1;
		c->next_snap++;
	}
	cli_progress_stage("shear");
	cli_progress_frac(row->gamma / o.sp.strain);	/* the bar and the ETA (cli.h) */
	/* the profile so far, as the run goes (kept when it stops or is killed); the end writes
	 * it again, to the strain reached, with the pack */
	if (o.profile && row->gamma >= o.sp.profile_from && row->gamma < o.sp.strain) {
		struct file_out out;
		double *mean = malloc((size_t)o.sp.profile_bins * sizeof *mean);
		int b, r;

		if (!mean)
			return -1;
		for (b = 0; b < o.sp.profile_bins; b++)	/* as plateshear_run makes res->profile */
			mean[b] = row->profile_n[b] > 0 ? row->profile_sum[b] / row->profile_n[b] : NAN;
		write_profile(mean, row->profile_n, row->gamma, &out);
		r = file_out_commit(&out);
		free(mean);
		if (r)
			return -1;
	}
	cli_progress("step %ld gamma %.3f of %g: tau/sigma %.3f  q/p %.3f  phi %.4f  Z %.2f", (long)row->step, row->gamma,
	    o.sp.strain, row->tau_ratio, row->qp, row->phi, row->z);
	return 0;
}

/* zlib's CRC-32 of n bytes, in pieces that fit its uInt */
static unsigned long
ck_crc_more(unsigned long crc, const char *b, size_t n)
{
	while (n > 0) {
		uInt k = n > (1u << 30) ? (1u << 30) : (uInt)n;

		crc = crc32(crc, (const Bytef *)b, k);
		b += k, n -= k;
	}
	return crc;
}

static unsigned long
ck_crc(const char *b, size_t n)
{
	return ck_crc_more(crc32(0, Z_NULL, 0), b, n);
}

/* The checkpoint's checksum, before anything of it is used: its last line "checksum crc32
 * X", X the CRC-32 of every byte before it (read as lines: plain or gzip alike).  A
 * checkpoint changed or damaged by a single byte, or cut short, is refused with its name;
 * so is one of version 1, which had no checksum. */
static void
ck_verify(const char *path)
{
	struct lines *in = lines_open_path(path);
	unsigned long crc = crc32(0, Z_NULL, 0), before = crc, want;
	char first[64] = "", last[64] = "", *line;
	size_t len;
	long n = 0;
	int r, k = 0;

	if (!in)
		msg_die_err(EXIT_DATA);
	while ((r = lines_next(in, &line, &len)) == 1) {
		before = crc;
		crc = ck_crc_more(crc, line, len);
		if (lines_newline(in))
			crc = ck_crc_more(crc, "\n", 1);
		snprintf(n++ ? last : first, sizeof last, "%.*s", (int)(len < 63 ? len : 63), line);
		if (n == 1)
			strcpy(last, first);
	}
	if (r < 0)
		msg_die_err(EXIT_DATA);
	lines_close(in);
	if (strcmp(first, CK_MAGIC_1) == 0)
		msg_die(EXIT_DATA, "%s: the checkpoint of an earlier qusgm (version 1, without a checksum): remove it to start the run afresh",
		    path);
	if (strcmp(first, CK_MAGIC) != 0)
		msg_die(EXIT_DATA, "%s:1: not a shear checkpoint (no '%s')", path, CK_MAGIC);
	if (sscanf(last, "checksum crc32 %8lx%n", &want, &k) != 1 || last[k] || k != 23)
		msg_die(EXIT_DATA, "%s:%ld: the checkpoint ends without its checksum line (cut short?): remove it to start the run afresh",
		    path, n);
	if (want != before)
		msg_die(EXIT_DATA, "%s:%ld: the checksum does not match (CRC-32 %08lx of the bytes before it): the checkpoint was "
		    "changed or damaged; remove it to start the run afresh", path, n, before);
}

/* After a row: the state to the checkpoint (atomically) when --checkpoint-every seconds
 * have passed since the last save, or when the next row, taken as long as the longest so
 * far in any call and followed by a save as long as the longest, would end past
 * --time-limit; then stop (1) if it would.  Each call so runs at least one row.  When the
 * state is saved does not change the run: it goes on from any row to the same bytes. */
static int
on_checkpoint(const struct shear_state *ss, void *vc)
{
	struct run_ctx *c = vc;
	double now = cli_elapsed(), wrote;
	struct file_out out;
	FILE *mem;
	char *buf = NULL;
	size_t len = 0;
	int past;

	c->longest = fmax(c->longest, now - c->last_row);
	c->last_row = now;
	past = o.time_limit > 0 && now + c->longest + c->longest_save > o.time_limit;
	if (!past && now - c->last_save < o.checkpoint_every)
		return 0;
	if (fflush(c->table) || !(mem = open_memstream(&buf, &len)))
		return -1;
	/* the whole in memory first, for its checksum */
	fprintf(mem, "%s\nrun %s\nclock %.3f %.3f %.3f %ld\nsnapshots %d\nrows %ld %a\ntable %zu\n", CK_MAGIC, c->run,
	    c->longest, c->longest_save, c->before + now, c->calls, c->next_snap, c->rows, c->gamma, c->tablelen);
	fwrite(c->tablebuf, 1, c->tablelen, mem);
	if (plateshear_state_write(ss, mem) || fclose(mem)) {
		free(buf);
		return -1;
	}
	if (file_out_open(&out, o.checkpoint)) {
		free(buf);
		return -1;
	}
	fwrite(buf, 1, len, out.fp);
	fprintf(out.fp, "checksum crc32 %08lx\n", ck_crc(buf, len));
	free(buf);
	if (file_out_commit(&out)) {
		file_out_abort(&out);
		return -1;
	}
	wrote = cli_elapsed();
	c->longest_save = fmax(c->longest_save, wrote - now);
	c->last_save = wrote;
	return o.time_limit > 0 && wrote + c->longest + c->longest_save > o.time_limit;
}

/* The checkpoint's preamble, when the file exists: the table so far printed again, and a
 * reader left at the run's state (NULL when there is no checkpoint). */
static struct lines *
resume_from(struct run_ctx *c)
{
	struct lines *in;
	char *line, *end;
	size_t len, tlen;
	int k;

	if (access(o.checkpoint, F_OK) != 0) {
		if (errno != ENOENT)
			msg_die(EXIT_DATA, "%s: %s", o.checkpoint, strerror(errno));
		return NULL;
	}
	ck_verify(o.checkpoint);
	if (!(in = lines_open_path(o.checkpoint)))
		msg_die_err(EXIT_DATA);
	if (lines_next(in, &line, NULL) != 1 || strcmp(line, CK_MAGIC) != 0)
		msg_die(EXIT_DATA, "%s:1: not a shear checkpoint (no '%s')", o.checkpoint, CK_MAGIC);
	if (lines_next(in, &line, NULL) != 1 || strncmp(line, "run ", 4) != 0 || strcmp(line + 4, c->run) != 0)
		msg_die(EXIT_DATA, "%s: the checkpoint of another run (other options or another input): remove it to start afresh",
		    o.checkpoint);
	if (lines_next(in, &line, NULL) != 1 ||
	    sscanf(line, "clock %lg %lg %lg %ld %n", &c->longest, &c->longest_save, &c->before, &c->calls, &k) != 4 ||
	    line[k] || !(c->longest >= 0 && c->longest_save >= 0 && c->before >= 0) || c->calls < 1)
		msg_die(EXIT_DATA, "%s:%ld: expected 'clock LONGEST_ROW LONGEST_SAVE WALL CALLS'", o.checkpoint, lines_lineno(in));
	if (lines_next(in, &line, NULL) != 1 || sscanf(line, "snapshots %d %n", &c->next_snap, &k) != 1 || line[k] ||
	    c->next_snap < 0 || c->next_snap > o.nsnap)
		msg_die(EXIT_DATA, "%s:%ld: expected 'snapshots K' (the snapshots written)", o.checkpoint, lines_lineno(in));
	if (lines_next(in, &line, NULL) != 1 || sscanf(line, "rows %ld %lg %n", &c->rows, &c->gamma, &k) != 2 || line[k] || c->rows < 1 ||
	    !(c->gamma > 0 && c->gamma < o.sp.strain))
		msg_die(EXIT_DATA, "%s:%ld: expected 'rows N GAMMA' (the rows so far, the last one's strain)", o.checkpoint,
		    lines_lineno(in));
	if (lines_next(in, &line, NULL) != 1 || strncmp(line, "table ", 6) != 0 ||
	    (tlen = strtoul(line + 6, &end, 10), *end))
		msg_die(EXIT_DATA, "%s:%ld: expected 'table BYTES'", o.checkpoint, lines_lineno(in));
	while (tlen > 0) {	/* the table's lines, as printed */
		if (lines_next(in, &line, &len) != 1 || len + 1 > tlen)
			msg_die(EXIT_DATA, "%s:%ld: the table ends early", o.checkpoint, lines_lineno(in));
		fprintf(c->table, "%s\n", line);
		tlen -= len + 1;
	}
	c->replay = 1;
	c->calls++;
	msg_info(1, "going on from %s, at gamma %g (call %ld)", o.checkpoint, c->gamma, c->calls);
	return in;
}

/* The profile up to strain `to` into out, uncommitted: each bin's mean (NaN where it saw no
 * grain) and samples. */
static void
write_profile(const double *mean, const double *n, double to, struct file_out *out)
{
	static const struct table_col pc[] = {{"y_over_yw", NULL}, {"vx_over_vw", NULL}, {"samples", NULL}};
	int b;

	if (file_out_open(out, o.profile))
		msg_die_err(EXIT_DATA);
	fprintf(out->fp, "## shear: <v_x>(y) / v_w over every grain, from gamma %g to %g, every 10 steps\n", o.sp.profile_from,
	    to);
	table_header(out->fp, pc, 3);
	for (b = 0; b < o.sp.profile_bins; b++) {
		double v[3] = {(b + 0.5) / o.sp.profile_bins, mean[b], n[b]};
		table_row(out->fp, v, 3);
	}
}

/* The checkpoint's table and identity; the checkpoint to go on from, or NULL (none yet). */
static struct lines *
start_checkpoint(struct run_ctx *c)
{
	/* where output goes, when to stop or save, and the snapshots' names change no row */
	static const char *const skip[] = {"checkpoint", "checkpoint-every", "time-limit", "profile", "snapshot-prefix", NULL};
	char id[64];

	if (!(c->table = open_memstream(&c->tablebuf, &c->tablelen)))
		msg_die(EXIT_DATA, "out of memory");
	pack_checksum(c->p, id, sizeof id);
	c->run = cli_run_identity(&tool, skip, id);
	return resume_from(c);
}

/* The end of a finished run: the profile and the pack, all or none; then the checkpoint,
 * which would only start the run again at its last save, goes. */
static void
write_outputs(struct pack *p, const struct cli_state *st, const struct shear_result *res)
{
	struct file_out profout, packout;
	char buf[40];

	if (o.profile)
		write_profile(res->profile, res->profile_n, o.sp.strain, &profout);
	if (st->output) {
		num_format(buf, o.sp.strain);
		if (pack_set_meta(p, "shear_gamma", buf) || pack_write_tool_out(p, &tool, st, &packout)) {
			if (o.profile)
				file_out_abort(&profout);
			msg_die_err(EXIT_DATA);
		}
	}
	{
		struct file_out *outs[2] = {o.profile ? &profout : NULL, st->output ? &packout : NULL};
		if (file_out_commit_all(outs, 2))
			msg_die_err(EXIT_DATA);
	}
	if (o.checkpoint && remove(o.checkpoint) != 0 && errno != ENOENT)
		msg_warn("%s: %s (the run is done; remove it)", o.checkpoint, strerror(errno));
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct pack p;
	struct shear_result res;
	struct run_ctx c = {&p, &res, &st, 0, 0, 0, NULL, NULL, 0, NULL, 0, 0, 0, 0, 0, 1, 0, 0};
	struct lines *from = NULL;
	const char *in;
	int r;

	msg_init(argv[0]);
	parse_args(argc, argv, &st);
	in = file_display_name(st.input);
	if (pack_read_path(st.input, &p))
		msg_die_err(EXIT_DATA);
	set_law(&p, in);
	if (o.checkpoint)
		from = start_checkpoint(&c);
	c.start = time(NULL);
	r = plateshear_run_resumable(&p, &o.sp, on_row, &c, o.checkpoint ? on_checkpoint : NULL, from, &res);
	if (from)
		lines_close(from);
	if (r == -2)	/* the checkpoint's own file:line message */
		msg_die_err(EXIT_DATA);
	if (r < 0)
		msg_die(EXIT_DATA, "%s: %s", in, msg_geterr());
	cli_progress_end();
	if (r == 2) {
		msg_info(0, "stopped at gamma %g at the time limit (%.0f s); the same command goes on from %s", c.gamma,
		    cli_elapsed(), o.checkpoint);
		fclose(c.table);
		free(c.tablebuf), free(c.run);
		pack_free(&p);
		return EXIT_STOPPED;
	}
	if (res.relax_steps)
		msg_info(1, "relaxed at sigma_w in %ld steps: packing fraction %.4f, coordination %.3f (walls counted once)",
		    res.relax_steps, res.relax_phi, res.relax_z);
	msg_info(1, "%zu grains glued to the bottom, %zu to the top; v_w %.4g m/s, gamma_dot %.4g 1/s, I %.4g, kappa %.4g; %ld rows",
	    res.glued_bottom, res.glued_top, res.v_w, res.gamma_dot, res.inertial, res.kappa, c.rows);
	write_outputs(&p, &st, &res);
	if (c.table)
		fclose(c.table);
	free(c.tablebuf), free(c.run);
	shear_result_free(&res);
	pack_free(&p);
	return 0;
}
