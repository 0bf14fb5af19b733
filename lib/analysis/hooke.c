/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hooke: least-squares Hooke's law (see hooke.h). */
#include "analysis/hooke.h"
#include "base/msg.h"

#include <gsl/gsl_multifit.h>
#include <math.h>

/* A column counts as determined when its norm is above this fraction of the larger one: the
 * deviatoric part of an isotropic increment is round-off (1e-16 of the trace). */
#define HOOKE_RANK_TOL 1e-9

int
hooke_fit(const double (*de)[3], const double (*ds)[3], size_t m, struct hooke *out)
{
	size_t rows = 3 * m, k, r;
	double vol2 = 0, dev2 = 0, big, s2 = 0, chisq;
	int a, ncol, cK = -1, cG = -1;
	gsl_matrix *X, *cov;
	gsl_vector *y, *c;
	gsl_multifit_linear_workspace *w;

	out->K = out->G = out->lambda = out->E = out->nu = NAN;
	out->K_se = out->G_se = NAN;
	out->has_K = out->has_G = 0;
	out->rms = out->rel = NAN;
	for (k = 0; k < m; k++) {
		double tr = de[k][0] + de[k][1] + de[k][2];
		for (a = 0; a < 3; a++) {
			double dv = de[k][a] - tr / 3;
			vol2 += tr * tr;
			dev2 += 4 * dv * dv;
			s2 += ds[k][a] * ds[k][a];
		}
	}
	big = fmax(vol2, dev2);
	if (!(big > 0)) {
		msg_seterr("no strain: the interval determines no modulus");
		return -1;
	}
	ncol = 0;
	if (vol2 > HOOKE_RANK_TOL * HOOKE_RANK_TOL * big)
		cK = ncol++;
	if (dev2 > HOOKE_RANK_TOL * HOOKE_RANK_TOL * big)
		cG = ncol++;
	X = gsl_matrix_alloc(rows, ncol);
	y = gsl_vector_alloc(rows);
	c = gsl_vector_alloc(ncol);
	cov = gsl_matrix_alloc(ncol, ncol);
	w = gsl_multifit_linear_alloc(rows, ncol);
	if (!X || !y || !c || !cov || !w)
		msg_die(1, "out of memory");
	for (k = 0, r = 0; k < m; k++) {
		double tr = de[k][0] + de[k][1] + de[k][2];
		for (a = 0; a < 3; a++, r++) {
			if (cK >= 0)
				gsl_matrix_set(X, r, cK, tr);
			if (cG >= 0)
				gsl_matrix_set(X, r, cG, 2 * (de[k][a] - tr / 3));
			gsl_vector_set(y, r, ds[k][a]);
		}
	}
	gsl_multifit_linear(X, y, c, cov, &chisq, w);
	if (cK >= 0) {
		out->K = gsl_vector_get(c, cK);
		out->has_K = 1;
	}
	if (cG >= 0) {
		out->G = gsl_vector_get(c, cG);
		out->has_G = 1;
	}
	if (out->has_K && out->has_G) {
		double K = out->K, G = out->G;
		out->lambda = K - 2 * G / 3;
		out->E = 9 * K * G / (3 * K + G);
		out->nu = (3 * K - 2 * G) / (2 * (3 * K + G));
	}
	/* the columns are orthogonal (sum_l dev_ll = 0), so X^T X is diagonal, vol2 and dev2 */
	if (rows > (size_t)ncol) {
		double var = chisq / (double)(rows - (size_t)ncol);
		if (out->has_K)
			out->K_se = sqrt(var / vol2);
		if (out->has_G)
			out->G_se = sqrt(var / dev2);
	}
	out->rms = sqrt(chisq / rows);
	out->rel = s2 > 0 ? out->rms / sqrt(s2 / rows) : 0;
	gsl_multifit_linear_free(w);
	gsl_matrix_free(X), gsl_matrix_free(cov);
	gsl_vector_free(y), gsl_vector_free(c);
	return 0;
}
