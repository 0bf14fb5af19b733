/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hooke: isotropic Hooke's-law fits of stress-strain increments (physics.md §8).
 *
 * For strain increments de (3 principal components, compression positive) and the stress
 * increments ds they caused, least squares of  ds_ll = lambda tr(de) + 2 G de_ll  over every
 * component of every increment.  Written as ds_ll = K tr(de) + 2 G dev_ll with dev = de - tr/3,
 * the two columns are orthogonal, so K is determined by the volumetric parts and G by the
 * deviatoric parts separately: an isotropic path gives K and no G (G is NaN, has_G = 0),
 * a path without volume change gives G and no K; neither is made up.  The fit is
 * gsl_multifit_linear on the columns that the path determines; lambda, E and nu follow from
 * K and G when both are known (NaN otherwise).
 *
 * The standard errors K_se and G_se are those of least squares: with s^2 = chisq / (3m - p)
 * the residual variance (p the number of fitted columns, 1 or 2), se_j = sqrt(s^2 [(X^T X)^-1]_jj);
 * the columns being orthogonal, K_se = s / sqrt(sum tr^2) and G_se = s / sqrt(sum 4 dev_ll^2)
 * over the 3m components.  They measure the scatter of the increments about Hooke's law, not
 * how the moduli depend on the strain step; NaN where the modulus is undetermined or 3m <= p. */
#ifndef QUSGM_HOOKE_H
#define QUSGM_HOOKE_H

#include <stddef.h>

struct hooke {
	double K, G, lambda, E, nu;	/* Pa, Pa, Pa, Pa, - (NaN when undetermined) */
	double K_se, G_se;	/* standard errors of K and G (Pa; NaN when undetermined) */
	int has_K, has_G;
	double rms;		/* rms of ds - fit over the 3m components (Pa) */
	double rel;		/* rms / rms(ds) */
};

/* m increments; returns 0, or -1 (msg_seterr) when the path determines neither K nor G. */
int hooke_fit(const double (*de)[3], const double (*ds)[3], size_t m, struct hooke *out);

#endif
