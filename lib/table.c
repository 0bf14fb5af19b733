/* table: TSV header and rows (see table.h). */
#include "table.h"
#include "numfmt.h"

void
table_header(FILE *fp, const struct table_col *cols, int n)
{
	int k;

	fputc('#', fp);
	for (k = 0; k < n; k++) {
		fprintf(fp, "%s%s", k ? "\t" : " ", cols[k].name);
		if (cols[k].unit)
			fprintf(fp, "[%s]", cols[k].unit);
	}
	fputc('\n', fp);
}

void
table_row(FILE *fp, const double *v, int n)
{
	char buf[40];
	int k;

	for (k = 0; k < n; k++) {
		num_format(buf, v[k]);
		fprintf(fp, "%s%s", k ? "\t" : "", buf);
	}
	fputc('\n', fp);
}
