/* SPDX-License-Identifier: GPL-3.0-or-later */
/* table: the TSV convention shared by every tool that writes tables.
 *
 * One header line: '#' then tab-separated column names, each optionally followed by its
 * unit in brackets ("sigma_c[Pa]"); then one tab-separated row per record, numbers written
 * with num_format.  A missing value is written as "nan" only where a column is optional
 * and the man page says so.  Lines starting "##" before the header (or between tables of a
 * stream) carry metadata (loadtest's path and equilibrium criterion) and are skipped by
 * readers. */
#ifndef QUSGM_TABLE_H
#define QUSGM_TABLE_H

#include <stdio.h>

struct table_col {
	const char *name;
	const char *unit;	/* NULL: dimensionless or a count */
};

void table_header(FILE *fp, const struct table_col *cols, int n);
void table_row(FILE *fp, const double *v, int n);
/* The same with a last text column named text_name (a word without tabs, e.g. packinfo's
 * file), its cell text on each row (tabs and newlines in it written as spaces). */
void table_header_text(FILE *fp, const struct table_col *cols, int n, const char *text_name);
void table_row_text(FILE *fp, const double *v, int n, const char *text);

/* A table read back: ncol named columns (units stripped), nrow rows of doubles.  Repeated
 * identical header lines (tables concatenated with cat) and "##" lines are skipped. */
struct table {
	int ncol;
	char **names;
	size_t nrow, cap;
	double *v;	/* row-major, nrow * ncol */
	long *line;	/* the input line of each row, for messages */
};

/* Read through base/lines.h (plain or gzip; a truncated .gz is an error), every line ending
 * with a newline.  0, or -1 with msg_seterr("display:line: what is wrong"). */
int table_read(FILE *fp, const char *display, struct table *t);
/* Index of the column called name, or -1. */
int table_find(const struct table *t, const char *name);
void table_free(struct table *t);

#endif
