/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hertz: the Hertz-Mindlin contact law's closed forms, the one home of each (physics.md §2-5).
 *
 * Normal (Hertz): R* = (1/R_i + 1/R_j)^-1 (wall: R_i), E* = ((1-nu_i^2)/E_i + (1-nu_j^2)/E_j)^-1,
 * overlap h, contact radius a = sqrt(R* h), P = 4/3 E* sqrt(R*) h^(3/2), U = 8/15 E* sqrt(R*)
 * h^(5/2) = 2/5 P h, dU/dh = P, dP/dh = 2 E* a.  Tangential (Mindlin-Deresiewicz): stick
 * stiffness k* = 8 a / Ct, sliding limit mu P (law_coulomb_limit), torsional stiffness
 * k*_t = 16/3 a^3 / Ctor and limit M_max = 3 pi / 16 a mu P (struct law_pair's compliances).
 * DEM: normal stiffness k_n = dP/dh, elastic force 2/3 k_n h, damped and with a tangential
 * spring as law.h's law_dem_damped.  SI units.
 *
 * Stateless inline kernels, called by the law's interface (hertz.c: contact_law_hertz_mindlin,
 * and its pair setup hertz_mindlin_pair) and by every fast path: the functional's Hertz
 * evaluation, Hessian and stiffness bound (qs/functional.c), friction's limits (qs/friction.c),
 * the contact network (contacts.c), the measures (analysis/measure.c) and the DEM engine
 * (its interactions of m elements, hertz_dem_interaction; its sphere pass's inlined
 * hertz_dem_force and two-lane hertz_dem_force2, dem/engine_spheres.c).  Where a
 * fast path keeps a product (the pair's coefficient 4/3 E* sqrt(R*) by list entry, E* from
 * per-grain compliances), the kernels are cut there, so that every path computes the same
 * operations in the same order: the same bytes. */
#ifndef QUSGM_HERTZ_H
#define QUSGM_HERTZ_H

#include <math.h>
#include "contact/law.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Hertz theory is for small strains: overlaps ~ (sigma/E)^(2/3) R reach 5 % near E/100, with
 * E the softest grain's modulus, whose contacts strain most (against the mean modulus a grain
 * of E = 1e-300 passed, and densify squeezed it by 0.47 R).  0 when stress (Pa) on pack p
 * is below E/100 of its softest grain, else -1 with the error slot set ("S Pa is beyond the
 * small-strain range of Hertz contacts (...)"). */
int hertz_stress_in_range(const struct pack *p, double stress);
/* E* of two grains of pack p's mean Young's modulus and Poisson ratio (Pa): the law's
 * stiffness number and the DEM's stiffness unit E* r0. */
double hertz_mean_Estar(const struct pack *p);

/* A grain's (or the walls') normal compliance (1 - nu^2) / E (1/Pa). */
LAW_INLINE double
hertz_compliance(double E, double nu)
{
	return (1.0 - nu * nu) / E;
}

/* E* of two compliances (hertz_compliance). */
LAW_INLINE double
hertz_Estar_c(double ci, double cj)
{
	return 1.0 / (ci + cj);
}

LAW_INLINE double
hertz_Estar(double Ei, double nui, double Ej, double nuj)
{
	return hertz_Estar_c(hertz_compliance(Ei, nui), hertz_compliance(Ej, nuj));
}

LAW_INLINE double
hertz_Rstar(double Ri, double Rj)
{
	return Ri * Rj / (Ri + Rj);
}

/* E* and R* of grain i with grain j, or with wall w when j = PACK_WALL(w) (the wall's moduli,
 * R* = r_i): the one rule of every consumer (the law's pair setup, the contact network,
 * friction's history checks, the measures). */
LAW_INLINE void
hertz_pair_moduli(const struct pack *p, size_t i, long j, double *Es, double *Rs)
{
	if (PACK_IS_WALL(j)) {
		*Es = hertz_Estar(p->E[i], p->nu[i], p->wall_E, p->wall_nu);
		*Rs = p->r[i];
	} else {
		*Es = hertz_Estar(p->E[i], p->nu[i], p->E[j], p->nu[j]);
		*Rs = hertz_Rstar(p->r[i], p->r[j]);
	}
}

/* The pair setup of Hertz-Mindlin (struct contact_law's pair; the linear law's too): E* and R*
 * (hertz_pair_moduli), the Mindlin compliances Ct and Ctor, and mu (pack_contact_mu). */
void hertz_mindlin_pair(const struct contact_law *law, const struct law_pack *lk, size_t i, long j, struct law_pair *lp);

/* The contact radius a = sqrt(R* h) at overlap h >= 0. */
LAW_INLINE double
hertz_radius(double Rs, double h)
{
	return sqrt(Rs * h);
}

/* The normal force's coefficient 4/3 E* sqrt(R*), from sqrt(R*): P = coef h^(3/2). */
LAW_INLINE double
hertz_coef(double Es, double sRs)
{
	return 4.0 / 3.0 * Es * sRs;
}

/* The normal force coef h^(3/2) at an overlap h > 0 (hertz_coef). */
LAW_INLINE double
hertz_force_c(double coef, double h)
{
	return coef * h * sqrt(h);
}

/* Normal force for overlap h (0 when h <= 0). */
LAW_INLINE double
hertz_force(double Es, double Rs, double h)
{
	return h > 0 ? hertz_force_c(hertz_coef(Es, sqrt(Rs)), h) : 0.0;
}

/* The elastic energy at overlap h of a contact carrying force P: 8/15 E* sqrt(R*) h^(5/2)
 * = 2/5 P h. */
LAW_INLINE double
hertz_energy_P(double P, double h)
{
	return 0.4 * P * h;
}

/* Elastic energy stored at overlap h. */
LAW_INLINE double
hertz_energy(double Es, double Rs, double h)
{
	return hertz_energy_P(hertz_force(Es, Rs, h), h);
}

/* Normal stiffness dP/dh = 2 E* a at an overlap h > 0 (the DEM's k_n). */
LAW_INLINE double
hertz_stiffness_t(double Es, double Rs, double h)
{
	return 2 * Es * hertz_radius(Rs, h);
}

/* Normal stiffness dP/dh = 2 E* sqrt(R* h) (0 when h <= 0). */
LAW_INLINE double
hertz_stiffness(double Es, double Rs, double h)
{
	return h > 0 ? hertz_stiffness_t(Es, Rs, h) : 0.0;
}

/* The normal force 2/3 k_n h from the stiffness k_n = dP/dh at overlap h (the DEM's form). */
LAW_INLINE double
hertz_force_k(double kn, double h)
{
	return kn * h * (2.0 / 3.0);
}

/* Overlap that carries force P (the inverse of hertz_force). */
LAW_INLINE double
hertz_overlap(double Es, double Rs, double P)
{
	return P > 0 ? cbrt(P * P * 9.0 / (16.0 * Es * Es * Rs)) : 0.0;
}

/* Mindlin-Deresiewicz stick stiffness 8 a / Ct at contact radius a (Ct: struct law_pair). */
LAW_INLINE double
mindlin_stiffness(double a, double Ct)
{
	return 8 * a / Ct;
}

/* Torsional stiffness 16/3 a^3 / Ctor (Ctor: struct law_pair). */
LAW_INLINE double
mindlin_twist_stiffness(double a, double Ctor)
{
	return 16.0 / 3.0 * a * a * a / Ctor;
}

/* pi as math.h's M_PI spells it, which strict ISO C (an installed header's user) lacks */
#define HERTZ_PI 3.14159265358979323846

/* The torsional limit's ratio to the sliding limit, 3 pi / 16 a: M_max = this times mu P. */
LAW_INLINE double
mindlin_twist_ratio(double a)
{
	return 3 * HERTZ_PI / 16 * a;
}

/* The twist limit M_max = 3 pi / 16 a mu P of a contact of radius a at normal force P. */
LAW_INLINE double
mindlin_twist_limit(double a, double mu, double P)
{
	return mindlin_twist_ratio(a) * mu * P;
}

/* The DEM force of Hertz-Mindlin (law.h's law_dem_damped at k_n = dP/dh, elastic force
 * 2/3 k_n h) with damping ratio zeta, tangential ratio kt_ratio, the pair's E*, R* and mu. */
LAW_INLINE double
hertz_dem_force(double zeta, double kt_ratio, const struct law_pair *lp, const struct law_dem_in *in, double *hist,
    double ft[3], double *fel)
{
	double kn = hertz_stiffness_t(lp->Es, lp->Rs, in->h);

	return law_dem_damped(zeta, kt_ratio, lp->mu, in, kn, hertz_force_k(kn, in->h), hist, ft, fel);
}

/* The DEM forces of an interaction of m element contacts (law.h, struct law_dem_elems) under
 * Hertz-Mindlin: element k carries the Hertz force 2/3 k_k h_k, k_k = 2 E* sqrt(R* h_k) its
 * stiffness dP/dh, less the viscous damping law_damping(zeta, m* / m, k_k) v_n,k, not below 0
 * (the interaction's reduced mass shared by its elements, so that a head-on collision has
 * the damping ratio zeta whether it meets one element or four); the interaction's tangential
 * spring has kt_ratio times the elements' summed stiffness, within the Coulomb limit of the
 * summed normal force.  Every element has the pair's E* and R* (for two spheroplates, R* of
 * their spheroradii: the element contacts are between the rounded rims and faces, and the
 * value joins the sphere's as the platyness goes to 0).  With one element this is
 * hertz_dem_force to the bit (tests/unit/test_law.c). */
LAW_INLINE double
hertz_dem_interaction(const struct law_pair *lp, const struct law_dem_elems *in, double *hist, double *fk,
    double ft[3], double *fel)
{
	double fsum = 0, ksum = 0, esum = 0;
	int k;

	for (k = 0; k < in->m; k++) {
		double h = in->h[k] > 0 ? in->h[k] : 0, kn = hertz_stiffness_t(lp->Es, lp->Rs, h), f0 = hertz_force_k(kn, h), f;

		f = f0 - law_damping(in->zeta, in->meff / in->m, kn) * in->vn[k];
		fk[k] = f < 0 ? 0 : f;
		fsum += fk[k], ksum += kn, esum += f0;
	}
	*fel = esum;
	law_dem_spring(hist, in->n, in->vt, in->dt, in->kt_ratio * ksum, law_coulomb_limit(lp->mu, fsum), ft);
	return fsum;
}

#if defined(QUSGM_BUILD) && LANES_OK
/* The twins of the kernels the engine's sphere pass calls, on two contacts at once, one in
 * each lane (lanes.h, and law.h's twins): lane by lane the same operations in the same order
 * as the scalar kernel named, so the same bytes (tests/unit/test_dem.c's test_lanes).  A
 * change to one goes to its twin. */
LAW_INLINE v2d
hertz_Rstar2(v2d Ri, v2d Rj)
{
	return Ri * Rj / (Ri + Rj);
}

LAW_INLINE v2d
hertz_stiffness_t2(double Es, v2d Rs, v2d h)
{
	return 2 * Es * V2_SQRT(Rs * h);
}

LAW_INLINE v2d
hertz_force_k2(v2d kn, v2d h)
{
	return kn * h * (2.0 / 3.0);
}

/* hertz_dem_force with one E* and mu for both contacts: overlaps h, effective radii Rs, the
 * rest as law_dem_damped2. */
LAW_INLINE v2d
hertz_dem_force2(double zeta, double kt_ratio, double mu, double Es, v2d Rs, v2d h, const v2d n[3], const v2d vr[3],
    v2d meff, double dt, v2d xi[3], v2d ft[3])
{
	v2d kn = hertz_stiffness_t2(Es, Rs, h);

	return law_dem_damped2(zeta, kt_ratio, mu, n, vr, meff, dt, kn, hertz_force_k2(kn, h), xi, ft);
}
#endif

#ifdef __cplusplus
}
#endif

#endif
