/* SPDX-License-Identifier: GPL-3.0-or-later */
/* psd: radius distributions (see psd.h). */
#include "pack/psd.h"
#include "base/lines.h"
#include "base/msg.h"
#include "base/numfmt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Up to max comma-separated finite numbers of s into v; their count, or -1. */
static int
parse_list(const char *s, double *v, int max)
{
	char *buf = strdup(s), *tok, *save = NULL;
	int n = 0;

	if (!buf)
		return -1;
	for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
		if (n == max || num_parse(tok, &v[n])) {
			n = -1;
			break;
		}
		n++;
	}
	free(buf);
	return n;
}

/* The blanks of a size table: what sscanf's %s stopped at, which the reader used to use. */
#define BLANKS " \t\n\v\f\r"

/* The radii and weights read so far. */
struct rows {
	double *r, *w;
	size_t n, cap;
};

static int
add_row(struct rows *t, double r, double w)
{
	if (t->n == t->cap) {
		size_t cap = t->cap ? 2 * t->cap : 64;
		double *nr = realloc(t->r, cap * sizeof *nr), *nw;
		if (!nr)
			return -1;
		t->r = nr;
		nw = realloc(t->w, cap * sizeof *nw);
		if (!nw)
			return -1;
		t->w = nw;
		t->cap = cap;
	}
	t->r[t->n] = r;
	t->w[t->n++] = w;
	return 0;
}

/* "radius [weight]", radius > 0, weight >= 0 (default 1). */
static int
table_line(struct lines *in, char *s, struct rows *t)
{
	char *tok[2];
	double r, wt = 1;
	int n = lines_split(s, BLANKS, tok, 2);

	if (n < 1 || n > 2 || num_parse(tok[0], &r) || (n == 2 && num_parse(tok[1], &wt)) || !(r > 0) ||
	    !(wt >= 0))
		return lines_error(in, "expected 'radius [weight]' with radius > 0 and weight >= 0");
	if (add_row(t, r, wt)) {
		msg_seterr("out of memory");
		return -1;
	}
	return 0;
}

static int
read_table(const char *path, struct psd *d)
{
	struct lines *in = lines_open_path(path);
	struct rows t = {NULL, NULL, 0, 0};
	char *s;
	int r;

	if (!in) {
		msg_seterr("%s: cannot open size table", path);
		return -1;
	}
	while ((r = lines_next(in, &s, NULL)) == 1) {
		if (s[0] == '#' || s[strspn(s, " \t\r\n")] == 0)
			continue;
		if ((r = table_line(in, s, &t)) < 0)
			break;
	}
	lines_close(in);
	if (r == 0 && t.n == 0) {
		msg_seterr("%s: the size table is empty", path);
		r = -1;
	}
	if (r == 0) {	/* weights all 0 made a distribution of nothing, which GSL took */
		double sum = 0;
		size_t k;

		for (k = 0; k < t.n; k++)
			sum += t.w[k];
		if (!(sum > 0)) {
			msg_seterr("%s: the weights are all 0: at least one must be positive", path);
			r = -1;
		} else if (!isfinite(sum)) {
			msg_seterr("%s: the weights sum to %g, more than a double holds: scale them down", path, sum);
			r = -1;
		}
	}
	if (r == 0 && !(d->disc = gsl_ran_discrete_preproc(t.n, t.w))) {
		msg_seterr("%s: the weights do not define a distribution", path);
		r = -1;
	}
	free(t.w);
	if (r < 0) {
		free(t.r);
		return -1;
	}
	d->table = t.r;
	d->ntable = t.n;
	return 0;
}

int
psd_parse(const char *spec, struct psd *d)
{
	double v[4];
	int n;

	memset(d, 0, sizeof *d);
	if (strncmp(spec, "uniform:", 8) == 0) {
		n = parse_list(spec + 8, v, 2);
		if (n != 2 || !(v[0] > 0) || !(v[1] >= v[0])) {
			msg_seterr("--psd %s: expected uniform:RMIN,RMAX with 0 < RMIN <= RMAX", spec);
			return -1;
		}
		d->kind = PSD_UNIFORM;
		d->lo = v[0];
		d->hi = v[1];
		return 0;
	}
	if (strncmp(spec, "lognormal:", 10) == 0) {
		n = parse_list(spec + 10, v, 4);
		if ((n != 2 && n != 4) || !(v[0] > 0) || !(v[1] >= 0)) {
			msg_seterr("--psd %s: expected lognormal:MEDIAN,SIGMA[,RMIN,RMAX]", spec);
			return -1;
		}
		d->kind = PSD_LOGNORMAL;
		d->a = v[0];
		d->b = v[1];
		d->lo = n == 4 ? v[2] : v[0] / 5;
		d->hi = n == 4 ? v[3] : v[0] * 5;
		if (!(d->lo > 0) || !(d->hi >= d->lo) || d->a < d->lo || d->a > d->hi) {
			msg_seterr("--psd %s: need 0 < RMIN <= MEDIAN <= RMAX", spec);
			return -1;
		}
		return 0;
	}
	if (strncmp(spec, "table:", 6) == 0) {
		if (!spec[6]) {
			msg_seterr("--psd table: names no file (table:FILE, a size table)");
			return -1;
		}
		d->kind = PSD_TABLE;
		return read_table(spec + 6, d);
	}
	msg_seterr("--psd %s: unknown distribution (uniform:RMIN,RMAX, lognormal:MEDIAN,SIGMA, table:FILE)", spec);
	return -1;
}

double
psd_draw(const struct psd *d, gsl_rng *rng)
{
	double r;

	switch (d->kind) {
	case PSD_UNIFORM:
		return d->lo + (d->hi - d->lo) * gsl_rng_uniform(rng);
	case PSD_LOGNORMAL:
		do
			r = d->a * exp(d->b * gsl_ran_gaussian(rng, 1.0));
		while (r < d->lo || r > d->hi);
		return r;
	case PSD_TABLE:
		return d->table[gsl_ran_discrete(rng, d->disc)];
	}
	return 0;
}

void
psd_free(struct psd *d)
{
	free(d->table);
	if (d->disc)
		gsl_ran_discrete_free(d->disc);
	memset(d, 0, sizeof *d);
}
