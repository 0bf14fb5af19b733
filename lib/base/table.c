/* SPDX-License-Identifier: GPL-3.0-or-later */
/* table: TSV header and rows (see table.h). */
#include "base/table.h"
#include "base/numfmt.h"
#include "base/msg.h"
#include "base/lines.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void
header_cells(FILE *fp, const struct table_col *cols, int n)
{
	int k;

	fputc('#', fp);
	for (k = 0; k < n; k++) {
		fprintf(fp, "%s%s", k ? "\t" : " ", cols[k].name);
		if (cols[k].unit)
			fprintf(fp, "[%s]", cols[k].unit);
	}
}

static void
row_cells(FILE *fp, const double *v, int n)
{
	char buf[40];
	int k;

	for (k = 0; k < n; k++) {
		num_format(buf, v[k]);
		fprintf(fp, "%s%s", k ? "\t" : "", buf);
	}
}

void
table_header(FILE *fp, const struct table_col *cols, int n)
{
	header_cells(fp, cols, n);
	fputc('\n', fp);
}

void
table_row(FILE *fp, const double *v, int n)
{
	row_cells(fp, v, n);
	fputc('\n', fp);
}

void
table_header_text(FILE *fp, const struct table_col *cols, int n, const char *text_name)
{
	header_cells(fp, cols, n);
	fprintf(fp, "%s%s\n", n ? "\t" : "# ", text_name);
}

void
table_row_text(FILE *fp, const double *v, int n, const char *text)
{
	const char *c;

	row_cells(fp, v, n);
	if (n)
		fputc('\t', fp);
	for (c = text; *c; c++)	/* one cell: a tab or a newline would make two, or two rows */
		fputc(*c == '\t' || *c == '\n' || *c == '\r' ? ' ' : *c, fp);
	fputc('\n', fp);
}

void
table_free(struct table *t)
{
	int k;

	for (k = 0; k < t->ncol; k++)
		free(t->names[k]);
	free(t->names);
	free(t->v);
	free(t->line);
	memset(t, 0, sizeof *t);
}

int
table_find(const struct table *t, const char *name)
{
	int k;

	for (k = 0; k < t->ncol; k++)
		if (strcmp(t->names[k], name) == 0)
			return k;
	return -1;
}

/* Split the header "# a[u]\tb\t..." into names without units. */
static int
parse_header(struct table *t, char *s)
{
	char *f, *save = NULL;

	for (f = strtok_r(s, "\t", &save); f; f = strtok_r(NULL, "\t", &save)) {
		char **nn = realloc(t->names, (t->ncol + 1) * sizeof *nn), *br;
		if (!nn)
			return -1;
		t->names = nn;
		if ((br = strchr(f, '[')) != NULL)
			*br = '\0';
		if (!(t->names[t->ncol] = strdup(f)))
			return -1;
		t->ncol++;
	}
	return 0;
}

/* One data row "v\tv\t..." with exactly ncol fields, appended to t. */
static int
parse_row(struct lines *in, struct table *t, char *p)
{
	char *end;
	int k;

	/* No columns: nothing to store a row in (and a realloc to size 0 would free t->v). */
	if (t->ncol == 0)
		return lines_error(in, "a row under a header with no columns");
	if (t->nrow == t->cap) {
		size_t cap = t->cap ? 2 * t->cap : 256;
		double *v = realloc(t->v, cap * t->ncol * sizeof *v);
		long *ln = v ? realloc(t->line, cap * sizeof *ln) : NULL;
		if (v)
			t->v = v;
		if (!v || !ln) {
			msg_seterr("out of memory");
			return -1;
		}
		t->line = ln;
		t->cap = cap;
	}
	for (k = 0; k < t->ncol; k++) {
		double x;
		char *tab = strchr(p, '\t');
		if (tab)
			*tab = '\0';
		else if (k + 1 < t->ncol)
			return lines_error(in, "%d fields, the header has %d", k + 1, t->ncol);
		x = strtod(p, &end);
		if (end == p || *end)
			return lines_error(in, "column %s: '%s' is not a number", t->names[k], p);
		t->v[t->nrow * t->ncol + k] = x;
		p = tab ? tab + 1 : p + strlen(p);
		if (!tab && k + 1 == t->ncol)
			break;
		if (tab && k + 1 == t->ncol)
			return lines_error(in, "more fields than the header's %d", t->ncol);
	}
	t->line[t->nrow++] = lines_lineno(in);
	return 0;
}

/* A '#' line: the header the first time, then only repeats of it. */
static int
header_line(struct lines *in, struct table *t, char **header, char *s)
{
	if (!*header) {
		if (strncmp(s, "# ", 2) != 0 || !(*header = strdup(s)) || parse_header(t, s + 2))
			return lines_error(in, "bad header line (expected '# name\\tname...')");
		/* one column whose name has spaces: a table written with spaces for tabs */
		if (t->ncol == 1 && strchr(t->names[0], ' '))
			return lines_error(in, "bad header line: one column name with spaces in it; "
			    "the columns are TAB-separated");
	} else if (strcmp(s, *header) != 0) {
		return lines_error(in, "a second, different header line");
	}
	return 0;
}

int
table_read(FILE *fp, const char *display, struct table *t)
{
	char *header = NULL, *s;
	int status = -1, r;
	struct lines *in = lines_open(fp, display);

	memset(t, 0, sizeof *t);
	if (!in)
		return -1;
	while ((r = lines_next(in, &s, NULL)) == 1) {
		if (!lines_newline(in)) {
			lines_error(in, "the last line has no newline (truncated?)");
			goto out;
		}
		if (strncmp(s, "##", 2) == 0)
			continue;
		if (s[0] == '#') {
			if (header_line(in, t, &header, s))
				goto out;
			continue;
		}
		if (!header) {
			/* a pack given where a table belongs: say so, not only what is missing */
			if (strncmp(s, "qusgm-pack", 10) == 0)
				lines_error(in, "a qusgm pack, not a table (a table is loadtest's output, a frictionalize or densify --log, or moduli's)");
			else
				lines_error(in, "no header line before the first row (a table starts with '# name name ...')");
			goto out;
		}
		if (parse_row(in, t, s))
			goto out;
	}
	if (r < 0)
		goto out;
	if (!header) {
		msg_seterr("%s: empty (no header line)", display);
		goto out;
	}
	status = 0;
out:
	lines_close(in);
	free(header);
	if (status)
		table_free(t);
	return status;
}
