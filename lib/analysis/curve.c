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
	snprintf(name, sizeof name, "sigma_c");
	if ((c->sigma_c = table_find(t, name)) < 0)
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

int
curve_moduli(const struct table *t, const struct curve_cols *c, const char *display, long k,
    struct curve_interval **out, size_t *nout)
{
	size_t *keep = malloc((t->nrow ? t->nrow : 1) * sizeof *keep), nk = 0, r, q, cap = 0, n = 0;
	struct curve_interval *iv = NULL;
	double (*de)[3] = malloc((k > 0 ? k : 1) * sizeof *de), (*ds)[3] = malloc((k > 0 ? k : 1) * sizeof *ds);
	int a;

	*out = NULL;
	*nout = 0;
	if (!keep || !de || !ds) {
		msg_seterr("out of memory");
		goto fail;
	}
	for (r = 0; r < t->nrow; r++) {
		for (a = 0; a < 3; a++)
			if (!isfinite(val(t, r, c->eps[a])) || !isfinite(val(t, r, c->sig[a]))) {
				msg_seterr("%s:%ld: strains and stresses must be finite numbers", display, t->line[r]);
				goto fail;
			}
		if (nk > 0 && c->inc >= 0) {
			double prev = val(t, keep[nk - 1], c->inc), cur = val(t, r, c->inc);
			if (cur == prev && c->seg >= 0 && val(t, r, c->seg) == 0)
				continue;	/* the start row of a continued test repeats the last one */
			if (!(cur > prev)) {
				msg_seterr("%s:%ld: rows out of order (inc %g after %g)", display, t->line[r], cur, prev);
				goto fail;
			}
		}
		keep[nk++] = r;
	}
	if (nk < 2) {
		msg_seterr("%s: %zu rows: a curve needs at least two", display, nk);
		goto fail;
	}
	for (q = 1; q < nk;) {
		int seg = c->seg >= 0 ? (int)val(t, keep[q], c->seg) : 0;
		size_t first = q, m = 0;
		struct curve_interval *I;

		while (q < nk && (long)m < k && (c->seg < 0 || (int)val(t, keep[q], c->seg) == seg)) {
			for (a = 0; a < 3; a++) {
				de[m][a] = val(t, keep[q], c->eps[a]) - val(t, keep[q - 1], c->eps[a]);
				ds[m][a] = val(t, keep[q], c->sig[a]) - val(t, keep[q - 1], c->sig[a]);
			}
			m++;
			q++;
		}
		if (n == cap) {
			size_t nc = cap ? 2 * cap : 64;
			struct curve_interval *p = realloc(iv, nc * sizeof *p);
			if (!p) {
				msg_seterr("out of memory");
				goto fail;
			}
			iv = p;
			cap = nc;
		}
		I = &iv[n];
		I->seg = seg;
		I->n = (long)m;
		I->inc_from = c->inc >= 0 ? (long)val(t, keep[first - 1], c->inc) : (long)(first - 1);
		I->inc_to = c->inc >= 0 ? (long)val(t, keep[q - 1], c->inc) : (long)(q - 1);
		I->row_to = keep[q - 1];
		I->sigma_c = 0.5 * (val(t, keep[first - 1], c->sigma_c) + val(t, keep[q - 1], c->sigma_c));
		I->sig_lat = 0.5 * (val(t, keep[first - 1], c->sig_lat) + val(t, keep[q - 1], c->sig_lat));
		if (hooke_fit((const double(*)[3])de, (const double(*)[3])ds, m, &I->hk)) {
			char why[256];
			snprintf(why, sizeof why, "%s", msg_geterr());
			msg_seterr("%s:%ld: %s", display, t->line[keep[q - 1]], why);
			goto fail;
		}
		n++;
	}
	free(keep), free(de), free(ds);
	*out = iv;
	*nout = n;
	return 0;
fail:
	free(keep), free(de), free(ds), free(iv);
	return -1;
}
