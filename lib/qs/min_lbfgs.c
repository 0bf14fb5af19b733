/* SPDX-License-Identifier: GPL-3.0-or-later */
/* min_lbfgs: limited-memory BFGS (minimize.h, method lbfgs, the default): the two-loop
 * recursion over the last lbfgs_m steps, H0 = (s.y / y.y) I or the grains' blocks
 * (min_precond_update), the same capped derivative line search as CG but first trying
 * alpha = 1 and accepting a weak Wolfe point (|dPi/dalpha| <= 0.9 |dPi/dalpha(0)|), as
 * quasi-Newton methods want.  Its memory outlives a move of the grains
 * (qs_minimizer_moved) and, on request, a new minimisation (qs_minimizer_resume). */
#include "qs/minimize.h"
#include "qs/minimize_priv.h"
#include "base/msg.h"
#include "base/par.h"

#include <math.h>
#include <stdlib.h>

struct lbfgs_state {
	double *S, *Y, *rho, *al;	/* lbfgs_m slots of n3 (S, Y) or 1 */
	double *sy, *yy;	/* s.y and y.y of what each slot of S, Y holds */
	double dg;		/* d.g of the direction lbfgs_direction made */
	int head, count;	/* the next slot, the pairs stored */
	struct min_precond pc;	/* H0, with precond_shift > 0 */
};

static int
lbfgs_alloc(struct qs_minimizer *m)
{
	struct lbfgs_state *lb = m->state;
	size_t mm = (size_t)m->mp.lbfgs_m, n3 = m->w.n3;

	lb->S = malloc(mm * n3 * sizeof *lb->S);
	lb->Y = malloc(mm * n3 * sizeof *lb->Y);
	lb->rho = malloc(mm * sizeof *lb->rho);
	lb->al = malloc(mm * sizeof *lb->al);
	lb->sy = malloc(mm * sizeof *lb->sy);
	lb->yy = malloc(mm * sizeof *lb->yy);
	if (!lb->S || !lb->Y || !lb->rho || !lb->al || !lb->sy || !lb->yy) {
		msg_seterr("out of memory for L-BFGS");
		return -1;
	}
	return min_precond_alloc(m, &lb->pc);
}

static void
lbfgs_free(struct qs_minimizer *m)
{
	struct lbfgs_state *lb = m->state;

	free(lb->S), free(lb->Y), free(lb->rho), free(lb->al), free(lb->sy), free(lb->yy);
	min_precond_free(&lb->pc);
}

/* keep (qs_minimizer_resume): the stored pairs and the preconditioner's blocks, their age
 * counting on; else none. */
static int
lbfgs_start(struct qs_minimizer *m, int keep)
{
	struct lbfgs_state *lb = m->state;

	if (!keep) {
		lb->head = lb->count = 0;
		lb->pc.age = -1;
	}
	return 0;
}

/* The two loops of L-BFGS's recursion over the stored pairs, each axpy fused with the dot
 * product that follows it (par.h: the same bytes as the plain passes).  lbfgs_loop1: v = -g,
 * then newest to oldest al_c = rho_c s_c.v, v -= al_c y_c; its last axpy scaled by scale and
 * dotted with last (returned), or, when last is NULL, left to the caller (al_c set: the
 * preconditioner's pass takes it, min_precond_scaled).  lbfgs_loop2: oldest to newest
 * b = rho_c y_c.v (t the first of these dots), v += (al_c - b) s_c; returns v.g. */
static double
lbfgs_loop1(struct qs_minimizer *m, double *v, double scale, const double *last)
{
	struct lbfgs_state *lb = m->state;
	struct min_work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, q, c, cn;
	size_t n3 = w->n3;
	double t;

	c = (lb->head - 1 + mm) % mm;
	t = par_neg_dot(v, w->g, lb->count ? lb->S + (size_t)c * n3 : w->g, n3);
	for (q = 0; q < lb->count; q++) {
		c = (lb->head - 1 - q + mm) % mm;
		lb->al[c] = lb->rho[c] * t;
		if (q + 1 < lb->count) {
			cn = (lb->head - 2 - q + mm) % mm;
			t = par_axpy_scale_dot(v, -lb->al[c], lb->Y + (size_t)c * n3, 1, lb->S + (size_t)cn * n3, n3);
		} else if (last) {
			t = par_axpy_scale_dot(v, -lb->al[c], lb->Y + (size_t)c * n3, scale, last, n3);
		}
	}
	return t;
}

static double
lbfgs_loop2(struct qs_minimizer *m, double *v, double t)
{
	struct lbfgs_state *lb = m->state;
	struct min_work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, q, c, cn;
	size_t n3 = w->n3;

	for (q = lb->count - 1; q >= 0; q--) {
		double b;
		c = (lb->head - 1 - q + mm) % mm;
		b = lb->rho[c] * t;
		cn = (lb->head - q + mm) % mm;
		t = par_axpy_scale_dot(v, lb->al[c] - b, lb->S + (size_t)c * n3, 1, q > 0 ? lb->Y + (size_t)cn * n3 : w->g,
		    n3);
	}
	return t;
}

/* d = -H g by the two-loop recursion over the stored pairs, each axpy fused with the dot
 * product that follows it (par.h: the same bytes as the plain passes), H0's gamma from the
 * dot products of the newest pair taken when it was stored; leaves d.g in lb->dg. */
static void
lbfgs_direction(struct qs_minimizer *m)
{
	struct lbfgs_state *lb = m->state;
	struct min_work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, c;
	size_t n3 = w->n3;
	double gamma, t;

	if (lb->count == 0) {
		/* first step: as far as the cap allows along -g */
		min_capped_descent(w, m->mp.cap);
		lb->dg = min_dot(w->d, w->g, n3);
	} else {
		c = (lb->head - 1 + mm) % mm;
		gamma = lb->sy[c] / lb->yy[c];
		/* the last axpy of the first loop with the scaling by gamma and the second loop's
		 * first dot (against the oldest y) */
		c = (lb->head - lb->count + mm) % mm;
		t = lbfgs_loop1(m, w->d, gamma, lb->Y + (size_t)c * n3);
		lb->dg = lbfgs_loop2(m, w->d, t);
	}
	if (lb->dg >= 0) {	/* not downhill: forget the history */
		lb->count = 0;
		min_capped_descent(w, m->mp.cap);
		lb->dg = NAN;	/* min_line_search takes d.g itself */
	}
}

/* The two-loop recursion with H0 = gamma P^-1 (precond_shift), gamma = s.y / y.P^-1 y of the
 * newest pair; the first step is -P^-1 g, whose length is already a displacement. */
static void
lbfgs_direction_precond(struct qs_minimizer *m)
{
	struct lbfgs_state *lb = m->state;
	struct min_work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, c, cn;
	size_t n3 = w->n3;
	double gamma = 1, t;

	if (lb->pc.age < 0 || lb->pc.age >= MIN_PRECOND_EVERY)
		min_precond_update(m, &lb->pc);
	lb->pc.age++;
	if (!lb->pc.on) {
		lbfgs_direction(m);
		return;
	}
	lbfgs_loop1(m, lb->pc.z, 1, NULL);
	if (lb->count > 0) {
		c = (lb->head - 1 + mm) % mm;
		gamma = lb->sy[c] / par_quad3(lb->pc.Minv, lb->Y + (size_t)c * n3, n3);
	}
	/* the first loop's last axpy (against the oldest y), P^-1 and the scaling by gamma in
	 * one pass; then the second loop's first dot, against that same y */
	cn = (lb->head - lb->count + mm) % mm;
	min_precond_scaled(&lb->pc, lb->pc.z, lb->count ? -lb->al[cn] : 0, lb->count ? lb->Y + (size_t)cn * n3 : NULL,
	    gamma, w->d, n3);
	t = par_dot(lb->count ? lb->Y + (size_t)cn * n3 : w->g, w->d, n3);
	t = lbfgs_loop2(m, w->d, t);
	lb->dg = t;
	if (!(lb->dg < 0)) {	/* not downhill (or no stiffness at all): forget the history */
		lb->count = 0;
		min_capped_descent(w, m->mp.cap);
		lb->dg = NAN;
	}
}

static int
lbfgs_iterate(struct qs_minimizer *m)
{
	struct lbfgs_state *lb = m->state;
	struct min_work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m;
	size_t n3 = w->n3;
	double amax, alpha, sy = 0, yy = 0, *x = m->x;

	if (lb->pc.on)
		lbfgs_direction_precond(m);
	else
		lbfgs_direction(m);
	amax = min_alpha_cap(w, w->d, m->mp.cap);
	alpha = min_line_search(w, x, 1.0, amax, 0.9, m->solver, lb->dg);
	if (alpha < 0)
		return -1;
	/* new pair s = alpha d, y = g_new - g, and their s.y, y.y in the same pass */
	{
		double *S = lb->S + (size_t)lb->head * n3, *Y = lb->Y + (size_t)lb->head * n3;
		par_diff_dots(S, w->xt, x, Y, w->gt, w->g, n3, &sy, &yy);
		/* the slot holds the new pair even when it is not kept (below) */
		lb->sy[lb->head] = sy;
		lb->yy[lb->head] = yy;
	}
	if (sy > 1e-300 && yy > 0) {
		lb->rho[lb->head] = 1 / sy;
		lb->head = (lb->head + 1) % mm;
		if (lb->count < mm)
			lb->count++;
	}
	m->eprev = min_accept_trial(w, x);
	return 0;
}

/* The grains moved: the stored pairs still describe the landscape around them, the
 * preconditioner's blocks not (the grains that moved have new contacts). */
static void
lbfgs_moved(struct qs_minimizer *m)
{
	struct lbfgs_state *lb = m->state;

	lb->pc.age = -1;
}

const struct qs_method_type qs_method_lbfgs = {
	.name = "lbfgs",
	.description = "limited-memory BFGS, preconditioned",
	.size = sizeof(struct lbfgs_state),
	.alloc = lbfgs_alloc,
	.free = lbfgs_free,
	.start = lbfgs_start,
	.iterate = lbfgs_iterate,
	.moved = lbfgs_moved,
	.stuck = NULL,
	.needs_hessian = 0,
};
