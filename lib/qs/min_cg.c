/* SPDX-License-Identifier: GPL-3.0-or-later */
/* min_cg: the papers' modified conjugate gradient (minimize.h, method cg): Fletcher-Reeves
 * beta, a steepest-descent restart every k_sd iterations, and the capped derivative line
 * search, each search starting from twice the last step. */
#include "qs/minimize.h"
#include "qs/minimize_priv.h"

#include <math.h>

struct cg_state {
	double gg;	/* g.g at x */
	double step;	/* the last line search's alpha; 0: none yet */
};

/* Along the steepest descent. */
static void
cg_restart(struct qs_minimizer *m)
{
	struct cg_state *c = m->state;
	struct min_work *w = &m->w;
	size_t k;

	c->gg = min_dot(w->g, w->g, w->n3);
	for (k = 0; k < w->n3; k++)
		w->d[k] = -w->g[k];
}

static int
cg_start(struct qs_minimizer *m, int keep)
{
	struct cg_state *c = m->state;

	(void)keep;	/* nothing to keep: a new functional needs a new direction */
	c->step = 0;
	cg_restart(m);
	return 0;
}

static int
cg_iterate(struct qs_minimizer *m)
{
	struct cg_state *c = m->state;
	struct min_work *w = &m->w;
	const struct qs_min_params *mp = &m->mp;
	double amax, alpha, gg_new, beta;
	size_t k;

	amax = min_alpha_cap(w, w->d, mp->cap);
	alpha = min_line_search(w, m->x, c->step > 0 ? 2 * c->step : amax, amax, mp->ls_sigma, m->solver, NAN);
	if (alpha < 0)
		return -1;
	c->step = alpha;
	m->eprev = min_accept_trial(w, m->x);
	gg_new = min_dot(w->g, w->g, w->n3);
	beta = (m->it + 1) % mp->k_sd == 0 ? 0 : gg_new / c->gg;
	for (k = 0; k < w->n3; k++)
		w->d[k] = -w->g[k] + beta * w->d[k];
	if (min_dot(w->d, w->g, w->n3) >= 0)	/* not a descent direction: restart */
		for (k = 0; k < w->n3; k++)
			w->d[k] = -w->g[k];
	c->gg = gg_new;
	return 0;
}

/* The grains moved: the conjugate direction no longer applies (the step length does, as a
 * guess). */
static void
cg_moved(struct qs_minimizer *m)
{
	cg_restart(m);
}

/* A zero gradient: no direction at all. */
static int
cg_stuck(const struct qs_minimizer *m)
{
	const struct cg_state *c = m->state;

	return c->gg == 0;
}

const struct qs_method_type qs_method_cg = {
	.name = "cg",
	.description = "the papers' modified CG",
	.size = sizeof(struct cg_state),
	.alloc = NULL,	/* two doubles, in the state */
	.free = NULL,
	.start = cg_start,
	.iterate = cg_iterate,
	.moved = cg_moved,
	.stuck = cg_stuck,
	.needs_hessian = 0,
};
