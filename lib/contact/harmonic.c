/* SPDX-License-Identifier: GPL-3.0-or-later */
/* harmonic: frictionless harmonic spheres, the soft-sphere model of jamming studies (O'Hern,
 * Silbert, Liu and Nagel, Phys. Rev. E 68, 011306, 2003): a normal spring of constant
 * stiffness and nothing else.
 *
 * Normal: P = k_n h, U = k_n h^2 / 2, dP/dh = k_n (h > 0), with k_n the pack's meta kn
 * (law_pack_kn; default 1e5 N/m).  Tangential: none (k = 0, sliding limit 0: a frictionless
 * contact), no torsion, so no history (law->history 0).  DEM: each element's damped normal
 * force k_n h - gamma_n dh/dt, never attractive, the linear law's (linear.h:
 * linear_element_force, gamma_n = law_damping(zeta, m* / m, k_n)); no tangential force.
 *
 * It is also the recipe's example (share/doc/library.md, "How to add a law"): one file and one
 * row of CONTACT_LAWS, with the spring laws' policy from law.h. */
#include "contact/law.h"
#include "contact/hertz.h"
#include "contact/linear.h"

static double
harmonic_normal(const struct contact_law *law, const struct law_pair *lp, double h, double *P, double *k)
{
	double kn = h > 0 ? lp->kn : 0, he = h > 0 ? h : 0;

	(void)law;
	if (P)
		*P = linear_force(kn, he);
	if (k)
		*k = kn;
	return linear_energy(kn, he);
}

static void
harmonic_tangent(const struct contact_law *law, const struct law_pair *lp, double h, double P, struct law_tangent *t)
{
	(void)law, (void)lp, (void)h, (void)P;
	t->k = t->qmax = t->kt = t->mmax = 0;
}

static double
harmonic_dem_interaction(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    double *hist, double *fk, double ft[3], double *fel)
{
	double gn = law_damping(in->zeta, in->meff / in->m, lp->kn), fsum = 0, esum = 0, fe;
	int k;

	(void)law, (void)hist;
	for (k = 0; k < in->m; k++) {
		fk[k] = linear_element_force(lp->kn, gn, in->h[k], in->vn[k], &fe);
		esum += fe, fsum += fk[k];
	}
	*fel = esum;
	ft[0] = ft[1] = ft[2] = 0;
	return fsum;
}

const struct contact_law contact_law_harmonic = {
	.name = "harmonic", .history = 0, .kn = 1e5, .kt_ratio = 0, .zeta = 0.3,
	.pair = hertz_mindlin_pair, .normal = harmonic_normal, .overlap = law_spring_overlap,
	.coulomb = law_coulomb_none, .tangent = harmonic_tangent,
	.dem_interaction = harmonic_dem_interaction, .pack_key = "harmonic", .stiffness = LAW_SPRING,
	.dem_units = law_spring_dem_units, .stiffest = law_spring_stiffest, .kappa = law_spring_kappa,
	.kappa_stress = law_spring_kappa_stress, .history_force = law_history_none, .history_set = law_history_set_none,
	.stress_in_range = law_spring_stress_in_range,
};
