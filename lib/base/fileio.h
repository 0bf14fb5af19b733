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

/* 1 when the name ends in ".gz" (and is more than the suffix). */
int file_is_gz(const char *path);

/* An output in progress: write to fp, then file_out_commit or file_out_abort. */
struct file_out {
	FILE *fp;
	char *path;	/* final path, NULL for stdout */
	char *tmp;	/* temporary path, NULL for stdout, a device or a pipe */
};

/* NULL or "-" gives stdout; 0 on success. */
int file_out_open(struct file_out *o, const char *path);
/* Checked flush and close, gzip for a .gz name, rename over the target; 0 on success,
 * otherwise the temporary file is removed. */
int file_out_commit(struct file_out *o);
/* Close and remove the temporary file; nothing reaches the target. */
void file_out_abort(struct file_out *o);

#endif
