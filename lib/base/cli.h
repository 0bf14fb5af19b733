/* SPDX-License-Identifier: GPL-3.0-or-later */
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

#ifdef __cplusplus
extern "C" {
#endif

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
/* What the tool reads from standard input, for the line that says it reads a terminal ("a
 * pack" unless set): "packinfo: reading a pack from standard input (Ctrl-D ends it)".  Call
 * before cli_parse. */
void cli_input_help(const char *what);

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

/* Progress on standard error, never with -q.  On a terminal one status line, redrawn in place
 * at most 4 times a second:
 *     densify: compact 12  it 3400  res 2.31e-03  1:05  [#########...........]  45% ETA 1:20  | SUMMARY
 * the stage now running, the iterations (or steps) in it and the last residual (or
 * unbalanced force), the elapsed time, a bar and an ETA where the run has a target, then what
 * the last stage reported; fitted to the terminal's width (TIOCGWINSZ, else COLUMNS, else 80):
 * the summary is cut, then the bar shortened and dropped, then the residual, the iterations
 * and the stage, never the percentage and the ETA.  The line is ended before any message, at
 * exit, and on a termination signal (fileio.h, file_signal_hook).  Not a terminal: nothing
 * unless -v, then one plain line per stage (the summary), and inside a stage that runs longer
 * one status line every 10 s.  At an exit with status 0 after progress was shown (on a
 * terminal, or with -v): one closing line "TOOL: done in ELAPSED: SUMMARY" (glibc's on_exit
 * gives the status; without it, no closing line).
 *  - cli_progress: the summary, after a stage, an increment or a row (the tools' callbacks);
 *  - cli_progress_stage: the stage that begins (the same name again changes nothing): its
 *    iteration count and residual start afresh;
 *  - cli_progress_frac: the share of the target reached, in [0, 1] (NaN: none, which also
 *    forgets the last); the ETA is extrapolated from the time since the first share given;
 *  - cli_progress_iter: one iteration of a minimiser or one step of a DEM loop, with its
 *    residual or unbalanced force (NaN: none); cheap (a clock read every 16th call) and free
 *    when progress is off, so the library's loops call it;
 *  - cli_progress_end: the last state, and the line ends (before other messages). */
int cli_progress_enabled(void);
void cli_progress(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void cli_progress_stage(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void cli_progress_frac(double f);
void cli_progress_iter(double residual);
void cli_progress_end(void);

/* Wall-clock seconds since cli_parse, to the millisecond: the logs' elapsed[s] column. */
double cli_elapsed(void);

#ifdef __cplusplus
}
#endif

#endif
