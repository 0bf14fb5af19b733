/* SPDX-License-Identifier: GPL-3.0-or-later */
/* minimize: the minimiser's machinery that every method shares (see minimize.h): the table of
 * the methods, the step cap, the line search, the convergence tests, the evaluation, the
 * grains' preconditioner, and the steppable interface, which calls the method's type object
 * (its hooks in min_cg.c, min_fire.c, min_lbfgs.c, min_newton.c). */
#include "qs/minimize.h"
#include "qs/minimize_priv.h"
#include "base/lanes.h"
#include "base/par.h"
#include "base/cli.h"
#include "base/msg.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void
qs_min_params_default(struct qs_min_params *mp)
{
	mp->method = &qs_method_lbfgs;
	mp->max_iter = 200000;
	mp->tol = 1e-4;
	mp->tol_floor = QS_RESIDUAL_FLOOR;
	mp->eps1 = 0;
	mp->eps2 = 0;
	mp->cap = 0.02;
	mp->k_sd = 50;
	mp->ls_sigma = 0.1;
	mp->fire_dt = 1.0;
	mp->lbfgs_m = QS_LBFGS_M;
	mp->precond_shift = 0.1;
	mp->newton_eta = 0.1;
	mp->newton_cg_max = 1000;
}

#define QS_METHOD_ROW(id) &qs_method_##id,
const struct qs_method_type *const qs_methods[] = {QS_METHODS(QS_METHOD_ROW) NULL};
#undef QS_METHOD_ROW

const struct qs_method_type *
qs_method_find(const char *name)
{
	const struct qs_method_type *const *t;
	char names[256];

	for (t = qs_methods; *t; t++)
		if (!strcmp(name, (*t)->name))
			return *t;
	qs_method_names(names, sizeof names);
	msg_seterr("no such method '%s' (the methods: %s)", name, names);
	return NULL;
}

void
qs_method_names(char *buf, size_t size)
{
	const struct qs_method_type *const *t;

	if (size == 0)
		return;
	buf[0] = 0;
	for (t = qs_methods; *t; t++)
		msg_list_add(buf, size, "%s", (*t)->name);
}

/* --- the shared machinery ---------------------------------------------------------- */

/* Largest alpha such that no grain moves (or turns its surface) more than cap * its radius
 * along d. */
double
min_alpha_cap(const struct min_work *w, const double *d, double cap)
{
	double amax = INFINITY;
	const double *r = w->s->p->r;
	size_t i = 0, n = w->s->n;

#if LANES_OK
	/* two grains at a time, their square roots and divisions in one instruction each
	 * (lanes.h: each lane the scalar loop's bytes); a smallest value is exact in any order
	 * (base/par.h) */
	{
		const struct qs_layout *lay = &w->s->layout;
		size_t q, np = n / 2;

#pragma omp parallel for schedule(static) reduction(min : amax) if (n >= PAR_MIN)
		for (q = 0; q < np; q++) {
			size_t k = 2 * q;
			v2d l = layout_grain_len_pair(lay, d, k);
			v2m pos = l > 0;
			v2d a = cap * (v2d){r[k], r[k + 1]} / V2_SELECT(pos, l, ((v2d){1, 1}));

			if (pos[0] && a[0] < amax)
				amax = a[0];
			if (pos[1] && a[1] < amax)
				amax = a[1];
		}
		i = 2 * np;
	}
#endif
	for (; i < n; i++) {
		double l = min_grain_len(w, d, i);
		if (l > 0 && cap * r[i] / l < amax)
			amax = cap * r[i] / l;
	}
	return amax;
}

/* d = -a g with a the largest step the cap allows along -g (one pass for the cap): the
 * first step of lbfgs, and where a method's own direction is not downhill. */
void
min_capped_descent(struct min_work *w, double cap)
{
	double a = min_alpha_cap(w, w->g, cap);
	size_t k;

#pragma omp parallel for schedule(static) if (w->n3 >= PAR_MIN_VEC)
	for (k = 0; k < w->n3; k++)
		w->d[k] = -w->g[k];
	par_scale(w->d, a, w->d, w->n3);
}

struct ls_ctx {
	struct min_work *w;
	const double *x;
	double last_alpha, last_e;
	int failed;
};

/* dPi/dalpha at x + alpha d; leaves the point in xt and its gradient in gt. */
static double
dphi(double alpha, void *vctx)
{
	struct ls_ctx *c = vctx;
	struct min_work *w = c->w;
	size_t k;

#pragma omp parallel for schedule(static) if (w->n3 >= PAR_MIN_VEC)
	for (k = 0; k < w->n3; k++)
		w->xt[k] = c->x[k] + alpha * w->d[k];
	c->last_e = w->et = qs_energy(w->s, w->xt, w->gt, w->ft);
	w->xt_evals = w->s->evals;
	if (isnan(c->last_e))
		c->failed = 1;
	c->last_alpha = alpha;
	return min_dot(w->gt, w->d, w->n3);
}

/* One-dimensional minimisation along w->d from x (d0: g.d there, or NAN to compute it):
 * bracket the root of dPi/dalpha (doubling from the previous step, never beyond the cap),
 * then Brent.  On return xt/gt hold the accepted point.  Returns alpha, or -1 on error. */
double
min_line_search(struct min_work *w, const double *x, double guess, double amax, double sigma,
    gsl_root_fsolver *solver, double d0)
{
	struct ls_ctx c = {w, x, 0, 0, 0};
	gsl_function F = {dphi, &c};
	double lo = 0, hi, dhi;
	int it;

	if (isnan(d0))
		d0 = min_dot(w->g, w->d, w->n3);
	hi = fmin(guess, amax);
	for (;;) {
		dhi = dphi(hi, &c);
		if (c.failed)
			return -1;
		if (dhi >= 0)
			break;
		if (fabs(dhi) <= sigma * fabs(d0) || hi >= amax)
			return hi;	/* flat enough, or capped: take the step */
		lo = hi;
		hi = fmin(2 * hi, amax);
	}
	if (fabs(dhi) <= sigma * fabs(d0))
		return hi;
	if (gsl_root_fsolver_set(solver, &F, lo, hi) != GSL_SUCCESS)
		return hi;
	for (it = 0; it < 60; it++) {
		double a;
		if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS || c.failed)
			break;
		a = gsl_root_fsolver_root(solver);
		if (c.last_alpha != a)
			dphi(a, &c);
		if (fabs(min_dot(w->gt, w->d, w->n3)) <= sigma * fabs(d0))
			break;
		if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 0,
		        1e-10) == GSL_SUCCESS)
			break;
	}
	return c.failed ? -1 : c.last_alpha;
}

/* The line search ends on the accepted point: move x there and take its energy, gradient
 * and forces, which the search computed.  Returns the previous energy. */
double
min_accept_trial(struct min_work *w, double *x)
{
	double eprev = w->e, *t;

	par_copy(x, w->xt, w->n3);
	w->x_evals = w->xt_evals;
	w->e = w->et;
	t = w->g;
	w->g = w->gt;
	w->gt = t;
	t = w->fmax;
	w->fmax = w->ft;
	w->ft = t;
	return eprev;
}

static int
converged(struct min_work *w, const struct qs_min_params *mp, double eprev, struct qs_min_report *rep, double scale2)
{
	qs_residual(w->s, w->g, w->fmax, mp->tol_floor, &rep->res_max, &rep->res_mean);
	if (rep->res_max <= mp->tol) {
		rep->stopped_by = "residual";
		return 1;
	}
	if (mp->eps1 > 0 && eprev - w->e >= 0 && eprev - w->e < mp->eps1 * fabs(eprev)) {
		rep->stopped_by = "eps1";
		return 1;
	}
	if (mp->eps2 > 0 && min_dot(w->g, w->g, w->n3) < mp->eps2 * scale2) {
		rep->stopped_by = "eps2";
		return 1;
	}
	return 0;
}

/* The test every method makes at the top of an iteration: converged, or out of iterations
 * (status 1). */
static int
should_stop(struct min_work *w, const struct qs_min_params *mp, long it, double eprev, struct qs_min_report *rep,
    double scale2)
{
	rep->iter = it;
	if (converged(w, mp, eprev, rep, scale2))
		return 1;
	if (it >= mp->max_iter) {
		rep->stopped_by = "max_iter";
		rep->status = 1;
		return 1;
	}
	return 0;
}

/* Gershgorin bound on the Hessian of Pi: twice the largest per-grain sum of the terms'
 * stiffnesses (functional.h). */
double
min_stiffness_bound(struct qs_system *s, const double *x)
{
	double *k = calloc(s->n, sizeof *k), kmax = 0;
	size_t i;

	if (!k)
		return NAN;
	qs_stiffness(s, x, k);
	for (i = 0; i < s->n; i++)
		kmax = fmax(kmax, k[i]);
	free(k);
	return 2 * kmax;
}

/* --- the grains' block-Jacobi preconditioner ----------------------------------------- */

/* The storage of lbfgs's and fire's preconditioner when precond_shift > 0: the diagonal
 * blocks, which min_precond_invert overwrites with their inverses, and a work vector. */
int
min_precond_alloc(struct qs_minimizer *m, struct min_precond *P)
{
	size_t n3 = m->w.n3;

	if (!(m->mp.precond_shift > 0))
		return 0;
	P->z = malloc(n3 * sizeof *P->z);
	P->eig = gsl_eigen_symmv_alloc(3);
	if (!P->z || !P->eig || qs_hessian_init(&P->H, n3 / 3))
		return -1;
	P->H.diag_only = 1;
	P->Minv = P->H.diag;
	P->on = 1;
	return 0;
}

void
min_precond_free(struct min_precond *P)
{
	if (P->Minv != P->H.diag)
		free(P->Minv);
	free(P->z);
	qs_hessian_free(&P->H);
	if (P->eig)
		gsl_eigen_symmv_free(P->eig);
}

/* Add f times the mean diagonal stiffness of its kind to every diagonal block of H: the
 * mean over the n centres' blocks to the centres', over the rotations' to the rotations'
 * (hessian.h's nodes).  Newton's Levenberg damping and L-BFGS's H0 shift. */
void
min_diag_shift(struct qs_hessian *H, size_t n, double f)
{
	size_t i;
	double kc = 0, kr = 0;

	for (i = 0; i < H->n; i++) {
		const double *D = H->diag + 9 * i, k = fabs(D[0] + D[4] + D[8]) / (3 * (double)n);
		if (i < n)
			kc += k;
		else
			kr += k;
	}
	for (i = 0; i < H->n; i++) {
		double *D = H->diag + 9 * i, sh = f * (i < n ? kc : kr);
		D[0] += sh, D[4] += sh, D[8] += sh;
	}
}

/* L-BFGS's H0 and FIRE's preconditioned force P^-1 g (with precond_shift > 0) from the
 * nodes' diagonal blocks of the Hessian (hessian.h): each block
 * shifted by precond_shift times the mean diagonal stiffness of its kind (centres, or
 * rotations), so that a grain with almost no stiffness of its own gets the inverse of a
 * typical one rather than a huge one, then inverted as Newton's block-Jacobi
 * preconditioner (min_precond_invert).  It scales each grain's step by its own stiffness: with
 * friction the centres and the rotations R Omega, and grains held by stiff and by soft
 * contacts, differ by orders of magnitude, which the one scalar of plain L-BFGS cannot
 * follow.  Assembled at the start and every MIN_PRECOND_EVERY iterations (only the diagonal
 * blocks); a functional with a term without second derivatives (friction under the paper's
 * rule) keeps the scalar H0 and the plain force. */
void
min_precond_update(struct qs_minimizer *m, struct min_precond *P)
{
	P->H.at_last_eval = qs_minimizer_current(m);
	if (qs_hessian(m->w.s, m->x, &P->H)) {
		P->on = 0;
		return;
	}
	min_diag_shift(&P->H, m->w.s->n, m->mp.precond_shift);
	min_precond_invert(P);
	P->age = 0;
}

/* The inverse of a symmetric 3x3 block by cofactors when it is clearly positive definite
 * (leading minors above 1e-9 of their scale: most grains, held by four or more contacts);
 * 0 otherwise. */
static int
spd_inverse3(const double *D, double *M)
{
	double c00 = D[4] * D[8] - D[5] * D[7], c01 = D[5] * D[6] - D[3] * D[8], c02 = D[3] * D[7] - D[4] * D[6];
	double det = D[0] * c00 + D[1] * c01 + D[2] * c02, tr = D[0] + D[4] + D[8], m2 = D[0] * D[4] - D[1] * D[3];

	if (!(D[0] > 1e-9 * tr && m2 > 1e-9 * tr * tr && det > 1e-9 * tr * tr * tr))
		return 0;
	M[0] = c00 / det;
	M[1] = M[3] = c01 / det;
	M[2] = M[6] = c02 / det;
	M[4] = (D[0] * D[8] - D[2] * D[6]) / det;
	M[5] = M[7] = (D[2] * D[3] - D[0] * D[5]) / det;
	M[8] = m2 / det;
	return 1;
}

/* The block-Jacobi preconditioner: each grain's diagonal block, made positive definite by
 * taking its eigenvalues' magnitudes (a grain held by one or two contacts has the negative
 * geometric stiffness P/d across them), floored at 1e-6 of its largest; a grain without
 * contacts gets zero (it has no force and stays where it is). */
void
min_precond_invert(struct min_precond *P)
{
	size_t i, n = P->H.n;
	double a[9], ev[3], vv[9];
	gsl_matrix_view A = gsl_matrix_view_array(a, 3, 3), V = gsl_matrix_view_array(vv, 3, 3);
	gsl_vector_view E = gsl_vector_view_array(ev, 3);

	for (i = 0; i < n; i++) {
		double D[9], *M = P->Minv + 9 * i, big = 0, inv[3];
		int u, v, c;

		memcpy(D, P->H.diag + 9 * i, sizeof D);	/* M may be the diagonal block itself */
		if (spd_inverse3(D, M))
			continue;
		memcpy(a, D, sizeof a);
		gsl_eigen_symmv(&A.matrix, &E.vector, &V.matrix, P->eig);
		for (c = 0; c < 3; c++)
			big = fmax(big, fabs(ev[c]));
		for (c = 0; c < 3; c++)
			inv[c] = big > 0 ? 1 / fmax(fabs(ev[c]), 1e-6 * big) : 0;
		for (u = 0; u < 3; u++)
			for (v = 0; v < 3; v++)
				M[3 * u + v] = vv[3 * u] * inv[0] * vv[3 * v] + vv[3 * u + 1] * inv[1] * vv[3 * v + 1] +
				    vv[3 * u + 2] * inv[2] * vv[3 * v + 2];
	}
}

void
min_precond_apply(const struct min_precond *P, const double *r, double *z, size_t n3)
{
	size_t i;

	/* node by node: the same bytes for any split */
#pragma omp parallel for schedule(static) if (n3 >= PAR_MIN_VEC)
	for (i = 0; i < P->H.n; i++) {
		const double *M = P->Minv + 9 * i, *ri = r + 3 * i;
		double *zi = z + 3 * i;

		zi[0] = M[0] * ri[0] + M[1] * ri[1] + M[2] * ri[2];
		zi[1] = M[3] * ri[0] + M[4] * ri[1] + M[5] * ri[2];
		zi[2] = M[6] * ri[0] + M[7] * ri[1] + M[8] * ri[2];
	}
}

/* z = gamma P^-1 (v + f y) node by node (y NULL: P^-1 v), with the bytes of par_axpy(v, f, y),
 * min_precond_apply(v, z) and par_axpy_scale_dot(z, 0, z, gamma, ...) one after the other,
 * in one pass and without writing v. */
void
min_precond_scaled(const struct min_precond *P, const double *v, double f, const double *y, double gamma,
    double *z, size_t n3)
{
	size_t i;

#pragma omp parallel for schedule(static) if (n3 >= PAR_MIN_VEC)
	for (i = 0; i < P->H.n; i++) {
		const double *M = P->Minv + 9 * i, *vi = v + 3 * i;
		double r0 = vi[0], r1 = vi[1], r2 = vi[2], z0, z1, z2, *zi = z + 3 * i;

		if (y) {
			const double *yi = y + 3 * i;
			r0 = r0 + f * yi[0], r1 = r1 + f * yi[1], r2 = r2 + f * yi[2];
		}
		z0 = M[0] * r0 + M[1] * r1 + M[2] * r2;
		z1 = M[3] * r0 + M[4] * r1 + M[5] * r2;
		z2 = M[6] * r0 + M[7] * r1 + M[8] * r2;
		zi[0] = gamma * (z0 + 0 * z0);
		zi[1] = gamma * (z1 + 0 * z1);
		zi[2] = gamma * (z2 + 0 * z2);
	}
}

/* --- the interface ------------------------------------------------------------------ */

/* L-BFGS's stored steps: mp's, or QS_LBFGS_M where mp leaves the choice (0). */
static long
lbfgs_memory(const struct qs_min_params *mp)
{
	return mp->lbfgs_m > 0 ? mp->lbfgs_m : QS_LBFGS_M;
}

struct qs_minimizer *
qs_minimizer_alloc(struct qs_system *s, const struct qs_min_params *mp)
{
	struct qs_minimizer *m = calloc(1, sizeof *m);
	struct min_work *w;
	double Em = 0, Rm = 0;
	size_t i;

	if (!mp->method) {	/* a zeroed qs_min_params names no method (qs_min_params_default does) */
		free(m);
		msg_seterr("the minimiser's parameters name no method");
		return NULL;
	}
	if (!m) {
		msg_seterr("out of memory for the minimiser");
		return NULL;
	}
	w = &m->w;
	m->mp = *mp;
	m->mp.lbfgs_m = lbfgs_memory(mp);
	w->s = s;
	w->n3 = s->dim;
	w->g = malloc(w->n3 * sizeof *w->g);
	w->fmax = malloc(s->n * sizeof *w->fmax);
	w->d = malloc(w->n3 * sizeof *w->d);
	w->xt = malloc(w->n3 * sizeof *w->xt);
	w->gt = malloc(w->n3 * sizeof *w->gt);
	w->ft = malloc(s->n * sizeof *w->ft);
	m->solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
	m->state = calloc(1, mp->method->size ? mp->method->size : 1);
	if (!w->g || !w->fmax || !w->d || !w->xt || !w->gt || !w->ft || !m->solver || !m->state ||
	    (mp->method->alloc && mp->method->alloc(m))) {
		qs_minimizer_free(m);
		msg_seterr("out of memory for the minimiser");
		return NULL;
	}
	for (i = 0; i < s->n; i++) {
		Em += s->p->E[i] / s->n;
		Rm += s->p->r[i] / s->n;
	}
	m->scale2 = (double)s->n * (Em * Rm * Rm) * (Em * Rm * Rm);
	return m;
}

void
qs_minimizer_free(struct qs_minimizer *m)
{
	struct min_work *w;

	if (!m)
		return;
	w = &m->w;
	free(w->g), free(w->fmax), free(w->d), free(w->xt), free(w->gt), free(w->ft);
	if (m->state && m->mp.method->free)
		m->mp.method->free(m);
	free(m->state);
	if (m->solver)
		gsl_root_fsolver_free(m->solver);
	free(m);
}

/* Evaluate at the caller's x. */
static int
evaluate(struct qs_minimizer *m)
{
	m->w.e = qs_energy(m->w.s, m->x, m->w.g, m->w.fmax);
	m->w.x_evals = m->w.s->evals;
	return isnan(m->w.e) ? -1 : 0;
}

/* qs_minimizer_set, and with keep qs_minimizer_resume. */
static int
minimizer_start(struct qs_minimizer *m, double *x, int keep)
{
	m->x = x;
	m->it = 0;
	m->eprev = INFINITY;
	m->evals0 = m->w.s->evals;
	if (evaluate(m))
		return -1;
	return m->mp.method->start(m, keep);
}

int
qs_minimizer_set(struct qs_minimizer *m, double *x)
{
	return minimizer_start(m, x, 0);
}

int
qs_minimizer_resume(struct qs_minimizer *m, double *x)
{
	return minimizer_start(m, x, 1);
}

int
qs_minimizer_moved(struct qs_minimizer *m)
{
	if (evaluate(m))
		return -1;
	m->eprev = INFINITY;	/* Pi jumped: no energy criterion across the move */
	if (m->mp.method->moved)
		m->mp.method->moved(m);
	return 0;
}

int
qs_minimizer_test(struct qs_minimizer *m, struct qs_min_report *rep)
{
	rep->energy = m->w.e;
	rep->evals = m->w.s->evals - m->evals0;
	if (should_stop(&m->w, &m->mp, m->it, m->eprev, rep, m->scale2)) {
		cli_progress_iter(rep->res_max);
		return rep->status == 1 ? QS_MIN_MAXITER : QS_MIN_SUCCESS;
	}
	cli_progress_iter(rep->res_max);	/* the progress line (a terminal, or -v) */
	if (m->mp.method->stuck && m->mp.method->stuck(m))
		return QS_MIN_SUCCESS;	/* nothing to move along */
	return QS_MIN_CONTINUE;
}

int
qs_minimizer_iterate(struct qs_minimizer *m)
{
	int st = m->mp.method->iterate(m);

	m->it++;
	return st;
}

int
qs_minimizer_current(const struct qs_minimizer *m)
{
	return m->x && m->w.s->evals == m->w.x_evals;
}

const double *
qs_minimizer_gradient(const struct qs_minimizer *m)
{
	return m->w.g;
}

void
qs_minimizer_set_max_iter(struct qs_minimizer *m, long max_iter)
{
	m->mp.max_iter = max_iter;
}

int
qs_minimizer_params(struct qs_minimizer *m, const struct qs_min_params *mp)
{
	long lm = lbfgs_memory(mp);

	if (mp->method != m->mp.method || lm != m->mp.lbfgs_m ||
	    (mp->precond_shift > 0) != (m->mp.precond_shift > 0)) {
		msg_seterr("a kept minimiser's method, memory or preconditioning changed");
		return -1;
	}
	m->mp = *mp;
	m->mp.lbfgs_m = lm;
	return 0;
}

/* Test and iterate until the test says stop; the report's status, or -1. */
static int
minimize_loop(struct qs_minimizer *m, struct qs_min_report *rep)
{
	int st;

	while ((st = qs_minimizer_test(m, rep)) == QS_MIN_CONTINUE)
		if (qs_minimizer_iterate(m))
			return -1;
	return rep->status;
}

int
qs_minimize_in(struct qs_minimizer *m, double *x, const struct qs_min_params *mp, struct qs_min_report *rep)
{
	int st = -1;

	memset(rep, 0, sizeof *rep);
	if (qs_minimizer_params(m, mp) == 0 && qs_minimizer_set(m, x) == 0)
		st = minimize_loop(m, rep);
	return qs_minimizer_report(m, st, rep);
}

int
qs_minimizer_continue(struct qs_minimizer *m, double tol, struct qs_min_report *rep)
{
	m->mp.tol = tol;
	memset(rep, 0, sizeof *rep);
	return qs_minimizer_report(m, minimize_loop(m, rep), rep);
}

int
qs_minimizer_report(const struct qs_minimizer *m, int st, struct qs_min_report *rep)
{
	rep->evals = m->w.s->evals - m->evals0;
	if (st < 0) {
		rep->status = -1;
		return -1;
	}
	rep->energy = m->w.e;
	return rep->status;
}

int
qs_minimize(struct qs_system *s, double *x, const struct qs_min_params *mp, struct qs_min_report *rep)
{
	struct qs_minimizer *m = qs_minimizer_alloc(s, mp);
	int st;

	if (!m) {
		memset(rep, 0, sizeof *rep);
		rep->status = -1;
		return -1;
	}
	st = qs_minimize_in(m, x, mp, rep);
	qs_minimizer_free(m);
	return st;
}
