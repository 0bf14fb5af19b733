/* SPDX-License-Identifier: GPL-3.0-or-later */
/* minimize: the papers' modified CG and FIRE (see minimize.h). */
#include "qs/minimize.h"
#include "base/lanes.h"
#include "qs/hessian.h"
#include "base/par.h"
#include "base/cli.h"
#include "base/msg.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void
qs_min_params_default(struct qs_min_params *mp)
{
	mp->method = QS_LBFGS;
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

int
qs_method_parse(const char *name, enum qs_method *m)
{
	if (strcmp(name, "cg") == 0)
		*m = QS_CG;
	else if (strcmp(name, "fire") == 0)
		*m = QS_FIRE;
	else if (strcmp(name, "lbfgs") == 0)
		*m = QS_LBFGS;
	else if (strcmp(name, "newton") == 0)
		*m = QS_NEWTON;
	else
		return -1;
	return 0;
}

const char *
qs_method_name(enum qs_method m)
{
	return m == QS_FIRE ? "fire" : m == QS_LBFGS ? "lbfgs" : m == QS_NEWTON ? "newton" : "cg";
}

/* Workspace shared by both methods. */
struct work {
	struct qs_system *s;
	size_t n3;
	double *g, *fmax, *d, *xt, *gt, *ft, *v;
	double e, et;	/* energy at x and at the trial point xt */
	/* s->evals just after the evaluation at x and at xt: when s->evals still equals x_evals,
	 * every term's state (the contacts' forces) is x's (qs_minimizer_current) */
	long x_evals, xt_evals;
};

/* The steppable minimiser: the work vectors, the method's state between iterations, and the
 * caller's x it moves. */
struct qs_minimizer {
	struct work w;
	struct qs_min_params mp;
	double *x;
	double scale2;		/* eps2's scale N (E_mean R_mean^2)^2 */
	long it, evals0;
	double eprev;
	gsl_root_fsolver *solver;
	/* cg */
	double gg, step;
	/* fire */
	double dt, dtmax, alpha;
	long npos;
	/* lbfgs */
	double *S, *Y, *rho, *al;
	double *sy, *yy;	/* s.y and y.y of what each slot of S, Y holds */
	double dg;		/* d.g of the direction lbfgs_direction made */
	int head, count;
	int precond;		/* lbfgs's H0, fire's force from the diagonal blocks (grain_precond) */
	long precond_age;	/* iterations since they were assembled; -1: not yet */
	/* newton */
	struct qs_hessian H;
	double *Minv, *r, *z, *q, *Hq;
	gsl_eigen_symmv_workspace *eig;
	double gnorm_prev, eta_prev;	/* the forcing term's memory */
	double lambda;		/* Levenberg damping: a fraction of the mean diagonal stiffness */
};

/* Dot products by blocks fixed by n, on threads: the same bytes for any count (par.h). */
static double
dot(const double *a, const double *b, size_t n)
{
	return par_dot(a, b, n);
}

static double
grain_len(const struct work *w, const double *d, size_t i)
{
	return layout_grain_len(&w->s->layout, d, i);
}

static void
grain_axpy(const struct work *w, double *x, const double *v, size_t i, double f)
{
	layout_grain_axpy(&w->s->layout, x, v, i, f);
}

/* Largest alpha such that no grain moves (or turns its surface) more than cap * its radius
 * along d. */
static double
alpha_cap(const struct work *w, const double *d, double cap)
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
		double l = grain_len(w, d, i);
		if (l > 0 && cap * r[i] / l < amax)
			amax = cap * r[i] / l;
	}
	return amax;
}

/* d = -a g with a the largest step the cap allows along -g (one pass for the cap): the
 * first step of lbfgs, and where a method's own direction is not downhill. */
static void
capped_descent(struct work *w, double cap)
{
	double a = alpha_cap(w, w->g, cap);
	size_t k;

#pragma omp parallel for schedule(static) if (w->n3 >= PAR_MIN_VEC)
	for (k = 0; k < w->n3; k++)
		w->d[k] = -w->g[k];
	par_scale(w->d, a, w->d, w->n3);
}

struct ls_ctx {
	struct work *w;
	const double *x;
	double last_alpha, last_e;
	int failed;
};

/* dPi/dalpha at x + alpha d; leaves the point in xt and its gradient in gt. */
static double
dphi(double alpha, void *vctx)
{
	struct ls_ctx *c = vctx;
	struct work *w = c->w;
	size_t k;

#pragma omp parallel for schedule(static) if (w->n3 >= PAR_MIN_VEC)
	for (k = 0; k < w->n3; k++)
		w->xt[k] = c->x[k] + alpha * w->d[k];
	c->last_e = w->et = qs_energy(w->s, w->xt, w->gt, w->ft);
	w->xt_evals = w->s->evals;
	if (isnan(c->last_e))
		c->failed = 1;
	c->last_alpha = alpha;
	return dot(w->gt, w->d, w->n3);
}

/* One-dimensional minimisation along w->d from x (d0: g.d there, or NAN to compute it): bracket the root of dPi/dalpha (doubling
 * from the previous step, never beyond the cap), then Brent.  On return xt/gt hold the
 * accepted point.  Returns alpha, or -1 on error. */
static double
line_search(struct work *w, const double *x, double guess, double amax, double sigma, gsl_root_fsolver *solver,
    double d0)
{
	struct ls_ctx c = {w, x, 0, 0, 0};
	gsl_function F = {dphi, &c};
	double lo = 0, hi, dhi;
	int it;

	if (isnan(d0))
		d0 = dot(w->g, w->d, w->n3);
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
		if (fabs(dot(w->gt, w->d, w->n3)) <= sigma * fabs(d0))
			break;
		if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 0,
		        1e-10) == GSL_SUCCESS)
			break;
	}
	return c.failed ? -1 : c.last_alpha;
}

/* The line search ends on the accepted point: move x there and take its energy, gradient
 * and forces, which the search computed.  Returns the previous energy. */
static double
accept_trial(struct work *w, double *x)
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
converged(struct work *w, const struct qs_min_params *mp, double eprev, struct qs_min_report *rep, double scale2)
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
	if (mp->eps2 > 0 && dot(w->g, w->g, w->n3) < mp->eps2 * scale2) {
		rep->stopped_by = "eps2";
		return 1;
	}
	return 0;
}

/* The test every method makes at the top of an iteration: converged, or out of iterations
 * (status 1). */
static int
should_stop(struct work *w, const struct qs_min_params *mp, long it, double eprev, struct qs_min_report *rep,
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
static double
stiffness_bound(struct qs_system *s, const double *x)
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

/* --- the papers' modified CG ------------------------------------------------------- */

static void
cg_restart(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	size_t k;

	m->gg = dot(w->g, w->g, w->n3);
	for (k = 0; k < w->n3; k++)
		w->d[k] = -w->g[k];
}

static int
cg_iterate(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	const struct qs_min_params *mp = &m->mp;
	double amax, alpha, gg_new, beta;
	size_t k;

	amax = alpha_cap(w, w->d, mp->cap);
	alpha = line_search(w, m->x, m->step > 0 ? 2 * m->step : amax, amax, mp->ls_sigma, m->solver, NAN);
	if (alpha < 0)
		return -1;
	m->step = alpha;
	m->eprev = accept_trial(w, m->x);
	gg_new = dot(w->g, w->g, w->n3);
	beta = (m->it + 1) % mp->k_sd == 0 ? 0 : gg_new / m->gg;
	for (k = 0; k < w->n3; k++)
		w->d[k] = -w->g[k] + beta * w->d[k];
	if (dot(w->d, w->g, w->n3) >= 0)	/* not a descent direction: restart */
		for (k = 0; k < w->n3; k++)
			w->d[k] = -w->g[k];
	m->gg = gg_new;
	return 0;
}

/* --- FIRE 2.0 -------------------------------------------------------------------------- */

#define FIRE_FINC 1.1
#define FIRE_FDEC 0.5
#define FIRE_ALPHA0 0.25
#define FIRE_FALPHA 0.99
#define FIRE_NDELAY 20

/* lbfgs's and fire's preconditioner: the diagonal blocks reassembled every so many
 * iterations (grain_precond) */
#define PRECOND_EVERY 50
static void grain_precond(struct qs_minimizer *m);
static void newton_precond(struct qs_minimizer *m);
static void precond_apply(const struct qs_minimizer *m, const double *r, double *z);
static void precond_scaled(const struct qs_minimizer *m, const double *v, double f, const double *y, double gamma,
    double *z);

/* The storage of lbfgs's and fire's preconditioner when precond_shift > 0: the diagonal
 * blocks, which newton_precond overwrites with their inverses, and a work vector. */
static int
precond_alloc(struct qs_minimizer *m)
{
	size_t n3 = m->w.n3;

	if (!(m->mp.precond_shift > 0))
		return 0;
	m->z = malloc(n3 * sizeof *m->z);
	m->eig = gsl_eigen_symmv_alloc(3);
	if (!m->z || !m->eig || qs_hessian_init(&m->H, n3 / 3))
		return -1;
	m->H.diag_only = 1;
	m->Minv = m->H.diag;
	m->precond = 1;
	return 0;
}

static int
fire_restart(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	double kb = stiffness_bound(w->s, m->x);

	if (isnan(kb)) {
		msg_seterr("out of memory");
		return -1;
	}
	if (kb <= 0)
		kb = 1;
	if (m->precond) {
		/* the preconditioned force P^-1 g: P^-1 H has its eigenvalues near 1 or below
		 * (block Jacobi), so the time step needs no stiffness bound */
		grain_precond(m);
		if (m->precond)
			kb = 1;
	}
	m->dtmax = m->mp.fire_dt / sqrt(kb);
	m->dt = 0.1 * m->dtmax;
	m->alpha = FIRE_ALPHA0;
	m->npos = 0;
	memset(w->v, 0, w->n3 * sizeof *w->v);
	return 0;
}

/* Half a step back along v, and a step forward, each grain's under the cap (cap times its
 * radius). */
static void
fire_back(struct work *w, double *x, double cap, double dt)
{
	size_t i;

	for (i = 0; i < w->s->n; i++) {
		double l = 0.5 * dt * grain_len(w, w->v, i), lim = cap * w->s->p->r[i], sc = l > lim ? lim / l : 1;
		grain_axpy(w, x, w->v, i, -sc * 0.5 * dt);
	}
}

static void
fire_forward(struct work *w, double *x, double cap, double dt)
{
	size_t i;

	for (i = 0; i < w->s->n; i++) {
		double l = grain_len(w, w->v, i) * dt, lim = cap * w->s->p->r[i], sc = l > lim ? lim / l : 1;
		grain_axpy(w, x, w->v, i, sc * dt);
	}
}

static int
fire_iterate(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	double *x = m->x, P, vn, fn;
	size_t k;

	const double *g = w->g;

	if (m->precond) {
		if (m->precond_age < 0 || m->precond_age >= PRECOND_EVERY)
			grain_precond(m);
		m->precond_age++;
	}
	if (m->precond) {
		precond_apply(m, w->g, m->z);
		g = m->z;
	}
	P = -dot(g, w->v, w->n3);
	if (P > 0) {
		if (++m->npos > FIRE_NDELAY) {
			m->dt = fmin(m->dt * FIRE_FINC, m->dtmax);
			m->alpha *= FIRE_FALPHA;
		}
	} else {
		m->npos = 0;
		m->dt = fmax(m->dt * FIRE_FDEC, 0.02 * m->dtmax);
		m->alpha = FIRE_ALPHA0;
		/* half a step back, under the same per-grain cap as a forward step */
		fire_back(w, x, m->mp.cap, m->dt);
		memset(w->v, 0, w->n3 * sizeof *w->v);
	}
	/* semi-implicit Euler with FIRE's mixing of the velocity towards the force */
	for (k = 0; k < w->n3; k++)
		w->v[k] -= m->dt * g[k];
	vn = sqrt(dot(w->v, w->v, w->n3));
	fn = sqrt(dot(g, g, w->n3));
	if (fn > 0)
		for (k = 0; k < w->n3; k++)
			w->v[k] = (1 - m->alpha) * w->v[k] - m->alpha * vn * g[k] / fn;
	fire_forward(w, x, m->mp.cap, m->dt);
	m->eprev = w->e;
	w->e = qs_energy(w->s, x, w->g, w->fmax);
	w->x_evals = w->s->evals;
	return isnan(w->e) ? -1 : 0;
}

/* --- L-BFGS ---------------------------------------------------------------------------- */

/* L-BFGS: the two-loop recursion over the last m steps, H0 = (s.y / y.y) I or the grains'
 * blocks (grain_precond), the same capped
 * derivative line search as CG but first trying alpha = 1 and accepting a weak Wolfe point
 * (|dPi/dalpha| <= 0.9 |dPi/dalpha(0)|), as quasi-Newton methods want. */
static int
lbfgs_alloc(struct qs_minimizer *m)
{
	size_t mm = (size_t)m->mp.lbfgs_m, n3 = m->w.n3;

	m->S = malloc(mm * n3 * sizeof *m->S);
	m->Y = malloc(mm * n3 * sizeof *m->Y);
	m->rho = malloc(mm * sizeof *m->rho);
	m->al = malloc(mm * sizeof *m->al);
	m->sy = malloc(mm * sizeof *m->sy);
	m->yy = malloc(mm * sizeof *m->yy);
	if (!m->S || !m->Y || !m->rho || !m->al || !m->sy || !m->yy) {
		msg_seterr("out of memory for L-BFGS");
		return -1;
	}
	return precond_alloc(m);
}

/* The two loops of L-BFGS's recursion over the stored pairs, each axpy fused with the dot
 * product that follows it (par.h: the same bytes as the plain passes).  lbfgs_loop1: v = -g,
 * then newest to oldest al_c = rho_c s_c.v, v -= al_c y_c; its last axpy scaled by scale and
 * dotted with last (returned), or, when last is NULL, left to the caller (al_c set: the
 * preconditioner's pass takes it, precond_scaled).  lbfgs_loop2: oldest to newest
 * b = rho_c y_c.v (t the first of these dots), v += (al_c - b) s_c; returns v.g. */
static double
lbfgs_loop1(struct qs_minimizer *m, double *v, double scale, const double *last)
{
	struct work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, q, c, cn;
	size_t n3 = w->n3;
	double t;

	c = (m->head - 1 + mm) % mm;
	t = par_neg_dot(v, w->g, m->count ? m->S + (size_t)c * n3 : w->g, n3);
	for (q = 0; q < m->count; q++) {
		c = (m->head - 1 - q + mm) % mm;
		m->al[c] = m->rho[c] * t;
		if (q + 1 < m->count) {
			cn = (m->head - 2 - q + mm) % mm;
			t = par_axpy_scale_dot(v, -m->al[c], m->Y + (size_t)c * n3, 1, m->S + (size_t)cn * n3, n3);
		} else if (last) {
			t = par_axpy_scale_dot(v, -m->al[c], m->Y + (size_t)c * n3, scale, last, n3);
		}
	}
	return t;
}

static double
lbfgs_loop2(struct qs_minimizer *m, double *v, double t)
{
	struct work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, q, c, cn;
	size_t n3 = w->n3;

	for (q = m->count - 1; q >= 0; q--) {
		double b;
		c = (m->head - 1 - q + mm) % mm;
		b = m->rho[c] * t;
		cn = (m->head - q + mm) % mm;
		t = par_axpy_scale_dot(v, m->al[c] - b, m->S + (size_t)c * n3, 1, q > 0 ? m->Y + (size_t)cn * n3 : w->g, n3);
	}
	return t;
}

/* d = -H g by the two-loop recursion over the stored pairs, each axpy fused with the dot
 * product that follows it (par.h: the same bytes as the plain passes), H0's gamma from the
 * dot products of the newest pair taken when it was stored; leaves d.g in m->dg. */
static void
lbfgs_direction(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, c;
	size_t n3 = w->n3;
	double gamma, t;

	if (m->count == 0) {
		/* first step: as far as the cap allows along -g */
		capped_descent(w, m->mp.cap);
		m->dg = dot(w->d, w->g, n3);
	} else {
		c = (m->head - 1 + mm) % mm;
		gamma = m->sy[c] / m->yy[c];
		/* the last axpy of the first loop with the scaling by gamma and the second loop's
		 * first dot (against the oldest y) */
		c = (m->head - m->count + mm) % mm;
		t = lbfgs_loop1(m, w->d, gamma, m->Y + (size_t)c * n3);
		m->dg = lbfgs_loop2(m, w->d, t);
	}
	if (m->dg >= 0) {	/* not downhill: forget the history */
		m->count = 0;
		capped_descent(w, m->mp.cap);
		m->dg = NAN;	/* line_search takes d.g itself */
	}
}

/* Add f times the mean diagonal stiffness of its kind to every diagonal block of H: the
 * mean over the n centres' blocks to the centres', over the rotations' to the rotations'
 * (hessian.h's nodes).  Newton's Levenberg damping and L-BFGS's H0 shift. */
static void
diag_shift(struct qs_hessian *H, size_t n, double f)
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
 * preconditioner (newton_precond).  It scales each grain's step by its own stiffness: with
 * friction the centres and the rotations R Omega, and grains held by stiff and by soft
 * contacts, differ by orders of magnitude, which the one scalar of plain L-BFGS cannot
 * follow.  Assembled at the start and every PRECOND_EVERY iterations (only the diagonal
 * blocks); a functional with a term without second derivatives (friction under the paper's
 * rule) keeps the scalar H0 and the plain force. */
static void
grain_precond(struct qs_minimizer *m)
{
	m->H.at_last_eval = qs_minimizer_current(m);
	if (qs_hessian(m->w.s, m->x, &m->H)) {
		m->precond = 0;
		return;
	}
	diag_shift(&m->H, m->w.s->n, m->mp.precond_shift);
	newton_precond(m);
	m->precond_age = 0;
}

/* The two-loop recursion with H0 = gamma P^-1 (precond_shift), gamma = s.y / y.P^-1 y of the
 * newest pair; the first step is -P^-1 g, whose length is already a displacement. */
static void
lbfgs_direction_precond(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m, c, cn;
	size_t n3 = w->n3;
	double gamma = 1, t;

	if (m->precond_age < 0 || m->precond_age >= PRECOND_EVERY)
		grain_precond(m);
	m->precond_age++;
	if (!m->precond) {
		lbfgs_direction(m);
		return;
	}
	lbfgs_loop1(m, m->z, 1, NULL);
	if (m->count > 0) {
		c = (m->head - 1 + mm) % mm;
		gamma = m->sy[c] / par_quad3(m->Minv, m->Y + (size_t)c * n3, n3);
	}
	/* the first loop's last axpy (against the oldest y), P^-1 and the scaling by gamma in
	 * one pass; then the second loop's first dot, against that same y */
	cn = (m->head - m->count + mm) % mm;
	precond_scaled(m, m->z, m->count ? -m->al[cn] : 0, m->count ? m->Y + (size_t)cn * n3 : NULL, gamma, w->d);
	t = par_dot(m->count ? m->Y + (size_t)cn * n3 : w->g, w->d, n3);
	t = lbfgs_loop2(m, w->d, t);
	m->dg = t;
	if (!(m->dg < 0)) {	/* not downhill (or no stiffness at all): forget the history */
		m->count = 0;
		capped_descent(w, m->mp.cap);
		m->dg = NAN;
	}
}

static int
lbfgs_iterate(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	int mm = (int)m->mp.lbfgs_m;
	size_t n3 = w->n3;
	double amax, alpha, sy = 0, yy = 0, *x = m->x;

	if (m->precond)
		lbfgs_direction_precond(m);
	else
		lbfgs_direction(m);
	amax = alpha_cap(w, w->d, m->mp.cap);
	alpha = line_search(w, x, 1.0, amax, 0.9, m->solver, m->dg);
	if (alpha < 0)
		return -1;
	/* new pair s = alpha d, y = g_new - g, and their s.y, y.y in the same pass */
	{
		double *S = m->S + (size_t)m->head * n3, *Y = m->Y + (size_t)m->head * n3;
		par_diff_dots(S, w->xt, x, Y, w->gt, w->g, n3, &sy, &yy);
		/* the slot holds the new pair even when it is not kept (below) */
		m->sy[m->head] = sy;
		m->yy[m->head] = yy;
	}
	if (sy > 1e-300 && yy > 0) {
		m->rho[m->head] = 1 / sy;
		m->head = (m->head + 1) % mm;
		if (m->count < mm)
			m->count++;
	}
	m->eprev = accept_trial(w, x);
	return 0;
}


/* --- Newton-Krylov ------------------------------------------------------------------ */

static int
newton_alloc(struct qs_minimizer *m)
{
	size_t n3 = m->w.n3, n = n3 / 3;	/* the Hessian's nodes: centres, then rotations (hessian.h) */

	m->Minv = malloc(9 * (n ? n : 1) * sizeof *m->Minv);
	m->r = malloc(n3 * sizeof *m->r);
	m->z = malloc(n3 * sizeof *m->z);
	m->q = malloc(n3 * sizeof *m->q);
	m->Hq = malloc(n3 * sizeof *m->Hq);
	m->eig = gsl_eigen_symmv_alloc(3);
	if (!m->Minv || !m->r || !m->z || !m->q || !m->Hq || !m->eig || qs_hessian_init(&m->H, n)) {
		msg_seterr("out of memory for Newton's method");
		return -1;
	}
	return 0;
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
static void
newton_precond(struct qs_minimizer *m)
{
	size_t i, n = m->H.n;
	double a[9], ev[3], vv[9];
	gsl_matrix_view A = gsl_matrix_view_array(a, 3, 3), V = gsl_matrix_view_array(vv, 3, 3);
	gsl_vector_view E = gsl_vector_view_array(ev, 3);

	for (i = 0; i < n; i++) {
		double D[9], *M = m->Minv + 9 * i, big = 0, inv[3];
		int u, v, c;

		memcpy(D, m->H.diag + 9 * i, sizeof D);	/* M may be the diagonal block itself */
		if (spd_inverse3(D, M))
			continue;
		memcpy(a, D, sizeof a);
		gsl_eigen_symmv(&A.matrix, &E.vector, &V.matrix, m->eig);
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

static void
precond_apply(const struct qs_minimizer *m, const double *r, double *z)
{
	size_t i;

	/* node by node: the same bytes for any split */
#pragma omp parallel for schedule(static) if (m->w.n3 >= PAR_MIN_VEC)
	for (i = 0; i < m->H.n; i++) {
		const double *M = m->Minv + 9 * i, *ri = r + 3 * i;
		double *zi = z + 3 * i;

		zi[0] = M[0] * ri[0] + M[1] * ri[1] + M[2] * ri[2];
		zi[1] = M[3] * ri[0] + M[4] * ri[1] + M[5] * ri[2];
		zi[2] = M[6] * ri[0] + M[7] * ri[1] + M[8] * ri[2];
	}
}

/* z = gamma P^-1 (v + f y) node by node (y NULL: P^-1 v), with the bytes of par_axpy(v, f, y),
 * precond_apply(v, z) and par_axpy_scale_dot(z, 0, z, gamma, ...) one after the other, in one
 * pass and without writing v. */
static void
precond_scaled(const struct qs_minimizer *m, const double *v, double f, const double *y, double gamma, double *z)
{
	size_t i;

#pragma omp parallel for schedule(static) if (m->w.n3 >= PAR_MIN_VEC)
	for (i = 0; i < m->H.n; i++) {
		const double *M = m->Minv + 9 * i, *vi = v + 3 * i;
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

/* The Newton direction: H d = -g by preconditioned CG from d = 0, to |r| <= eta |g|, stopped
 * at the first direction of negative curvature (Steihaug): the iterate so far, or at the
 * first CG step the preconditioned steepest descent, is still downhill. */
static void
newton_direction(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	size_t n3 = w->n3;
	double gg = dot(w->g, w->g, n3), eta = m->mp.newton_eta, tol2, rz, rr;
	long it;

	/* Eisenstat-Walker's second forcing term: loose while the gradient falls slowly, tight
	 * once Newton converges, never looser than newton_eta */
	if (m->gnorm_prev > 0 && eta > 0) {
		double e = 0.9 * gg / (m->gnorm_prev * m->gnorm_prev), safe = 0.9 * m->eta_prev * m->eta_prev;
		eta = fmin(eta, safe > 0.1 ? fmax(e, safe) : e);
	}
	m->eta_prev = eta;
	m->gnorm_prev = sqrt(gg);
	tol2 = eta * eta * gg;

	par_zero(w->d, n3);
	par_scale(m->r, -1, w->g, n3);
	precond_apply(m, m->r, m->z);
	par_copy(m->q, m->z, n3);
	rz = dot(m->r, m->z, n3);
	for (it = 0; it < m->mp.newton_cg_max; it++) {
		double qHq, a, rz1;

		qs_hessian_mul(&m->H, m->q, m->Hq);
		qHq = dot(m->q, m->Hq, n3);
		if (!(qHq > 0)) {
			if (it == 0)
				memcpy(w->d, m->q, n3 * sizeof *w->d);
			break;
		}
		a = rz / qHq;
		par_axpy(w->d, a, m->q, n3);
		rr = par_axpy_scale_dot(m->r, -a, m->Hq, 1, m->r, n3);	/* r -= a Hq, then r.r: one pass */
		if (rr <= tol2)
			break;
		precond_apply(m, m->r, m->z);
		rz1 = dot(m->r, m->z, n3);
		{
			double beta = rz1 / rz;
			long kk;
			/* elementwise, no sum: the same bytes on any thread count */
#pragma omp parallel for schedule(static) if (n3 >= PAR_MIN_VEC)
			for (kk = 0; kk < (long)n3; kk++)
				m->q[kk] = m->z[kk] + beta * m->q[kk];
		}
		rz = rz1;
	}
	if (dot(w->d, w->g, n3) >= 0)	/* no progress at all: along -g */
		capped_descent(w, m->mp.cap);
}

/* Each grain's part of the Newton direction cut to the step cap (cap times its radius),
 * rather than the whole direction scaled until its worst grain fits: a nearly free grain
 * (see the damping in newton_iterate) would otherwise shrink the step of all the others,
 * and with friction it did in most Newton steps (an increment at 8.8 MPa, 2740 grains:
 * 1536 Newton steps with the whole direction scaled, 84 with each grain cut).  The cut direction is kept when it
 * is still downhill, else the uncut one. */
static void
newton_clip(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	size_t i;
	int cut = 0;

	memcpy(w->v, w->d, w->n3 * sizeof *w->v);
	for (i = 0; i < w->s->n; i++) {
		double l = grain_len(w, w->d, i), lim = m->mp.cap * w->s->p->r[i];
		if (l > lim) {
			grain_axpy(w, w->d, w->d, i, lim / l - 1);
			cut = 1;
		}
	}
	if (cut && !(dot(w->d, w->g, w->n3) < 0))
		memcpy(w->d, w->v, w->n3 * sizeof *w->v);
}

static int
newton_iterate(struct qs_minimizer *m)
{
	struct work *w = &m->w;
	double amax, alpha;

	if (qs_hessian(w->s, m->x, &m->H))
		return -1;
	/* Levenberg damping: an absolute shift, not a fraction of each grain's own stiffness
	 * (diag_shift): a nearly free grain (a rattler touching one or two neighbours, whose
	 * rolling modes have almost no stiffness with friction, or the negative geometric
	 * stiffness of a chain) gets a bounded step, g / (lambda k_mean), not an unbounded one */
	if (m->lambda > 0)
		diag_shift(&m->H, w->s->n, m->lambda);
	newton_precond(m);
	newton_direction(m);
	newton_clip(m);
	amax = alpha_cap(w, w->d, m->mp.cap);
	alpha = line_search(w, m->x, 1.0, amax, 0.9, m->solver, NAN);
	if (alpha < 0)
		return -1;
	/* Levenberg: the full step taken, trust the model more; a short one, less */
	if (alpha >= 1)
		m->lambda = m->lambda < 1e-6 ? 0 : 0.1 * m->lambda;
	else if (alpha < 0.1 && alpha < amax)
		m->lambda = fmax(10 * m->lambda, 1e-4);
	m->eprev = accept_trial(w, m->x);
	return 0;
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
	struct work *w;
	double Em = 0, Rm = 0;
	size_t i;

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
	w->v = malloc(w->n3 * sizeof *w->v);
	w->ft = malloc(s->n * sizeof *w->ft);
	m->solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
	if (!w->g || !w->fmax || !w->d || !w->xt || !w->gt || !w->v || !w->ft || !m->solver ||
	    (mp->method == QS_LBFGS && lbfgs_alloc(m)) || (mp->method == QS_NEWTON && newton_alloc(m)) ||
	    (mp->method == QS_FIRE && precond_alloc(m))) {
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
	struct work *w;

	if (!m)
		return;
	w = &m->w;
	free(w->g), free(w->fmax), free(w->d), free(w->xt), free(w->gt), free(w->v), free(w->ft);
	free(m->S), free(m->Y), free(m->rho), free(m->al), free(m->sy), free(m->yy);
	if (m->Minv != m->H.diag)
		free(m->Minv);
	free(m->r), free(m->z), free(m->q), free(m->Hq);
	qs_hessian_free(&m->H);
	if (m->eig)
		gsl_eigen_symmv_free(m->eig);
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
	m->step = 0;
	if (!(keep && m->mp.method == QS_LBFGS)) {
		m->head = m->count = 0;
		m->precond_age = -1;
	}
	m->lambda = 0;
	m->gnorm_prev = 0;
	if (evaluate(m))
		return -1;
	if (m->mp.method == QS_CG)
		cg_restart(m);
	else if (m->mp.method == QS_FIRE)
		return fire_restart(m);
	return 0;
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
	m->precond_age = -1;	/* the grains that moved have new contacts */
	if (m->mp.method == QS_CG)
		cg_restart(m);
	else if (m->mp.method == QS_FIRE)
		memset(m->w.v, 0, m->w.n3 * sizeof *m->w.v);
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
	if (m->mp.method == QS_CG && m->gg == 0)
		return QS_MIN_SUCCESS;	/* a zero gradient: nothing to move along */
	return QS_MIN_CONTINUE;
}

int
qs_minimizer_iterate(struct qs_minimizer *m)
{
	int st = m->mp.method == QS_FIRE     ? fire_iterate(m)
	    : m->mp.method == QS_LBFGS  ? lbfgs_iterate(m)
	    : m->mp.method == QS_NEWTON ? newton_iterate(m)
	                                : cg_iterate(m);

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
