/* SPDX-License-Identifier: GPL-3.0-or-later */
/* dem: packgen's loose sphere packs by explicit DEM compaction (see dem.h), on the engine of
 * every shape (engine.h): placement, the compaction schedule and the rest criterion here;
 * the forces, the integration and the walls there. */
#include "dem/dem.h"
#include "dem/engine.h"
#include "dem/servo.h"
#include "contact/cell.h"
#include "contact/contacts.h"
#include "contact/hertz.h"
#include "base/msg.h"
#include "base/lanes.h"
#include "base/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The contact law of the settling: Hertz-Mindlin's DEM force (law.h: tangential spring
 * 2(1-nu)/(2-nu) = 0.889 of the normal stiffness at nu = 0.2, viscous damping ratio 0.3),
 * in the law's DEM units (its dem_units: E* = 1 between two mean grains) with rigid walls
 * (settle_units), and the settling's friction coefficient dem_params.mu for pairs and walls
 * alike. */
#define DEM_LAW (&contact_law_hertz_mindlin)

/* What the compaction keeps beside the engine: the largest radius, the unloading stage,
 * the servo's rate, the time step's safety factor, a cell grid for placement and sorting. */
struct dem {
	struct engine e;
	double rmax, dt_safety, rate;
	int unloading;
	struct cell_grid grid;
};

/* The time step over sqrt(m_eff / k) of the stiffest likely contact.  The settling is for
 * geometry only, so the step is as long as the integration stays stable with margin:
 * at 2740 grains (seed 1) 1.2 was stable and 1.6 was not; half of the largest stable
 * value is taken.  The step count it saves is the creep after unloading, which runs in
 * physical time: 0.2 took 101300 steps at 2740 grains and 123200 at 1e4,
 * 0.6 takes 39400 and 54700, with the same porosity, coordination and grains under 4 to
 * within the scatter between seeds (bench/packgen-scaling.md).  Masses scaled so that every
 * size has the same m/k (m ~ sqrt(r)) would save 2.4x in steps at 0.9, but diverge at 1.0:
 * at half their limit they save 1.3x, so the real masses stay. */
#define DEM_DT_SAFETY 0.6

void
dem_params_default(struct dem_params *dp)
{
	dp->mu = 0.3;
	dp->overlap = 1e-4;
	dp->damping = 0.7;
	dp->phi0 = 0.3;
	dp->aspect[0] = dp->aspect[1] = dp->aspect[2] = 1;
	dp->rest_tol = 2e-2;
	dp->rate = 2e-5;
	dp->dt_safety = DEM_DT_SAFETY;
	dp->viscous = 0;
	dp->preload = 200;
	dp->max_steps = 2000000;
	dp->pair_lanes = 1;
}

/* Random sequential placement without overlap, largest grains first. */
static int
place_random(struct dem *d, gsl_rng *rng, const double *rs, size_t *order)
{
	struct cell_grid *g = &d->grid;
	double edge = 2 * d->rmax, lo[3], inv[3];
	int nc[3], a;
	size_t ncells = 1, k, *head, *next;

	for (a = 0; a < 3; a++) {
		double len = d->e.hi[a] - d->e.lo[a];
		nc[a] = (int)fmax(1, fmin(1024, floor(len / edge)));
		lo[a] = d->e.lo[a];
		inv[a] = nc[a] / len;
		ncells *= (size_t)nc[a];
	}
	(void)g;
	head = malloc(ncells * sizeof *head);
	next = malloc(d->e.n * sizeof *next);
	if (!head || !next) {
		free(head), free(next);
		msg_seterr("out of memory placing grains");
		return -1;
	}
	for (k = 0; k < ncells; k++)
		head[k] = (size_t)-1;
	for (k = 0; k < d->e.n; k++) {
		size_t i = order[k];
		double ri = rs[i];
		long tries;

		for (tries = 0; tries < 100000; tries++) {
			double y[3];
			int c[3], ok = 1, dz, dy, dx;

			for (a = 0; a < 3; a++) {
				y[a] = d->e.lo[a] + ri + (d->e.hi[a] - d->e.lo[a] - 2 * ri) * gsl_rng_uniform(rng);
				c[a] = (int)floor((y[a] - lo[a]) * inv[a]);
				c[a] = c[a] < 0 ? 0 : c[a] >= nc[a] ? nc[a] - 1 : c[a];
			}
			for (dz = -1; dz <= 1 && ok; dz++)
				for (dy = -1; dy <= 1 && ok; dy++)
					for (dx = -1; dx <= 1 && ok; dx++) {
						int ox = c[0] + dx, oy = c[1] + dy, oz = c[2] + dz;
						size_t q;
						if (ox < 0 || oy < 0 || oz < 0 || ox >= nc[0] || oy >= nc[1] || oz >= nc[2])
							continue;
						for (q = head[((size_t)oz * nc[1] + oy) * nc[0] + ox]; q != (size_t)-1; q = next[q]) {
							double e0 = y[0] - d->e.x[3 * q], e1 = y[1] - d->e.x[3 * q + 1],
							    e2 = y[2] - d->e.x[3 * q + 2], s = ri + rs[q];
							if (e0 * e0 + e1 * e1 + e2 * e2 < s * s) {
								ok = 0;
								break;
							}
						}
					}
			if (ok) {
				size_t cell = ((size_t)c[2] * nc[1] + c[1]) * nc[0] + c[0];
				memcpy(d->e.x + 3 * i, y, sizeof y);
				next[i] = head[cell];
				head[cell] = i;
				break;
			}
		}
		if (tries == 100000) {
			free(head), free(next);
			msg_seterr("cannot place grain %zu of %zu at random: lower the initial packing fraction", k + 1, d->e.n);
			return -1;
		}
	}
	free(head), free(next);
	return 0;
}

/* Renumber the grains in cell order, so that neighbours sit close in memory (a 3-4x
 * speed-up at 1e5 grains); perm[k] receives the caller's index of internal grain k. */
static int
sort_spatially(struct dem *d, size_t *perm)
{
	size_t n = d->e.n, k, *tmp = malloc(n * sizeof *tmp);
	double *buf = malloc(3 * n * sizeof *buf);
	int a;

	if (!tmp || !buf || cell_build(&d->grid, d->e.x, n, d->e.lo, d->e.hi, 2 * d->rmax, NULL)) {
		free(tmp), free(buf);
		msg_seterr("out of memory sorting grains");
		return -1;
	}
	memcpy(perm, d->grid.idx, n * sizeof *perm);
	memcpy(buf, d->e.x, 3 * n * sizeof *buf);
	for (k = 0; k < n; k++)
		for (a = 0; a < 3; a++)
			d->e.x[3 * k + a] = buf[3 * perm[k] + a];
#define PERMUTE(arr)                                  \
	do {                                          \
		memcpy(buf, arr, n * sizeof *buf);   \
		for (k = 0; k < n; k++)               \
			arr[k] = buf[perm[k]];        \
	} while (0)
	PERMUTE(d->e.r);
	PERMUTE(d->e.m);
#undef PERMUTE
	free(tmp), free(buf);
	return 0;
}

struct overlap_acc {
	const double *r;
	double mo;
	size_t nc;
};

static int
on_overlap(const struct contact *c, void *va)
{
	struct overlap_acc *o = va;

	if (PACK_IS_WALL(c->j)) {
		o->mo = fmax(o->mo, c->h / o->r[c->i]);
		o->nc++;
	} else {
		o->mo = fmax(o->mo, c->h / fmin(o->r[c->i], o->r[c->j]));
		o->nc += 2;
	}
	return 0;
}

/* Largest overlap over the smaller radius, and the coordination (contacts per grain). */
static double
max_overlap(const struct dem *d, double *coord)
{
	struct overlap_acc o = {d->e.r, 0, 0};

	contact_foreach(&d->e.ce, d->e.x, CONTACT_TOUCHING, on_overlap, &o);
	*coord = (double)o.nc / d->e.n;
	return o.mo;
}

/* Time step from the stiffest likely contact: the two smallest grains (R* = rmin / 2), or
 * the smallest grain on a wall (R* = rmin), at overlap h rmin (h relative to the radius).
 * The law's stiffest (Hertz's 2 E* sqrt(R* overlap)) with R* overlap as (R* h) rmin, the
 * product in the order of the steps packgen has always taken. */
static void
dt_for_overlap(struct dem *d, double mmin, double rmin, double h)
{
	const struct contact_law *law = d->e.law;
	double k = fmax(law->stiffest(law, &d->e.lp_grain, 0.5 * rmin * h, rmin),
	    law->stiffest(law, &d->e.lp_wall, rmin * h, rmin));

	d->e.dt = d->dt_safety * sqrt(0.5 * mmin / k);
}

/* The settling's pair constants from the law's DEM units (grain-grain E* 1): the walls rigid
 * whatever the pack's wall material, since the settling makes geometry only and its stresses
 * only set the overlap scale (for rigid walls Hertz's wall E* is 2 to the bit: 1/c over
 * 1/(2c)). */
static void
settle_units(struct dem *d, const struct pack *p)
{
	struct pack rigid = *p;	/* a view of p's materials, its walls rigid */

	rigid.wall_E = 0;
	d->e.law = DEM_LAW;
	DEM_LAW->dem_units(DEM_LAW, &rigid, 1, 1, &d->e.lp_grain, &d->e.lp_wall);
}

/* Scaled copies of the grains (mean radius 1, density 1), in the order of placement:
 * largest first, so random placement rarely fails (a counting sort of the radii into 256
 * bins, descending). */
static int
dem_setup(struct dem *d, const struct pack *p, size_t *order, double *rmean, double *vol, double *mmin, double *rmin)
{
	size_t n = p->n, i, bins[257] = {0}, *tmp;

	if (engine_alloc(&d->e, n))
		return -1;
	cell_init(&d->grid);
	if (!(tmp = malloc(n * sizeof *tmp))) {
		msg_seterr("out of memory for %zu grains", n);
		return -1;
	}
	*rmean = *vol = 0;
	*mmin = *rmin = INFINITY;
	for (i = 0; i < n; i++)
		*rmean += p->r[i];
	*rmean /= n;
	for (i = 0; i < n; i++) {
		d->e.r[i] = p->r[i] / *rmean;
		d->e.m[i] = 4.0 / 3.0 * M_PI * d->e.r[i] * d->e.r[i] * d->e.r[i];
		*vol += d->e.m[i];
		d->rmax = fmax(d->rmax, d->e.r[i]);
		*rmin = fmin(*rmin, d->e.r[i]);
		*mmin = fmin(*mmin, d->e.m[i]);
		order[i] = i;
	}
	for (i = 0; i < n; i++)
		bins[255 - (int)fmin(255, floor((d->e.r[i] - *rmin) / (d->rmax - *rmin + 1e-300) * 255.999)) + 1]++;
	for (i = 0; i < 256; i++)
		bins[i + 1] += bins[i];
	for (i = 0; i < n; i++)
		tmp[bins[255 - (int)fmin(255, floor((d->e.r[i] - *rmin) / (d->rmax - *rmin + 1e-300) * 255.999))]++] = i;
	memcpy(order, tmp, n * sizeof *order);
	free(tmp);
	return 0;
}

/* The wall stress over the target, at a check of the settling. */
static double
stress_ratio(const struct dem *d, double ptarget)
{
	double s = 0;
	int a;

	for (a = 0; a < 3; a++)
		s += pack_wall_stress(d->e.lo, d->e.hi, a, d->e.wallf[2 * a] + d->e.wallf[2 * a + 1]);
	return s / 3 / ptarget;
}

/* Settle under the servo: jam at the preload, then unload to the final stress and rest. */
static int
dem_settle(struct dem *d, const struct dem_params *dp, double pfinal, double vol, double mmin, double rmin,
    dem_progress_fn fn, void *ctx, struct dem_status *st)
{
	double ptarget = pfinal * dp->preload;
	long step;

	dt_for_overlap(d, mmin, rmin, fmax(dp->overlap, 1e-6) * pow(dp->preload, 2.0 / 3.0) * 10);
	for (step = 1; step <= dp->max_steps; step++) {
		if (engine_forces(&d->e))
			return -1;
		if (step % 100 == 0 || step == dp->max_steps) {
			double coord, ub = engine_unbalanced(&d->e);
			st->step = step;
			st->unbalanced = ub;
			st->max_overlap = max_overlap(d, &coord);
			st->coordination = coord;
			st->phi = vol / ((d->e.hi[0] - d->e.lo[0]) * (d->e.hi[1] - d->e.lo[1]) * (d->e.hi[2] - d->e.lo[2]));
			st->p_ratio = stress_ratio(d, ptarget);
			st->stage = ptarget > pfinal ? 1 : 2;
			/* the stresses only set the overlap scale: within a factor of 1.25 of the preload
			 * and of 2 of the final target is close enough; rest is what matters */
			st->at_rest = fabs(log(st->p_ratio)) < log(ptarget > pfinal ? 1.25 : 2.0) && ub < dp->rest_tol;
			if (fn && step % 1000 == 0)
				fn(st, ctx);
			/* an overlap of half a radius is far outside anything the servo allows: the
			 * integration has gone unstable (a step too long for the stiffest contacts);
			 * stop instead of stepping NaNs to max_steps */
			if (!(st->max_overlap < 0.5) || !isfinite(st->p_ratio)) {
				msg_seterr("the DEM diverged at step %ld (largest overlap/r %.3g, stress/target %.3g): "
				    "the time step is too long for these grains", step, st->max_overlap, st->p_ratio);
				return -1;
			}
			if (st->at_rest && ptarget > pfinal) {
				ptarget = pfinal;	/* jammed at the preload: now unload */
				d->unloading = 1;
				st->at_rest = 0;
			} else if (st->at_rest) {
				break;
			}
			dt_for_overlap(d, mmin, rmin, fmax(st->max_overlap, dp->overlap));
		}
		engine_integrate(&d->e);
		dem_servo(d->e.lo, d->e.hi, d->e.wallf, ptarget, d->unloading ? d->rate * 0.05 : d->rate, NULL, d->e.x, d->e.n);
	}
	if (!st->at_rest) {
		msg_seterr("the pack did not come to rest in %ld steps (stress/target %.3g, unbalanced %.3g)",
		    dp->max_steps, st->p_ratio, st->unbalanced);
		return -1;
	}
	return 0;
}

/* The pack takes the settled positions, in real units, and the spatial order too (ids 1..N
 * along it): every later stage then walks memory in the order neighbours are met.  Radii
 * and moduli were drawn independently, so renumbering loses nothing. */
static int
dem_write_back(const struct dem *d, struct pack *p, const size_t *order, double rmean)
{
	size_t n = p->n, i;
	double *tmp = malloc(n * sizeof *tmp);
	double *arrs[4] = {p->r, p->E, p->nu, p->rho};
	int q, a;

	if (!tmp) {
		msg_seterr("out of memory");
		return -1;
	}
	for (q = 0; q < 4; q++) {
		memcpy(tmp, arrs[q], n * sizeof *tmp);
		for (i = 0; i < n; i++)
			arrs[q][i] = tmp[order[i]];
	}
	/* a pack with shape columns keeps each grain's side and orientation with it (the
	 * spheres packgen makes have none; this is for any caller that gives some) */
	if (p->has_shapes) {
		memcpy(tmp, p->side, n * sizeof *tmp);
		for (i = 0; i < n; i++)
			p->side[i] = tmp[order[i]];
		free(tmp);
		if (!(tmp = malloc(4 * n * sizeof *tmp))) {
			msg_seterr("out of memory");
			return -1;
		}
		memcpy(tmp, p->q, 4 * n * sizeof *tmp);
		for (i = 0; i < n; i++)
			memcpy(p->q + 4 * i, tmp + 4 * order[i], 4 * sizeof *tmp);
		for (i = 0; i < n; i++)	/* the kinds, through tmp's first n doubles */
			tmp[i] = p->shape[order[i]];
		for (i = 0; i < n; i++)
			p->shape[i] = (unsigned char)tmp[i];
	}
	if (p->has_phase) {	/* the phase tag too (packgen --hydrate-volume tags before settling) */
		unsigned char *ph = malloc(n);

		if (!ph) {
			free(tmp);
			msg_seterr("out of memory");
			return -1;
		}
		memcpy(ph, p->phase, n);
		for (i = 0; i < n; i++)
			p->phase[i] = ph[order[i]];
		free(ph);
	}
	free(tmp);
	for (i = 0; i < n; i++) {
		p->id[i] = (long)i + 1;
		for (a = 0; a < 3; a++)
			p->x[3 * i + a] = d->e.x[3 * i + a] * rmean;
	}
	for (a = 0; a < 3; a++) {
		p->box[a] = d->e.lo[a] * rmean;
		p->box[a + 3] = d->e.hi[a] * rmean;
	}
	return 0;
}

int
dem_loose_pack(struct pack *p, const struct dem_params *dp, gsl_rng *rng, dem_progress_fn fn, void *ctx,
    struct dem_status *st)
{
	struct dem d;
	size_t n = p->n, i, *order = NULL;
	double rmean, vol, L0, pfinal, mmin, rmin;
	int a, status = -1;

	memset(&d, 0, sizeof d);
	memset(st, 0, sizeof *st);
	if (n == 0) {
		msg_seterr("no grains to place");
		return -1;
	}
	order = malloc(n * sizeof *order);
	if (!order) {
		msg_seterr("out of memory for %zu grains", n);
		return -1;
	}
	if (dem_setup(&d, p, order, &rmean, &vol, &mmin, &rmin))
		goto out;
	L0 = cbrt(vol / dp->phi0 / (dp->aspect[0] * dp->aspect[1] * dp->aspect[2]));
	for (a = 0; a < 3; a++) {
		d.e.lo[a] = 0;
		d.e.hi[a] = L0 * dp->aspect[a];
	}
	if (place_random(&d, rng, d.e.r, order) || sort_spatially(&d, order))
		goto out;
	/* the engine's spheres (their frames the lab's), law and coefficients */
	for (i = 0; i < n; i++) {
		d.e.rb[i] = d.e.r[i];
		d.e.J[3 * i] = d.e.J[3 * i + 1] = d.e.J[3 * i + 2] = 0.4 * d.e.m[i] * d.e.r[i] * d.e.r[i];
	}
	settle_units(&d, p);
	d.e.mu = d.e.wall_mu = d.e.lp_grain.mu = d.e.lp_wall.mu = dp->mu;
	d.e.zeta = DEM_LAW->zeta;
	d.e.kt_ratio = DEM_LAW->kt_ratio;
	d.e.damping = dp->damping;
	d.e.viscous = dp->viscous;
	d.e.pair_lanes = dp->pair_lanes && LANES_OK;
	d.e.u_len = rmean;
	d.rate = dp->rate;
	d.dt_safety = dp->dt_safety;
	if (engine_start(&d.e, 0.3 * rmin))
		goto out;
	/* Target stress from the mean overlap: Love-Weber p = Z phi <F> / (4 pi r^2) with
	 * Z ~ 4.5 and phi ~ 0.6 for a loose frictional pack and <F> the Hertz force at that
	 * overlap between two mean grains (E* = 1, R* = 1/2).  Such a small stress cannot be
	 * told apart from the kinetic and drag stresses of a compacting gas, so the pack is
	 * first jammed at a stress 'preload' times larger (mean overlap ~ 30x) and then
	 * unloaded to the target: unloading is nearly elastic and the frictional contact
	 * network, hence the loose structure, survives it. */
	pfinal = 4.5 * 0.6 * (hertz_coef(d.e.lp_grain.Es, sqrt(0.5)) * pow(dp->overlap, 1.5)) / (4 * M_PI);
	if (dem_settle(&d, dp, pfinal, vol, mmin, rmin, fn, ctx, st) || dem_write_back(&d, p, order, rmean))
		goto out;
	status = 0;
out:
	free(order);
	engine_free(&d.e);
	cell_free(&d.grid);
	return status;
}
