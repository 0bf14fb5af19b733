/* SPDX-License-Identifier: GPL-3.0-or-later */
/* minimize_priv: what a method's file (min_cg.c, min_fire.c, min_lbfgs.c, min_newton.c) sees
 * of the minimiser: its state (struct qs_minimizer, the method's own part behind m->state)
 * and minimize.c's shared machinery: the per-grain step cap, the capped derivative line
 * search and the move to its point, the stiffness bound, and the grains' block-Jacobi
 * preconditioner (lbfgs's H0, fire's force, newton's CG).  Private to lib/qs.
 *
 * Include qs/minimize.h first: this header does not include it, because minimize.c includes
 * both and tests/layers.sh would see minimize.c -> minimize_priv.h -> minimize.h as an
 * include circle. */
#ifndef QUSGM_MINIMIZE_PRIV_H
#define QUSGM_MINIMIZE_PRIV_H

#ifndef QUSGM_MINIMIZE_H
#error "include qs/minimize.h before qs/minimize_priv.h"
#endif

#include "qs/hessian.h"
#include "qs/layout.h"
#include "base/par.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_roots.h>

/* The work vectors every method shares. */
struct min_work {
	struct qs_system *s;
	size_t n3;
	double *g, *fmax, *d, *xt, *gt, *ft;
	double e, et;	/* energy at x and at the trial point xt */
	/* s->evals just after the evaluation at x and at xt: when s->evals still equals x_evals,
	 * every term's state (the contacts' forces) is x's (qs_minimizer_current) */
	long x_evals, xt_evals;
};

/* The steppable minimiser: the work vectors, the method (mp.method) and its state, and the
 * caller's x it moves. */
struct qs_minimizer {
	struct min_work w;
	struct qs_min_params mp;
	void *state;		/* the method's own: mp.method->size bytes */
	double *x;
	double scale2;		/* eps2's scale N (E_mean R_mean^2)^2 */
	long it, evals0;
	double eprev;		/* the energy before the last iteration (eps1) */
	gsl_root_fsolver *solver;	/* the line search's */
};

/* Dot products by blocks fixed by n, on threads: the same bytes for any count (par.h). */
static inline double
min_dot(const double *a, const double *b, size_t n)
{
	return par_dot(a, b, n);
}

static inline double
min_grain_len(const struct min_work *w, const double *d, size_t i)
{
	return layout_grain_len(&w->s->layout, d, i);
}

static inline void
min_grain_axpy(const struct min_work *w, double *x, const double *v, size_t i, double f)
{
	layout_grain_axpy(&w->s->layout, x, v, i, f);
}

/* Largest alpha such that no grain moves (or turns its surface) more than cap * its radius
 * along d. */
double min_alpha_cap(const struct min_work *w, const double *d, double cap);
/* d = -a g with a the largest step the cap allows along -g: the first step of lbfgs, and
 * where a method's own direction is not downhill. */
void min_capped_descent(struct min_work *w, double cap);
/* One-dimensional minimisation along w->d from x (d0: g.d there, or NAN to compute it):
 * bracket the root of dPi/dalpha (doubling from guess, never beyond amax), then Brent, to
 * |dPi/dalpha| <= sigma |dPi/dalpha(0)|.  On return xt/gt hold the accepted point.  Returns
 * alpha, or -1 on error. */
double min_line_search(struct min_work *w, const double *x, double guess, double amax, double sigma,
    gsl_root_fsolver *solver, double d0);
/* Move x to the line search's point and take its energy, gradient and forces, which the
 * search computed.  Returns the previous energy. */
double min_accept_trial(struct min_work *w, double *x);
/* Gershgorin bound on the Hessian of Pi: twice the largest per-grain sum of the terms'
 * stiffnesses (functional.h); NAN when out of memory. */
double min_stiffness_bound(struct qs_system *s, const double *x);

/* The grains' block-Jacobi preconditioner: the nodes' diagonal blocks of the Hessian
 * (hessian.h) and their inverses.  lbfgs and fire (with precond_shift > 0) keep the diagonal
 * blocks only and invert them in place (Minv is H.diag), reassembled every
 * MIN_PRECOND_EVERY iterations; newton assembles the whole Hessian every iteration and keeps
 * the inverses apart. */
struct min_precond {
	struct qs_hessian H;
	double *Minv;		/* 9 per node: the inverse blocks */
	double *z;		/* a work vector (3 per node) */
	gsl_eigen_symmv_workspace *eig;
	int on;			/* lbfgs, fire: in use (precond_shift > 0, and every term has a Hessian) */
	long age;		/* lbfgs, fire: iterations since the blocks were assembled; -1: not yet */
};

#define MIN_PRECOND_EVERY 50

/* lbfgs's and fire's: the diagonal blocks' storage when m's precond_shift > 0 (P->on then),
 * nothing otherwise.  0 or -1 (out of memory). */
int min_precond_alloc(struct qs_minimizer *m, struct min_precond *P);
void min_precond_free(struct min_precond *P);
/* Assemble the diagonal blocks at m's x, shift them by precond_shift times the mean and
 * invert them (age 0); P->on cleared when a term has no Hessian. */
void min_precond_update(struct qs_minimizer *m, struct min_precond *P);
/* Minv from H's diagonal blocks, each made positive definite. */
void min_precond_invert(struct min_precond *P);
/* z = P^-1 r (n3 each). */
void min_precond_apply(const struct min_precond *P, const double *r, double *z, size_t n3);
/* z = gamma P^-1 (v + f y) (y NULL: P^-1 v), with the bytes of par_axpy, min_precond_apply
 * and par_axpy_scale_dot(z, 0, z, gamma, ...) one after the other, without writing v. */
void min_precond_scaled(const struct min_precond *P, const double *v, double f, const double *y, double gamma,
    double *z, size_t n3);
/* Add f times the mean diagonal stiffness of its kind to every diagonal block of H (the n
 * centres', the rotations'). */
void min_diag_shift(struct qs_hessian *H, size_t n, double f);

#endif
