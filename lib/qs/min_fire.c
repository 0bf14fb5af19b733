/* SPDX-License-Identifier: GPL-3.0-or-later */
/* min_fire: FIRE 2.0 (minimize.h, method fire; Guénolé et al. 2020, as in LAMMPS min_fire)
 * with unit masses, the time step bounded by 1 / sqrt(the stiffness bound) at the start, each
 * grain's step under the cap; with precond_shift > 0 the force is P^-1 g (the grains'
 * preconditioner, minimize_priv.h) and the time step fire_dt. */
#include "qs/minimize.h"
#include "qs/minimize_priv.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FIRE_FINC 1.1
#define FIRE_FDEC 0.5
#define FIRE_ALPHA0 0.25
#define FIRE_FALPHA 0.99
#define FIRE_NDELAY 20

struct fire_state {
	double *v;		/* the velocity */
	double dt, dtmax, alpha;
	long npos;		/* steps with positive power in a row */
	struct min_precond pc;	/* with precond_shift > 0 */
};

static int
fire_alloc(struct qs_minimizer *m)
{
	struct fire_state *f = m->state;

	f->v = malloc(m->w.n3 * sizeof *f->v);
	if (!f->v)
		return -1;
	return min_precond_alloc(m, &f->pc);
}

static void
fire_free(struct qs_minimizer *m)
{
	struct fire_state *f = m->state;

	free(f->v);
	min_precond_free(&f->pc);
}

/* From rest, at the first time step. */
static int
fire_restart(struct qs_minimizer *m)
{
	struct fire_state *f = m->state;
	struct min_work *w = &m->w;
	double kb = min_stiffness_bound(w->s, m->x);

	if (isnan(kb)) {
		msg_seterr("out of memory");
		return -1;
	}
	if (kb <= 0)
		kb = 1;
	if (f->pc.on) {
		/* the preconditioned force P^-1 g: P^-1 H has its eigenvalues near 1 or below
		 * (block Jacobi), so the time step needs no stiffness bound */
		min_precond_update(m, &f->pc);
		if (f->pc.on)
			kb = 1;
	}
	f->dtmax = m->mp.fire_dt / sqrt(kb);
	f->dt = 0.1 * f->dtmax;
	f->alpha = FIRE_ALPHA0;
	f->npos = 0;
	memset(f->v, 0, w->n3 * sizeof *f->v);
	return 0;
}

/* FIRE keeps nothing across minimisations: the stiffness, and so the time step, changed. */
static int
fire_start(struct qs_minimizer *m, int keep)
{
	struct fire_state *f = m->state;

	(void)keep;
	f->pc.age = -1;
	return fire_restart(m);
}

/* Half a step back along v, and a step forward, each grain's under the cap (cap times its
 * radius). */
static void
fire_back(const struct min_work *w, double *x, const double *v, double cap, double dt)
{
	size_t i;

	for (i = 0; i < w->s->n; i++) {
		double l = 0.5 * dt * min_grain_len(w, v, i), lim = cap * w->s->p->r[i], sc = l > lim ? lim / l : 1;
		min_grain_axpy(w, x, v, i, -sc * 0.5 * dt);
	}
}

static void
fire_forward(const struct min_work *w, double *x, const double *v, double cap, double dt)
{
	size_t i;

	for (i = 0; i < w->s->n; i++) {
		double l = min_grain_len(w, v, i) * dt, lim = cap * w->s->p->r[i], sc = l > lim ? lim / l : 1;
		min_grain_axpy(w, x, v, i, sc * dt);
	}
}

static int
fire_iterate(struct qs_minimizer *m)
{
	struct fire_state *f = m->state;
	struct min_work *w = &m->w;
	double *x = m->x, P, vn, fn;
	size_t k;

	const double *g = w->g;

	if (f->pc.on) {
		if (f->pc.age < 0 || f->pc.age >= MIN_PRECOND_EVERY)
			min_precond_update(m, &f->pc);
		f->pc.age++;
	}
	if (f->pc.on) {
		min_precond_apply(&f->pc, w->g, f->pc.z, w->n3);
		g = f->pc.z;
	}
	P = -min_dot(g, f->v, w->n3);
	if (P > 0) {
		if (++f->npos > FIRE_NDELAY) {
			f->dt = fmin(f->dt * FIRE_FINC, f->dtmax);
			f->alpha *= FIRE_FALPHA;
		}
	} else {
		f->npos = 0;
		f->dt = fmax(f->dt * FIRE_FDEC, 0.02 * f->dtmax);
		f->alpha = FIRE_ALPHA0;
		/* half a step back, under the same per-grain cap as a forward step */
		fire_back(w, x, f->v, m->mp.cap, f->dt);
		memset(f->v, 0, w->n3 * sizeof *f->v);
	}
	/* semi-implicit Euler with FIRE's mixing of the velocity towards the force */
	for (k = 0; k < w->n3; k++)
		f->v[k] -= f->dt * g[k];
	vn = sqrt(min_dot(f->v, f->v, w->n3));
	fn = sqrt(min_dot(g, g, w->n3));
	if (fn > 0)
		for (k = 0; k < w->n3; k++)
			f->v[k] = (1 - f->alpha) * f->v[k] - f->alpha * vn * g[k] / fn;
	fire_forward(w, x, f->v, m->mp.cap, f->dt);
	m->eprev = w->e;
	w->e = qs_energy(w->s, x, w->g, w->fmax);
	w->x_evals = w->s->evals;
	return isnan(w->e) ? -1 : 0;
}

/* The grains moved: from rest (the time step kept), the preconditioner reassembled at the
 * next iteration (the grains that moved have new contacts). */
static void
fire_moved(struct qs_minimizer *m)
{
	struct fire_state *f = m->state;

	f->pc.age = -1;
	memset(f->v, 0, m->w.n3 * sizeof *f->v);
}

const struct qs_method_type qs_method_fire = {
	.name = "fire",
	.description = "FIRE 2.0",
	.size = sizeof(struct fire_state),
	.alloc = fire_alloc,
	.free = fire_free,
	.start = fire_start,
	.iterate = fire_iterate,
	.moved = fire_moved,
	.stuck = NULL,
	.needs_hessian = 0,
};
