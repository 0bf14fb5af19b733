/* SPDX-License-Identifier: GPL-3.0-or-later */
/* dissociate: hydrate dissociation in a pack (physics.md section 11; S section 4.2).
 *
 * A drop dS < 0 of the hydrate saturation S = V_hydrate / V_pores (the hydrate counted as
 * pore space) and an excess pore pressure p_ex > 0 act on a pack in three ways, in this order:
 *   (a) every hydrate grain shrinks by the same volumetric strain dV/V = dS / S, so that the
 *       hydrate volume falls by the fraction dS / S and, box and mineral unchanged, S by dS;
 *   (b) every grain is compressed by the fluid: dV_i / V_i = -p_ex / K_i, with
 *       K_i = E_i / (3 (1 - 2 nu_i)) the bulk modulus of its material (the fluid's net force on
 *       a grain is neglected, as in S);
 *   (c) the box expands isotropically by the volumetric strain eps_kk = alpha_b p_ex / K, with
 *       alpha_b the Biot-Willis coefficient and K the drained bulk modulus of the pack before
 *       dissociation: each box length grows by the factor 1 + eps_kk / 3 (the three linear
 *       strains sum to eps_kk, as the strains of the tables are summed);
 * and (d) the grains find the new equilibrium in the expanded box, one increment of the
 * loader (qs/loading.h) with the grains carried affinely, friction history committed.
 *
 * Stresses are the volume-averaged (Love-Weber) mean stress, the skeleton's effective stress
 * (the stress the contacts carry); the total stress is sigma' + alpha_b p_ex (Biot). */
#ifndef QUSGM_DISSOCIATE_H
#define QUSGM_DISSOCIATE_H

#include "qs/loading.h"
#include "pack/pack.h"

struct dissociation {
	double dS;		/* change of the hydrate saturation, <= 0 */
	double pex;		/* excess pore pressure applied, >= 0 (Pa) */
	double alpha;		/* Biot-Willis coefficient, in (0, 1] */
	double K;		/* the pack's bulk modulus (Pa); NaN: measured by the probe */
	double probe;		/* the probe's isotropic extension per axis (strain) */
};

struct dissociation_report {
	double S_before, S_after;	/* hydrate saturation */
	double K;			/* bulk modulus used for (c) (Pa) */
	int K_measured;			/* 1 when the probe measured it */
	double eps_kk;			/* the box's volumetric expansion of (c) */
	double sigma_before, sigma_after;		/* Love-Weber mean stress (Pa) */
	double sigma_wall_before, sigma_wall_after;	/* mean of the wall stresses (Pa) */
	double sigma_total_after;	/* sigma_after + alpha p_ex */
	struct load_row before, after;	/* the states, as load rows */
	long probe_iterations;
};

/* The bulk modulus K_i = E / (3 (1 - 2 nu)) of a grain's material. */
double dissociate_grain_K(double E, double nu);

/* Refuse what has no meaning, with the reason in msg_seterr: dS > 0, p_ex < 0, dS < 0 on a
 * pack without hydrate grains, dS <= -S (it would remove all the hydrate there is or more), a
 * p_ex above 1 % of the smallest grain K_i (beyond small strain), alpha outside (0, 1], a K
 * given that is not positive, a probe outside (0, 1e-3].  *S receives the pack's saturation.  0 or -1. */
int dissociate_check(const struct pack *p, const struct dissociation *d, double *S);

/* Steps (a) and (b) on the radii of p: hydrate grains r *= cbrt(1 + dS / S), then every grain
 * r *= cbrt(1 - p_ex / K_i).  S is the pack's saturation before (dissociate_check). */
void dissociate_radii(struct pack *p, double dS, double S, double pex);

/* The drained bulk modulus of p by a probe on a copy: the isotropic extension 'probe' per
 * axis in one loader increment from the pack's state, K = -d(mean sig_lw) / (3 probe), the
 * volumetric strain against the current box (as in step (c)).  An
 * extension, because dissociation unloads the skeleton (on a frictional pack the unloading
 * modulus is the one that applies).  p is not changed.  before receives the pack's state.
 * 0, or -1 (msg_seterr; the minimiser not converging is an error too). */
int dissociate_probe_K(const struct pack *p, const struct load_params *lp, double probe, struct load_row *before,
    double *K, long *iterations);

/* The whole dissociation on p: check, probe (when d->K is NaN and p_ex > 0), (a)-(d).  With
 * dS = 0 and p_ex = 0 nothing is changed and nothing is computed.  0, or -1 (msg_seterr). */
int dissociate_run(struct pack *p, const struct load_params *lp, const struct dissociation *d,
    struct dissociation_report *rep);

#endif
