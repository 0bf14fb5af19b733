/* SPDX-License-Identifier: GPL-3.0-or-later */
/* law: a contact law as an interface, so that the enumerator and the engines never name one,
 * the pieces every law shares, and the table of the laws.
 *
 * A law gives, for one contact with its pair parameters (struct law_pair, set once per pair
 * by the law's pair setup from the two grains' materials, or a grain and a wall): its
 * quasi-static normal energy, force and stiffness at an overlap h (the functional and the
 * minimisers' stiffness bound); its frozen tangential and torsional stiffnesses and sliding
 * limits at a reference state (the friction of an increment, physics.md §3-5); and its force
 * in an explicit DEM step, with the history doubles it keeps per contact (the tangential
 * spring).
 *
 * Each law's closed forms live once, as stateless inline kernels in the law's own header,
 * and the law's interface functions and every fast path call them (the way LAMMPS
 * GRANULAR's sub-model kernels serve its generic and its accelerated paths):
 *
 *  - contact/hertz.h, contact_law_hertz_mindlin (contact/hertz.c): Hertz normal,
 *    U = 8/15 E* sqrt(R*) h^(5/2), Mindlin-Deresiewicz stick stiffness
 *    k* = 8 a / ((2-nu_i)/G_i + (2-nu_j)/G_j), sliding limit mu P, torsion
 *    k*_t = 16/3 a^3 / (1/G_i + 1/G_j) and M_max = 3 pi / 16 a mu P, a = sqrt(R* h); in DEM a
 *    viscous normal damping 2 zeta sqrt(m* k_n) and a tangential spring of kt_ratio k_n with
 *    a Coulomb limit.  The functional, friction, the contact network, the measures and the
 *    DEM engine (its sphere pass and two-lane copy, its plate pass) call its kernels.
 *  - contact/linear.h, contact_law_linear (contact/linear.c): a linear spring,
 *    U = k_n h^2 / 2, tangential k_t = kt_ratio k_n with a Coulomb limit, torsion none; in
 *    DEM the platy-particle paper's spring-dashpot law (per-element damped normal forces, a
 *    tangential spring of force increments with a dashpot).  k_n (N/m) is a field of the law.
 *
 * Either law's DEM entry (dem_interaction) takes an interaction of m element contacts, one
 * for spheres, so the DEM engine (dem/engine.h) runs each law on each shape.
 *
 * Here: the interface, the kernels every law's DEM force shares (the Coulomb limit, the
 * viscous damping coefficient, the tangential spring, the damped force; each with its
 * two-lane twin for the engine's sphere pass), and the table (CONTACT_LAWS), through which
 * a law is found by name or by a pack's contact-law key.  Adding a law: one file and one
 * row of CONTACT_LAWS (share/doc/library.md, "How to add a law").  SI units. */
#ifndef QUSGM_LAW_H
#define QUSGM_LAW_H

#include <math.h>
/* The SIMD twins of the kernels (lanes.h) are the library's own: QUSGM_BUILD, defined by the
 * Makefile for what it compiles, shows them; a program that includes the installed header
 * sees neither them nor lanes.h (its vector extensions warn under -pedantic). */
#ifdef QUSGM_BUILD
#include "base/lanes.h"
#endif
#include "pack/pack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A pair's physics, set once per pair by the law's pair setup (struct contact_law's pair;
 * hertz_mindlin_pair for both laws of the table). */
struct law_pair {
	double Es;	/* E* (Pa) */
	double Rs;	/* R* (m) */
	double Ct;	/* (2 - nu_i)/G_i + (2 - nu_j)/G_j (1/Pa): Mindlin tangential compliance */
	double Ctor;	/* 1/G_i + 1/G_j (1/Pa): torsional compliance */
	double mu;	/* friction coefficient (pack_contact_mu: grain-grain or grain-wall) */
	double kn;	/* linear law: normal stiffness (N/m; the law's kn, or the DEM's scaled 1) */
};

/* What a law's pair setup needs of a pack, resolved once (law_pack_bind) rather than per
 * pair: the pack, and a spring law's k_n (its meta kn: a string to parse). */
struct law_pack {
	const struct pack *p;
	double kn;		/* N/m: a spring law's (law_pack_kn), else the law's own kn */
};

/* The frozen tangential state of a contact at its reference overlap. */
struct law_tangent {
	double k, qmax;		/* stick stiffness (N/m), sliding limit (N) */
	double kt, mmax;	/* torsional stiffness (N m), limit (N m) */
};

/* One explicit step's input for a contact: overlap, unit normal on i, relative velocity
 * of the contact point (i minus j), reduced mass, time step. */
struct law_dem_in {
	double h, n[3], vr[3], meff, dt;
};

/* The most element contacts of one interaction (contact/plate.h's PLATE_MAX_ELEMENTS). */
#define LAW_DEM_ELEMENTS 16

/* One explicit step's input for an interaction of m element contacts sharing the unit normal
 * n (on i): a pair of spheres, or a sphere and a wall, has one; two spheroplates up to
 * LAW_DEM_ELEMENTS (vertex-face, edge-edge, ...).  Element k has overlap h[k] (at most 0: it
 * carries no elastic force) and relative normal velocity vn[k] of its two material points
 * (i minus j, along n: -dh/dt); vt is the relative velocity at the interaction's contact
 * point in the tangent plane; meff the reduced mass, dt the step; zeta the normal damping
 * ratio of the whole interaction and kt_ratio its tangential over normal stiffness (the
 * engine's: the law's own defaults, or a restitution coefficient's). */
struct law_dem_elems {
	int m;
	double h[LAW_DEM_ELEMENTS], vn[LAW_DEM_ELEMENTS];
	double n[3], vt[3], meff, dt, zeta, kt_ratio;
};

struct contact_law {
	const char *name;
	unsigned history;	/* doubles kept per contact in DEM (the tangential spring) */
	double kn;		/* linear law: normal stiffness (N/m) */
	double kt_ratio;	/* DEM: tangential spring over normal stiffness */
	double zeta;		/* DEM: viscous normal damping ratio */
	/* The pair's physics, of grain i and grain j, or wall w when j = PACK_WALL(w), of the
	 * pack lk binds (law_pack_bind). */
	void (*pair)(const struct contact_law *law, const struct law_pack *lk, size_t i, long j, struct law_pair *lp);
	/* Energy at overlap h > 0; the force dU/dh into *P and the stiffness dP/dh into *k
	 * unless NULL. */
	double (*normal)(const struct contact_law *law, const struct law_pair *lp, double h, double *P, double *k);
	/* The overlap h > 0 that carries normal force P > 0 (normal's inverse; 0 for P <= 0):
	 * what a limit at a committed force P0 is measured at (law_contact_limits). */
	double (*overlap)(const struct contact_law *law, const struct law_pair *lp, double P);
	/* The sliding limit at normal force P (mu P for a frictional law, 0 for a frictionless
	 * one): the tangent's qmax, which needs no overlap, for the checks of every history line
	 * at every commit. */
	double (*coulomb)(const struct contact_law *law, const struct law_pair *lp, double P);
	/* The tangential state at overlap h carrying normal force P, with the pair's mu: its
	 * stiffnesses and its Coulomb and twist limits (qmax, mmax), every consumer's limits. */
	void (*tangent)(const struct contact_law *law, const struct law_pair *lp, double h, double P, struct law_tangent *t);
	/* DEM: the forces of one interaction (struct law_dem_elems): each element's normal
	 * force magnitude into fk[k] (>= 0, damping included), their sum returned, its elastic
	 * part into *fel, and the interaction's tangential force on i into ft, updating its
	 * history (law->history doubles: the tangential spring); the Coulomb limit at the pair's
	 * mu times the summed normal force.  The one DEM entry of a law: the engine
	 * (dem/engine.h) calls it for every shape. */
	double (*dem_interaction)(const struct contact_law *law, const struct law_pair *lp,
	    const struct law_dem_elems *in, double *hist, double *fk, double ft[3], double *fel);
	/* The value of a pack's meta key contact-law that names this law ('hertz'; packgen's
	 * plates write 'linear'). */
	const char *pack_key;
	/* What the law's stiffness is made of: LAW_MODULI (the grains' E and nu, Hertz's) or
	 * LAW_SPRING (a constant k_n in N/m, the pack's meta kn: law_pack_kn). */
	enum law_stiffness { LAW_MODULI, LAW_SPRING } stiffness;
	/* Its policy, the decisions a consumer would otherwise take by asking which law it is:
	 *
	 * The DEM's units and scaled pairs (dem/engine.h): for pack p of mean spheroradius r0
	 * (m) and a run's spring stiffness kn (N/m; a LAW_MODULI law ignores it), the stiffness
	 * unit k0 (N/m) returned, and the grain-grain and grain-wall pair constants in those
	 * units (Es, kn; R* and mu are set by the engine) into g and w. */
	double (*dem_units)(const struct contact_law *law, const struct pack *p, double r0, double kn, struct law_pair *g,
	    struct law_pair *w);
	/* The normal stiffness, in the same units, of the stiffest contact a time step is made
	 * for: a grain of radius r on a wall of pair constants w at overlap h (the run's largest
	 * likely, ENGINE_OVERLAP_KAPPA / kappa of r; a spring law's stiffness has no overlap). */
	double (*stiffest)(const struct contact_law *law, const struct law_pair *w, double r, double h);
	/* The stiffness number kappa of a normal stress sigma (Pa) on pack p under the law at
	 * spring stiffness kn (engine.h's engine_kappa), and its inverse. */
	double (*kappa)(const struct contact_law *law, const struct pack *p, double kn, double sigma);
	double (*kappa_stress)(const struct contact_law *law, const struct pack *p, double kn, double kappa);
	/* The DEM history (law->history doubles; none when 0) and the tangential force on i it
	 * carries, both ways, for an interaction of elements in (its overlaps, kt_ratio; its
	 * velocities unused) with pair constants lp: what a pack's Q0 lines carry
	 * (pack-format.md), so that a pack written and read back goes on with the same spring. */
	void (*history_force)(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
	    const double *hist, double Q[3]);
	void (*history_set)(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
	    const double Q[3], double *hist);
	/* 0 when a confining stress (Pa) on pack p keeps the contacts in the law's range of
	 * validity, else -1 with the error slot set (Hertz: small strains, E/100). */
	int (*stress_in_range)(const struct contact_law *law, const struct pack *p, double stress);
};

/* The normal stiffness k_n (N/m) of a LAW_SPRING law on pack p: the pack's meta kn (packgen
 * and shear record the one they ran), else the law's default law->kn.  The one reader of
 * meta kn. */
double law_pack_kn(const struct contact_law *law, const struct pack *p);
/* lk bound to pack p for law's pair setup: a spring law's k_n read once (law_pack_kn). */
void law_pack_bind(const struct contact_law *law, const struct pack *p, struct law_pack *lk);
/* Whether pack p records what law's forces need: always for LAW_MODULI (the grains' E and
 * nu), the pack's meta kn for a spring law (a pack without one has unknown forces). */
int law_pack_knows_stiffness(const struct contact_law *law, const struct pack *p);
/* The spring laws' policy (struct contact_law): units k0 = k_n, pairs of scaled k_n 1;
 * stiffest 1 (k_n); kappa = k_n / (sigma r0), r0 the mean spheroradius (P eq. 6); a stress
 * is in range when its stiffness number is at least LAW_SPRING_KAPPA_MIN. */
#define LAW_SPRING_KAPPA_MIN 100.0
double law_spring_overlap(const struct contact_law *law, const struct law_pair *lp, double P);	/* P / k_n */
/* The Coulomb limit law_coulomb_limit(lp->mu, P) (Hertz-Mindlin's and the linear law's
 * coulomb), and a frictionless law's 0. */
double law_coulomb_mu(const struct contact_law *law, const struct law_pair *lp, double P);
double law_coulomb_none(const struct contact_law *law, const struct law_pair *lp, double P);
double law_spring_dem_units(const struct contact_law *law, const struct pack *p, double r0, double kn, struct law_pair *g,
    struct law_pair *w);
double law_spring_stiffest(const struct contact_law *law, const struct law_pair *w, double r, double h);
double law_spring_kappa(const struct contact_law *law, const struct pack *p, double kn, double sigma);
double law_spring_kappa_stress(const struct contact_law *law, const struct pack *p, double kn, double kappa);
int law_spring_stress_in_range(const struct contact_law *law, const struct pack *p, double stress);
/* The mean spheroradius of pack p (m): the DEM's length unit r0. */
double law_mean_radius(const struct pack *p);
/* A history that carries no force (history 0, a law without tangential force): Q = 0. */
void law_history_none(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double *hist, double Q[3]);
void law_history_set_none(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double Q[3], double *hist);
/* A spring that keeps its force (the linear law's): Q = -hist, hist = -Q. */
void law_history_force_kept(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double *hist, double Q[3]);
void law_history_set_force_kept(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double Q[3], double *hist);

/* The table of the laws, one row each: X(C name of the law's object, after contact_law_).
 * The first row is the default, the law of a pack without a contact-law key. */
#define CONTACT_LAWS(X) \
	X(hertz_mindlin) \
	X(linear) \
	X(harmonic)

#define CONTACT_LAW_EXTERN(id) extern const struct contact_law contact_law_##id;
CONTACT_LAWS(CONTACT_LAW_EXTERN)
#undef CONTACT_LAW_EXTERN

/* The sliding and twist limits of a contact of pair constants lp at normal force P (the
 * law's tangent at its overlap), into *qmax and *mmax unless NULL: a history line's limits at
 * its P0, the frictional chain's history checks and commit clamp. */
void law_contact_limits(const struct contact_law *law, const struct law_pair *lp, double P, double *qmax,
    double *mmax);
/* Whether history line c of the pack lk binds sits at its sliding limit: |Q0| at the law's
 * limit at P0 (its coulomb), to 1e-9 (a frictionless law's limit is 0: never).  The sliding
 * ratio's count; law_line_at_limit with the line's pair constants lp already made. */
int law_contact_at_limit(const struct contact_law *law, const struct law_pack *lk, const struct pack_contact *c);
int law_line_at_limit(const struct contact_law *law, const struct law_pair *lp, const struct pack_contact *c);

/* The laws of the table, in its order, NULL-terminated. */
extern const struct contact_law *const contact_laws[];
/* Find a law by name ("hertz-mindlin", "linear") or by its pack key ("hertz"); NULL when
 * unknown. */
const struct contact_law *contact_law_find(const char *name);
/* The law of pack p: its meta contact-law key's (contact_law_find), the table's first
 * (Hertz-Mindlin) without the key; NULL, with the error slot set, for a key no law has. */
const struct contact_law *contact_law_of_pack(const struct pack *p);
/* The names of the table's laws, as "hertz-mindlin (hertz), linear": each law's name and,
 * where it differs, its pack key, in the table's order, into buf (truncated to size). */
void contact_law_names(char *buf, size_t size);
/* The help line of a tool's --law option, from the table: "contact law: hertz-mindlin
 * (hertz), linear, ... (default: ...)". */
void contact_law_option_help(char *buf, size_t size);
/* The law a tool runs: the one named `name` (an option: contact_law_find) when name is not
 * NULL, else pack p's (contact_law_of_pack).  NULL, with the error slot set, for a name or
 * key no law has ("no such contact law '...': the laws are ..."). */
const struct contact_law *contact_law_choose(const struct pack *p, const char *name);
/* The laws of the quasi-static frictional chain (frictionalize, loadtest, dissociate, and
 * packinfo's sphere report of their packs): those whose tangential closed forms its
 * incremental solve, its history checks (qs/friction.c) and the sphere report's limits
 * (analysis/measure.c) implement, Mindlin's Coulomb and twist limits through the contact
 * radius.  A pack of another law is refused there (contact_law_require), not run as Hertz,
 * and packinfo gives it the report of the DEM's packs.  NULL-terminated. */
extern const struct contact_law *const contact_laws_qs_friction[];
/* Whether law is one of laws (NULL-terminated). */
int contact_law_in(const struct contact_law *law, const struct contact_law *const *laws);
/* The law of pack p (contact_law_of_pack) when it is one of laws (NULL-terminated): a tool
 * that runs only some laws (who: its name).  NULL with the error slot set for a law not
 * among them ("the pack's contact law is linear; frictionalize runs hertz-mindlin"). */
const struct contact_law *contact_law_require(const struct pack *p, const char *who,
    const struct contact_law *const *laws);
/* Record law as pack p's, for a tool that ran p under it: p's contact-law key set to the
 * law's pack key, unless p's law is law already (a pack without the key, Hertz-Mindlin's,
 * stays without it).  0 or -1 (out of memory). */
int contact_law_claim(struct pack *p, const struct contact_law *law);

/* The DEM kernels, inline so that the DEM's force loop, which uses Hertz-Mindlin by design,
 * inlines them (through the law's pointer they cost a call per contact and step: packgen
 * 20 % more instructions, measured with callgrind). */
#if defined(__GNUC__)
#define LAW_INLINE static inline __attribute__((always_inline))
#else
#define LAW_INLINE static inline
#endif

/* The Coulomb limit: the largest tangential force mu P a contact carries at normal force P. */
LAW_INLINE double
law_coulomb_limit(double mu, double P)
{
	return mu * P;
}

/* The viscous damping coefficient 2 zeta sqrt(m k) of damping ratio zeta, mass m, stiffness k. */
LAW_INLINE double
law_damping(double zeta, double m, double k)
{
	return 2 * zeta * sqrt(m * k);
}

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

/* The DEM force of a law of DEM damping ratio zeta and tangential ratio kt_ratio, for normal
 * stiffness kn, elastic normal force fn0 and friction coefficient mu: the normal force
 * fn0 - law_damping(zeta, m*, kn) v_n, not below 0 (returned; fn0 into *fel), and the
 * spring's tangential force at kt_ratio kn within law_coulomb_limit(mu, fn). */
LAW_INLINE double
law_dem_damped(double zeta, double kt_ratio, double mu, const struct law_dem_in *in, double kn, double fn0,
    double *hist, double ft[3], double *fel)
{
	double vn = in->vr[0] * in->n[0] + in->vr[1] * in->n[1] + in->vr[2] * in->n[2], vt[3], fn;
	int a;

	*fel = fn0;
	fn = fn0 - law_damping(zeta, in->meff, kn) * vn;
	if (fn < 0)
		fn = 0;
	for (a = 0; a < 3; a++)
		vt[a] = in->vr[a] - vn * in->n[a];
	law_dem_spring(hist, in->n, vt, in->dt, kt_ratio * kn, law_coulomb_limit(mu, fn), ft);
	return fn;
}

/* A tangential force Q scaled to magnitude qmax when it is larger. */
LAW_INLINE void
law_clamp_tangential(double Q[3], double qmax)
{
	double q = sqrt(Q[0] * Q[0] + Q[1] * Q[1] + Q[2] * Q[2]);
	int a;

	if (q > qmax && q > 0)
		for (a = 0; a < 3; a++)
			Q[a] *= qmax / q;
}

#if defined(QUSGM_BUILD) && LANES_OK
/* The twins of the kernels above on two contacts at once, one in each lane of v2d (lanes.h):
 * lane by lane the same operations in the same order, so the scalar kernel's bytes
 * (tests/unit/test_dem.c's test_lanes checks the sphere DEM both ways); both branches of a
 * clamp computed and one chosen by a mask.  A change above goes here too. */
LAW_INLINE v2d
law_coulomb_limit2(double mu, v2d P)
{
	return mu * P;
}

LAW_INLINE v2d
law_damping2(double zeta, v2d m, v2d k)
{
	return 2 * zeta * V2_SQRT(m * k);
}

/* law_dem_spring: xi and ft three-vectors of v2d. */
LAW_INLINE void
law_dem_spring2(v2d xi[3], const v2d n[3], const v2d vt[3], double dt, v2d kt, v2d fmaxt, v2d ft[3])
{
	const v2d zero = {0, 0}, one = {1, 1};
	v2d xn = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2], old, now, sc;
	v2m m;
	int a;

	old = V2_SQRT(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	for (a = 0; a < 3; a++)
		xi[a] -= xn * n[a];
	now = V2_SQRT(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	m = now > 0;
	sc = V2_SELECT(m, old / V2_SELECT(m, now, one), zero);
	for (a = 0; a < 3; a++) {
		xi[a] = xi[a] * sc + vt[a] * dt;
		ft[a] = -kt * xi[a];
	}
	now = V2_SQRT(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
	m = (now > fmaxt) & (now > 0);
	if (m[0] | m[1]) {
		sc = fmaxt / V2_SELECT(m, now, one);
		for (a = 0; a < 3; a++) {
			ft[a] = V2_SELECT(m, ft[a] * sc, ft[a]);
			xi[a] = V2_SELECT(m, -ft[a] / kt, xi[a]);
		}
	}
}

/* law_dem_damped: unit normals n, relative velocities vr, reduced masses meff, springs xi. */
LAW_INLINE v2d
law_dem_damped2(double zeta, double kt_ratio, double mu, const v2d n[3], const v2d vr[3], v2d meff, double dt,
    v2d kn, v2d fn0, v2d xi[3], v2d ft[3])
{
	const v2d zero = {0, 0};
	v2d vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2], vt[3], fn;
	int a;

	fn = fn0 - law_damping2(zeta, meff, kn) * vn;
	fn = V2_SELECT(fn < 0, zero, fn);
	for (a = 0; a < 3; a++)
		vt[a] = vr[a] - vn * n[a];
	law_dem_spring2(xi, n, vt, dt, kt_ratio * kn, law_coulomb_limit2(mu, fn), ft);
	return fn;
}
#endif

#ifdef __cplusplus
}
#endif

#endif
