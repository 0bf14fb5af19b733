/* SPDX-License-Identifier: GPL-3.0-or-later */
/* frictionalize: uniaxial loading with friction until the sliding ratio saturates (see
 * frictionalize.h). */
#include "qs/frictionalize.h"
#include "contact/contacts.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
fric_params_default(struct fric_params *fp)
{
	memset(fp, 0, sizeof *fp);
	fp->axis = 2;
	fp->strain_step = 1e-4;
	fp->window = 10;
	fp->min_inc = 1;	/* the two windows set the least: 2 x window */
	fp->max_inc = 1000;
	fp->sat_tol = 0.05;	/* relative change of the window mean */
	/* 13 increments of 1e-4 at 4 MPa in a glass pack (mean overlap / R about 5e-3), 75 at 74 MPa */
	fp->window_overlap = 0.25;
	load_params_default(&fp->lp);
}

long
fric_window(const struct pack *p, const struct fric_params *fp)
{
	struct geo_contacts gc;
	double hsum = 0, w;
	size_t k;

	if (!(fp->window_overlap > 0))
		return fp->window;
	contacts_init(&gc);
	if (contacts_find(p, &gc) || gc.n == 0) {
		contacts_free(&gc);
		return fp->window;
	}
	for (k = 0; k < gc.n; k++) {
		const struct geo_contact *c = &gc.c[k];
		double r = c->j >= 0 ? 0.5 * (p->r[c->i] + p->r[c->j]) : p->r[c->i];
		hsum += c->h / r;
	}
	w = ceil(fp->window_overlap * (hsum / gc.n) / fabs(fp->strain_step));
	contacts_free(&gc);
	return w > fp->window ? (w < 1e6 ? (long)w : 1000000) : fp->window;
}

int
frictionalize_run(struct pack *p, const struct fric_params *fp, fric_row_fn fn, void *ctx, struct load_row *last)
{
	struct loader L;
	struct load_row prev, row;
	struct hooke hk;
	double de[3] = {0, 0, 0}, *ratio, *shear;
	long k, window = fric_window(p, fp), min_inc = fp->min_inc;
	int st = 2, a;

	ratio = malloc((fp->max_inc + 1) * sizeof *ratio);
	shear = malloc((fp->max_inc + 1) * sizeof *shear);
	if (!ratio || !shear) {
		free(ratio), free(shear);
		msg_seterr("out of memory");
		return -1;
	}
	if (loader_open(&L, p, &fp->lp) || loader_measure(&L, &prev)) {
		free(ratio), free(shear);
		loader_close(&L);
		return -1;
	}
	if (fn) {
		memset(&hk, 0, sizeof hk);
		hk.K = hk.G = NAN;
		fn(&prev, &hk, ctx);
	}
	*last = prev;
	de[fp->axis] = fp->strain_step;
	for (k = 1; k <= fp->max_inc; k++) {
		double dE[1][3], dS[1][3];
		int r = loader_step(&L, de, &row);

		if (r < 0) {
			st = -1;
			break;
		}
		for (a = 0; a < 3; a++) {
			dE[0][a] = row.eps[a] - prev.eps[a];
			dS[0][a] = row.sig_lw[a] - prev.sig_lw[a];
		}
		if (hooke_fit((const double(*)[3])dE, (const double(*)[3])dS, 1, &hk))
			hk.K = hk.G = NAN;
		row.seg = 1;
		if (fn)
			fn(&row, &hk, ctx);
		*last = row;
		prev = row;
		if (r == 1) {
			char note[96];
			msg_seterr("increment %ld: the minimiser hit its iteration limit (residual %.3g)%s", k, row.res_max,
			    loader_limit_note(&L, note, sizeof note));
			st = 1;
			break;
		}
		ratio[k] = row.sliding_ratio;
		shear[k] = hk.G;
		if (k >= min_inc && k >= 2 * window) {
			const double *v = fp->until == FRIC_UNTIL_SHEAR ? shear : ratio;
			double m1 = 0, m0 = 0;
			long q;
			for (q = k - window + 1; q <= k; q++) {
				m1 += v[q];
				m0 += v[q - window];
			}
			if (fp->until == FRIC_UNTIL_SHEAR ? m1 > m0 : fabs(m1 - m0) <= fp->sat_tol * m1) {
				st = 0;
				break;
			}
		}
	}
	if (st == 2)
		msg_seterr(fp->until == FRIC_UNTIL_SHEAR ? "G did not pass its minimum in %ld increments (sliding ratio %.4f)" :
		    "the sliding ratio did not saturate in %ld increments (last %.4f)", fp->max_inc, last->sliding_ratio);
	free(ratio), free(shear);
	loader_close(&L);
	return st;
}
