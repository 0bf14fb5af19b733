/* frictionalize: uniaxial loading with friction until the sliding ratio saturates (see
 * frictionalize.h). */
#include "frictionalize.h"
#include "msg.h"

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
	fp->min_inc = 10;
	fp->max_inc = 300;
	fp->sat_tol = 0.005;
	load_params_default(&fp->lp);
}

int
frictionalize_run(struct pack *p, const struct fric_params *fp, fric_row_fn fn, void *ctx, struct load_row *last)
{
	struct loader L;
	struct load_row prev, row;
	struct hooke hk;
	double de[3] = {0, 0, 0}, *ratio;
	long k;
	int st = 2, a;

	ratio = malloc((fp->max_inc + 1) * sizeof *ratio);
	if (!ratio) {
		msg_seterr("out of memory");
		return -1;
	}
	if (loader_open(&L, p, &fp->lp) || loader_measure(&L, &prev)) {
		free(ratio);
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
			dS[0][a] = row.sig[a] - prev.sig[a];
		}
		if (hooke_fit((const double(*)[3])dE, (const double(*)[3])dS, 1, &hk))
			hk.K = hk.G = NAN;
		row.seg = 1;
		if (fn)
			fn(&row, &hk, ctx);
		*last = row;
		prev = row;
		if (r == 1) {
			msg_seterr("increment %ld: the minimiser hit its iteration limit (residual %.3g)", k, row.res_max);
			st = 1;
			break;
		}
		ratio[k] = row.sliding_ratio;
		if (k >= fp->window && k >= fp->min_inc) {
			double lo = INFINITY, hi = -INFINITY;
			long q;
			for (q = k - fp->window + 1; q <= k; q++) {
				lo = fmin(lo, ratio[q]);
				hi = fmax(hi, ratio[q]);
			}
			if (hi - lo < fp->sat_tol) {
				st = 0;
				break;
			}
		}
	}
	if (st == 2)
		msg_seterr("the sliding ratio did not saturate in %ld increments (last %.4f)", fp->max_inc,
		    last->sliding_ratio);
	free(ratio);
	loader_close(&L);
	return st;
}
