/* SPDX-License-Identifier: GPL-3.0-or-later */
/* dem: explicit DEM compaction for loose packs (see dem.h). */
#include "dem/dem.h"
#include "dem/servo.h"
#include "contact/cell.h"
#include "contact/contacts.h"
#include "contact/hertz.h"
#include "base/msg.h"
#include "base/lanes.h"
#include "base/par.h"
#include "base/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define E_GRAIN 1.0			/* the scaled grain-grain E* (dem.h) */
#define E_WALL 2.0			/* grain-wall E* over grain-grain E* for rigid walls */
/* The contact law of the settling: Hertz-Mindlin's DEM force (law.h: tangential spring
 * 2(1-nu)/(2-nu) = 0.889 of the normal stiffness at nu = 0.2, viscous damping ratio 0.3),
 * with the scaled E* of dem.h and the settling's friction coefficient dem_params.mu for
 * pairs and walls alike, called inline (hertz.h: hertz_dem_force, and hertz_dem_force2 on
 * two pairs at once). */
#define DEM_LAW (&contact_law_hertz_mindlin)

struct dem {
	size_t n;
	double *x, *v, *w, *f, *t, *r, *m, *I;
	double *mob, mob_dt;	/* dt / m and dt / I per grain (interleaved), made for the step mob_dt */
	double lo[3], hi[3];
	double rmax, skin, dt, dt_safety, mu, damping, rate, viscous;
	int unloading;		/* slow, quasi-static expansion towards the final stress */
	int pair_lanes;		/* dem_params.pair_lanes (and LANES_OK) */
	/* the contacts, with the tangential spring of every listed pair and grain-wall pair
	 * as their history, carried over a rebuild of the list */
	struct contact_enum ce;
	double wallf[NWALLS];
	struct cell_grid grid;
	size_t ncontacts;
	double sum_cf;			/* sum of contact force magnitudes */
	/* the threads' force loop (forces()): block sums, and the records of the pairs that
	 * cross from one thread's grains to a later one's, made for x_team threads on the list
	 * of rebuild x_builds */
	struct dem_block *blk;
	size_t blk_cap;
	size_t *xslot, *xin_first;
	struct dem_xrec *xrec;
	long stamp, x_builds;
	size_t x_team;
};

static void
dem_free(struct dem *d)
{
	free(d->x), free(d->v), free(d->w), free(d->f), free(d->t), free(d->r), free(d->m), free(d->I), free(d->mob);
	free(d->blk), free(d->xslot), free(d->xin_first), free(d->xrec);
	contact_enum_free(&d->ce);
	cell_free(&d->grid);
}

/* The time step over sqrt(m_eff / k) of the stiffest likely contact.  The settling is for
 * geometry only, so the step is as long as the integration stays stable with margin:
 * at 2740 grains (seed 1) 1.2 was stable and 1.6 was not; half of the largest stable
 * value is taken.  The step count it saves is the creep after unloading, which runs in
 * physical time: 0.2 (until 2026-12) took 101300 steps at 2740 grains and 123200 at 1e4,
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
		double len = d->hi[a] - d->lo[a];
		nc[a] = (int)fmax(1, fmin(1024, floor(len / edge)));
		lo[a] = d->lo[a];
		inv[a] = nc[a] / len;
		ncells *= (size_t)nc[a];
	}
	(void)g;
	head = malloc(ncells * sizeof *head);
	next = malloc(d->n * sizeof *next);
	if (!head || !next) {
		free(head), free(next);
		msg_seterr("out of memory placing grains");
		return -1;
	}
	for (k = 0; k < ncells; k++)
		head[k] = (size_t)-1;
	for (k = 0; k < d->n; k++) {
		size_t i = order[k];
		double ri = rs[i];
		long tries;

		for (tries = 0; tries < 100000; tries++) {
			double y[3];
			int c[3], ok = 1, dz, dy, dx;

			for (a = 0; a < 3; a++) {
				y[a] = d->lo[a] + ri + (d->hi[a] - d->lo[a] - 2 * ri) * gsl_rng_uniform(rng);
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
							double e0 = y[0] - d->x[3 * q], e1 = y[1] - d->x[3 * q + 1],
							    e2 = y[2] - d->x[3 * q + 2], s = ri + rs[q];
							if (e0 * e0 + e1 * e1 + e2 * e2 < s * s) {
								ok = 0;
								break;
							}
						}
					}
			if (ok) {
				size_t cell = ((size_t)c[2] * nc[1] + c[1]) * nc[0] + c[0];
				memcpy(d->x + 3 * i, y, sizeof y);
				next[i] = head[cell];
				head[cell] = i;
				break;
			}
		}
		if (tries == 100000) {
			free(head), free(next);
			msg_seterr("cannot place grain %zu of %zu at random: lower the initial packing fraction", k + 1, d->n);
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
	size_t n = d->n, k, *tmp = malloc(n * sizeof *tmp);
	double *buf = malloc(3 * n * sizeof *buf);
	int a;

	if (!tmp || !buf || cell_build(&d->grid, d->x, n, d->lo, d->hi, 2 * d->rmax, NULL)) {
		free(tmp), free(buf);
		msg_seterr("out of memory sorting grains");
		return -1;
	}
	memcpy(perm, d->grid.idx, n * sizeof *perm);
	memcpy(buf, d->x, 3 * n * sizeof *buf);
	for (k = 0; k < n; k++)
		for (a = 0; a < 3; a++)
			d->x[3 * k + a] = buf[3 * perm[k] + a];
#define PERMUTE(arr)                                  \
	do {                                          \
		memcpy(buf, arr, n * sizeof *buf);   \
		for (k = 0; k < n; k++)               \
			arr[k] = buf[perm[k]];        \
	} while (0)
	PERMUTE(d->r);
	PERMUTE(d->m);
	PERMUTE(d->I);
#undef PERMUTE
	free(tmp), free(buf);
	return 0;
}

/* The force F (on i) and the cross product n x ft (whose torque on i is -r_i n x ft, on j
 * -r_j n x ft) of one contact, from the law's DEM force at the contact point's relative
 * velocity; the normal force magnitude is returned, its elastic part goes into *fel.  The
 * contact's tangential spring (its history slot) is advanced. */
CONTACT_INLINE double
contact_force(const struct dem *d, const struct contact *c, double F[3], double cr[3], double *fel)
{
	size_t i = c->i;
	int wall = PACK_IS_WALL(c->j), a;
	double ri = d->r[i], wr[3], ca[3], cb[3] = {0, 0, 0}, ft[3], fn;
	struct law_pair lp;
	struct law_dem_in in;

	contact_normal(c, in.n);
	lp.Es = wall ? E_WALL : E_GRAIN;
	lp.Rs = contact_Rstar(c, d->r);
	lp.mu = d->mu;
	in.h = c->h;
	in.dt = d->dt;
	for (a = 0; a < 3; a++)
		wr[a] = -ri * in.n[a];
	vec3_cross(d->w + 3 * i, wr, ca);
	if (!wall) {
		size_t j = (size_t)c->j;
		in.meff = d->m[i] * d->m[j] / (d->m[i] + d->m[j]);
		for (a = 0; a < 3; a++)
			wr[a] = d->r[j] * in.n[a];
		vec3_cross(d->w + 3 * j, wr, cb);
		for (a = 0; a < 3; a++)
			in.vr[a] = d->v[3 * i + a] + ca[a] - d->v[3 * j + a] - cb[a];
	} else {
		in.meff = d->m[i];
		for (a = 0; a < 3; a++)
			in.vr[a] = d->v[3 * i + a] + ca[a];
	}
	fn = hertz_dem_force(DEM_LAW->zeta, DEM_LAW->kt_ratio, &lp, &in, c->hist, ft, fel);
	for (a = 0; a < 3; a++)
		F[a] = fn * in.n[a] + ft[a];
	vec3_cross(in.n, ft, cr);
	return fn;
}

/* One thread's sums over a block of rows (grains), added in block order after the walk. */
struct dem_block {
	double sum_cf;
	double wallf[NWALLS];
	size_t nc;
};

/* What the walk of one block carries: the grains from jend on are a later thread's, whose
 * share of a pair's force that thread gathers (the pair's record, dem.xrec); and a touching
 * pair waiting for a second, with which it shares the lanes of contact_force2. */
struct dem_walk {
	struct dem *d;
	size_t jend;
	struct dem_block b;
	int npend;
	struct contact pend;
};

#if LANES_OK
/* contact_force of two grain-grain contacts at once, each in one lane of the same
 * arithmetic (lanes.h: the same bytes as contact_force, tests/unit/test_dem.c checks it).
 * A pair's force costs six square roots and five divisions, in one dependent chain; the
 * divider does two lanes in the time of one, and the two chains overlap. */
CONTACT_INLINE void
contact_force2(const struct dem *d, const struct contact *A, const struct contact *B, double F[2][3], double cr[2][3])
{
	const struct contact_law *law = DEM_LAW;
	size_t i0 = A->i, i1 = B->i, j0 = (size_t)A->j, j1 = (size_t)B->j;
	const double *v = d->v, *w = d->w;
	double *hA = A->hist, *hB = B->hist;
	v2d dd = {A->d, B->d}, h = {A->h, B->h}, ri = {d->r[i0], d->r[i1]}, rj = {d->r[j0], d->r[j1]};
	v2d mi = {d->m[i0], d->m[i1]}, mj = {d->m[j0], d->m[j1]};
	v2d n[3], wi[3], wj[3], wr[3], ca[3], cb[3], vr[3], xi[3], ft[3], Fv[3], cv[3];
	v2d Rs, meff, fn;
	int a;

	for (a = 0; a < 3; a++) {
		n[a] = (v2d){A->dx[a], B->dx[a]} / dd;
		wi[a] = (v2d){w[3 * i0 + a], w[3 * i1 + a]};
		wj[a] = (v2d){w[3 * j0 + a], w[3 * j1 + a]};
		xi[a] = (v2d){hA[a], hB[a]};
	}
	Rs = hertz_Rstar2(ri, rj);
	for (a = 0; a < 3; a++)
		wr[a] = -ri * n[a];
	V2_CROSS(wi, wr, ca);
	meff = mi * mj / (mi + mj);
	for (a = 0; a < 3; a++)
		wr[a] = rj * n[a];
	V2_CROSS(wj, wr, cb);
	for (a = 0; a < 3; a++)
		vr[a] = (v2d){v[3 * i0 + a], v[3 * i1 + a]} + ca[a] - (v2d){v[3 * j0 + a], v[3 * j1 + a]} - cb[a];
	/* hertz_dem_force's twin, E* = E_GRAIN */
	fn = hertz_dem_force2(law->zeta, law->kt_ratio, d->mu, E_GRAIN, Rs, h, n, vr, meff, d->dt, xi, ft);
	for (a = 0; a < 3; a++)
		Fv[a] = fn * n[a] + ft[a];
	V2_CROSS(n, ft, cv);
	for (a = 0; a < 3; a++) {
		hA[a] = xi[a][0], hB[a] = xi[a][1];
		F[0][a] = Fv[a][0], F[1][a] = Fv[a][1];
		cr[0][a] = cv[a][0], cr[1][a] = cv[a][1];
	}
}
#endif

/* A pair whose j is a later thread's: its force, computed before the walk by its row's
 * thread (pass 1 of forces()), for i to add and j's thread to gather. */
struct dem_xrec {
	double F[3], cr[3];
	long stamp;		/* the forces() call that wrote it: older, the pair was apart */
};

CONTACT_INLINE void
add_to_i(struct dem *d, size_t i, const double F[3], const double cr[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		d->f[3 * i + a] += F[a];
		d->t[3 * i + a] -= d->r[i] * cr[a];
	}
}

CONTACT_INLINE void
add_to_j(struct dem *d, size_t j, const double F[3], const double cr[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		d->f[3 * j + a] -= F[a];
		d->t[3 * j + a] -= d->r[j] * cr[a];
	}
}

/* A pair's force F in the block's count and force sum. */
CONTACT_INLINE void
pair_sums(struct dem_walk *w, const double F[3])
{
	w->b.nc++;
	w->b.sum_cf += sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
}

/* A computed pair's force into both grains and the block's sums. */
CONTACT_INLINE void
pair_add(struct dem_walk *w, const struct contact *c, const double F[3], const double cr[3])
{
	add_to_i(w->d, c->i, F, cr);
	add_to_j(w->d, (size_t)c->j, F, cr);
	pair_sums(w, F);
}

/* The waiting pair alone, before anything else is added (so every grain's sum keeps the
 * walk's order). */
CONTACT_INLINE void
pend_flush(struct dem_walk *w)
{
	double F[3], cr[3], fel;

	if (!w->npend)
		return;
	contact_force(w->d, &w->pend, F, cr, &fel);
	pair_add(w, &w->pend, F, cr);
	w->npend = 0;
}

CONTACT_INLINE int
on_pair(const struct contact *c, void *vw)
{
	struct dem_walk *w = vw;
	struct dem *d = w->d;
	size_t j = (size_t)c->j;

#if LANES_OK
	if (j < w->jend && d->pair_lanes) {
		double F2[2][3], cr2[2][3];

		if (!w->npend) {	/* wait for a second pair */
			/* what contact_force reads, not the whole record */
			w->pend.i = c->i, w->pend.j = c->j, w->pend.hist = c->hist;
			w->pend.dx[0] = c->dx[0], w->pend.dx[1] = c->dx[1], w->pend.dx[2] = c->dx[2];
			w->pend.d = c->d, w->pend.h = c->h;
			w->npend = 1;
			return 0;
		}
		contact_force2(d, &w->pend, c, F2, cr2);
		pair_add(w, &w->pend, F2[0], cr2[0]);
		pair_add(w, c, F2[1], cr2[1]);
		w->npend = 0;
		return 0;
	}
#endif
	if (j < w->jend) {
		double F[3], cr[3], fel;

		contact_force(d, c, F, cr, &fel);
		pair_add(w, c, F, cr);
	} else {
		const struct dem_xrec *x = &d->xrec[d->xslot[contact_pair_index(&d->ce, c)]];

		pend_flush(w);
		add_to_i(d, c->i, x->F, x->cr);
		pair_sums(w, x->F);
	}
	return 0;
}

CONTACT_INLINE int
on_wall(const struct contact *c, void *vw)
{
	struct dem_walk *w = vw;
	double F[3], cr[3], fel, fn;

	pend_flush(w);
	fn = contact_force(w->d, c, F, cr, &fel);
	w->b.wallf[PACK_WALL_INDEX(c->j)] += fel;	/* the servo reads the elastic wall force */
	add_to_i(w->d, c->i, F, cr);
	w->b.nc++;
	w->b.sum_cf += fn;
	return 0;
}

/* Pass 1: the pairs of this thread's rows whose j is a later thread's. */
CONTACT_INLINE int
on_cross_pair(const struct contact *c, void *vw)
{
	struct dem_walk *w = vw;
	struct dem_xrec *x;
	double fel;

	if ((size_t)c->j < w->jend)
		return 0;
	x = &w->d->xrec[w->d->xslot[contact_pair_index(&w->d->ce, c)]];
	contact_force(w->d, c, x->F, x->cr, &fel);
	x->stamp = w->d->stamp;
	return 0;
}

CONTACT_INLINE int
on_no_wall(const struct contact *c, void *vw)
{
	(void)c, (void)vw;
	return 0;
}

/* The record slots of the pairs that cross from one thread's grains to a later one's, for
 * the team of T threads on the current list: xslot[k] for list entry k, and the slots
 * gathered by grain j, xin_first[j] .. xin_first[j + 1] - 1, in ascending i (rows are walked
 * in ascending i), which is the order in which the one-pass walk scatters into j. */
static int
cross_slots(struct dem *d, size_t T)
{
	const struct nlist *nl = &d->ce.nl;
	size_t n = d->n, bl = par_block(n), nb = (n + bl - 1) / bl, t, i, k, *fill;

	if (d->xslot && d->x_builds == d->ce.rebuilds && d->x_team == T)
		return 0;
	free(d->xslot), free(d->xin_first), free(d->xrec);
	d->xrec = NULL;
	d->xslot = malloc((nl->npairs + 1) * sizeof *d->xslot);
	d->xin_first = calloc(n + 1, sizeof *d->xin_first);
	fill = calloc(n + 1, sizeof *fill);
	if (!d->xslot || !d->xin_first || !fill)
		goto oom;
	for (t = 0; t < T; t++) {
		size_t g0 = nb * t / T * bl, g1 = nb * (t + 1) / T * bl;
		g0 = g0 < n ? g0 : n, g1 = g1 < n ? g1 : n;
		for (i = g0; i < g1; i++)
			for (k = nl->first[i]; k < nl->first[i + 1]; k++)
				if (nl->nbr[k] >= g1)
					d->xin_first[nl->nbr[k] + 1]++;
	}
	for (i = 0; i < n; i++)
		d->xin_first[i + 1] += d->xin_first[i];
	if (!(d->xrec = malloc((d->xin_first[n] + 1) * sizeof *d->xrec)))
		goto oom;
	for (k = 0; k <= d->xin_first[n]; k++)
		d->xrec[k].stamp = -1;
	for (t = 0; t < T; t++) {
		size_t g0 = nb * t / T * bl, g1 = nb * (t + 1) / T * bl;
		g0 = g0 < n ? g0 : n, g1 = g1 < n ? g1 : n;
		for (i = g0; i < g1; i++)
			for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
				size_t j = nl->nbr[k];
				d->xslot[k] = j >= g1 ? d->xin_first[j] + fill[j]++ : 0;
			}
	}
	free(fill);
	d->x_builds = d->ce.rebuilds;
	d->x_team = T;
	return 0;
oom:
	free(fill);
	free(d->xslot), free(d->xin_first), free(d->xrec);
	d->xslot = d->xin_first = NULL;
	d->xrec = NULL;
	msg_seterr("out of memory");
	return -1;
}

/* Every grain's force and torque, the walls' forces, the contact count and force sum, on
 * threads with the same bytes for any number (base/par.h).  Each thread takes a run of whole
 * blocks of grains (par_block(n), fixed by n).  A pair's force goes into both grains; where
 * j is a later thread's, the pair is computed first (pass 1, so that its tangential spring
 * advances once) and j's thread gathers it before walking its own rows.  Every grain's sum
 * then has the one-pass walk's terms in its order: the pairs (m, j) by ascending m, then
 * j's own pairs and walls.  The count and force sums are kept per block and added in block
 * order. */
static int
forces(struct dem *d)
{
	struct contact_enum *e = &d->ce;
	size_t n = d->n, bl = par_block(n), nb = (n + bl - 1) / bl, q;
	int threads = n >= PAR_MIN && par_threads() > 1, w;

	if (nb > d->blk_cap) {
		free(d->blk);
		d->blk = malloc(nb * sizeof *d->blk);
		d->blk_cap = d->blk ? nb : 0;
		if (!d->blk) {
			msg_seterr("out of memory");
			return -1;
		}
	}
	if (threads && cross_slots(d, (size_t)par_threads()))
		return -1;
	d->stamp++;
#pragma omp parallel if (threads)
	{
		size_t T = (size_t)par_team(), t = (size_t)par_tid(), b, i, s;
		size_t b0 = nb * t / T, b1 = nb * (t + 1) / T;
		size_t g0 = b0 * bl < n ? b0 * bl : n, g1 = b1 * bl < n ? b1 * bl : n;
		long calls = 0;

		if (T > 1 && t + 1 < T) {
			struct dem_walk cw = {d, g1, {0, {0}, 0}, 0, {0}};
			for (i = g0; i < g1; i++)
				if (e->nl.first[i + 1] > e->nl.first[i] && e->nl.nbr[e->nl.first[i + 1] - 1] >= g1)
					contact_foreach_row(e, d->x, i, CONTACT_TOUCHING, 0, 3, on_cross_pair, on_no_wall, &cw, &calls);
		}
		memset(d->f + 3 * g0, 0, 3 * (g1 - g0) * sizeof *d->f);
		memset(d->t + 3 * g0, 0, 3 * (g1 - g0) * sizeof *d->t);
#pragma omp barrier
		if (T > 1 && t > 0)
			for (i = g0; i < g1; i++)
				for (s = d->xin_first[i]; s < d->xin_first[i + 1]; s++)
					if (d->xrec[s].stamp == d->stamp)
						add_to_j(d, i, d->xrec[s].F, d->xrec[s].cr);
		for (b = b0; b < b1; b++) {
			struct dem_walk dw = {d, g1, {0, {0}, 0}, 0, {0}};
			size_t i1 = (b + 1) * bl < n ? (b + 1) * bl : n;

			for (i = b * bl; i < i1; i++)
				contact_foreach_row(e, d->x, i, CONTACT_TOUCHING, 0, 3, on_pair, on_wall, &dw, &calls);
			pend_flush(&dw);
			d->blk[b] = dw.b;
		}
	}
	memset(d->wallf, 0, sizeof d->wallf);
	d->ncontacts = 0;
	d->sum_cf = 0;
	for (q = 0; q < nb; q++) {
		d->ncontacts += d->blk[q].nc;
		d->sum_cf += d->blk[q].sum_cf;
		for (w = 0; w < NWALLS; w++)
			d->wallf[w] += d->blk[q].wallf[w];
	}
	return 0;
}

/* One explicit step of every grain's velocity, spin and centre, grain by grain.  The
 * mobilities dt / m and dt / I are made once per time step length (it changes at most every
 * 100 steps): two divisions per grain and step were a tenth of packgen's time, and an index
 * division per component once a fifth. */
static void
integrate(struct dem *d)
{
	size_t i, n = d->n;
	double dt = d->dt, al = d->damping, keep = 1 - d->viscous;

	if (dt != d->mob_dt) {
#pragma omp parallel for schedule(static) if (n >= PAR_MIN)
		for (i = 0; i < n; i++) {
			d->mob[2 * i] = dt / d->m[i];
			d->mob[2 * i + 1] = dt / d->I[i];
		}
		d->mob_dt = dt;
	}
#pragma omp parallel for schedule(static) if (n >= PAR_MIN)
	for (i = 0; i < n; i++) {
		double am = d->mob[2 * i], aI = d->mob[2 * i + 1];
		int a;

		for (a = 0; a < 3; a++) {
			size_t k = 3 * i + a;
			double f = d->f[k], t = d->t[k], v = d->v[k], w = d->w[k];
			/* Cundall's local damping: remove a fraction of the force that drives the motion */
			f -= al * fabs(f) * (double)((v > 0) - (v < 0));
			t -= al * fabs(t) * (double)((w > 0) - (w < 0));
			/* background viscous damping: free flight decays, so no granular gas builds up
			 * whose kinetic pressure the wall servo would mistake for a force network */
			v = v * keep + f * am;
			d->v[k] = v;
			d->w[k] = w * keep + t * aI;
			d->x[k] += v * dt;
		}
	}
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
	struct overlap_acc o = {d->r, 0, 0};

	contact_foreach(&d->ce, d->x, CONTACT_TOUCHING, on_overlap, &o);
	*coord = (double)o.nc / d->n;
	return o.mo;
}

/* Time step from the stiffest likely contact: the two smallest grains (R* = rmin / 2), or
 * the smallest grain on a wall (R* = rmin), at overlap h rmin (h relative to the radius).
 * hertz_stiffness_t's sqrt(R* overlap) as (R* h) rmin, the product in the order of the
 * steps packgen has always taken. */
static void
dt_for_overlap(struct dem *d, double mmin, double rmin, double h)
{
	double k = fmax(hertz_stiffness_t(E_GRAIN, 0.5 * rmin * h, rmin), hertz_stiffness_t(E_WALL, rmin * h, rmin));

	d->dt = d->dt_safety * sqrt(0.5 * mmin / k);
}

/* Scaled copies of the grains (mean radius 1, density 1), in the order of placement:
 * largest first, so random placement rarely fails (a counting sort of the radii into 256
 * bins, descending). */
static int
dem_setup(struct dem *d, const struct pack *p, size_t *order, double *rmean, double *vol, double *mmin, double *rmin)
{
	size_t n = p->n, i, bins[257] = {0}, *tmp;

	d->n = n;
	d->x = calloc(3 * n, sizeof *d->x);
	d->v = calloc(3 * n, sizeof *d->v);
	d->w = calloc(3 * n, sizeof *d->w);
	d->f = calloc(3 * n, sizeof *d->f);
	d->t = calloc(3 * n, sizeof *d->t);
	d->r = malloc(n * sizeof *d->r);
	d->m = malloc(n * sizeof *d->m);
	d->I = malloc(n * sizeof *d->I);
	d->mob = malloc(2 * n * sizeof *d->mob);
	d->mob_dt = NAN;	/* made at the first step, whatever its length (even 0) */
	cell_init(&d->grid);
	tmp = malloc(n * sizeof *tmp);
	if (!d->x || !d->v || !d->w || !d->f || !d->t || !d->r || !d->m || !d->I || !d->mob || !tmp) {
		free(tmp);
		msg_seterr("out of memory for %zu grains", n);
		return -1;
	}
	*rmean = *vol = 0;
	*mmin = *rmin = INFINITY;
	for (i = 0; i < n; i++)
		*rmean += p->r[i];
	*rmean /= n;
	for (i = 0; i < n; i++) {
		d->r[i] = p->r[i] / *rmean;
		d->m[i] = 4.0 / 3.0 * M_PI * d->r[i] * d->r[i] * d->r[i];
		d->I[i] = 0.4 * d->m[i] * d->r[i] * d->r[i];
		*vol += d->m[i];
		d->rmax = fmax(d->rmax, d->r[i]);
		*rmin = fmin(*rmin, d->r[i]);
		*mmin = fmin(*mmin, d->m[i]);
		order[i] = i;
	}
	for (i = 0; i < n; i++)
		bins[255 - (int)fmin(255, floor((d->r[i] - *rmin) / (d->rmax - *rmin + 1e-300) * 255.999)) + 1]++;
	for (i = 0; i < 256; i++)
		bins[i + 1] += bins[i];
	for (i = 0; i < n; i++)
		tmp[bins[255 - (int)fmin(255, floor((d->r[i] - *rmin) / (d->rmax - *rmin + 1e-300) * 255.999))]++] = i;
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
		s += pack_wall_stress(d->lo, d->hi, a, d->wallf[2 * a] + d->wallf[2 * a + 1]);
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
		if (contact_enum_update(&d->ce, d->x, 0))
			return -1;
		if (forces(d))
			return -1;
		if (step % 100 == 0 || step == dp->max_steps) {
			double coord, ub = dem_unbalanced(d->f, d->n, d->sum_cf, d->ncontacts);
			st->step = step;
			st->unbalanced = ub;
			st->max_overlap = max_overlap(d, &coord);
			st->coordination = coord;
			st->phi = vol / ((d->hi[0] - d->lo[0]) * (d->hi[1] - d->lo[1]) * (d->hi[2] - d->lo[2]));
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
		integrate(d);
		dem_servo(d->lo, d->hi, d->wallf, ptarget, d->unloading ? d->rate * 0.05 : d->rate, NULL, d->x, d->n);
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
			p->x[3 * i + a] = d->x[3 * i + a] * rmean;
	}
	for (a = 0; a < 3; a++) {
		p->box[a] = d->lo[a] * rmean;
		p->box[a + 3] = d->hi[a] * rmean;
	}
	return 0;
}

int
dem_loose_pack(struct pack *p, const struct dem_params *dp, gsl_rng *rng, dem_progress_fn fn, void *ctx,
    struct dem_status *st)
{
	struct dem d;
	size_t n = p->n, *order = NULL;
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
		d.lo[a] = 0;
		d.hi[a] = L0 * dp->aspect[a];
	}
	if (place_random(&d, rng, d.r, order) || sort_spatially(&d, order))
		goto out;
	d.mu = dp->mu;
	d.damping = dp->damping;
	d.rate = dp->rate;
	d.dt_safety = dp->dt_safety;
	d.viscous = dp->viscous;
	d.pair_lanes = dp->pair_lanes && LANES_OK;
	d.skin = 0.3 * rmin;
	if (contact_enum_init(&d.ce, n, d.r, d.lo, d.hi, NULL, d.skin, DEM_LAW->history))
		goto out;
	/* Target stress from the mean overlap: Love-Weber p = Z phi <F> / (4 pi r^2) with
	 * Z ~ 4.5 and phi ~ 0.6 for a loose frictional pack and <F> the Hertz force at that
	 * overlap between two mean grains (E* = 1, R* = 1/2).  Such a small stress cannot be
	 * told apart from the kinetic and drag stresses of a compacting gas, so the pack is
	 * first jammed at a stress 'preload' times larger (mean overlap ~ 30x) and then
	 * unloaded to the target: unloading is nearly elastic and the frictional contact
	 * network, hence the loose structure, survives it. */
	pfinal = 4.5 * 0.6 * (hertz_coef(E_GRAIN, sqrt(0.5)) * pow(dp->overlap, 1.5)) / (4 * M_PI);
	if (dem_settle(&d, dp, pfinal, vol, mmin, rmin, fn, ctx, st) || dem_write_back(&d, p, order, rmean))
		goto out;
	status = 0;
out:
	free(order);
	dem_free(&d);
	return status;
}
