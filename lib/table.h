/* table: the TSV convention shared by every tool that writes tables.
 *
 * One header line: '#' then tab-separated column names, each optionally followed by its
 * unit in brackets ("sigma_c[Pa]"); then one tab-separated row per record, numbers written
 * with num_format.  A missing value is written as "nan" only where a column is optional
 * and the man page says so.  The reader side (table_read) lives with the tools that need it. */
#ifndef QUSGM_TABLE_H
#define QUSGM_TABLE_H

#include <stdio.h>

struct table_col {
	const char *name;
	const char *unit;	/* NULL: dimensionless or a count */
};

void table_header(FILE *fp, const struct table_col *cols, int n);
void table_row(FILE *fp, const double *v, int n);

#endif
