/* minimize: the papers' modified CG and FIRE (see minimize.h). */
#include "qs/minimize.h"
#include "base/msg.h"

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
	mp->lbfgs_m = 8;
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
	else
		return -1;
	return 0;
}

const char *
qs_method_name(enum qs_method m)
{
	return m == QS_FIRE ? "fire" : m == QS_LBFGS ? "lbfgs" : "cg";
}

/* Workspace shared by both methods. */
struct work {
	struct qs_system *s;
	size_t n3;
	double *g, *fmax, *d, *xt, *gt, *ft, *v;
	double e, et;	/* energy at x and at the trial point xt */
};

static double
dot(const double *a, const double *b, size_t n)
{
	double s = 0;
	size_t k;

	for (k = 0; k < n; k++)
		s += a[k] * b[k];
	return s;
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
	size_t i;

	for (i = 0; i < w->s->n; i++) {
		double l = grain_len(w, d, i);
		if (l > 0 && cap * w->s->p->r[i] / l < amax)
			amax = cap * w->s->p->r[i] / l;
	}
	return amax;
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

	for (k = 0; k < w->n3; k++)
		w->xt[k] = c->x[k] + alpha * w->d[k];
	c->last_e = w->et = qs_energy(w->s, w->xt, w->gt, w->ft);
	if (isnan(c->last_e))
		c->failed = 1;
	c->last_alpha = alpha;
	return dot(w->gt, w->d, w->n3);
}

/* One-dimensional minimisation along w->d from x: bracket the root of dPi/dalpha (doubling
 * from the previous step, never beyond the cap), then Brent.  On return xt/gt hold the
 * accepted point.  Returns alpha, or -1 on error. */
static double
line_search(struct work *w, const double *x, double guess, double amax, double sigma, gsl_root_fsolver *solver)
{
	struct ls_ctx c = {w, x, 0, 0, 0};
	gsl_function F = {dphi, &c};
	double d0 = dot(w->g, w->d, w->n3), lo = 0, hi, dhi;
	int it;

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

	memcpy(x, w->xt, w->n3 * sizeof *x);
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

static int
run_cg(struct work *w, double *x, const struct qs_min_params *mp, struct qs_min_report *rep, double scale2)
{
	gsl_root_fsolver *solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
	double gg, step = 0, eprev = INFINITY;
	size_t k;
	long it;

	if (!solver) {
		msg_seterr("out of memory");
		return -1;
	}
	gg = dot(w->g, w->g, w->n3);
	for (k = 0; k < w->n3; k++)
		w->d[k] = -w->g[k];
	for (it = 0;; it++) {
		double amax, alpha, gg_new, beta;

		if (should_stop(w, mp, it, eprev, rep, scale2))
			break;
		if (gg == 0)
			break;
		amax = alpha_cap(w, w->d, mp->cap);
		alpha = line_search(w, x, step > 0 ? 2 * step : amax, amax, mp->ls_sigma, solver);
		if (alpha < 0) {
			gsl_root_fsolver_free(solver);
			return -1;
		}
		step = alpha;
		eprev = accept_trial(w, x);
		gg_new = dot(w->g, w->g, w->n3);
		beta = (it + 1) % mp->k_sd == 0 ? 0 : gg_new / gg;
		for (k = 0; k < w->n3; k++)
			w->d[k] = -w->g[k] + beta * w->d[k];
		if (dot(w->d, w->g, w->n3) >= 0)	/* not a descent direction: restart */
			for (k = 0; k < w->n3; k++)
				w->d[k] = -w->g[k];
		gg = gg_new;
	}
	gsl_root_fsolver_free(solver);
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

static int
run_fire(struct work *w, double *x, const struct qs_min_params *mp, struct qs_min_report *rep, double scale2)
{
	const double finc = 1.1, fdec = 0.5, alpha0 = 0.25, falpha = 0.99;
	const long ndelay = 20;
	double kb = stiffness_bound(w->s, x), dtmax, dt, alpha = alpha0, eprev = INFINITY;
	long it, npos = 0;
	size_t k, i;

	if (isnan(kb)) {
		msg_seterr("out of memory");
		return -1;
	}
	if (kb <= 0)
		kb = 1;
	dtmax = mp->fire_dt / sqrt(kb);
	dt = 0.1 * dtmax;
	memset(w->v, 0, w->n3 * sizeof *w->v);
	for (it = 0;; it++) {
		double P = 0, vn, fn;

		if (should_stop(w, mp, it, eprev, rep, scale2))
			break;
		P = -dot(w->g, w->v, w->n3);
		if (P > 0) {
			if (++npos > ndelay) {
				dt = fmin(dt * finc, dtmax);
				alpha *= falpha;
			}
		} else {
			npos = 0;
			dt = fmax(dt * fdec, 0.02 * dtmax);
			alpha = alpha0;
			/* half a step back, under the same per-grain cap as a forward step */
			for (i = 0; i < w->s->n; i++) {
				double l = 0.5 * dt * grain_len(w, w->v, i), lim = mp->cap * w->s->p->r[i],
				       sc = l > lim ? lim / l : 1;
				grain_axpy(w, x, w->v, i, -sc * 0.5 * dt);
			}
			memset(w->v, 0, w->n3 * sizeof *w->v);
		}
		/* semi-implicit Euler with FIRE's mixing of the velocity towards the force */
		for (k = 0; k < w->n3; k++)
			w->v[k] -= dt * w->g[k];
		vn = sqrt(dot(w->v, w->v, w->n3));
		fn = sqrt(dot(w->g, w->g, w->n3));
		if (fn > 0)
			for (k = 0; k < w->n3; k++)
				w->v[k] = (1 - alpha) * w->v[k] - alpha * vn * w->g[k] / fn;
		for (i = 0; i < w->s->n; i++) {
			double l = grain_len(w, w->v, i) * dt, lim = mp->cap * w->s->p->r[i], sc = l > lim ? lim / l : 1;
			grain_axpy(w, x, w->v, i, sc * dt);
		}
		eprev = w->e;
		w->e = qs_energy(w->s, x, w->g, w->fmax);
		if (isnan(w->e))
			return -1;
	}
	return 0;
}

/* L-BFGS: the two-loop recursion over the last m steps, H0 = (s.y / y.y) I, the same capped
 * derivative line search as CG but first trying alpha = 1 and accepting a weak Wolfe point
 * (|dPi/dalpha| <= 0.9 |dPi/dalpha(0)|), as quasi-Newton methods want. */
static int
run_lbfgs(struct work *w, double *x, const struct qs_min_params *mp, struct qs_min_report *rep, double scale2)
{
	int m = (int)mp->lbfgs_m, head = 0, count = 0, q;
	size_t n3 = w->n3, k;
	double *S = malloc((size_t)m * n3 * sizeof *S), *Y = malloc((size_t)m * n3 * sizeof *Y);
	double *rho = malloc((size_t)m * sizeof *rho), *al = malloc((size_t)m * sizeof *al), eprev = INFINITY;
	gsl_root_fsolver *solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
	long it;
	int status = 0;

	if (!S || !Y || !rho || !al || !solver) {
		msg_seterr("out of memory for L-BFGS");
		status = -1;
		goto out;
	}
	for (it = 0;; it++) {
		double amax, alpha, gamma = 1, sy, yy;

		if (should_stop(w, mp, it, eprev, rep, scale2))
			break;
		/* d = -H g by the two-loop recursion */
		for (k = 0; k < n3; k++)
			w->d[k] = -w->g[k];
		for (q = 0; q < count; q++) {
			int c = (head - 1 - q + m) % m;
			al[c] = rho[c] * dot(S + (size_t)c * n3, w->d, n3);
			for (k = 0; k < n3; k++)
				w->d[k] -= al[c] * Y[(size_t)c * n3 + k];
		}
		if (count > 0) {
			int c = (head - 1 + m) % m;
			gamma = dot(S + (size_t)c * n3, Y + (size_t)c * n3, n3) / dot(Y + (size_t)c * n3, Y + (size_t)c * n3, n3);
		} else {
			/* first step: as far as the cap allows along -g */
			gamma = alpha_cap(w, w->g, mp->cap);
		}
		for (k = 0; k < n3; k++)
			w->d[k] *= gamma;
		for (q = count - 1; q >= 0; q--) {
			int c = (head - 1 - q + m) % m;
			double b = rho[c] * dot(Y + (size_t)c * n3, w->d, n3);
			for (k = 0; k < n3; k++)
				w->d[k] += (al[c] - b) * S[(size_t)c * n3 + k];
		}
		if (dot(w->d, w->g, n3) >= 0) {	/* not downhill: forget the history */
			count = 0;
			for (k = 0; k < n3; k++)
				w->d[k] = -w->g[k] * alpha_cap(w, w->g, mp->cap);
		}
		amax = alpha_cap(w, w->d, mp->cap);
		alpha = line_search(w, x, 1.0, amax, 0.9, solver);
		if (alpha < 0) {
			status = -1;
			goto out;
		}
		/* new pair s = alpha d, y = g_new - g */
		sy = yy = 0;
		for (k = 0; k < n3; k++) {
			double sk = w->xt[k] - x[k], yk = w->gt[k] - w->g[k];
			S[(size_t)head * n3 + k] = sk;
			Y[(size_t)head * n3 + k] = yk;
			sy += sk * yk;
			yy += yk * yk;
		}
		if (sy > 1e-300 && yy > 0) {
			rho[head] = 1 / sy;
			head = (head + 1) % m;
			if (count < m)
				count++;
		}
		eprev = accept_trial(w, x);
	}
out:
	free(S), free(Y), free(rho), free(al);
	if (solver)
		gsl_root_fsolver_free(solver);
	return status;
}

int
qs_minimize(struct qs_system *s, double *x, const struct qs_min_params *mp, struct qs_min_report *rep)
{
	struct work w;
	long evals0 = s->evals;
	double Em = 0, Rm = 0, scale2;
	size_t i;
	int st;

	memset(rep, 0, sizeof *rep);
	memset(&w, 0, sizeof w);
	w.s = s;
	w.n3 = s->dim;
	w.g = malloc(w.n3 * sizeof *w.g);
	w.fmax = malloc(s->n * sizeof *w.fmax);
	w.d = malloc(w.n3 * sizeof *w.d);
	w.xt = malloc(w.n3 * sizeof *w.xt);
	w.gt = malloc(w.n3 * sizeof *w.gt);
	w.v = malloc(w.n3 * sizeof *w.v);
	w.ft = malloc(s->n * sizeof *w.ft);
	if (!w.g || !w.fmax || !w.d || !w.xt || !w.gt || !w.v || !w.ft) {
		msg_seterr("out of memory for the minimiser");
		st = rep->status = -1;
		goto out;
	}
	for (i = 0; i < s->n; i++) {
		Em += s->p->E[i] / s->n;
		Rm += s->p->r[i] / s->n;
	}
	scale2 = (double)s->n * (Em * Rm * Rm) * (Em * Rm * Rm);
	w.e = qs_energy(s, x, w.g, w.fmax);
	if (isnan(w.e)) {
		st = rep->status = -1;
		goto out;
	}
	st = mp->method == QS_FIRE ? run_fire(&w, x, mp, rep, scale2) :
	    mp->method == QS_LBFGS ? run_lbfgs(&w, x, mp, rep, scale2) : run_cg(&w, x, mp, rep, scale2);
	if (st < 0)
		rep->status = -1;
	else
		st = rep->status;
	rep->energy = w.e;
out:
	rep->evals = s->evals - evals0;
	free(w.g), free(w.fmax), free(w.d), free(w.xt), free(w.gt), free(w.v), free(w.ft);
	return st;
}
