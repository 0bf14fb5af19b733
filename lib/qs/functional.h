/* SPDX-License-Identifier: GPL-3.0-or-later */
/* functional: the total potential energy Pi of a pack and its exact gradient (physics.md §2, §6).
 *
 * Pi is a sum of terms (struct qs_term), each adding its energy, its gradient and its part
 * of the minimisers' stiffness bound: the contact law's normal energy over every contact,
 * installed by qs_init (Hertz: U(h) = 8/15 E* sqrt(R*) h^(5/2) at grain centres x inside the
 * walls of the current box; dPi/dx_i = -F_i, the sum of contact forces on grain i), and the
 * friction of an increment (friction.h) when fr_begin adds it; a pore-pressure or growth
 * term plugs in the same way.  The constant U(h0) of the papers' Pi is left out: minimisers
 * only need differences.  Contacts come from the contact enumerator (contact/contacts.h),
 * whose Verlet list is rebuilt whenever it may have gone stale, so no contact is missed
 * however far the grains move between evaluations.  The order of the unknowns is layout.h's.
 *
 * Public API (share/doc/library.md): qs_init(&s, &p, 0.3) makes a system over a pack that the
 * caller owns and keeps alive (s->p points at it; the radii, moduli and box are read at each
 * evaluation); qs_free releases what qs_init allocated, never the pack.  qs_energy reads x
 * (s->dim values, p->x itself for the stored centres) and writes g and fmax, arrays of the
 * caller.  Errors: qs_init returns -1 and qs_energy NAN with the error slot set (base/msg.h).
 * A system is not thread-safe (its neighbour list is updated by every evaluation); an
 * evaluation itself runs on par_threads() threads (base/par.h) and gives the same bytes for
 * any count. */
#ifndef QUSGM_FUNCTIONAL_H
#define QUSGM_FUNCTIONAL_H

#include "contact/contacts.h"
#include "contact/law.h"
#include "pack/pack.h"
#include "qs/layout.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Default floor of a grain's largest contact force in the residual, relative to the mean
 * normal contact force (see qs_residual); packinfo and the minimisers share it. */
#define QS_RESIDUAL_FLOOR CONTACT_RESIDUAL_FLOOR

struct qs_system;
struct qs_hessian;

/* A term of Pi.  energy adds the term's energy at x (returned), its gradient into g (dim)
 * unless NULL and each grain's largest contact force into fmax (n) unless NULL; stiffness
 * adds each grain's stiffness bound (N/m per unit of the scaled unknowns) into k (n);
 * hessian, where the term has one (NULL otherwise), adds its second derivatives at x into H
 * (hessian.h; 0 or -1 with the message set). */
struct qs_term {
	const char *name;
	double (*energy)(struct qs_term *t, struct qs_system *s, const double *x, double *g, double *fmax);
	void (*stiffness)(struct qs_term *t, struct qs_system *s, const double *x, double *k);
	void *data;
	int (*hessian)(struct qs_term *t, struct qs_system *s, const double *x, struct qs_hessian *H);
};

#define QS_MAX_TERMS 4

struct qs_system {
	struct pack *p;		/* radii, moduli; p->box is the current box */
	size_t n;
	size_t dim;		/* unknowns: layout.dim, kept here for the minimisers */
	struct qs_layout layout;
	const struct contact_law *law;	/* the normal term's law (qs_init: Hertz-Mindlin) */
	struct qs_term term[QS_MAX_TERMS];	/* term[0]: the normal contact term */
	int nterms;
	double *comp;		/* (1 - nu^2) / E per grain (1/Pa) */
	double wall_comp;
	double rmin, rmax, skin;
	struct contact_enum ce;
	long evals;		/* energy/gradient evaluations so far */
	double force_floor;	/* N: see qs_residual */
	/* the threaded Hertz evaluation's sums per block of grains (functional.c) */
	struct qs_block_sums *blk;
	size_t blk_cap;
	/* Hertz's 4/3 E* sqrt(R*) of every listed pair, by list index, made at each rebuild of
	 * the list (coef_builds: ce.rebuilds then) */
	double *hertz_coef;
	size_t coef_cap;
	long coef_builds;
	/* from the last evaluation */
	size_t ncontacts;
	double sum_force;	/* sum of normal contact forces (N) */
	double wall_force[NWALLS];	/* normal force on each wall (N) */
};

/* skin: Verlet skin over the smallest radius (0.3 is a good default). 0 or -1. */
int qs_init(struct qs_system *s, struct pack *p, double skin);
void qs_free(struct qs_system *s);
/* Add a term after the ones there (its energy is summed in that order); 0, or -1 when
 * QS_MAX_TERMS are there.  qs_remove_terms drops every term but the normal one. */
int qs_add_term(struct qs_system *s, const struct qs_term *t);
void qs_remove_terms(struct qs_system *s);
/* The term of that name, or NULL. */
struct qs_term *qs_term_named(struct qs_system *s, const char *name);
/* The unknowns: 3N centres, or with rotations 6N (layout.h). */
void qs_set_rotations(struct qs_system *s, int rotations);
/* Each grain's stiffness bound from every term at x (after an evaluation there) into k (n). */
void qs_stiffness(struct qs_system *s, const double *x, double *k);

/* Pi at x (s->dim unknowns); gradient into g (s->dim) unless NULL; per-grain largest contact force into fmax (n)
 * unless NULL.  Returns NAN when the neighbour list cannot be built (slot set). */
double qs_energy(struct qs_system *s, const double *x, double *g, double *fmax);

/* Residual of a gradient: the largest |F_i| / (largest contact force on i) over grains with
 * contacts (with friction, the larger of |F_i| and |M_i| / R_i), and the mean unbalanced-force ratio mean|F_i| / mean contact force.  A grain's
 * largest contact force is floored at floor_rel times the mean contact force and at
 * s->force_floor (N): a grain that carries almost nothing (a rattler losing its last
 * contact) could otherwise only satisfy the ratio when that contact has fully opened, which
 * the minimiser approaches asymptotically (the Hertz force vanishes as h^(3/2)). */
void qs_residual(const struct qs_system *s, const double *g, const double *fmax, double floor_rel,
    double *res_max, double *res_mean);

/* Release the grains that frictionless equilibrium cannot hold: a grain with 1, 2 or 3
 * contacts (grains and walls) whose normals are linearly independent balances only when
 * every one of those contacts carries zero force, i.e. once they have opened.  The
 * minimiser gets there only asymptotically, because a Hertz contact's stiffness vanishes as
 * h^(1/2); this moves each such grain, in index order, by the smallest displacement u with
 * u.n_c = h_c for each of its contacts c (overlap h_c, normal n_c pointing at the grain), so
 * that they all just touch.  A move is skipped when it would open a new overlap, when the
 * normals are nearly dependent (a grain squeezed between two opposite contacts can be in
 * equilibrium) or when it is longer than a quarter of the Verlet skin.  Frictionless
 * systems only (with friction a grain's state carries tangential history): returns the
 * number of grains moved, 0 with friction, -1 on error (message set). */
long qs_release_unbraced(struct qs_system *s, double *x);

/* H of every term of s at x, where s was last evaluated (its neighbour list current).
 * 0, or -1 with the message set (a term without second derivatives, rotations among the
 * unknowns, out of memory). */
int qs_hessian(struct qs_system *s, const double *x, struct qs_hessian *H);

/* Wall stresses of the last evaluation: normal force on the two walls of each axis,
 * averaged, over the current wall area (Pa, compression positive). */
void qs_wall_stress(const struct qs_system *s, double sig[3]);


/* After an evaluation at x: contacts per grain (grain and wall) into counts (n). */
void qs_coordination(const struct qs_system *s, const double *x, unsigned *counts);
/* Radii changed (grains grown): rebuild the neighbour list at the next evaluation. */
void qs_radii_changed(struct qs_system *s);

#ifdef __cplusplus
}
#endif

#endif
