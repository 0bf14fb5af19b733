/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linear: the linear spring-dashpot contact law's closed forms, the one home of each.
 *
 * Normal: P = k_n h, U = k_n h^2 / 2, dP/dh = k_n (h > 0).  Tangential (quasi-static):
 * k_t = kt_ratio k_n, sliding limit mu P (law_coulomb_limit), no torsion.
 *
 * DEM (linear_dem_interaction, for spheres and spheroplates alike): the spring-dashpot law of
 * the platy-particle paper (Boton et al. 2013, eqs. 2-4), an interaction of M element
 * contacts (vertex-face, edge-edge, ...; one for spheres) sharing the normal n;
 *  - each element's normal force k_n h - gamma_n dh/dt, with h its overlap (below 0: 0) and
 *    dh/dt = -v_n (v_n: the elements' relative velocity along n), not below 0
 *    (linear_element_force);
 *  - one tangential force for the interaction at its overlap-weighted contact point: a spring
 *    that keeps its force (increments k_t v_t dt, turned into the current tangent plane), a
 *    dashpot -gamma_t v_t, each capped at mu times the sum of the elements' normal forces
 *    (linear_tangential_force);
 *  - damping coefficients law_damping(zeta, m, k): gamma_n at the interaction's reduced mass
 *    shared by its elements (m* / M), gamma_t at m* and the interaction's k_t (M elements
 *    each of kt_ratio k_n).
 * SI units (or any consistent scaled ones: the plate engine's k_n = 1). */
#ifndef QUSGM_LINEAR_H
#define QUSGM_LINEAR_H

#include <math.h>
#include "base/vec3.h"
#include "contact/law.h"

/* Normal force k_n h of an overlap h > 0. */
LAW_INLINE double
linear_force(double kn, double h)
{
	return kn * h;
}

/* Elastic energy k_n h^2 / 2 of an overlap h > 0. */
LAW_INLINE double
linear_energy(double kn, double h)
{
	return 0.5 * kn * h * h;
}

/* One element's normal force k_n h - gn v_n, not below 0 (returned), with overlap h (below 0
 * counted as 0), v_n the relative velocity along n of the element's point (i minus j: -dh/dt)
 * and damping coefficient gn; its elastic part k_n h into *fel. */
LAW_INLINE double
linear_element_force(double kn, double gn, double h, double vn, double *fel)
{
	double he = h > 0 ? h : 0, f = linear_force(kn, he) - gn * vn;

	*fel = linear_force(kn, he);
	return f < 0 ? 0 : f;
}

/* The tangential force ft on i of an interaction of tangential stiffness kt, dashpot gt and
 * Coulomb cap cap (law_coulomb_limit of the summed normal force) at relative tangential
 * velocity vt (in the tangent plane of n): the spring hist (3 doubles: minus the force it
 * carries) advanced by kt vt dt in the current tangent plane and capped (law_dem_spring at
 * unit stiffness on force increments, so that a change of kt, elements coming and going,
 * makes no jump), then the dashpot -gt vt added and the sum capped again. */
LAW_INLINE void
linear_tangential_force(double *hist, const double n[3], const double vt[3], double dt, double kt, double gt,
    double cap, double ft[3])
{
	double kv[3] = {kt * vt[0], kt * vt[1], kt * vt[2]}, fm;
	int a;

	law_dem_spring(hist, n, kv, dt, 1.0, cap, ft);
	for (a = 0; a < 3; a++)
		ft[a] -= gt * vt[a];
	fm = vec3_norm(ft);
	if (fm > cap && fm > 0)
		for (a = 0; a < 3; a++)
			ft[a] *= cap / fm;
}


/* The DEM forces of an interaction of m element contacts (law.h, struct law_dem_elems) under
 * the linear law, P eqs. 2-4 (see above): each element k_n h_k - gamma_n v_n,k, not below 0,
 * gamma_n = law_damping(zeta, m* / m, k_n); one tangential force of stiffness m kt_ratio k_n
 * and dashpot law_damping(zeta, m*, that stiffness) within the Coulomb limit of the summed
 * normal force.  A pair of spheres or a sphere on a wall is its one-element case. */
LAW_INLINE double
linear_dem_interaction(const struct law_pair *lp, const struct law_dem_elems *in, double *hist, double *fk,
    double ft[3], double *fel)
{
	double gn = law_damping(in->zeta, in->meff / in->m, lp->kn), Kt = in->m * in->kt_ratio * lp->kn;
	double fsum = 0, esum = 0, fe;
	int k;

	for (k = 0; k < in->m; k++) {
		fk[k] = linear_element_force(lp->kn, gn, in->h[k], in->vn[k], &fe);
		esum += fe, fsum += fk[k];
	}
	*fel = esum;
	linear_tangential_force(hist, in->n, in->vt, in->dt, Kt, law_damping(in->zeta, in->meff, Kt),
	    law_coulomb_limit(lp->mu, fsum), ft);
	return fsum;
}

#endif
