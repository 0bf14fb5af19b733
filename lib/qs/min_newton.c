/* SPDX-License-Identifier: GPL-3.0-or-later */
/* min_newton: Newton-Krylov on the exact sparse Hessian (minimize.h, method newton;
 * hessian.h): each iteration assembles H, adds Levenberg damping after short steps, solves
 * H d = -g by CG preconditioned with the nodes' 3x3 diagonal blocks to |H d + g| <= eta |g|
 * (Eisenstat-Walker), stopping at negative curvature, cuts each grain's part of d to the step
 * cap, and takes the capped line search from the full step. */
#include "qs/minimize.h"
#include "qs/minimize_priv.h"
#include "base/msg.h"
#include "base/par.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct newton_state {
	struct min_precond pc;	/* the whole Hessian, its diagonal blocks' inverses apart */
	double *r, *q, *Hq;	/* CG's residual, direction and H q (its z is pc.z) */
	double *d0;		/* the direction before newton_clip cut it */
	double gnorm_prev, eta_prev;	/* the forcing term's memory */
	double lambda;		/* Levenberg damping: a fraction of the mean diagonal stiffness */
};

static int
newton_alloc(struct qs_minimizer *m)
{
	struct newton_state *nt = m->state;
	size_t n3 = m->w.n3, n = n3 / 3;	/* the Hessian's nodes: centres, then rotations (hessian.h) */

	nt->pc.Minv = malloc(9 * (n ? n : 1) * sizeof *nt->pc.Minv);
	nt->r = malloc(n3 * sizeof *nt->r);
	nt->pc.z = malloc(n3 * sizeof *nt->pc.z);
	nt->q = malloc(n3 * sizeof *nt->q);
	nt->Hq = malloc(n3 * sizeof *nt->Hq);
	nt->d0 = malloc(n3 * sizeof *nt->d0);
	nt->pc.eig = gsl_eigen_symmv_alloc(3);
	if (!nt->pc.Minv || !nt->r || !nt->pc.z || !nt->q || !nt->Hq || !nt->d0 || !nt->pc.eig ||
	    qs_hessian_init(&nt->pc.H, n)) {
		msg_seterr("out of memory for Newton's method");
		return -1;
	}
	return 0;
}

static void
newton_free(struct qs_minimizer *m)
{
	struct newton_state *nt = m->state;

	min_precond_free(&nt->pc);
	free(nt->r), free(nt->q), free(nt->Hq), free(nt->d0);
}

/* Each minimisation afresh (the Hessian is assembled at every iteration anyway): no damping,
 * the forcing term from newton_eta. */
static int
newton_start(struct qs_minimizer *m, int keep)
{
	struct newton_state *nt = m->state;

	(void)keep;
	nt->lambda = 0;
	nt->gnorm_prev = 0;
	return 0;
}

/* The Newton direction: H d = -g by preconditioned CG from d = 0, to |r| <= eta |g|, stopped
 * at the first direction of negative curvature (Steihaug): the iterate so far, or at the
 * first CG step the preconditioned steepest descent, is still downhill. */
static void
newton_direction(struct qs_minimizer *m)
{
	struct newton_state *nt = m->state;
	struct min_work *w = &m->w;
	size_t n3 = w->n3;
	double gg = min_dot(w->g, w->g, n3), eta = m->mp.newton_eta, tol2, rz, rr;
	long it;

	/* Eisenstat-Walker's second forcing term: loose while the gradient falls slowly, tight
	 * once Newton converges, never looser than newton_eta */
	if (nt->gnorm_prev > 0 && eta > 0) {
		double e = 0.9 * gg / (nt->gnorm_prev * nt->gnorm_prev), safe = 0.9 * nt->eta_prev * nt->eta_prev;
		eta = fmin(eta, safe > 0.1 ? fmax(e, safe) : e);
	}
	nt->eta_prev = eta;
	nt->gnorm_prev = sqrt(gg);
	tol2 = eta * eta * gg;

	par_zero(w->d, n3);
	par_scale(nt->r, -1, w->g, n3);
	min_precond_apply(&nt->pc, nt->r, nt->pc.z, n3);
	par_copy(nt->q, nt->pc.z, n3);
	rz = min_dot(nt->r, nt->pc.z, n3);
	for (it = 0; it < m->mp.newton_cg_max; it++) {
		double qHq, a, rz1;

		qs_hessian_mul(&nt->pc.H, nt->q, nt->Hq);
		qHq = min_dot(nt->q, nt->Hq, n3);
		if (!(qHq > 0)) {
			if (it == 0)
				memcpy(w->d, nt->q, n3 * sizeof *w->d);
			break;
		}
		a = rz / qHq;
		par_axpy(w->d, a, nt->q, n3);
		rr = par_axpy_scale_dot(nt->r, -a, nt->Hq, 1, nt->r, n3);	/* r -= a Hq, then r.r: one pass */
		if (rr <= tol2)
			break;
		min_precond_apply(&nt->pc, nt->r, nt->pc.z, n3);
		rz1 = min_dot(nt->r, nt->pc.z, n3);
		{
			double beta = rz1 / rz;
			long kk;
			/* elementwise, no sum: the same bytes on any thread count */
#pragma omp parallel for schedule(static) if (n3 >= PAR_MIN_VEC)
			for (kk = 0; kk < (long)n3; kk++)
				nt->q[kk] = nt->pc.z[kk] + beta * nt->q[kk];
		}
		rz = rz1;
	}
	if (min_dot(w->d, w->g, n3) >= 0)	/* no progress at all: along -g */
		min_capped_descent(w, m->mp.cap);
}

/* Each grain's part of the Newton direction cut to the step cap (cap times its radius),
 * rather than the whole direction scaled until its worst grain fits: a nearly free grain
 * (see the damping in newton_iterate) would otherwise shrink the step of all the others,
 * and with friction it did in most Newton steps (an increment at 8.8 MPa, 2740 grains:
 * 1536 Newton steps with the whole direction scaled, 84 with each grain cut).  The cut
 * direction is kept when it is still downhill, else the uncut one. */
static void
newton_clip(struct qs_minimizer *m)
{
	struct newton_state *nt = m->state;
	struct min_work *w = &m->w;
	size_t i;
	int cut = 0;

	memcpy(nt->d0, w->d, w->n3 * sizeof *nt->d0);
	for (i = 0; i < w->s->n; i++) {
		double l = min_grain_len(w, w->d, i), lim = m->mp.cap * w->s->p->r[i];
		if (l > lim) {
			min_grain_axpy(w, w->d, w->d, i, lim / l - 1);
			cut = 1;
		}
	}
	if (cut && !(min_dot(w->d, w->g, w->n3) < 0))
		memcpy(w->d, nt->d0, w->n3 * sizeof *w->d);
}

static int
newton_iterate(struct qs_minimizer *m)
{
	struct newton_state *nt = m->state;
	struct min_work *w = &m->w;
	double amax, alpha;

	if (qs_hessian(w->s, m->x, &nt->pc.H))
		return -1;
	/* Levenberg damping: an absolute shift, not a fraction of each grain's own stiffness
	 * (min_diag_shift): a nearly free grain (a rattler touching one or two neighbours, whose
	 * rolling modes have almost no stiffness with friction, or the negative geometric
	 * stiffness of a chain) gets a bounded step, g / (lambda k_mean), not an unbounded one */
	if (nt->lambda > 0)
		min_diag_shift(&nt->pc.H, w->s->n, nt->lambda);
	min_precond_invert(&nt->pc);
	newton_direction(m);
	newton_clip(m);
	amax = min_alpha_cap(w, w->d, m->mp.cap);
	alpha = min_line_search(w, m->x, 1.0, amax, 0.9, m->solver, NAN);
	if (alpha < 0)
		return -1;
	/* Levenberg: the full step taken, trust the model more; a short one, less */
	if (alpha >= 1)
		nt->lambda = nt->lambda < 1e-6 ? 0 : 0.1 * nt->lambda;
	else if (alpha < 0.1 && alpha < amax)
		nt->lambda = fmax(10 * nt->lambda, 1e-4);
	m->eprev = min_accept_trial(w, m->x);
	return 0;
}

const struct qs_method_type qs_method_newton = {
	.name = "newton",
	.description = "Newton-Krylov, exact Hessian",
	.size = sizeof(struct newton_state),
	.alloc = newton_alloc,
	.free = newton_free,
	.start = newton_start,
	.iterate = newton_iterate,
	.moved = NULL,	/* nothing kept between iterations but the forcing term and the damping */
	.stuck = NULL,
	.needs_hessian = 1,
};
