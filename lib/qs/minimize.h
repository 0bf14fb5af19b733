/* SPDX-License-Identifier: GPL-3.0-or-later */
/* minimize: finding the equilibrium of a pack by minimising Pi (physics.md §7).
 *
 * Methods (each in its own file, min_NAME.c, and a row of QS_METHODS below):
 *  - cg: the papers' modified conjugate gradient: Fletcher-Reeves beta, a steepest-descent
 *    restart every k_sd iterations, and a one-dimensional minimisation along the direction
 *    capped so that no grain moves more than cap times its radius.  The 1-D minimisation
 *    finds the root of the directional derivative dPi/dalpha with Brent's method
 *    (gsl_root_fsolver_brent) after bracketing it: energy differences run out of precision
 *    near the minimum (rms force ratio 1e-6..1e-7), the derivative does not.
 *  - fire: FIRE 2.0 (Guénolé et al. 2020, as in LAMMPS min_fire) with unit masses, the time
 *    step bounded by 1 / sqrt(Gershgorin bound on the stiffness) at the start, and the same
 *    per-grain displacement cap; with precond_shift > 0 the force is P^-1 g (lbfgs's
 *    preconditioner below) and the time step fire_dt.
 *  - lbfgs: limited-memory BFGS (m stored steps) with the same capped derivative line
 *    search, trying the quasi-Newton step first and accepting |dPi/dalpha| <= 0.9 |dPi/dalpha(0)|;
 *    H0 of the two-loop recursion is each grain's diagonal block of the Hessian, shifted by
 *    precond_shift times the mean and inverted, reassembled every 50 iterations (scaled by
 *    s.y / y.H0 y), or with precond_shift 0 (or a term without second derivatives) the
 *    scalar s.y / y.y.
 *  - newton: Newton-Krylov on the exact sparse Hessian (hessian.h; with friction the return
 *    map's consistent tangent, not with the paper's rule): each iteration assembles H, adds
 *    Levenberg damping after short steps, solves H d = -g by CG preconditioned with the
 *    nodes' 3x3 diagonal blocks to |H d + g| <= newton_eta |g| (Eisenstat-Walker), stopping
 *    at negative curvature, cuts each grain's part of d to the step cap, and takes the same
 *    line search from the full step.
 *
 * The default is lbfgs with precond_shift 0.1: make bench found it the fastest to the same
 * residual (bench/lbfgs-precond.md; 2740 grains at 9 MPa, mu 0.3: 278 iterations and 0.29 s
 * per 1e-4 increment, against 874 and 0.70 s with the scalar H0 and 53 Newton steps and
 * 0.83 s with newton).
 *
 * Stopping: the residual (largest per-grain |F_i| / largest contact force on i, that force
 * floored at tol_floor times the mean contact force, see qs_residual) at or below tol; or the papers' criteria when set (> 0): Pi^(k-1) - Pi^k < eps1 |Pi^(k-1)|, or
 * |grad Pi|^2 < eps2 N (E_mean R_mean^2)^2; or max_iter iterations, reported as status 1. */
#ifndef QUSGM_MINIMIZE_H
#define QUSGM_MINIMIZE_H

#include "qs/functional.h"

/* A method, in the shape of GSL's gsl_multimin_fdfminimizer_type: a const object in the
 * method's own file (min_cg.c, min_fire.c, min_lbfgs.c, min_newton.c), which the minimiser
 * calls through; what they share (the line search, the step cap, the convergence tests, the
 * evaluation, the grains' preconditioner) is minimize.c's (minimize_priv.h).  Each hook takes
 * the minimiser, whose state (struct qs_minimizer) the method's file sees through
 * qs/minimize_priv.h, its own part behind m->state. */
struct qs_minimizer;
struct qs_method_type {
	const char *name;		/* --method's NAME */
	const char *description;	/* one line, for --method's help */
	size_t size;			/* the method's state (m->state, zeroed) */
	/* Its vectors, for the minimiser's system and parameters: 0, or -1 (out of memory;
	 * free then releases what was allocated).  NULL: none, the state is all. */
	int (*alloc)(struct qs_minimizer *m);
	void (*free)(struct qs_minimizer *m);
	/* A start at the minimiser's x, just evaluated (qs_minimizer_set; with keep
	 * qs_minimizer_resume, which keeps what the method can keep of the last minimisation).
	 * 0 or -1. */
	int (*start)(struct qs_minimizer *m, int keep);
	/* One iteration: 0 or -1 (msg_seterr). */
	int (*iterate)(struct qs_minimizer *m);
	/* The caller moved x, just evaluated there (qs_minimizer_moved): what of the method's
	 * memory still holds.  NULL: all of it. */
	void (*moved)(struct qs_minimizer *m);
	/* Nonzero when the method has nothing to move along (CG's zero gradient): the test
	 * stops there, converged.  NULL: never. */
	int (*stuck)(const struct qs_minimizer *m);
	/* Needs every term's second derivatives (qs_hessian), so not the friction term under
	 * the paper's rule, which has none (loader_open refuses the pair). */
	int needs_hessian;
};

/* The table of the methods, one row each: X(C name of the method's object, after
 * qs_method_).  Adding a method: its file and its row (share/doc/library.md, "How to add a
 * minimiser"). */
#define QS_METHODS(X) \
	X(cg) \
	X(fire) \
	X(lbfgs) \
	X(newton)

#define QS_METHOD_EXTERN(id) extern const struct qs_method_type qs_method_##id;
QS_METHODS(QS_METHOD_EXTERN)
#undef QS_METHOD_EXTERN

/* The methods of the table, in its order, NULL-terminated. */
extern const struct qs_method_type *const qs_methods[];
/* The method named name; NULL, with the error slot set ("no such method 'foo' (the methods:
 * cg, fire, lbfgs, newton)"), for a name no method has. */
const struct qs_method_type *qs_method_find(const char *name);
/* The names of the table's methods, as "cg, fire, lbfgs, newton", into buf (truncated to
 * size). */
void qs_method_names(char *buf, size_t size);

/* L-BFGS's stored steps by default (qs_min_params_default), and where lbfgs_m is 0. */
#define QS_LBFGS_M 8

struct qs_min_params {
	const struct qs_method_type *method;	/* default qs_method_lbfgs */
	long max_iter;
	double tol;		/* target largest per-grain force ratio */
	double tol_floor;	/* floor of a grain's largest force / mean contact force */
	double eps1, eps2;	/* the papers' criteria; 0 = off */
	double cap;		/* largest displacement per iteration / radius */
	long k_sd;		/* CG: steepest-descent restart period */
	double ls_sigma;	/* CG: stop the line search at |dPi/dalpha| <= sigma |dPi/dalpha(0)| */
	double fire_dt;		/* FIRE: dt_max in units of 1/sqrt(k bound) */
	long lbfgs_m;		/* L-BFGS: stored steps; 0: QS_LBFGS_M (the loader: LOAD_LBFGS_M with friction) */
	double precond_shift;	/* L-BFGS's H0, FIRE's force: the grains' stiffness blocks, shifted by this
				 * times the mean (0: the scalar H0 of plain L-BFGS) */
	double newton_eta;	/* Newton: CG stops at |H d + g| <= eta |g| */
	long newton_cg_max;	/* Newton: CG iterations per Newton step at most */
};

struct qs_min_report {
	long iter, evals;
	double energy, res_max, res_mean;
	int status;		/* 0 converged, 1 iteration limit, -1 error */
	const char *stopped_by;	/* "residual", "eps1", "eps2", "max_iter" */
};

void qs_min_params_default(struct qs_min_params *mp);

/* Minimise from x (3n, updated in place).  Returns the report's status.  It is the loop
 * below: alloc, set, then test and iterate until the test says stop. */
int qs_minimize(struct qs_system *s, double *x, const struct qs_min_params *mp, struct qs_min_report *rep);
/* qs_minimize with a minimiser the caller keeps (qs_minimizer_alloc on the same system, with
 * the same method, lbfgs_m and preconditioning as mp: qs_minimizer_params), so that a run of
 * minimisations (a frictional increment and its settle passes) allocates its memory once. */
int qs_minimize_in(struct qs_minimizer *m, double *x, const struct qs_min_params *mp, struct qs_min_report *rep);

/* The steppable minimiser, in the shape of GSL's multimin: INITIALIZE (alloc, set),
 * ITERATE, TEST.  The caller owns x, which the minimiser moves in place; between
 * iterations the caller may change x itself (densify releases unbraced grains) and call
 * qs_minimizer_moved, which evaluates there and keeps the method's memory (L-BFGS's stored
 * pairs; CG restarts along the steepest descent, FIRE from rest).  The objective, its
 * gradient, the per-grain step cap (mp->cap times the radius) and the stiffness bound come
 * from the functional (functional.h) and its layout of the unknowns (layout.h). */
enum { QS_MIN_CONTINUE = 2, QS_MIN_SUCCESS = 0, QS_MIN_MAXITER = 1 };

/* NULL when out of memory (msg_seterr).  The method and every parameter are copied. */
struct qs_minimizer *qs_minimizer_alloc(struct qs_system *s, const struct qs_min_params *mp);
void qs_minimizer_free(struct qs_minimizer *m);
/* Start from x: evaluate, iteration count and method state reset.  0 or -1. */
int qs_minimizer_set(struct qs_minimizer *m, double *x);
/* qs_minimizer_set that keeps L-BFGS's stored pairs and its preconditioner's blocks (their
 * age counts on): for a start at the point where the last minimisation ended, whose
 * functional changed little (a frictional settle pass after its commit: the same grains and
 * contacts, the history moved).  Other methods start afresh as with qs_minimizer_set. */
int qs_minimizer_resume(struct qs_minimizer *m, double *x);
/* x was moved by the caller: evaluate there, keep the iteration count and memory.  0 or -1. */
int qs_minimizer_moved(struct qs_minimizer *m);
/* One iteration.  0 or -1 (msg_seterr). */
int qs_minimizer_iterate(struct qs_minimizer *m);
/* QS_MIN_CONTINUE, or why to stop (QS_MIN_SUCCESS: a criterion of mp met; QS_MIN_MAXITER),
 * with rep's iter, energy, evals (since set), residuals and stopped_by filled in. */
int qs_minimizer_test(struct qs_minimizer *m, struct qs_min_report *rep);
/* The gradient at x (dim), and a new iteration limit (counted from set). */
const double *qs_minimizer_gradient(const struct qs_minimizer *m);
void qs_minimizer_set_max_iter(struct qs_minimizer *m, long max_iter);
/* Whether the functional's last evaluation was at the minimiser's x (so every term's state,
 * such as the friction term's contact forces, is x's): true after set and after every
 * iteration of every method, until something else evaluates. */
int qs_minimizer_current(const struct qs_minimizer *m);
/* New parameters for the next set (the same method, lbfgs_m and preconditioning; else -1). */
int qs_minimizer_params(struct qs_minimizer *m, const struct qs_min_params *mp);
/* From where the minimiser stands (after set, or a stop), on to the tolerance tol: test and
 * iterate as qs_minimize does; rep counts from set.  The status, or -1. */
int qs_minimizer_continue(struct qs_minimizer *m, double tol, struct qs_min_report *rep);
/* rep's evaluations (since set) and energy after a loop that ended with status st; returns st. */
int qs_minimizer_report(const struct qs_minimizer *m, int st, struct qs_min_report *rep);

#endif
