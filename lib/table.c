/* table: TSV header and rows (see table.h). */
#include "table.h"
#include "numfmt.h"
#include "msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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

int
table_read(FILE *fp, const char *display, struct table *t)
{
	char *buf = NULL, *header = NULL;
	size_t bcap = 0;
	ssize_t len;
	long lineno = 0;
	int status = -1;

	memset(t, 0, sizeof *t);
	while ((len = getline(&buf, &bcap, fp)) >= 0) {
		char *p, *end;
		int k;

		lineno++;
		if (len > 0 && buf[len - 1] == '\n')
			buf[--len] = '\0';
		else {
			msg_seterr("%s:%ld: the last line has no newline (truncated?)", display, lineno);
			goto out;
		}
		if (strncmp(buf, "##", 2) == 0)
			continue;
		if (buf[0] == '#') {
			if (!header) {
				if (strncmp(buf, "# ", 2) != 0 || !(header = strdup(buf)) || parse_header(t, buf + 2)) {
					msg_seterr("%s:%ld: bad header line (expected '# name\\tname...')", display, lineno);
					goto out;
				}
			} else if (strcmp(buf, header) != 0) {
				msg_seterr("%s:%ld: a second, different header line", display, lineno);
				goto out;
			}
			continue;
		}
		if (!header) {
			msg_seterr("%s:%ld: no header line before the first row", display, lineno);
			goto out;
		}
		if (t->nrow == t->cap) {
			size_t cap = t->cap ? 2 * t->cap : 256;
			double *v = realloc(t->v, cap * t->ncol * sizeof *v);
			long *ln = v ? realloc(t->line, cap * sizeof *ln) : NULL;
			if (v)
				t->v = v;
			if (!v || !ln) {
				msg_seterr("out of memory");
				goto out;
			}
			t->line = ln;
			t->cap = cap;
		}
		p = buf;
		for (k = 0; k < t->ncol; k++) {
			double x;
			char *tab = strchr(p, '\t');
			if (tab)
				*tab = '\0';
			else if (k + 1 < t->ncol) {
				msg_seterr("%s:%ld: %d fields, the header has %d", display, lineno, k + 1, t->ncol);
				goto out;
			}
			x = strtod(p, &end);
			if (end == p || *end) {
				msg_seterr("%s:%ld: column %s: '%s' is not a number", display, lineno, t->names[k], p);
				goto out;
			}
			t->v[t->nrow * t->ncol + k] = x;
			p = tab ? tab + 1 : p + strlen(p);
			if (!tab && k + 1 == t->ncol)
				break;
			if (tab && k + 1 == t->ncol) {
				msg_seterr("%s:%ld: more fields than the header's %d", display, lineno, t->ncol);
				goto out;
			}
		}
		t->line[t->nrow++] = lineno;
	}
	if (ferror(fp)) {
		msg_seterr("%s: read error", display);
		goto out;
	}
	if (!header) {
		msg_seterr("%s: empty (no header line)", display);
		goto out;
	}
	status = 0;
out:
	free(buf);
	free(header);
	if (status)
		table_free(t);
	return status;
}
