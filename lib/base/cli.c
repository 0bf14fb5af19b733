/* cli: option tables, help, atomic output, progress (see cli.h). */
#include "base/cli.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>
#include <sys/stat.h>
#include <unistd.h>

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

/* The temporary file in flight, removed by the signal handler and at exit. */
/* The temporary files in flight (a tool may write a pack and a log at once), removed by
 * the signal handler and at exit unless committed. */
#define MAX_TMP 8
static volatile sig_atomic_t tmp_live[MAX_TMP];
static char tmp_pending[MAX_TMP][4096];

static void
remove_all_tmp(void)
{
	int k;

	for (k = 0; k < MAX_TMP; k++)
		if (tmp_live[k])
			unlink(tmp_pending[k]);
}

static void
forget_tmp(const char *path)
{
	int k;

	for (k = 0; k < MAX_TMP; k++)
		if (tmp_live[k] && strcmp(tmp_pending[k], path) == 0)
			tmp_live[k] = 0;
}

static struct cli_opt common_opts[] = {
	{"output", 'o', CLI_STRING, &output_path, "FILE", "write to FILE (atomically) instead of stdout; .gz compresses", NULL},
	{"verbose", 'v', CLI_FLAG, &verbose_count, NULL, "report progress on stderr (twice: solver detail)", NULL},
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
	/* one line per error (style.md 13): the hint goes on the same line */
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

static void
print_opt(const struct cli_opt *o, int show_default)
{
	char left[96], def[128];

	if (o->shortname)
		snprintf(left, sizeof left, "-%c, --%s%s%s", o->shortname, o->name,
		    o->arg ? " " : "", o->arg ? o->arg : "");
	else
		snprintf(left, sizeof left, "    --%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
	printf("  %-28s %s", left, o->help);
	if (o->unit)
		printf(" (%s)", o->unit);
	if (show_default && o->type != CLI_FLAG) {
		format_value(o, def, sizeof def);
		if (def[0])
			printf(" [default: %s]", def);
	}
	putchar('\n');
}

static void
print_help(const struct cli_tool *t)
{
	size_t i, n = count_opts(t->opts);

	printf("Usage: %s %s\n%s\n\nOptions:\n", t->name, t->usage, t->purpose);
	for (i = 0; i < n; i++)
		print_opt(&t->opts[i], 1);
	for (i = 0; common_opts[i].type != CLI_END; i++)
		print_opt(&common_opts[i], 0);
	printf("\nFILE '-' or no FILE reads standard input; .gz input is detected.\n"
	    "Exit status: 0 success, 1 bad data or failure, 2 usage error.\n"
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
			} else if (*c == '\n') {
				*p++ = ' ';	/* history is one line */
			} else {
				*p++ = *c;
			}
		}
		*p++ = '\'';
	}
	*p = 0;
	return s;
}

void
cli_parse(const struct cli_tool *t, int argc, char **argv, struct cli_state *st)
{
	size_t n = count_opts(t->opts), nc = count_opts(common_opts), i;
	struct option *lo = calloc(n + nc + 1, sizeof *lo);
	const struct cli_opt **map = calloc(n + nc, sizeof *map);
	char shortopts[256] = ":";
	int c, idx;

	if (!lo || !map)
		msg_die(EXIT_DATA, "out of memory");
	for (i = 0; i < n + nc; i++) {
		const struct cli_opt *o = i < n ? &t->opts[i] : &common_opts[i - n];
		int has_arg = o->type == CLI_FLAG ? no_argument : required_argument;

		map[i] = o;
		lo[i].name = o->name;
		lo[i].has_arg = has_arg;
		lo[i].flag = NULL;
		lo[i].val = 256 + (int)i;
		if (o->shortname) {
			size_t l = strlen(shortopts);
			shortopts[l] = (char)o->shortname;
			if (has_arg == required_argument)
				shortopts[++l] = ':';
			shortopts[l + 1] = 0;
		}
	}
	memset(st, 0, sizeof *st);
	opterr = 0;
	while ((c = getopt_long(argc, argv, shortopts, lo, &idx)) != -1) {
		const struct cli_opt *o = NULL;

		if (c >= 256) {
			o = map[c - 256];
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
			for (i = 0; i < n + nc; i++)
				if (map[i]->shortname == c)
					o = map[i];
		}
		if (o)
			parse_value(o, optarg);
	}
	free(lo);	/* before the exits below: LeakSanitizer counts them otherwise */
	free(map);
	if (help_flag) {
		print_help(t);
		exit(0);
	}
	if (version_flag) {
		printf("%s (qusgm) %s\n", t->name, QUSGM_VERSION);
		exit(0);
	}
	msg_verbosity = quiet_flag ? -1 : verbose_count;
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

char *
cli_resolved(const struct cli_tool *t)
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
		format_value(&t->opts[i], val, sizeof val);
		used += (size_t)sprintf(s + used, "%s--%s=%s", i ? " " : "", t->opts[i].name, val);
	}
	return s;
}

char *
cli_history_line(const struct cli_tool *t, const struct cli_state *st)
{
	char *res = cli_resolved(t), *s;
	size_t len = strlen(t->name) + strlen(st->argv_text) + strlen(res) + 64;

	s = malloc(len);
	if (!s)
		msg_die(EXIT_DATA, "out of memory");
	snprintf(s, len, "%s %s: %s ; %s", t->name, QUSGM_VERSION, st->argv_text, res);
	free(res);
	return s;
}

static void
remove_tmp_on_signal(int sig)
{
	remove_all_tmp();
	signal(sig, SIG_DFL);
	raise(sig);
}

static void
remove_tmp_at_exit(void)
{
	remove_all_tmp();
}

int
cli_out_open(struct cli_out *o, const char *path)
{
	static int hooked;
	const char *slash;
	size_t dirlen;
	int fd;

	memset(o, 0, sizeof *o);
	if (!path || strcmp(path, "-") == 0) {
		o->fp = stdout;
		return 0;
	}
	{
		/* a device or a pipe (-o /dev/null, -o /dev/stderr, a FIFO): write into it.  The
		 * temporary file and rename would replace the device node with a regular file (as
		 * root, /dev/null itself) */
		struct stat sb;
		if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode)) {
			if (S_ISDIR(sb.st_mode)) {
				msg_seterr("%s: is a directory", path);
				return -1;
			}
			o->fp = fopen(path, "w");
			if (!o->fp) {
				msg_seterr("%s: %s", path, strerror(errno));
				return -1;
			}
			o->path = strdup(path);
			if (!o->path) {
				fclose(o->fp);
				o->fp = NULL;
				msg_seterr("out of memory");
				return -1;
			}
			return 0;
		}
	}
	if (strlen(path) + 16 >= sizeof tmp_pending[0]) {
		msg_seterr("%s: path too long", path);
		return -1;
	}
	slash = strrchr(path, '/');
	dirlen = slash ? (size_t)(slash - path) + 1 : 0;
	o->path = strdup(path);
	o->tmp = malloc(strlen(path) + 16);
	if (!o->path || !o->tmp) {
		msg_seterr("out of memory");
		return -1;
	}
	memcpy(o->tmp, path, dirlen);
	sprintf(o->tmp + dirlen, ".%s.XXXXXX", path + dirlen);
	if (!hooked) {
		atexit(remove_tmp_at_exit);
		signal(SIGINT, remove_tmp_on_signal);
		signal(SIGTERM, remove_tmp_on_signal);
		signal(SIGHUP, remove_tmp_on_signal);
		signal(SIGPIPE, remove_tmp_on_signal);
		hooked = 1;
	}
	fd = mkstemp(o->tmp);
	if (fd < 0) {
		msg_seterr("%s: cannot create temporary file: %s", path, strerror(errno));
		return -1;
	}
	{
		int k;
		for (k = 0; k < MAX_TMP && tmp_live[k]; k++)
			;
		if (k == MAX_TMP) {
			close(fd);
			unlink(o->tmp);
			msg_seterr("%s: too many outputs at once", path);
			return -1;
		}
		strcpy(tmp_pending[k], o->tmp);
		tmp_live[k] = 1;
	}
	{
		mode_t mask = umask(0);

		umask(mask);
		fchmod(fd, 0666 & ~mask);
	}
	o->fp = fdopen(fd, "w");
	if (!o->fp) {
		msg_seterr("%s: %s", path, strerror(errno));
		close(fd);
		cli_out_abort(o);
		return -1;
	}
	return 0;
}

/* Compress the finished temporary file of an output named *.gz: the tables are written as
 * text and gzipped whole at the commit, so that the rename stays the one atomic step. */
static int
gzip_in_place(const char *tmp)
{
	char buf[1 << 15], *ztmp = malloc(strlen(tmp) + 4);
	FILE *in = fopen(tmp, "rb");
	gzFile z = NULL;
	size_t n;
	int bad = 0;

	if (ztmp)
		sprintf(ztmp, "%s.z", tmp);
	if (!ztmp || !in || !(z = gzopen(ztmp, "wb6"))) {
		if (in)
			fclose(in);
		free(ztmp);
		return -1;
	}
	while ((n = fread(buf, 1, sizeof buf, in)) > 0)
		if (gzwrite(z, buf, (unsigned)n) != (int)n)
			bad = 1;
	bad |= ferror(in) != 0;
	fclose(in);
	bad |= gzclose(z) != Z_OK;
	if (bad || rename(ztmp, tmp) != 0) {
		unlink(ztmp);
		free(ztmp);
		return -1;
	}
	free(ztmp);
	return 0;
}

int
cli_out_commit(struct cli_out *o)
{
	int bad;

	if (!o->fp)
		return -1;
	bad = fflush(o->fp) != 0 || ferror(o->fp);
	if (o->fp == stdout) {
		o->fp = NULL;
		if (bad) {
			msg_seterr("<stdout>: write error: %s", strerror(errno));
			return -1;
		}
		return 0;
	}
	if (fclose(o->fp) != 0)
		bad = 1;
	o->fp = NULL;
	if (bad) {
		msg_seterr("%s: write error: %s", o->path, strerror(errno));
		cli_out_abort(o);
		return -1;
	}
	if (!o->tmp) {	/* written straight into a device or pipe */
		free(o->path);
		o->path = NULL;
		return 0;
	}
	if (path_is_gz(o->path) && gzip_in_place(o->tmp)) {
		msg_seterr("%s: cannot compress: %s", o->path, strerror(errno));
		cli_out_abort(o);
		return -1;
	}
	if (rename(o->tmp, o->path) != 0) {
		msg_seterr("%s: cannot rename temporary file: %s", o->path, strerror(errno));
		cli_out_abort(o);
		return -1;
	}
	forget_tmp(o->tmp);
	free(o->tmp);
	free(o->path);
	o->tmp = o->path = NULL;
	return 0;
}

void
cli_out_abort(struct cli_out *o)
{
	if (o->fp && o->fp != stdout)
		fclose(o->fp);
	o->fp = NULL;
	if (o->tmp) {
		unlink(o->tmp);
		forget_tmp(o->tmp);
	}
	free(o->tmp);
	free(o->path);
	o->tmp = o->path = NULL;
}

FILE *
cli_in_open(const char *path, const char **display)
{
	FILE *fp;

	if (!path || strcmp(path, "-") == 0) {
		*display = "<stdin>";
		return stdin;
	}
	*display = path;
	fp = fopen(path, "rb");
	if (!fp)
		msg_seterr("%s: %s", path, strerror(errno));
	return fp;
}

static int progress_shown;

int
cli_progress_enabled(void)
{
	if (msg_verbosity < 0)
		return 0;
	return msg_verbosity > 0 || isatty(2);
}

void
cli_progress(const char *fmt, ...)
{
	va_list ap;

	if (!cli_progress_enabled())
		return;
	if (isatty(2))
		fputc('\r', stderr);
	fprintf(stderr, "%s: ", msg_progname);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	if (isatty(2)) {
		fputs("\033[K", stderr);
		progress_shown = 1;
	} else {
		fputc('\n', stderr);
	}
	fflush(stderr);
}

void
cli_progress_end(void)
{
	if (progress_shown) {
		fputc('\n', stderr);
		progress_shown = 0;
	}
}
