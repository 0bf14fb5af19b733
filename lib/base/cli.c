/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cli: option tables, help, history line, progress (see cli.h). */
#include "base/cli.h"
#include "base/par.h"
#include "base/msg.h"
#include "base/fileio.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

/* The Makefile defines it for this file alone (its objects depend on build/source-version) */
#ifndef QUSGM_SOURCE_VERSION
#define QUSGM_SOURCE_VERSION QUSGM_VERSION
#endif

const char *
cli_source_version(void)
{
	return QUSGM_SOURCE_VERSION;
}

static int usage_errors;
static char *argv_text_owned;

static void
free_argv_text(void)
{
	free(argv_text_owned);
}

static int help_flag, version_flag;
static const char *output_path;
static int verbose_count, quiet_flag;
static long threads_opt;

static const char *output_help;	/* cli_output_help */

void
cli_output_help(const char *help)
{
	output_help = help;
}

static struct cli_opt common_opts[] = {
	{"output", 'o', CLI_STRING, &output_path, "FILE", "write to FILE (atomically) instead of stdout; .gz compresses", NULL},
	{"verbose", 'v', CLI_FLAG, &verbose_count, NULL, "report progress on stderr, also when it is not a terminal", NULL},
	{"threads", 0, CLI_LONG, &threads_opt, "N", "threads (0: OMP_NUM_THREADS, else the cores this process may use less those busy at the start); same results for any N", NULL},
	{"quiet", 'q', CLI_FLAG, &quiet_flag, NULL, "no warnings or progress", NULL},
	{"help", 'h', CLI_FLAG, &help_flag, NULL, "print this help and exit", NULL},
	{"version", 'V', CLI_FLAG, &version_flag, NULL, "print the version and exit", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

void
cli_usage_error(const char *fmt, ...)
{
	va_list ap;

	fprintf(stderr, "%s: ", msg_progname);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	/* one line per error (architecture.md, "Conventions"): the hint goes on the same line */
	fprintf(stderr, " (try '%s --help')\n", msg_progname);
	usage_errors++;
}

void
cli_usage_done(void)
{
	if (usage_errors)
		exit(EXIT_USAGE);
}

static size_t
count_opts(const struct cli_opt *o)
{
	size_t n = 0;

	while (o && o[n].type != CLI_END)
		n++;
	return n;
}

static void
format_value(const struct cli_opt *o, char *buf, size_t len)
{
	switch (o->type) {
	case CLI_FLAG:
		snprintf(buf, len, "%s", *(int *)o->dest ? "on" : "off");
		break;
	case CLI_LONG:
		snprintf(buf, len, "%ld", *(long *)o->dest);
		break;
	case CLI_DOUBLE:
		snprintf(buf, len, "%.10g", *(double *)o->dest);
		break;
	case CLI_STRING:
		snprintf(buf, len, "%s", *(const char **)o->dest ? *(const char **)o->dest : "");
		break;
	default:
		buf[0] = 0;
	}
}

/* The width --help is wrapped to, and the column an option's text starts at. */
#define HELP_WIDTH 80
#define HELP_TEXT_COL 31
/* Within a word of print_wrapped, printed as a space: "[default: X]" stays on one line. */
#define HELP_NBSP '\001'

/* text from column col (the cursor's), wrapped at HELP_WIDTH between words, continuation
 * lines starting at column indent; a word longer than a line stands alone on its own. */
static void
print_wrapped(const char *text, int col, int indent)
{
	const char *w = text;

	while (*w) {
		const char *e = w;
		int len;

		while (*e && *e != ' ')
			e++;
		len = (int)(e - w);
		if (col > indent && col + 1 + len > HELP_WIDTH) {
			printf("\n%*s", indent, "");
			col = indent;
		} else if (w != text) {
			putchar(' ');
			col++;
		}
		for (; w < e; w++)	/* HELP_NBSP: a space the line does not break at */
			putchar(*w == HELP_NBSP ? ' ' : *w);
		col += len;
		while (*e == ' ')
			e++;
		w = e;
	}
	putchar('\n');
}

static void
print_opt(const struct cli_opt *o, int show_default)
{
	char left[96], def[128], text[1024];
	size_t at;

	if (o->shortname)
		snprintf(left, sizeof left, "-%c, --%s%s%s", o->shortname, o->name,
		    o->arg ? " " : "", o->arg ? o->arg : "");
	else
		snprintf(left, sizeof left, "    --%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
	at = (size_t)snprintf(text, sizeof text, "%s", o->help);
	if (o->unit && at < sizeof text)
		at += (size_t)snprintf(text + at, sizeof text - at, " (%s)", o->unit);
	/* One statement of the default: a help text that says it ("(default: the pack's)",
	 * "(default 1e-3)") gets no bracket, whatever the variable holds before the tool
	 * resolves it; a nan double is "not given", which is none unless the text says more. */
	if (!show_default || strstr(o->help, "(default") || at >= sizeof text) {
		/* said, or not to be said */
	} else if (o->type == CLI_DOUBLE && isnan(*(double *)o->dest)) {
		snprintf(text + at, sizeof text - at, " [default:%cnone]", HELP_NBSP);
	} else if (o->type != CLI_FLAG) {
		format_value(o, def, sizeof def);
		if (def[0])
			snprintf(text + at, sizeof text - at, " [default:%c%s]", HELP_NBSP, def);
	}
	/* an option name too long for its column gets a line of its own */
	if (strlen(left) > HELP_TEXT_COL - 3) {
		printf("  %s\n%*s", left, HELP_TEXT_COL, "");
	} else {
		printf("  %-28s ", left);
	}
	print_wrapped(text, HELP_TEXT_COL, HELP_TEXT_COL);
}

static void
print_help(const struct cli_tool *t)
{
	size_t i, n = count_opts(t->opts);
	int col = printf("Usage: %s ", t->name);

	print_wrapped(t->usage, col, col);
	print_wrapped(t->purpose, 0, 0);
	printf("\nOptions:\n");
	for (i = 0; i < n; i++)
		print_opt(&t->opts[i], 1);
	for (i = 0; common_opts[i].type != CLI_END; i++) {
		struct cli_opt o = common_opts[i];

		if (o.shortname == 'o' && output_help)
			o.help = output_help;
		print_opt(&o, 0);
	}
	/* a tool without operands (packgen) reads no input */
	printf("\n%s", t->max_operands > 0 ? "FILE '-' or no FILE reads standard input; .gz input is detected.\n" : "");
	printf("Exit status: 0 success, 1 bad data or failure, 2 usage error.\n"
	    "See %s(1) and qusgm-pack(5).\n", t->name);
}

static int
parse_value(const struct cli_opt *o, const char *arg)
{
	char *end;

	switch (o->type) {
	case CLI_FLAG:
		(*(int *)o->dest)++;
		return 0;
	case CLI_LONG: {
		long v;
		errno = 0;
		v = strtol(arg, &end, 10);
		if (errno || end == arg || *end) {
			cli_usage_error("--%s: '%s' is not an integer", o->name, arg);
			return -1;
		}
		*(long *)o->dest = v;
		return 0;
	}
	case CLI_DOUBLE: {
		double v;
		errno = 0;
		v = strtod(arg, &end);
		if (errno == ERANGE || end == arg || *end || !isfinite(v)) {
			cli_usage_error("--%s: '%s' is not a finite number", o->name, arg);
			return -1;
		}
		*(double *)o->dest = v;
		return 0;
	}
	case CLI_STRING:
		*(const char **)o->dest = arg;
		return 0;
	default:
		return -1;
	}
}

static char *
shell_quote_argv(int argc, char **argv)
{
	size_t len = 1;
	int i;
	char *s, *p;

	for (i = 0; i < argc; i++)
		len += 4 * strlen(argv[i]) + 3;
	s = p = malloc(len);
	if (!s)
		msg_die(EXIT_DATA, "out of memory");
	for (i = 0; i < argc; i++) {
		const char *a = i == 0 ? msg_progname : argv[i];
		int plain = *a != 0;
		const char *c;

		/* The output name is left out: where the bytes go must not change them. */
		if (i > 0 && (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0)) {
			i++;
			continue;
		}
		if (i > 0 && (strncmp(a, "--output=", 9) == 0 || (a[0] == '-' && a[1] == 'o' && a[2])))
			continue;

		for (c = a; *c; c++)
			if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.,:=+/@%", *c))
				plain = 0;
		if (i)
			*p++ = ' ';
		if (plain) {
			p += sprintf(p, "%s", a);
			continue;
		}
		*p++ = '\'';
		for (c = a; *c; c++) {
			if (*c == '\'') {
				memcpy(p, "'\\''", 4);
				p += 4;
			} else if (*c == '\n' || *c == '\r') {
				*p++ = ' ';	/* history is one line, read back as written */
			} else {
				*p++ = *c;
			}
		}
		*p++ = '\'';
	}
	*p = 0;
	return s;
}

/* getopt_long's view of the tool's table followed by the common options: lo[i] returns
 * 256 + i, map[i] is the option it stands for, and shortopts lists the short names. */
struct getopt_table {
	struct option *lo;
	const struct cli_opt **map;
	size_t n;
	char shortopts[256];
};

static void
getopt_table_build(struct getopt_table *g, const struct cli_tool *t)
{
	size_t n = count_opts(t->opts), i;

	g->n = n + count_opts(common_opts);
	g->lo = calloc(g->n + 1, sizeof *g->lo);
	g->map = calloc(g->n, sizeof *g->map);
	if (!g->lo || !g->map)
		msg_die(EXIT_DATA, "out of memory");
	strcpy(g->shortopts, ":");
	for (i = 0; i < g->n; i++) {
		const struct cli_opt *o = i < n ? &t->opts[i] : &common_opts[i - n];
		int has_arg = o->type == CLI_FLAG ? no_argument : required_argument;

		g->map[i] = o;
		g->lo[i].name = o->name;
		g->lo[i].has_arg = has_arg;
		g->lo[i].flag = NULL;
		g->lo[i].val = 256 + (int)i;
		if (o->shortname) {
			size_t l = strlen(g->shortopts);
			g->shortopts[l] = (char)o->shortname;
			if (has_arg == required_argument)
				g->shortopts[++l] = ':';
			g->shortopts[l + 1] = 0;
		}
	}
}

/* Every option of argv stored through its table entry; each bad one reported. */
static void
getopt_table_run(const struct getopt_table *g, int argc, char **argv)
{
	int c, idx;
	size_t i;

	opterr = 0;
	while ((c = getopt_long(argc, argv, g->shortopts, g->lo, &idx)) != -1) {
		const struct cli_opt *o = NULL;

		if (c >= 256) {
			o = g->map[c - 256];
		} else if (c == '?') {
			if (optopt >= 256 || optopt == 0)
				cli_usage_error("unknown option '%s'", argv[optind - 1]);
			else
				cli_usage_error("unknown option '-%c'", optopt);
			continue;
		} else if (c == ':') {
			cli_usage_error("option '%s' needs an argument", argv[optind - 1]);
			continue;
		} else {
			for (i = 0; i < g->n; i++)
				if (g->map[i]->shortname == c)
					o = g->map[i];
		}
		if (o)
			parse_value(o, optarg);
	}
}

static void progress_start(void);

/* The most threads: --threads and OMP_NUM_THREADS alike (a thread's stack and its share of the
 * neighbour list's buffers are reserved up front; 5000 threads took 4 GB). */
#define THREADS_MAX 4096

/* OMP_NUM_THREADS, the count when --threads is 0, held to --threads' range: a number from 1 to
 * THREADS_MAX, with blanks around it and, as OpenMP allows, a list of counts for nested
 * levels after a comma (only the first is used).  Anything else is a usage error that names
 * the variable (the runtime itself warned of a value it cannot read and went on with its
 * default; 100000 was taken and failed later as "out of memory for the neighbour list"). */
static void
omp_num_threads_check(void)
{
	const char *env = getenv("OMP_NUM_THREADS"), *c;
	char typed[48];
	unsigned long n = 0;
	size_t k;
	int digits = 0;

	if (!env)
		return;
	for (c = env; *c == ' ' || *c == '\t'; c++)
		;
	for (; *c >= '0' && *c <= '9'; c++, digits++)
		n = n > THREADS_MAX ? n : 10 * n + (unsigned long)(*c - '0');
	while (*c == ' ' || *c == '\t')
		c++;
	if (digits && (*c == 0 || *c == ',') && n >= 1 && n <= THREADS_MAX)
		return;
	/* the value as typed, on one line and not too long */
	for (k = 0; env[k] && k + 4 < sizeof typed; k++)
		typed[k] = env[k] >= ' ' && env[k] < 127 ? env[k] : '?';
	strcpy(typed + k, env[k] ? "..." : "");
	cli_usage_error("OMP_NUM_THREADS: expected 1 to %d (the threads when --threads is 0), got '%s'", THREADS_MAX, typed);
}

/* What a tool reads from standard input (cli_input_help), named when that is a terminal. */
static const char *input_help = "a pack";

void
cli_input_help(const char *what)
{
	input_help = what;
}

/* file_in_open's hook: a tool given no file on a terminal would wait without a word. */
static void
stdin_notice(void)
{
	static int said;

	if (said || !isatty(0))
		return;
	said = 1;
	msg_info(0, "reading %s from standard input (Ctrl-D ends it)", input_help);
}

void
cli_parse(const struct cli_tool *t, int argc, char **argv, struct cli_state *st)
{
	struct getopt_table g;

	/* an empty argv[0] (or none) named no one in the messages: the tool's own name instead */
	if (argc < 1 || !argv[0] || !*(strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0]))
		msg_progname = t->name;
	progress_start();	/* the progress line's and the logs' elapsed time */
	getopt_table_build(&g, t);
	memset(st, 0, sizeof *st);
	getopt_table_run(&g, argc, argv);
	free(g.lo);	/* before the exits below: LeakSanitizer counts them otherwise */
	free(g.map);
	if (help_flag || version_flag) {
		if (help_flag)
			print_help(t);
		else
			printf("%s (qusgm) %s\n", t->name, cli_source_version());
		exit(0);
	}
	msg_verbosity = quiet_flag ? -1 : verbose_count;
	if (threads_opt < 0 || threads_opt > THREADS_MAX)
		cli_usage_error("--threads: expected 0 (the default) to %d, got %ld", THREADS_MAX, threads_opt);
	else if (threads_opt == 0)
		omp_num_threads_check();
	/* a usage error exits before any work: no threads for it (a bad OMP_NUM_THREADS is not
	 * handed on) */
	par_set_threads(usage_errors ? 1 : (int)threads_opt);
	file_stdin_hook = stdin_notice;
	file_catch_signals();	/* on this, the main thread; a status line is ended there too */
	msg_info(1, "%d thread%s (--threads)", par_threads(), par_threads() == 1 ? "" : "s");
	st->operands = argv + optind;
	st->noperands = argc - optind;
	if (st->noperands > t->max_operands)
		cli_usage_error("too many operands (at most %d input file%s)", t->max_operands,
		    t->max_operands == 1 ? "" : "s");
	st->input = st->noperands > 0 ? st->operands[0] : NULL;
	st->output = output_path;
	st->argv_text = argv_text_owned = shell_quote_argv(argc, argv);
	atexit(free_argv_text);
}

static int
skipped(const char *name, const char *const *skip)
{
	for (; skip && *skip; skip++)
		if (strcmp(name, *skip) == 0)
			return 1;
	return 0;
}

static char *
resolved_except(const struct cli_tool *t, const char *const *skip)
{
	size_t n = count_opts(t->opts), i, len = 1, used = 0;
	char *s;
	char val[256];

	for (i = 0; i < n; i++) {
		format_value(&t->opts[i], val, sizeof val);
		len += strlen(t->opts[i].name) + strlen(val) + 4;
	}
	s = malloc(len);
	if (!s)
		msg_die(EXIT_DATA, "out of memory");
	s[0] = 0;
	for (i = 0; i < n; i++) {
		/* skipped, or a nan double: not given, and its absence gives it back */
		if (skipped(t->opts[i].name, skip) ||
		    (t->opts[i].type == CLI_DOUBLE && isnan(*(double *)t->opts[i].dest)))
			continue;
		format_value(&t->opts[i], val, sizeof val);
		used += (size_t)sprintf(s + used, "%s--%s=%s", used ? " " : "", t->opts[i].name, val);
	}
	return s;
}

char *
cli_resolved(const struct cli_tool *t)
{
	return resolved_except(t, NULL);
}

char *
cli_run_identity(const struct cli_tool *t, const char *const *skip, const char *input)
{
	char *res = resolved_except(t, skip), *s, *c;
	size_t len = strlen(t->name) + strlen(QUSGM_VERSION) + strlen(input) + strlen(res) + 16;

	if (!(s = malloc(len)))
		msg_die(EXIT_DATA, "out of memory");
	snprintf(s, len, "%s %s %s ; %s", t->name, QUSGM_VERSION, input, res);
	for (c = s; *c; c++)
		if (*c == '\n' || *c == '\r')
			*c = ' ';
	free(res);
	return s;
}

char *
cli_history_line(const struct cli_tool *t, const struct cli_state *st)
{
	char *res = cli_resolved(t), *s, *c;
	size_t len = strlen(t->name) + strlen(cli_source_version()) + strlen(st->argv_text) + strlen(res) + 64;

	s = malloc(len);
	if (!s)
		msg_die(EXIT_DATA, "out of memory");
	/* the thread count is provenance, not an input: it changes no result, but a run's
	 * record says how it was made */
	snprintf(s, len, "%s %s: %s ; %s --threads=%d", t->name, cli_source_version(), st->argv_text, res,
	    par_threads());
	free(res);
	/* one line, without a carriage return, that a pack reader gives back byte for byte */
	for (c = s; *c; c++)
		if (*c == '\n' || *c == '\r')
			*c = ' ';
	return s;
}

/* Progress (cli.h).  The line on a terminal: "TOOL: STAGE  it N  res R  ELAPSED  [bar] P% ETA T
 * | SUMMARY", fitted to the terminal's width so that "\r" redraws it in place: the summary is
 * cut first, then the bar shortened and left out, then the residual, the iterations and the
 * stage, so that the percentage and the ETA stay whole. */
#define PROGRESS_EVERY 0.25	/* s between redraws on a terminal */
#define PROGRESS_PLAIN 10.0	/* s between plain lines inside a stage (-v, not a terminal) */

static void fmt_dur(char *b, size_t n, double s);

/* The status line is on the terminal and not ended: read by the signal handler. */
static volatile sig_atomic_t line_shown;

static struct {
	int init, tty;
	int reported;			/* a line was drawn or printed */
	struct timespec t0;		/* the start (cli_parse) */
	double drawn, printed;		/* when the line was last drawn, or a plain line printed */
	double stage_t0;
	char stage[96];
	int stage_new;			/* a stage began since the last plain line */
	long iters;			/* cli_progress_iter calls in the stage */
	double residual;
	double frac, frac0, frac_t0;	/* the share of the target, the first seen and when */
	char summary[512];
} pg = {.frac = NAN, .frac0 = NAN, .residual = NAN};

static double
now_s(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void
progress_start(void)
{
	clock_gettime(CLOCK_MONOTONIC, &pg.t0);
}

/* A line left on the terminal (a tool that never called cli_progress_end, or an exit in the
 * middle) ends before the shell's prompt. */
static void
progress_at_exit(void)
{
	if (line_shown)
		fputc('\n', stderr);
	line_shown = 0;
}

/* The same on a signal that kills the tool (fileio.c's handler): write(2) alone. */
static void
progress_on_signal(void)
{
	if (line_shown) {
		ssize_t r = write(2, "\n", 1);
		(void)r;
		line_shown = 0;
	}
}

/* At an exit with status 0, after a run that showed its progress (on a terminal, or plain lines
 * with -v): one line that says so, with the run's time and its last summary in full. */
static void
progress_done(int status)
{
	char el[32];

	progress_at_exit();
	if (status != 0 || !pg.reported || msg_verbosity < 0)
		return;
	fmt_dur(el, sizeof el, cli_elapsed());
	if (pg.summary[0] || pg.stage[0])
		fprintf(stderr, "%s: done in %s: %s\n", msg_progname, el, pg.summary[0] ? pg.summary : pg.stage);
	else
		fprintf(stderr, "%s: done in %s\n", msg_progname, el);
	fflush(stderr);
}

#ifdef __GLIBC__
static void
progress_on_exit(int status, void *arg)
{
	(void)arg;
	progress_done(status);
}
#endif

static void
progress_init(void)
{
	if (pg.init)
		return;
	pg.init = 1;
	pg.tty = isatty(2);
	if (pg.tty) {
		msg_before = progress_at_exit;	/* a message ends the line; the next update draws it anew */
		file_signal_hook = progress_on_signal;
	}
	/* the exit status decides the closing line: on_exit gives it (glibc); elsewhere a line
	 * left is ended and no closing line is printed */
#ifdef __GLIBC__
	on_exit(progress_on_exit, NULL);
#else
	atexit(progress_at_exit);
#endif
	if (pg.t0.tv_sec == 0 && pg.t0.tv_nsec == 0)
		clock_gettime(CLOCK_MONOTONIC, &pg.t0);
}

double
cli_elapsed(void)
{
	struct timespec t;
	double s;

	progress_init();
	clock_gettime(CLOCK_MONOTONIC, &t);
	s = (double)(t.tv_sec - pg.t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - pg.t0.tv_nsec);
	return floor(s * 1e3 + 0.5) / 1e3;	/* milliseconds: the clock says no more */
}

int
cli_progress_enabled(void)
{
	if (msg_verbosity < 0)
		return 0;
	progress_init();
	return msg_verbosity > 0 || pg.tty;
}

/* "12s", "3:05", "1:02:05" */
static void
fmt_dur(char *b, size_t n, double s)
{
	long t = isfinite(s) && s > 0 ? (long)(s + 0.5) : 0;

	if (t < 60)
		snprintf(b, n, "%lds", t);
	else if (t < 3600)
		snprintf(b, n, "%ld:%02ld", t / 60, t % 60);
	else
		snprintf(b, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
}

/* The terminal's columns: its window size, else COLUMNS, else 80. */
static int
term_width(void)
{
	struct winsize ws;
	const char *env = getenv("COLUMNS");
	long c;

	if (ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0)
		return ws.ws_col;
	c = env ? strtol(env, NULL, 10) : 0;
	return c > 0 && c < 10000 ? (int)c : 80;
}

/* The bar (bar_len characters, none for 0) and the ETA, or nothing without a target. */
static void
fmt_target(char *b, size_t n, double now, int bar_len)
{
	char eta[32] = "?", bar[24] = "";
	int k, fill;

	b[0] = 0;
	if (!isfinite(pg.frac))
		return;
	fill = (int)(pg.frac * bar_len + 1e-9);
	for (k = 0; k < bar_len; k++)
		bar[k] = k < fill ? '#' : '.';
	bar[bar_len] = 0;
	if (pg.frac > pg.frac0 && now > pg.frac_t0)
		fmt_dur(eta, sizeof eta, (now - pg.frac_t0) * (1 - pg.frac) / (pg.frac - pg.frac0));
	snprintf(b, n, "  %s%s%s%3.0f%% ETA %s", bar_len ? "[" : "", bar, bar_len ? "] " : "", 100 * pg.frac, eta);
}

/* The status: stage, iterations, residual, elapsed, target; shorter for a higher level (1: a
 * bar of 10, 2: no bar, 3: no residual, 4: no iterations, 5: no stage). */
static void
fmt_status(char *b, size_t n, double now, int level)
{
	char el[32], tg[96] = "", res[32] = "", it[32] = "";
	const char *stage = level < 5 ? pg.stage : "";

	fmt_dur(el, sizeof el, now - ((double)pg.t0.tv_sec + 1e-9 * (double)pg.t0.tv_nsec));
	if (isfinite(pg.residual) && level < 3)
		snprintf(res, sizeof res, "  res %.2e", pg.residual);
	fmt_target(tg, sizeof tg, now, level == 0 ? 20 : level == 1 ? 10 : 0);
	if (pg.iters > 0 && level < 4)	/* a tool whose loops do not count (packgen's DEM) says its steps itself */
		snprintf(it, sizeof it, "it %ld  ", pg.iters);
	snprintf(b, n, "%s%s%s%s%s", stage, stage[0] ? "  " : "", it, res[0] ? res + 2 : "", res[0] ? "  " : "");
	snprintf(b + strlen(b), n - strlen(b), "%s%s", el, tg);
}

/* The status line for a terminal of width columns, in line (at most width - 1 characters, so
 * that the cursor stays on the line): the longest form that fits, the summary after it as far
 * as it goes (where a dozen characters of it fit); cut only where even "TOOL: ELAPSED  P% ETA
 * T" does not fit. */
static void
fit_line(char *line, size_t n, double now, int width)
{
	char st[256];
	int w = width - 1, level, len;

	for (level = 0; level <= 5; level++) {
		fmt_status(st, sizeof st, now, level);
		snprintf(line, n, "%s: %s", msg_progname, st);
		if ((int)strlen(line) <= w)
			break;
	}
	len = (int)strlen(line);
	if (len > w && w >= 0)
		line[w] = 0;
	else if (pg.summary[0] && len + 4 + 12 <= w)	/* "  | " and a dozen characters of it at least */
		snprintf(line + len, n - (size_t)len, "  | %.*s", w - len - 4, pg.summary);
}

/* The terminal's line, redrawn in place. */
static void
draw(double now)
{
	char line[1024];

	fit_line(line, sizeof line, now, term_width());
	fprintf(stderr, "\r%s\033[K", line);
	fflush(stderr);
	line_shown = 1;
	pg.reported = 1;
	pg.drawn = now;
}

void
cli_progress(const char *fmt, ...)
{
	va_list ap;
	double now;

	if (!cli_progress_enabled())
		return;
	va_start(ap, fmt);
	vsnprintf(pg.summary, sizeof pg.summary, fmt, ap);
	va_end(ap);
	now = now_s();
	if (pg.tty) {
		if (now - pg.drawn >= PROGRESS_EVERY || !line_shown)
			draw(now);
		return;
	}
	/* one plain line per stage (or per PROGRESS_PLAIN s where the tool reports more often) */
	if (pg.stage_new || !pg.stage[0] || now - pg.printed >= PROGRESS_PLAIN) {
		fprintf(stderr, "%s: %s\n", msg_progname, pg.summary);
		fflush(stderr);
		pg.printed = now;
		pg.stage_new = 0;
		pg.reported = 1;
	}
}

void
cli_progress_stage(const char *fmt, ...)
{
	char name[sizeof pg.stage];
	va_list ap;

	if (!cli_progress_enabled())
		return;
	va_start(ap, fmt);
	vsnprintf(name, sizeof name, fmt, ap);
	va_end(ap);
	if (strcmp(name, pg.stage) == 0)
		return;
	strcpy(pg.stage, name);
	pg.stage_new = 1;
	pg.iters = 0;
	pg.residual = NAN;
	pg.stage_t0 = now_s();
	if (pg.tty && (pg.stage_t0 - pg.drawn >= PROGRESS_EVERY || !line_shown))
		draw(pg.stage_t0);
}

void
cli_progress_frac(double f)
{
	if (!cli_progress_enabled())
		return;
	if (!isfinite(f)) {
		pg.frac = pg.frac0 = NAN;
		return;
	}
	f = f < 0 ? 0 : f > 1 ? 1 : f;
	if (!isfinite(pg.frac0)) {
		pg.frac0 = f;
		pg.frac_t0 = now_s();
	}
	pg.frac = f;
}

void
cli_progress_iter(double residual)
{
	static int on = -1;
	static unsigned calls;
	double now;

	if (on < 0)
		on = cli_progress_enabled();
	if (!on)
		return;
	pg.iters++;
	pg.residual = residual;
	if (++calls % 16)	/* the clock read every 16th call: an iteration may take microseconds */
		return;
	now = now_s();
	if (pg.tty) {
		if (now - pg.drawn >= PROGRESS_EVERY)
			draw(now);
	} else if (now - pg.printed >= PROGRESS_PLAIN && now - pg.stage_t0 >= PROGRESS_PLAIN) {
		char st[256];

		fmt_status(st, sizeof st, now, 0);
		fprintf(stderr, "%s: %s\n", msg_progname, st);
		fflush(stderr);
		pg.printed = now;
		pg.reported = 1;
	}
}

void
cli_progress_end(void)
{
	if (line_shown) {
		double now = now_s();

		draw(now);	/* the last state, then the line is left as it stands */
		fputc('\n', stderr);
		line_shown = 0;
	}
}
