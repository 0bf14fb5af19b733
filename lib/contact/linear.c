/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linear: the linear spring law through the interface of law.h, from the kernels of linear.h
 * (see there and law.h). */
#include "contact/linear.h"
#include "contact/hertz.h"

static double
linear_normal(const struct contact_law *law, const struct law_pair *lp, double h, double *P, double *k)
{
	(void)law;
	if (h <= 0) {
		if (P)
			*P = 0;
		if (k)
			*k = 0;
		return 0;
	}
	if (P)
		*P = linear_force(lp->kn, h);
	if (k)
		*k = lp->kn;
	return linear_energy(lp->kn, h);
}

static void
linear_tangent(const struct contact_law *law, const struct law_pair *lp, double h, double P, struct law_tangent *t)
{
	(void)h;
	t->k = law->kt_ratio * lp->kn;
	t->qmax = law_coulomb_limit(lp->mu, P);
	t->kt = 0;
	t->mmax = 0;
}

static double
linear_law_dem_interaction(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    double *hist, double *fk, double ft[3], double *fel)
{
	(void)law;
	return linear_dem_interaction(lp, in, hist, fk, ft, fel);
}

/* The pair setup: Hertz-Mindlin's (the moduli unused; mu; k_n the pack's, law_pack_bind);
 * the spring laws' policy (law.h); the history is the force the spring keeps. */
const struct contact_law contact_law_linear = {
	.name = "linear", .history = 3, .kn = 1e5, .kt_ratio = 0.888888888888889, .zeta = 0.3,
	.pair = hertz_mindlin_pair, .normal = linear_normal, .overlap = law_spring_overlap, .coulomb = law_coulomb_mu,
	.tangent = linear_tangent,
	.dem_interaction = linear_law_dem_interaction, .pack_key = "linear", .stiffness = LAW_SPRING,
	.dem_units = law_spring_dem_units, .stiffest = law_spring_stiffest, .kappa = law_spring_kappa,
	.kappa_stress = law_spring_kappa_stress, .history_force = law_history_force_kept,
	.history_set = law_history_set_force_kept, .stress_in_range = law_spring_stress_in_range,
};
