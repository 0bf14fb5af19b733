/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fileio: opening an input by name, and writing an output atomically.
 *
 * Inputs: NULL or "-" is standard input, shown as "<stdin>" in messages.  Outputs named by
 * a path are written to a temporary file in the same directory (".NAME.XXXXXX"), and only
 * after fflush, ferror and fclose have all succeeded is it renamed over the target, so a
 * failed or interrupted tool leaves no half-written file; the temporaries in flight are
 * removed at exit and on SIGINT, SIGTERM, SIGHUP and SIGPIPE.  An output whose name ends in
 * ".gz" is gzip-compressed at the commit (the temporary file is written as plain text).
 * Standard output and devices or pipes named by path (/dev/null, a FIFO) are written
 * directly.  Failures fill the error slot (msg_seterr) and return nonzero. */
#ifndef QUSGM_FILEIO_H
#define QUSGM_FILEIO_H

#include <stdio.h>

/* Open path for reading in binary mode; NULL or "-" gives stdin.  *display is set to the
 * name to use in messages (path, or "<stdin>").  NULL with "path: strerror" in the slot. */
FILE *file_in_open(const char *path, const char **display);
/* Called by file_in_open each time it gives stdin (NULL: nothing): the tools' cli_parse sets it
 * to say that a terminal is read. */
extern void (*file_stdin_hook)(void);
/* The name by which messages call an input path: the path, or "<stdin>" for NULL or "-"
 * (what file_in_open sets *display to). */
const char *file_display_name(const char *path);

/* 1 when the name ends in ".gz" (and is more than the suffix). */
int file_is_gz(const char *path);

/* Whether paths a and b (b may be NULL or "-": never) name the same file: the same inode
 * when both exist, else the same directory (by inode) and the same last component.
 * b_output: b is an output, which the rename of file_out_commit replaces, so a symbolic
 * link there is a file of its own (lstat); a is followed (stat). */
int file_same(const char *a, const char *b, int b_output);

/* Whether path is standard output: NULL, "-", /dev/stdout, /dev/fd/1, /proc/self/fd/1, or
 * the regular file standard output is redirected to.  file_out_open and file_log_open
 * write such a path through stdout (never a second stream over it, nor a rename over
 * /dev/stdout). */
int file_is_stdout(const char *path);

/* The checks a tool makes before any work on the files it is given, so that a run of hours
 * does not find out at its end that it cannot write, or that it wrote one output over
 * another or over its input (densify --log X -o X kept the log as X and lost the pack;
 * packinfo -o X X replaced its input).  Each file is a role: its path (NULL: not given), how
 * the messages name it ("-o", "--log", "the input") and what it is:
 *   FILE_IN     an input, read through a symbolic link;
 *   FILE_OUT    an output replaced by the rename of file_out_commit (a symbolic link there is
 *               replaced, not followed);
 *   FILE_UPDATE the same, and it may be the input: a tool that reads its input whole before
 *               it writes (densify, frictionalize, dissociate, loadtest and shear's -o pack)
 *               updates it in place, atomically;
 *   FILE_LOG    an output written under its own name as the run goes (file_log_open), so
 *               through a symbolic link into the file it names: never the input or another
 *               output, by the file the link names.
 * 0 when no output is the same file as another role (a FILE_UPDATE may be the input), no
 * two outputs are standard output ("-", or /dev/stdout and the like: file_is_stdout), and
 * every output named by a path has a name and can be written: it is not a directory, and its
 * directory exists and is writable (a device or a FIFO, written into, is not checked, nor
 * compared: /dev/null may take two outputs).  Otherwise -1 with the first problem in the
 * slot, for the tool to report as a usage error. */
enum { FILE_IN = 0, FILE_OUT = 1, FILE_LOG = 2, FILE_UPDATE = 3 };
struct file_role {
	const char *path;
	const char *what;
	int output;	/* FILE_IN, FILE_OUT, FILE_LOG or FILE_UPDATE */
};
int file_roles_check(const struct file_role *r, int n);

/* An output in progress: write to fp, then file_out_commit or file_out_abort. */
struct file_out {
	FILE *fp;
	char *path;	/* final path, NULL for stdout */
	char *tmp;	/* temporary path, NULL for stdout, a device or a pipe */
	int err;	/* the errno of the first failed write or flush seen, 0 if none */
	int ready;	/* file_out_ready has run: only the rename is left */
};

/* NULL or "-" gives stdout; 0 on success.  A temporary file is created and recorded with the
 * termination signals held (a signal in between is handled once it is recorded, and removes
 * it): file_catch_signals. */
int file_out_open(struct file_out *o, const char *path);
/* The termination signals (INT, TERM, HUP, PIPE) caught, unless ignored at the start (nohup's
 * HUP stays ignored), and the temporaries removed at exit; file_out_open does it, once.  The
 * handler runs on the thread that called this first (the main thread: another thread that
 * gets a signal hands it on), calls file_signal_hook (NULL: none; async-signal-safe only:
 * cli.c ends its status line there), removes the temporary files of the outputs not committed
 * and dies of the signal. */
void file_catch_signals(void);
extern void (*file_signal_hook)(void);
/* fflush, keeping the errno of a failure (or of an earlier failed write, which only leaves
 * the stream's error flag: its errno is the one at hand right after the write) for the
 * commit's message: the errno at the commit was another one (--log /dev/full said
 * "Inappropriate ioctl for device").  A tool that writes rows as it runs calls it after
 * each; 0, or -1 once a write has failed. */
int file_out_flush(struct file_out *o);
/* Checked flush and close, gzip for a .gz name: everything but the rename, which cannot
 * fail for want of room.  0, or -1 with the slot set and o aborted. */
int file_out_ready(struct file_out *o);
/* file_out_ready, then the rename over the target; 0 on success, otherwise the temporary
 * file is removed. */
int file_out_commit(struct file_out *o);
/* Commit n outputs all or none: every one made ready first, and only when all are, each
 * renamed over its target; when one fails, all are aborted and none reaches its target (a
 * pack committed before its log failed to write was left behind, with a status of 1).
 * NULL entries are skipped.  0, or -1 with the first failure in the slot. */
int file_out_commit_all(struct file_out *const *o, int n);
/* Close and remove the temporary file; nothing reaches the target. */
void file_out_abort(struct file_out *o);

/* A log (--log, shear's --profile): unlike an output it is written under its own name from
 * the start, so that `tail -f` follows it while the run goes, and it keeps the rows written so
 * far when the run fails, stops at a limit or is killed (SIGTERM, SIGINT, SIGHUP).  The writer
 * calls file_out_flush after each row (and after the header): the row reaches the file whole,
 * and a failed write is reported with its own errno (a line-buffered stream writes inside
 * fputs, where the errno is lost by the time anyone looks).  NULL or "-" gives stdout.  A name
 * ending in ".gz" is refused: a log grows as plain text (gzip it afterwards).  The tool's
 * file_out_commit or file_out_commit_all closes it, checking the last writes, and
 * file_out_abort closes it and keeps it.  0, or -1 with the slot set. */
int file_log_open(struct file_out *o, const char *path);

#endif
