/* SPDX-License-Identifier: GPL-3.0-or-later */
/* curve: per-interval Hooke fits of a loading curve (see curve.h). */
#include "analysis/curve.h"
#include "base/msg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int
curve_columns(const struct table *t, const char *display, const char *stress_prefix, struct curve_cols *c)
{
	static const char *const ax[3] = {"xx", "yy", "zz"};
	char name[64];
	int a;

	for (a = 0; a < 3; a++) {
		snprintf(name, sizeof name, "eps_%s", ax[a]);
		if ((c->eps[a] = table_find(t, name)) < 0)
			goto missing;
		snprintf(name, sizeof name, "%s_%s", stress_prefix, ax[a]);
		if ((c->sig[a] = table_find(t, name)) < 0)
			goto missing;
	}
	c->from_sig = strcmp(stress_prefix, "sig") != 0;
	c->pool = 0;
	snprintf(name, sizeof name, "sigma_c");
	if ((c->sigma_c = table_find(t, name)) < 0 && !c->from_sig)
		goto missing;
	c->sig_lat = table_find(t, "sig_lat");
	c->seg = table_find(t, "seg");
	c->inc = table_find(t, "inc");
	return 0;
missing:
	msg_seterr("%s: no column '%s' (a loadtest table has eps_xx.. sig_xx.. sigma_c)", display, name);
	return -1;
}

static double
val(const struct table *t, size_t row, int col)
{
	return col < 0 ? NAN : t->v[row * t->ncol + col];
}

/* What curve_moduli works on: the table, the rows of the curve, and the increments of the
 * interval being fitted. */
struct work {
	const struct table *t;
	const struct curve_cols *c;
	const char *display;
	size_t *keep, nk;		/* table rows of the curve, in increment order */
	double (*de)[3], (*ds)[3];	/* one interval's strain and stress increments */
};

static int
keep_rows(struct work *w)
{
	const struct table *t = w->t;
	const struct curve_cols *c = w->c;
	size_t r;
	int a;

	for (r = 0; r < t->nrow; r++) {
		for (a = 0; a < 3; a++)
			if (!isfinite(val(t, r, c->eps[a])) || !isfinite(val(t, r, c->sig[a]))) {
				msg_seterr("%s:%ld: strains and stresses must be finite numbers", w->display, t->line[r]);
				return -1;
			}
		if (w->nk > 0 && c->inc >= 0) {
			double prev = val(t, w->keep[w->nk - 1], c->inc), cur = val(t, r, c->inc);
			if (cur == prev && c->seg >= 0 && val(t, r, c->seg) == 0)
				continue;	/* the start row of a continued test repeats the last one */
			if (!(cur > prev)) {
				msg_seterr("%s:%ld: rows out of order (inc %g after %g)", w->display, t->line[r], cur, prev);
				return -1;
			}
		}
		w->keep[w->nk++] = r;
	}
	if (w->nk < 2) {
		msg_seterr("%s: %zu rows: a curve needs at least two", w->display, w->nk);
		return -1;
	}
	return 0;
}

/* The increments into kept rows q, q+1, ... of segment seg, k at most, into w->de and
 * w->ds; *m gets their number.  Returns the kept row after the interval. */
static size_t
gather_increments(struct work *w, size_t q, int seg, long k, size_t *m)
{
	const struct table *t = w->t;
	const struct curve_cols *c = w->c;
	int a;

	*m = 0;
	while (q < w->nk && (long)*m < k && (c->seg < 0 || c->pool || (int)val(t, w->keep[q], c->seg) == seg)) {
		for (a = 0; a < 3; a++) {
			w->de[*m][a] = val(t, w->keep[q], c->eps[a]) - val(t, w->keep[q - 1], c->eps[a]);
			w->ds[*m][a] = val(t, w->keep[q], c->sig[a]) - val(t, w->keep[q - 1], c->sig[a]);
		}
		++*m;
		q++;
	}
	return q;
}

/* The interval from kept row first - 1 to kept row end - 1, whose m increments are in w. */
static int
fit_interval(const struct work *w, size_t first, size_t end, int seg, size_t m, struct curve_interval *I)
{
	const struct table *t = w->t;
	const struct curve_cols *c = w->c;
	size_t from = w->keep[first - 1], to = w->keep[end - 1];

	I->seg = seg;
	I->n = (long)m;
	I->inc_from = c->inc >= 0 ? (long)val(t, from, c->inc) : (long)(first - 1);
	I->inc_to = c->inc >= 0 ? (long)val(t, to, c->inc) : (long)(end - 1);
	I->row_to = to;
	if (c->from_sig) {
		int a, ax = 0;
		double big = -1;
		for (a = 0; a < 3; a++) {
			double d = fabs(val(t, to, c->eps[a]) - val(t, from, c->eps[a]));
			if (d > big)
				big = d, ax = a;
		}
		I->sigma_c = I->sig_lat = 0;
		for (a = 0; a < 3; a++) {
			double s = 0.5 * (val(t, from, c->sig[a]) + val(t, to, c->sig[a]));
			I->sigma_c += s / 3;
			if (a != ax)
				I->sig_lat += s / 2;
		}
	} else {
		I->sigma_c = 0.5 * (val(t, from, c->sigma_c) + val(t, to, c->sigma_c));
		I->sig_lat = 0.5 * (val(t, from, c->sig_lat) + val(t, to, c->sig_lat));
	}
	if (hooke_fit((const double(*)[3])w->de, (const double(*)[3])w->ds, m, &I->hk)) {
		char why[256];
		snprintf(why, sizeof why, "%s", msg_geterr());
		msg_seterr("%s:%ld: %s", w->display, t->line[to], why);
		return -1;
	}
	I->K_negative = I->G_negative = NAN;
	if (I->hk.has_K && I->hk.K < 0) {
		I->K_negative = I->hk.K;
		I->hk.K = I->hk.K_se = NAN;
	}
	if (I->hk.has_G && I->hk.G < 0) {
		I->G_negative = I->hk.G;
		I->hk.G = I->hk.G_se = NAN;
	}
	if (!isnan(I->K_negative) || !isnan(I->G_negative))
		I->hk.lambda = I->hk.E = I->hk.nu = NAN;
	return 0;
}

/* Room for interval n, doubling the array; NULL when out of memory. */
static struct curve_interval *
next_slot(struct curve_interval **iv, size_t n, size_t *cap)
{
	if (n == *cap) {
		size_t nc = *cap ? 2 * *cap : 64;
		struct curve_interval *p = realloc(*iv, nc * sizeof *p);
		if (!p) {
			msg_seterr("out of memory");
			return NULL;
		}
		*iv = p;
		*cap = nc;
	}
	return &(*iv)[n];
}

int
curve_moduli(const struct table *t, const struct curve_cols *c, const char *display, long k,
    struct curve_interval **out, size_t *nout)
{
	struct work w = {t, c, display, NULL, 0, NULL, NULL};
	struct curve_interval *iv = NULL, *I;
	size_t q, n = 0, cap = 0;

	*out = NULL;
	*nout = 0;
	w.keep = malloc((t->nrow ? t->nrow : 1) * sizeof *w.keep);
	w.de = malloc((k > 0 ? k : 1) * sizeof *w.de);
	w.ds = malloc((k > 0 ? k : 1) * sizeof *w.ds);
	if (!w.keep || !w.de || !w.ds) {
		msg_seterr("out of memory");
		goto fail;
	}
	if (keep_rows(&w))
		goto fail;
	for (q = 1; q < w.nk;) {
		int seg = c->seg >= 0 ? (int)val(t, w.keep[q], c->seg) : 0;
		size_t first = q, m;

		q = gather_increments(&w, q, seg, k, &m);
		if (!(I = next_slot(&iv, n, &cap)) || fit_interval(&w, first, q, seg, m, I))
			goto fail;
		n++;
	}
	free(w.keep), free(w.de), free(w.ds);
	*out = iv;
	*nout = n;
	return 0;
fail:
	free(w.keep), free(w.de), free(w.ds), free(iv);
	return -1;
}
