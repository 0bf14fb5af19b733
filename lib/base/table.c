/* table: TSV header and rows (see table.h). */
#include "base/table.h"
#include "base/numfmt.h"
#include "base/msg.h"
#include "pack/packio.h"

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
	const char *text;
	size_t bcap = 0, len;
	long lineno = 0;
	int status = -1, nl, r;
	struct pack_reader *rd = pack_reader_open(fp, display);

	memset(t, 0, sizeof *t);
	if (!rd)
		return -1;
	/* through the pack reader: plain and gzip tables alike, a truncated .gz is an error */
	while ((r = pack_reader_line(rd, &text, &lineno, &nl)) == 1) {
		char *p, *end;
		int k;

		if (!nl) {
			msg_seterr("%s:%ld: the last line has no newline (truncated?)", display, lineno);
			goto out;
		}
		len = strlen(text);
		if (len + 1 > bcap) {
			char *b = realloc(buf, 2 * (len + 1));
			if (!b) {
				msg_seterr("out of memory");
				goto out;
			}
			buf = b;
			bcap = 2 * (len + 1);
		}
		memcpy(buf, text, len + 1);
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
	if (r < 0)
		goto out;
	if (!header) {
		msg_seterr("%s: empty (no header line)", display);
		goto out;
	}
	status = 0;
out:
	pack_reader_close(rd);
	free(buf);
	free(header);
	if (status)
		table_free(t);
	return status;
}
