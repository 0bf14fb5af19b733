/* SPDX-License-Identifier: GPL-3.0-or-later */
/* platepack: spheroplate packs by grid placement and DEM compaction (see platepack.h). */
#include "dem/platepack.h"
#include "dem/servo.h"
#include "base/msg.h"
#include "base/quat.h"
#include "pack/shape.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
platepack_params_default(struct platepack_params *pp)
{
	engine_params_default(&pp->dyn);
	pp->dyn.damping = 0.3;
	pp->spacing = 0;
	pp->jitter = 0;
	pp->sigma0 = 0;
	pp->rest_tol = 1e-3;
	pp->rate = 1e-4;
	pp->max_steps = 2000000;
	pp->periodic[0] = pp->periodic[1] = pp->periodic[2] = 0;
}

/* The grid: n_a = ceil(cbrt N) nodes per axis, filled x fastest, the box one spacing per
 * node; each grain turned by a uniform random rotation, drawn in id order, and, with jitter
 * > 0, moved off its node by a uniform random vector, each component within jitter times the
 * room its bounding sphere leaves in the node's cell (s/2 - r_b), so no two can overlap; its
 * three uniforms follow the rotation's, and jitter 0 draws none. */
static void
place_on_grid(struct pack *p, double s, double jitter, gsl_rng *rng)
{
	size_t i, na = (size_t)ceil(cbrt((double)p->n) - 1e-9);
	int a;

	while (na * na * na < p->n)
		na++;
	for (i = 0; i < p->n; i++) {
		size_t k[3] = {i % na, i / na % na, i / (na * na)};
		double u1 = gsl_rng_uniform(rng), u2 = gsl_rng_uniform(rng), u3 = gsl_rng_uniform(rng);
		double room = s / 2 - shape_of(pack_grain_shape(p, i))->bounding_radius(p->r[i], p->side[i]);

		for (a = 0; a < 3; a++)
			p->x[3 * i + a] = (k[a] + 0.5) * s;
		quat_from_uniform(u1, u2, u3, p->q + 4 * i);
		if (jitter > 0 && room > 0)
			for (a = 0; a < 3; a++)
				p->x[3 * i + a] += jitter * room * (2 * gsl_rng_uniform(rng) - 1);
	}
	for (a = 0; a < 3; a++)
		p->box[a] = 0, p->box[3 + a] = na * s;
}

static double
grains_volume(const struct engine *d)
{
	double v = 0;
	size_t i;

	for (i = 0; i < d->n; i++)
		v += shape_table[d->kind[i]]->volume(d->r[i], 2 * d->half[i]);
	return v;
}

/* The wall stress over the target (mean over the wall axes), without moving anything. */
static double
wall_ratio(const struct engine *d, double target)
{
	double s = 0;
	int a, nw = 0;

	for (a = 0; a < 3; a++) {
		if (d->periodic[a])
			continue;
		s += pack_wall_stress(d->lo, d->hi, a, d->wallf[2 * a] + d->wallf[2 * a + 1]);
		nw++;
	}
	return nw ? s / nw / target : 0;
}

int
platepack_settle(struct engine *d, const struct platepack_params *pp, double target, int stage, platepack_progress_fn fn,
    void *ctx, struct platepack_status *st)
{
	double vol = grains_volume(d);
	long step;

	st->stage = stage;
	st->at_rest = 0;
	for (step = 1; step <= pp->max_steps; step++) {
		if (engine_forces(d))
			return -1;
		if (step % 100 == 0) {
			st->step = step;
			st->unbalanced = engine_unbalanced(d);
			st->p_ratio = wall_ratio(d, target);
			st->phi = vol / ((d->hi[0] - d->lo[0]) * (d->hi[1] - d->lo[1]) * (d->hi[2] - d->lo[2]));
			st->z = (2.0 * d->ninter - d->nwall) / d->n;	/* packinfo's coordination: walls counted once */
			st->elements = d->ninter ? (double)d->nelem / d->ninter : 0;
			st->at_rest = fabs(st->p_ratio - 1) < 0.05 && st->unbalanced < pp->rest_tol;
			if (fn && step % 1000 == 0)
				fn(st, ctx);
			if (st->at_rest)
				return 0;
		}
		engine_integrate(d);
		dem_servo(d->lo, d->hi, d->wallf, target, pp->rate, d->periodic, d->x, d->n);
	}
	msg_seterr("the plates did not come to rest in %ld steps (stage %d: stress/target %.3g, unbalanced %.3g)",
	    pp->max_steps, stage, st->p_ratio, st->unbalanced);
	return -1;
}

int
platepack_make(struct pack *p, const struct platepack_params *pp, gsl_rng *rng, platepack_progress_fn fn, void *ctx,
    struct platepack_status *st)
{
	struct engine d;
	double target;
	int status = -1;

	memset(st, 0, sizeof *st);
	if (!p->q || !p->side) {
		msg_seterr("platepack: the pack has no shape columns");
		return -1;
	}
	place_on_grid(p, pp->spacing, pp->jitter, rng);
	if (engine_init(&d, p, &pp->dyn))
		return -1;
	target = pp->sigma0 * d.u_len / d.u_force * d.u_len;	/* stress unit: k_n / r0 */
	st->kappa = 1 / target;	/* r0 = 1, k_n = 1 */
	st->inertial = pp->rate / d.dt * sqrt(1 / target);
	if (platepack_settle(&d, pp, target, 1, fn, ctx, st))
		goto out;
	if (pp->periodic[0] || pp->periodic[1] || pp->periodic[2]) {
		if (engine_make_periodic(&d, pp->periodic) || platepack_settle(&d, pp, target, 2, fn, ctx, st))
			goto out;
	}
	engine_wrap(&d);
	if (engine_write_back(&d, p))
		goto out;
	status = 0;
out:
	engine_free(&d);
	return status;
}
