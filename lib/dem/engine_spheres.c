/* SPDX-License-Identifier: GPL-3.0-or-later */
/* engine_spheres: the engine's force pass when every grain is a sphere (engine.h).
 *
 * A sphere's geometry is its neighbour-list record: the contact point on the line of the
 * centres, the normal along the branch vector, the overlap r_i + r_j - d, the lever arms
 * -r_i n and r_j n; so a pair needs no narrow phase and no record per list entry.  The law's
 * forces are those of its dem_interaction with one element; Hertz-Mindlin's are inlined
 * (hertz_dem_force, the same bytes as its dem_interaction at one element, tests/unit/test_law.c)
 * and, with pair_lanes, computed two pairs at a time in the lanes of base/lanes.h
 * (hertz_dem_force2: a pair's force is six square roots and five divisions in one dependent
 * chain; the divider does two lanes in the time of one, and the two chains overlap).
 *
 * Threads with the same bytes for any number (base/par.h): each thread takes a run of whole
 * blocks of grains (par_block(n), fixed by n) of about equal list pairs (engine_blocks_share,
 * as the plate pass).  A pair's force goes into both grains; where
 * j is a later thread's, the pair is computed first (pass 1, so that its tangential spring
 * advances once) and j's thread gathers it before walking its own rows.  Every grain's sum
 * then has the one-pass walk's terms in its order: the pairs (m, j) by ascending m, then j's
 * own pairs and walls.  The sums are kept per block and added in block order. */
#include "dem/engine.h"
#include "contact/hertz.h"
#include "base/lanes.h"
#include "base/msg.h"
#include "base/par.h"
#include "base/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define HERTZ (&contact_law_hertz_mindlin)

/* A pair whose j is a later thread's: its force, computed before the walk by its row's
 * thread (pass 1), for i to add and j's thread to gather. */
struct engine_xrec {
	double F[3], cr[3];
	long stamp;		/* the pass that wrote it: older, the pair was apart */
};

/* The force F (on i) and the cross product n x ft (whose torque on i is -r_i n x ft, on j
 * -r_j n x ft) of one contact at the relative velocity of its point; the normal force
 * magnitude is returned, its elastic part goes into *fel.  The tangential spring (the
 * contact's history slot) is advanced. */
CONTACT_INLINE double
sphere_force(const struct engine *d, const struct contact *c, double F[3], double cr[3], double *fel)
{
	size_t i = c->i;
	int wall = PACK_IS_WALL(c->j), a;
	double ri = d->r[i], wr[3], ca[3], cb[3] = {0, 0, 0}, ft[3], fn;
	const struct law_pair *pp = wall ? &d->lp_wall : &d->lp_grain;
	struct law_pair lp;
	struct law_dem_in in;

	contact_normal(c, in.n);
	lp.Es = pp->Es, lp.mu = pp->mu;	/* what Hertz's DEM force reads */
	lp.Rs = contact_Rstar(c, d->r);
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
		const double *vw = d->wallv[PACK_WALL_INDEX(c->j)];
		in.meff = d->m[i];
		for (a = 0; a < 3; a++)
			in.vr[a] = d->v[3 * i + a] + ca[a] - vw[a];
	}
	if (d->law == HERTZ) {
		fn = hertz_dem_force(d->zeta, d->kt_ratio, &lp, &in, c->hist, ft, fel);
	} else {	/* any other law through its one DEM entry, one element */
		struct law_dem_elems el;
		double fk[1], vn = vec3_dot(in.vr, in.n);

		lp.kn = pp->kn;
		el.m = 1;
		el.h[0] = in.h;
		el.vn[0] = vn;
		for (a = 0; a < 3; a++) {
			el.n[a] = in.n[a];
			el.vt[a] = in.vr[a] - vn * in.n[a];
		}
		el.meff = in.meff, el.dt = in.dt, el.zeta = d->zeta, el.kt_ratio = d->kt_ratio;
		fn = d->law->dem_interaction(d->law, &lp, &el, c->hist, fk, ft, fel);
	}
	for (a = 0; a < 3; a++)
		F[a] = fn * in.n[a] + ft[a];
	vec3_cross(in.n, ft, cr);
	return fn;
}

/* What the walk of one block carries: the grains from jend on are a later thread's, whose
 * share of a pair's force that thread gathers (the pair's record); and a touching pair
 * waiting for a second, with which it shares the lanes of sphere_force2. */
struct sphere_walk {
	struct engine *d;
	size_t jend;
	struct engine_sums s;
	int plain;		/* no glue and no stress sums: a contact counts its force alone */
	size_t plain_pairs, plain_walls;	/* the contacts so counted (pair_count, on_wall) */
	int npend;
	struct contact pend;
};

#if LANES_OK
/* sphere_force of two Hertz grain-grain contacts at once, each in one lane of the same
 * arithmetic (lanes.h: the same bytes as sphere_force; tests/unit/test_dem.c checks it). */
CONTACT_INLINE void
sphere_force2(const struct engine *d, const struct contact *A, const struct contact *B, double F[2][3], double cr[2][3])
{
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
	fn = hertz_dem_force2(d->zeta, d->kt_ratio, d->lp_grain.mu, d->lp_grain.Es, Rs, h, n, vr, meff, d->dt, xi, ft);
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

CONTACT_INLINE void
add_to_i(struct engine *d, size_t i, const double F[3], const double cr[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		d->f[3 * i + a] += F[a];
		d->t[3 * i + a] -= d->r[i] * cr[a];
	}
}

CONTACT_INLINE void
add_to_j(struct engine *d, size_t j, const double F[3], const double cr[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		d->f[3 * j + a] -= F[a];
		d->t[3 * j + a] -= d->r[j] * cr[a];
	}
}

/* A pair into the block's sums: engine_count's, or, in a plain pass (packgen's: no glue, no
 * stress sums), its force magnitude alone, the counts it would add (an interaction, an
 * element, two ends on free grains) made up per block in engine_sphere_forces; a wall's there
 * too, after its elastic force (on_wall). */
CONTACT_INLINE void
pair_count(struct sphere_walk *w, const struct contact *c, const double F[3])
{
	if (w->plain) {
		w->plain_pairs++;
		w->s.sum_f += sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
		return;
	}
	engine_count(w->d, c->i, c->j, c->dx, F, 0, 1, &w->s);
}

/* A computed pair's force into both grains and the block's sums. */
CONTACT_INLINE void
pair_add(struct sphere_walk *w, const struct contact *c, const double F[3], const double cr[3])
{
	add_to_i(w->d, c->i, F, cr);
	add_to_j(w->d, (size_t)c->j, F, cr);
	pair_count(w, c, F);
}

/* The waiting pair alone, before anything else is added (so every grain's sum keeps the
 * walk's order). */
CONTACT_INLINE void
pend_flush(struct sphere_walk *w)
{
	double F[3], cr[3], fel;

	if (!w->npend)
		return;
	sphere_force(w->d, &w->pend, F, cr, &fel);
	pair_add(w, &w->pend, F, cr);
	w->npend = 0;
}

CONTACT_INLINE int
on_pair(const struct contact *c, void *vw)
{
	struct sphere_walk *w = vw;
	struct engine *d = w->d;
	size_t j = (size_t)c->j;

#if LANES_OK
	if (j < w->jend && d->pair_lanes) {
		double F2[2][3], cr2[2][3];

		if (!w->npend) {	/* wait for a second pair */
			/* what sphere_force reads, not the whole record */
			w->pend.i = c->i, w->pend.j = c->j, w->pend.hist = c->hist;
			w->pend.dx[0] = c->dx[0], w->pend.dx[1] = c->dx[1], w->pend.dx[2] = c->dx[2];
			w->pend.d = c->d, w->pend.h = c->h;
			w->pend.ri = c->ri, w->pend.rj = c->rj;
			w->npend = 1;
			return 0;
		}
		sphere_force2(d, &w->pend, c, F2, cr2);
		pair_add(w, &w->pend, F2[0], cr2[0]);
		pair_add(w, c, F2[1], cr2[1]);
		w->npend = 0;
		return 0;
	}
#endif
	if (j < w->jend) {
		double F[3], cr[3], fel;

		sphere_force(d, c, F, cr, &fel);
		pair_add(w, c, F, cr);
	} else {
		const struct engine_xrec *x = &d->xrec[d->xslot[contact_pair_index(&d->ce, c)]];

		pend_flush(w);
		add_to_i(d, c->i, x->F, x->cr);
		pair_count(w, c, x->F);
	}
	return 0;
}

CONTACT_INLINE int
on_wall(const struct contact *c, void *vw)
{
	struct sphere_walk *w = vw;
	struct engine *d = w->d;
	double F[3], cr[3], fel;

	pend_flush(w);
	if (d->glue && d->glue[c->i] == 1 + PACK_WALL_INDEX(c->j))
		return 0;	/* glued to that wall: part of it */
	sphere_force(d, c, F, cr, &fel);
	add_to_i(d, c->i, F, cr);
	if (w->plain) {	/* the servo's elastic force and the force magnitude (see pair_count) */
		w->plain_walls++;
		w->s.wallf[PACK_WALL_INDEX(c->j)] += fel;
		w->s.sum_f += sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
		return 0;
	}
	engine_count(d, c->i, c->j, NULL, F, fel, 1, &w->s);
	return 0;
}

/* Pass 1: the pairs of this thread's rows whose j is a later thread's. */
CONTACT_INLINE int
on_cross_pair(const struct contact *c, void *vw)
{
	struct sphere_walk *w = vw;
	struct engine_xrec *x;
	double fel;

	if ((size_t)c->j < w->jend)
		return 0;
	x = &w->d->xrec[w->d->xslot[contact_pair_index(&w->d->ce, c)]];
	sphere_force(w->d, c, x->F, x->cr, &fel);
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
cross_slots(struct engine *d, size_t T)
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
		size_t g0 = engine_blocks_share(nl, bl, nb, T, t) * bl, g1 = engine_blocks_share(nl, bl, nb, T, t + 1) * bl;
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
		size_t g0 = engine_blocks_share(nl, bl, nb, T, t) * bl, g1 = engine_blocks_share(nl, bl, nb, T, t + 1) * bl;
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

/* A row's walk for a law whose history is not a tangential spring's 3 doubles (harmonic's
 * 0): out of line, so that the inlined walks below stay as they are for the 3 of the laws
 * of friction (inlined a third time, the sphere pass ran 10-25 % slower). */
static __attribute__((noinline)) int
sphere_row_any(const struct contact_enum *e, const double *x, size_t i, int per, contact_fn pf, contact_fn wf, void *ctx,
    long *calls)
{
	return contact_foreach_row(e, x, i, CONTACT_TOUCHING, per, e->hsize, pf, wf, ctx, calls);
}

/* One row's walk, with the periodic branch compiled in or out (per a constant) and the
 * history's size the constant 3 (a tangential spring), else sphere_row_any. */
#define SPHERE_ROW(e, x, i, per, pf, wf, ctx, calls) \
	((e)->hsize != 3 ? sphere_row_any(e, x, i, per, pf, wf, ctx, calls) \
	 : (per) ? contact_foreach_row(e, x, i, CONTACT_TOUCHING, 1, 3, pf, wf, ctx, calls) \
	         : contact_foreach_row(e, x, i, CONTACT_TOUCHING, 0, 3, pf, wf, ctx, calls))

int
engine_sphere_forces(struct engine *d)
{
	struct contact_enum *e = &d->ce;
	size_t n = d->n, bl = par_block(n), nb = (n + bl - 1) / bl;
	int per = e->any_periodic;

	d->threads = n >= PAR_MIN && par_threads() > 1;
	if (contact_enum_update(e, d->x, 0) || engine_sums_fit(d, nb))
		return -1;
	if (d->threads && cross_slots(d, (size_t)par_threads()))
		return -1;
	d->stamp++;
#pragma omp parallel if (d->threads)
	{
		size_t T = (size_t)par_team(), t = (size_t)par_tid(), b, i, s;
		size_t b0 = engine_blocks_share(&e->nl, bl, nb, T, t), b1 = engine_blocks_share(&e->nl, bl, nb, T, t + 1);
		size_t g0 = b0 * bl < n ? b0 * bl : n, g1 = b1 * bl < n ? b1 * bl : n;
		long calls = 0;

		if (T > 1 && t + 1 < T) {
			struct sphere_walk cw;

			memset(&cw, 0, sizeof cw);
			cw.d = d, cw.jend = g1;
			for (i = g0; i < g1; i++)
				if (e->nl.first[i + 1] > e->nl.first[i] && e->nl.nbr[e->nl.first[i + 1] - 1] >= g1)
					SPHERE_ROW(e, d->x, i, per, on_cross_pair, on_no_wall, &cw, &calls);
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
			struct sphere_walk dw;
			size_t i1 = (b + 1) * bl < n ? (b + 1) * bl : n;

			memset(&dw, 0, sizeof dw);
			dw.d = d, dw.jend = g1, dw.plain = !d->glue && !d->stress;
			for (i = b * bl; i < i1; i++)
				SPHERE_ROW(e, d->x, i, per, on_pair, on_wall, &dw, &calls);
			pend_flush(&dw);
			/* the counts of the plain pass's contacts (wallF is not kept: no stress sums) */
			dw.s.ninter += dw.plain_pairs + dw.plain_walls, dw.s.nelem += dw.plain_pairs + dw.plain_walls;
			dw.s.zends += 2 * dw.plain_pairs + dw.plain_walls, dw.s.nwall += dw.plain_walls;
			d->sums[b] = dw.s;
		}
	}
	engine_sums_total(d, nb);
	return 0;
}
