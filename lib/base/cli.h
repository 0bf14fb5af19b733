/* cli: the command-line conventions every tool keeps.
 *
 * A tool declares its options once, in a table (name, argument, destination, help, unit);
 * the table drives getopt_long, --help (with defaults in brackets), the resolved-options
 * string recorded in a pack's history line, and the man-page test.  The common options
 * -o/--output, -v/--verbose, -q/--quiet, -h/--help and -V/--version are added here.
 * Opening the input and writing the output atomically are base/fileio.h's. */
#ifndef QUSGM_CLI_H
#define QUSGM_CLI_H

#include <stdio.h>

/* The release: the Makefile's VERSION (tests/tools/version.sh checks that they agree). */
#define QUSGM_VERSION "0.2.0"

/* The exact source of this build, which --version and every history line name: the release,
 * and from a git checkout "+" and its `git describe --always --dirty`, e.g.
 * "0.2.0+<hash>-dirty" (the Makefile's QUSGM_SOURCE_VERSION); the release alone when cli.c
 * was compiled outside git or without the Makefile. */
const char *cli_source_version(void);

enum cli_type { CLI_END = 0, CLI_FLAG, CLI_LONG, CLI_DOUBLE, CLI_STRING };

struct cli_opt {
	const char *name;	/* long name, without "--" */
	int shortname;		/* 0 for none */
	enum cli_type type;
	void *dest;		/* int *, long *, double *, const char ** */
	const char *arg;	/* argument name in --help, e.g. "PA" */
	const char *help;	/* one line */
	const char *unit;	/* "Pa", "m", NULL for none */
};

struct cli_tool {
	const char *name;
	const char *usage;	/* after the tool name, e.g. "[options] [FILE]" */
	const char *purpose;	/* one line */
	struct cli_opt *opts;	/* terminated by CLI_END */
	int max_operands;	/* input files allowed (usually 1) */
};

struct cli_state {
	const char *output;	/* -o FILE, or NULL for stdout */
	const char *input;	/* the operand, or NULL/"-" for stdin */
	char **operands;
	int noperands;
	char *argv_text;	/* the command line as typed, shell-quoted; owned by cli, freed at exit */
};

/* -o's help line when it is not "write to FILE instead of stdout": for a tool whose standard
 * output is a table and whose -o writes the final pack.  Call before cli_parse. */
void cli_output_help(const char *help);

/* Parse argv against the tool's table; exits 0 for --help/--version, 2 for usage errors
 * (after reporting every bad option).  Fills st. */
void cli_parse(const struct cli_tool *t, int argc, char **argv, struct cli_state *st);

/* Report one usage error; the tool calls cli_usage_done() after checking everything. */
void cli_usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void cli_usage_done(void);

/* "--name=value ..." for every option in the table, as resolved: goes into history. */
char *cli_resolved(const struct cli_tool *t);

/* What a checkpoint must match to be gone on from: "tool VERSION INPUT ; --name=value ..."
 * with every option that changes the result (all but those named in skip, a NULL-ended
 * list: where output goes, when to stop) and input, what identifies the input (e.g.
 * "grains N crc32 X": pack_checksum).  One line; the caller frees it. */
char *cli_run_identity(const struct cli_tool *t, const char *const *skip, const char *input);

/* A history line: "tool SOURCE_VERSION: argv ; resolved options" (cli_source_version).
 * Caller frees. */
char *cli_history_line(const struct cli_tool *t, const struct cli_state *st);

/* Progress on stderr: shown when stderr is a terminal or with -v, never with -q. */
int cli_progress_enabled(void);
void cli_progress(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void cli_progress_end(void);

#endif
