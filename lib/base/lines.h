/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lines: the one reader of text lines, behind every qusgm reader (packs, tables, material
 * files, size tables, "x y z r" spheres).
 *
 * Input is read with read(2) and, when it starts with gzip's magic bytes (1f 8b), inflated
 * with zlib member after member, as gzip -d does, so plain and gzip input share one code
 * path; a truncated or corrupt gzip stream is one error, "NAME:LINE: corrupt or truncated
 * input (why)", at the line that was being read when the data stopped, never a silently
 * shortened input, and bytes after the last member that are not another member ("trailing
 * data after the end of the gzip stream": a plain file appended to a .gz one, which zlib's
 * gzread dropped without a word) are an error too, but for zero bytes to the end (padding,
 * which gzip -d accepts).  Input that starts as no text does (xz, bzip2, zstd, lz4, zlib,
 * compress or zip data, UTF-16, a UTF-8 byte-order mark), before or inside the gzip stream,
 * and a gzip inside a gzip, are refused at line 1 with what they are and how to convert them, and so is a file of CR-only (old Mac) line
 * endings, whose first line would run to the end of the input.  Lines may be of any
 * length.  A line ends at "\n"; the "\n" and one "\r" before it (or at the very end of the
 * input) are stripped, so CRLF files read as LF ones.  A line holding a NUL byte is an error
 * ("binary data (NUL byte) in a text file").  Line numbers count from 1, and lines_error
 * writes the "NAME:LINE: what is wrong" message that tools print as "tool: ...".  Errors
 * fill the slot (base/msg.h); once the reader has failed, lines_next keeps returning -1. */
#ifndef QUSGM_LINES_H
#define QUSGM_LINES_H

#include <stddef.h>
#include <stdio.h>

struct lines;

/* Read fp, an open stream (stdin included), naming it name in messages.  The stream is
 * read through a duplicate of its descriptor and is not closed by lines_close.  NULL with
 * the slot set on failure. */
struct lines *lines_open(FILE *fp, const char *name);
/* Open path (NULL or "-": stdin, named "<stdin>") and read it; lines_close closes it.
 * NULL with "path: strerror" (or another reason) in the slot. */
struct lines *lines_open_path(const char *path);
void lines_close(struct lines *in);

/* 1: *line is the next line, its end stripped, with *len its length (len may be NULL); the
 * text stays valid, and may be changed in place, until the next call.  0: the end of the
 * input.  -1: an error, in the slot. */
int lines_next(struct lines *in, char **line, size_t *len);
/* Return the current line again from the next lines_next, with the same number; the line
 * must not have been changed in place. */
void lines_unread(struct lines *in);

/* The number of the last line returned (0 before the first), whether it ended with "\n"
 * (0 only for the last line of an input that does not end with one), the input's name. */
long lines_lineno(const struct lines *in);
int lines_newline(const struct lines *in);
const char *lines_name(const struct lines *in);

/* Split s in place into the fields separated by runs of the characters in blanks (leading
 * and trailing ones ignored); returns the number of fields, storing the first max in tok. */
int lines_split(char *s, const char *blanks, char **tok, int max);

/* Fill the slot with "NAME:LINE: what" and return -1: at the last line returned (line 1
 * before the first), or at the given line. */
int lines_error(const struct lines *in, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int lines_error_at(const struct lines *in, long line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
