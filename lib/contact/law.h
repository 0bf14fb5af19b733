/* law: a contact law as an interface, so that the enumerator and the engines never name one.
 *
 * A law gives, for one contact with its pair parameters (struct law_pair, from the two
 * grains' materials or a grain and a wall): its quasi-static normal energy, force and
 * stiffness at an overlap h (the functional and the minimisers' stiffness bound); its
 * frozen tangential and torsional stiffnesses and sliding limits at a reference state (the
 * friction of an increment, physics.md §3-5); and its force in an explicit DEM step, with
 * the history doubles it keeps per contact (the tangential spring).  Two laws:
 *
 *  - contact_law_hertz_mindlin: Hertz normal, U = 8/15 E* sqrt(R*) h^(5/2) (hertz.h), with
 *    Mindlin-Deresiewicz stick stiffness k* = 8 a / ((2-nu_i)/G_i + (2-nu_j)/G_j), sliding
 *    limit mu P, torsion k*_t = 16/3 a^3 / (1/G_i + 1/G_j) and M_max = 3 pi / 16 a mu P,
 *    a = sqrt(R* h); in DEM a viscous normal damping 2 zeta sqrt(m* k_n) and a tangential
 *    spring of kt_ratio k_n with a Coulomb limit.  The functional inlines it (its fast path).
 *  - contact_law_linear: a linear spring, U = k_n h^2 / 2, tangential k_t = kt_ratio k_n with
 *    a Coulomb limit, torsion none; the same DEM damping.  For spheroplates' explicit DEM
 *    (the platy-particle paper uses linear springs); k_n (N/m) is a field of the law.
 * SI units. */
#ifndef QUSGM_LAW_H
#define QUSGM_LAW_H

#include <math.h>
#include "pack/pack.h"

struct law_pair {
	double Es;	/* E* (Pa) */
	double Rs;	/* R* (m) */
	double Ct;	/* (2 - nu_i)/G_i + (2 - nu_j)/G_j (1/Pa): Mindlin tangential compliance */
	double Ctor;	/* 1/G_i + 1/G_j (1/Pa): torsional compliance */
};

/* The frozen tangential state of a contact at its reference overlap. */
struct law_tangent {
	double k, qmax;		/* stick stiffness (N/m), sliding limit (N) */
	double kt, mmax;	/* torsional stiffness (N m), limit (N m) */
};

/* One explicit step's input for a contact: overlap, unit normal on i, relative velocity
 * of the contact point (i minus j), reduced mass, time step, friction coefficient. */
struct law_dem_in {
	double h, n[3], vr[3], meff, dt, mu;
};

struct contact_law {
	const char *name;
	unsigned history;	/* doubles kept per contact in DEM (the tangential spring) */
	double kn;		/* linear law: normal stiffness (N/m) */
	double kt_ratio;	/* DEM: tangential spring over normal stiffness */
	double zeta;		/* DEM: viscous normal damping ratio */
	/* Pair parameters of grain i and grain j, or wall w when j = PACK_WALL(w). */
	void (*pair)(const struct contact_law *law, const struct pack *p, size_t i, long j, struct law_pair *lp);
	/* Energy at overlap h > 0; the force dU/dh into *P and the stiffness dP/dh into *k
	 * unless NULL. */
	double (*normal)(const struct contact_law *law, const struct law_pair *lp, double h, double *P, double *k);
	/* The tangential state at overlap h carrying normal force P, with friction mu. */
	void (*tangent)(const struct contact_law *law, const struct law_pair *lp, double h, double P, double mu,
	    struct law_tangent *t);
	/* DEM: the normal force magnitude (returned, >= 0, damping included), its elastic part
	 * into *fel, and the tangential force on i into ft, updating the contact's history
	 * (law->history doubles). */
	double (*dem_force)(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_in *in,
	    double *hist, double ft[3], double *fel);
};

/* The DEM force pieces, inline so that the DEM's force loop, which uses Hertz-Mindlin by
 * design, inlines them (through the law's pointer they cost a call per contact and step:
 * packgen 20 % more instructions, measured with callgrind). */
#if defined(__GNUC__)
#define LAW_INLINE static inline __attribute__((always_inline))
#else
#define LAW_INLINE static inline
#endif

/* The tangential spring xi (3 doubles of history): turned into the current tangent plane
 * with its length kept, advanced by the sliding velocity, its force clamped to the Coulomb
 * limit (the spring then set back to the force it carries). */
LAW_INLINE void
law_dem_spring(double *xi, const double n[3], const double vt[3], double dt, double kt, double fmaxt, double ft[3])
{
	double xn = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2], old, now, s;
	int a;

	old = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	for (a = 0; a < 3; a++)
		xi[a] -= xn * n[a];
	now = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	s = now > 0 ? old / now : 0;
	for (a = 0; a < 3; a++) {
		xi[a] = xi[a] * s + vt[a] * dt;
		ft[a] = -kt * xi[a];
	}
	now = sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
	if (now > fmaxt && now > 0) {
		s = fmaxt / now;
		for (a = 0; a < 3; a++) {
			ft[a] *= s;
			xi[a] = -ft[a] / kt;
		}
	}
}

/* The DEM force for normal stiffness kn and elastic normal force fn0.  (lib/dem/dem.c's
 * contact_force2 repeats this and law_dem_spring, two contacts at a time in lanes: a change
 * here goes there too; tests/unit/test_dem.c's test_lanes catches a difference.) */
LAW_INLINE double
law_dem_damped(const struct contact_law *law, const struct law_dem_in *in, double kn, double fn0, double *hist,
    double ft[3], double *fel)
{
	double vn = in->vr[0] * in->n[0] + in->vr[1] * in->n[1] + in->vr[2] * in->n[2], vt[3], fn;
	int a;

	*fel = fn0;
	fn = fn0 - 2 * law->zeta * sqrt(in->meff * kn) * vn;
	if (fn < 0)
		fn = 0;
	for (a = 0; a < 3; a++)
		vt[a] = in->vr[a] - vn * in->n[a];
	law_dem_spring(hist, in->n, vt, in->dt, law->kt_ratio * kn, in->mu * fn, ft);
	return fn;
}

LAW_INLINE double
law_hertz_dem_force(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_in *in, double *hist,
    double ft[3], double *fel)
{
	double kn = 2 * lp->Es * sqrt(lp->Rs * in->h);

	return law_dem_damped(law, in, kn, kn * in->h * (2.0 / 3.0), hist, ft, fel);
}

extern const struct contact_law contact_law_hertz_mindlin;
extern const struct contact_law contact_law_linear;

/* The shared pair parameters from the grains' (and walls') moduli and radii. */
void law_pair_from_pack(const struct contact_law *law, const struct pack *p, size_t i, long j, struct law_pair *lp);
/* Find a law by name ("hertz-mindlin", "linear"); NULL when unknown. */
const struct contact_law *contact_law_find(const char *name);

#endif
