/* SPDX-License-Identifier: GPL-3.0-or-later */
/* contacts: the one contact enumerator of the library, and the contact network it collects.
 *
 * Every consumer of contacts (the functional and its gradient, the minimisers' stiffness
 * bound, densify's growth, the release of unbraced grains, the DEM forces, packinfo's
 * measures, the exports) visits them through contact_foreach() or contact_foreach_grain():
 * a Verlet list over the cell grid (nlist.h) for the grain pairs, then the walls, with the
 * boundary applied here and nowhere else.  Along an axis that is periodic (pack.periodic)
 * a pair's branch vector is its nearest image and that axis has no walls, so periodic packs
 * need no change in any consumer.
 *
 * The record (struct contact) holds the pair, the branch vector dx = x_i - x_j (wall: from
 * the wall's foot point to the centre), its length d, the overlap h = r_i + r_j - d (wall:
 * r_i - d; negative is a gap) and the contact's history slot.  What not every consumer
 * needs (the unit normal, the lever arms, the contact point, the effective radius) comes
 * from the inline accessors below, so the hot loops pay only for what they read: the
 * functional's evaluation inlines contact_foreach and its callback (bench/evalscale).
 *
 * History slots: an enumerator made with hsize > 0 keeps hsize doubles for every listed
 * pair and every grain-wall pair (the DEM's tangential springs), carried over a rebuild of
 * the list for the pairs listed in both, and zeroed by the enumerator when a pair is apart
 * (h <= 0) as contact_foreach visits it in CONTACT_NEAR mode.
 *
 * Order: grain by grain; for grain i its pairs (i, j > i) in ascending j, then its walls in
 * the order xlo xhi ylo yhi zlo zhi.  Sums over contacts are taken in this order
 * everywhere, so results do not depend on the grid. */
#ifndef QUSGM_CONTACTS_H
#define QUSGM_CONTACTS_H

#include <math.h>
#include <stddef.h>
#include <string.h>
#include "contact/hertz.h"
#include "contact/nlist.h"
#include "pack/pack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The enumerator and its callbacks in the hot loops must be inlined into each other, or the
 * callback is a call through a pointer per contact (1.7x slower per evaluation, measured
 * with bench/evalscale): GCC and clang are told so. */
#if defined(__GNUC__)
#define CONTACT_INLINE static inline __attribute__((always_inline))
#else
#define CONTACT_INLINE static inline
#endif

struct contact {
	size_t i;
	long j;			/* grain index, or PACK_WALL(w) */
	double dx[3];		/* branch vector, on i: from j (its nearest image) or the wall */
	double d;		/* |dx| */
	double h;		/* overlap (m); negative: the gap of a near pair */
	double ri, rj;		/* the radii (rj = 0 for a wall) */
	double *hist;		/* the pair's history slot (hsize doubles), or NULL */
	size_t k;		/* in contact_foreach_row, a pair's index in the list (e->nl.nbr) */
};

/* What contact_foreach visits: CONTACT_TOUCHING, pairs closer than r_i + r_j and walls
 * nearer than r_i; CONTACT_NEAR, every listed pair (within the skin) and every wall of every
 * grain, whatever the gap. */
enum { CONTACT_TOUCHING = 0, CONTACT_NEAR = 1 };

struct contact_enum {
	size_t n;
	const double *r;	/* radii (n), owned by the caller */
	const double *lo, *hi;	/* the box: lower and upper corners, owned by the caller */
	int periodic[3];
	int any_periodic;
	double rmax, skin;
	struct nlist nl;
	struct nlist prev;	/* the list before the last rebuild (history carry) */
	int stale;		/* radii changed: rebuild at the next update */
	/* history slots: hsize doubles per listed pair (two buffers, swapped at a rebuild) and
	 * per grain-wall pair (NWALLS per grain) */
	unsigned hsize;
	double *hpair[2];
	size_t hcap[2];
	int hcur;
	double *hwall;
	unsigned char *hwall_set;	/* per grain, bit w: wall w's slot went to a callback since it was
					 * last zeroed, so it may hold something (else it is zero, and the
					 * walk leaves its memory alone) */
	size_t *full_first, *full_nbr;	/* both directions of the list, for contact_foreach_grain */
	size_t *col_first, *col_nbr;	/* per grain j, its listed lower neighbours m < j */
	size_t *col_k;			/* ... and the list entries of those pairs (m, j) */
	size_t *col_pos;		/* per list entry, its place in the columns (col_k's inverse) */
	long col_builds;		/* rebuilds when col_* were made */
	long rebuilds;			/* lists built so far (nl and prev swap: their own counts repeat) */
	/* contact_enum_skin_auto: the skin's ceiling (0: the skin is fixed), the updates so far
	 * and at the last build */
	double skin_max;
	long updates, updates_built;
	long full_builds;		/* rebuilds when the full rows were made */
	struct contact_prune *prune;	/* contact_enum_prune's, or NULL */
};

/* A shape's finer test at list time: of the pairs whose bounding spheres (the radii r) are
 * within the skin, keep (nlist.h) lists only those whose shapes may come within range before
 * the list goes stale; prepare (NULL: none) is called before each build, to ready what keep
 * reads and zero extra; extra (n, the caller's) is what each grain's points may have moved
 * beyond its centre since the last build (its turning), which the staleness test adds to the
 * centre's displacement.  A pair left out must have its shapes farther apart than the skin:
 * then, while the list is fresh, they are apart, and no result depends on the pruning. */
struct contact_prune {
	nlist_keep_fn keep;
	void (*prepare)(void *ctx);
	const double *extra;
	void *ctx;
};

/* r: n radii; lo, hi: the box corners (read at every update, so the caller may move them);
 * periodic: 3 flags or NULL (all walls); skin: Verlet skin (m); hsize: history doubles per
 * contact (0: none).  0 or -1 (msg_seterr). */
int contact_enum_init(struct contact_enum *e, size_t n, const double *r, const double *lo, const double *hi,
    const int *periodic, double skin, unsigned hsize);
void contact_enum_free(struct contact_enum *e);
/* Make the list valid for positions x: rebuilt when it may have gone stale (or was never
 * built, or force is set).  0 or -1 (out of memory; a periodic axis shorter than three
 * interaction distances). */
int contact_enum_update(struct contact_enum *e, const double *x, int force);
/* A skin that follows the motion, up to skin_max: the next list is built with a sixth of it,
 * and each list that goes stale within CONTACT_SKIN_GROW updates is followed by one with twice
 * the skin.  The contacts and their order do not depend on the skin (only pairs within it are
 * listed, touching ones always), so neither does anything computed from them: the skin
 * trades the pairs each walk visits against the rebuilds.  Near equilibrium (a loading's
 * increments, whose affine part the staleness test discounts) a list lasts hundreds of
 * evaluations with a small skin, and the walks visit a third fewer pairs apart; a relaxation
 * that moves grains far grows the skin back in a few rebuilds. */
#define CONTACT_SKIN_GROW 100

/* Floor of a grain's largest contact force in a residual, relative to the mean normal
 * contact force: packinfo's (MEASURE_RESIDUAL_FLOOR) and the minimisers' (QS_RESIDUAL_FLOOR,
 * qs_residual), one value. */
#define CONTACT_RESIDUAL_FLOOR 1e-3
void contact_enum_skin_auto(struct contact_enum *e, double skin_max);
/* Prune the lists from the next build on (pr, the caller's, outlives e; NULL: no more):
 * the list is rebuilt at the next update. */
void contact_enum_prune(struct contact_enum *e, struct contact_prune *pr);
/* The radii changed (grains grew): the list is rebuilt at the next update. */
void contact_enum_radii_changed(struct contact_enum *e);
/* Make col_first, col_nbr, col_k and col_pos current for the list: the columns of the half
 * list, i.e. for each grain j its listed neighbours m < j, ascending, which is the order in
 * which contact_foreach reaches the pairs (m, j), those pairs' list entries, and for each
 * entry its place in the columns (where the plate DEM keeps a pair's record, so that its
 * gather reads them in order).  They let a thread gather what the rows of other
 * threads would have scattered into its grains, in contact_foreach's order (the
 * functional's threads).  0 or -1 (out of memory). */
int contact_enum_columns(struct contact_enum *e);

/* The history slots that hold something (any bit set, -0.0 too), for a checkpoint: returns
 * their count and, when ij and h are not NULL, stores each one's pair into ij (two longs: i,
 * then j, or PACK_WALL(w) for a wall) and its hsize doubles into h; pairs in the list's
 * order, then the walls grain by grain.  The list must have been built. */
size_t contact_enum_history_get(const struct contact_enum *e, long *ij, double *h);
/* Put m slots of contact_enum_history_get back after building the list afresh for positions x
 * (every other slot zeroed).  The contacts and their order do not depend on when a list was
 * built (the order above; touching pairs are always listed), so a run going on from a
 * checkpoint sees what the uninterrupted one would.  A saved pair the new list does not hold
 * is apart (its slot would be zeroed at its next visit): it is left out.  0, or -1 (out of
 * memory, or ij not in the order of contact_enum_history_get: msg_seterr). */
int contact_enum_history_set(struct contact_enum *e, const double *x, size_t m, const long *ij, const double *h);

/* Nearest image of a branch vector along the periodic axes.  A component shorter than half
 * the period is its own nearest image: dx - L nearbyint(dx / L) gives dx back to the bit
 * (nearbyint is a signed zero, except for dx = -0, which the test leaves to the formula), and
 * the test spares most pairs a call into libm (x86-64 has no rounding instruction before
 * SSE4.1). */
CONTACT_INLINE void
contact_wrap(double *dx, double L)
{
	if (!(2 * fabs(*dx) < L && *dx != 0))
		*dx -= L * nearbyint(*dx / L);
}

CONTACT_INLINE void
contact_min_image(const struct contact_enum *e, double dx[3])
{
	int a;

	for (a = 0; a < 3; a++)
		if (e->periodic[a])
			contact_wrap(dx + a, e->hi[a] - e->lo[a]);
}

/* The periods of e's axes (0 along an axis with walls), for contact_branch. */
CONTACT_INLINE void
contact_periods(const struct contact_enum *e, double len[3])
{
	int a;

	for (a = 0; a < 3; a++)
		len[a] = e->periodic[a] ? e->hi[a] - e->lo[a] : 0;
}

/* Calls fn(c, ctx) for every contact of the pack at x (see the order above); in
 * CONTACT_NEAR mode the history of a pair that is apart is zeroed before the call.  The
 * list must be up to date (contact_enum_update).  Returns the number of calls, or -1 when fn
 * returns nonzero. */
typedef int (*contact_fn)(const struct contact *c, void *ctx);

/* The branch vector from grain j (its nearest image when per) to the centre (xi0, xi1, xi2)
 * into c->dx; returns its squared length.  Every pair record starts here (contact_branch).
 * len: the periods (contact_periods, taken once per walk rather than from e at every pair). */
CONTACT_INLINE double
contact_branch_in(const double len[3], struct contact *c, double xi0, double xi1, double xi2, const double *x,
    size_t j, int per)
{
	c->dx[0] = xi0 - x[3 * j], c->dx[1] = xi1 - x[3 * j + 1], c->dx[2] = xi2 - x[3 * j + 2];
	if (per) {
		if (len[0] > 0)
			contact_wrap(c->dx, len[0]);
		if (len[1] > 0)
			contact_wrap(c->dx + 1, len[1]);
		if (len[2] > 0)
			contact_wrap(c->dx + 2, len[2]);
	}
	return c->dx[0] * c->dx[0] + c->dx[1] * c->dx[1] + c->dx[2] * c->dx[2];
}

CONTACT_INLINE double
contact_branch(const struct contact_enum *e, struct contact *c, double xi0, double xi1, double xi2, const double *x,
    size_t j, int per)
{
	double len[3];

	contact_periods(e, len);
	return contact_branch_in(len, c, xi0, xi1, xi2, x, j, per);
}

/* Zero hs doubles of history (a tangential spring: three stores, not a call to memset). */
CONTACT_INLINE void
row_clear(double *h, unsigned hs)
{
	unsigned q;

	if (hs == 3) {
		h[0] = h[1] = h[2] = 0;
		return;
	}
	for (q = 0; q < hs; q++)
		h[q] = 0;
}

/* Whether any of hs doubles of history has a bit set (-0.0 too: clearing it gives +0.0, as
 * an unconditional clear would). */
CONTACT_INLINE int
row_nonzero(const double *h, unsigned hs)
{
	unsigned q;
	unsigned long long b = 0;

	for (q = 0; q < hs; q++) {
		unsigned long long u;
		memcpy(&u, h + q, sizeof u);
		b |= u;
	}
	return b != 0;
}

/* Wall w of grain c->i (radius c->ri) at distance dist, in contact_foreach_row; hist is its
 * history slot or NULL, set the grain's hwall_set byte (bit w: the slot went to a callback
 * since it was last zeroed).  A slot apart from its wall is zeroed only when that bit is set:
 * in a CONTACT_TOUCHING walk (the DEM's sphere pass) a grain far from the walls then costs no stores
 * into the walls' history, which every grain has (at 1e5 grains 14 MB a step).  A
 * CONTACT_NEAR walk (the plate DEM) hands every slot to its callback, so its slots are
 * zeroed at every visit apart, as before. */
CONTACT_INLINE int
row_wall(struct contact *c, int w, double dist, double *hist, unsigned char *set, unsigned hs, int mode,
    contact_fn fn, void *ctx, long *calls)
{
	int a = w / 2;
	unsigned char bit = (unsigned char)(1u << w);

	c->h = c->ri - dist;
	c->hist = hist;
	if (c->h <= 0 && hist && (*set & bit)) {
		row_clear(hist, hs);
		*set &= (unsigned char)~bit;
	}
	if (mode == CONTACT_TOUCHING && c->h <= 0)
		return 0;
	if (hist)
		*set |= bit;
	c->j = PACK_WALL(w);
	c->d = dist;
	c->dx[a] = w % 2 ? -dist : dist;
	if (fn(c, ctx))
		return -1;
	c->dx[a] = 0;
	(*calls)++;
	return 0;
}

/* The contacts of grain i, pairs then walls, with i's centre and radius held in registers:
 * the hot loops of the functional and of the DEM.  The history of a pair apart is zeroed.
 * per (any periodic axis) and hs (history doubles) are e's, passed as constants where the
 * caller can, so that each kind of walk compiles without the others' branches. */
CONTACT_INLINE int
contact_foreach_row(const struct contact_enum *e, const double *x, size_t i, int mode, int per, unsigned hs,
    contact_fn pair_fn, contact_fn wall_fn, void *ctx, long *calls)
{
	const double *r = e->r;
	double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2], ri = r[i];
	size_t k, kend = e->nl.first[i + 1];
	double *hp = hs ? e->hpair[e->hcur] : NULL, *hw = hs ? e->hwall + (size_t)hs * NWALLS * i : NULL;
	unsigned char *hset = hs ? e->hwall_set + i : NULL;
	struct contact c;
	double len[3];

	c.i = i;
	c.ri = ri;
	c.hist = NULL;
	if (per)	/* a walk without periodic axes reads no period (packgen's spheres: 2 % of its instructions) */
		contact_periods(e, len);
	else
		len[0] = len[1] = len[2] = 0;
	for (k = e->nl.first[i]; k < kend; k++) {
		size_t j = e->nl.nbr[k];
		double rj = r[j], sum = ri + rj, dd = contact_branch_in(len, &c, xi0, xi1, xi2, x, j, per);

		if (hp)
			c.hist = hp + (size_t)hs * k;
		if (mode == CONTACT_TOUCHING && dd >= sum * sum) {
			/* apart: its spring is zero, and stays so; most listed pairs are apart and
			 * already zero, so look before storing (a store dirties the line, and at 1e5
			 * grains the pairs' slots are tens of MB a DEM step) */
			if (hp && row_nonzero(c.hist, hs))
				row_clear(c.hist, hs);
			continue;
		}
		c.j = (long)j;
		c.k = k;
		c.rj = rj;
		c.d = sqrt(dd);
		c.h = sum - c.d;
		if (hp && c.h <= 0)
			row_clear(c.hist, hs);
		if (pair_fn(&c, ctx))
			return -1;
		(*calls)++;
	}
	c.rj = 0;
	c.dx[0] = c.dx[1] = c.dx[2] = 0;
	/* the six walls written out: the centre stays in registers; none on a periodic axis */
	if ((!(per && e->periodic[0]) && (row_wall(&c, 0, xi0 - e->lo[0], hw, hset, hs, mode, wall_fn, ctx, calls) ||
	    row_wall(&c, 1, e->hi[0] - xi0, hw ? hw + hs : NULL, hset, hs, mode, wall_fn, ctx, calls))) ||
	    (!(per && e->periodic[1]) && (row_wall(&c, 2, xi1 - e->lo[1], hw ? hw + 2 * hs : NULL, hset, hs, mode, wall_fn, ctx, calls) ||
	    row_wall(&c, 3, e->hi[1] - xi1, hw ? hw + 3 * hs : NULL, hset, hs, mode, wall_fn, ctx, calls))) ||
	    (!(per && e->periodic[2]) && (row_wall(&c, 4, xi2 - e->lo[2], hw ? hw + 4 * hs : NULL, hset, hs, mode, wall_fn, ctx, calls) ||
	    row_wall(&c, 5, e->hi[2] - xi2, hw ? hw + 5 * hs : NULL, hset, hs, mode, wall_fn, ctx, calls))))
		return -1;
	return 0;
}

CONTACT_INLINE long
contact_foreach_split(const struct contact_enum *e, const double *x, int mode, contact_fn pair_fn, contact_fn wall_fn,
    void *ctx)
{
	size_t i;
	long calls = 0;
	int r = 0;

	if (!e->any_periodic && e->hsize == 0)	/* the functional */
		for (i = 0; i < e->n && !r; i++)
			r = contact_foreach_row(e, x, i, mode, 0, 0, pair_fn, wall_fn, ctx, &calls);
	else if (!e->any_periodic && e->hsize == 3)	/* the DEM */
		for (i = 0; i < e->n && !r; i++)
			r = contact_foreach_row(e, x, i, mode, 0, 3, pair_fn, wall_fn, ctx, &calls);
	else
		for (i = 0; i < e->n && !r; i++)
			r = contact_foreach_row(e, x, i, mode, e->any_periodic, e->hsize, pair_fn, wall_fn, ctx, &calls);
	return r ? -1 : calls;
}

/* The same walk with one callback for the pairs and another for the walls, for consumers
 * whose work differs between the two (the functional's fast path). */
CONTACT_INLINE long
contact_foreach(const struct contact_enum *e, const double *x, int mode, contact_fn fn, void *ctx)
{
	return contact_foreach_split(e, x, mode, fn, fn, ctx);
}

/* Calls fn for every contact of grain i alone, with i first in each record (its pairs with
 * every listed neighbour, lower and higher indices, ascending, then its walls), at x, which
 * may have changed since the update only by moves shorter than a quarter of the skin.  For
 * the grain-by-grain passes (the release of unbraced grains).  The history slot is not
 * given (NULL).  Returns the number of calls, -1 when fn returned nonzero (it may stop the
 * walk that way), -2 when out of memory (msg_seterr). */
long contact_foreach_grain(struct contact_enum *e, const double *x, size_t i, int mode, contact_fn fn, void *ctx);

/* The list entry k of a grain pair visited by contact_foreach(_row) of an enumerator with
 * history (its slot is hpair + hsize k): for callers that keep their own per-pair arrays
 * beside the history (the DEM's threads).  The walk's record carries it (the slot's offset
 * over hsize was a division per pair, a tenth of a plate DEM step's walk). */
CONTACT_INLINE size_t
contact_pair_index(const struct contact_enum *e, const struct contact *c)
{
	(void)e;
	return c->k;
}

/* The unit normal on i, from j (or out of the wall) to i. */
CONTACT_INLINE void
contact_normal(const struct contact *c, double n[3])
{
	if (PACK_IS_WALL(c->j)) {
		int w = PACK_WALL_INDEX(c->j);
		n[0] = n[1] = n[2] = 0;
		n[w / 2] = w % 2 ? -1.0 : 1.0;
	} else {
		n[0] = c->dx[0] / c->d, n[1] = c->dx[1] / c->d, n[2] = c->dx[2] / c->d;
	}
}

/* Lever-arm lengths from the centres of i and j to the contact plane (physics.md §3) for a
 * contact of i (radius Ri) with j (radius Rj, or a wall) at distance d and overlap h: the
 * plane of the circle where the two spheres intersect; a wall's plane for a grain-wall
 * contact (lj = 0). */
static inline void
contact_lever_lengths(int wall, double Ri, double Rj, double d, double h, double *li, double *lj)
{
	double A2;

	if (wall) {
		*li = Ri - h;
		*lj = 0;
		return;
	}
	A2 = (d - Ri + Rj) * (d + Ri - Rj) * (Ri + Rj - d) * (Ri + Rj + d) / (4 * d * d);
	if (A2 < 0)
		A2 = 0;
	*li = sqrt(fmax(Ri * Ri - A2, 0));
	*lj = sqrt(fmax(Rj * Rj - A2, 0));
}

/* The record of one given pair (i, j) or grain and wall (j = PACK_WALL(w)) of pack p at
 * positions x, with p's box and boundary, whether they touch or not (no history slot). */
void contact_between(const struct pack *p, const double *x, size_t i, long j, struct contact *c);

/* Effective radius R* = (1/r_i + 1/r_j)^-1 (hertz_Rstar); r_i for a wall. */
static inline double
contact_Rstar(const struct contact *c, const double *r)
{
	return PACK_IS_WALL(c->j) ? r[c->i] : hertz_Rstar(r[c->i], r[c->j]);
}

/* The contact network at the pack's own positions: every contact with h > 0, grain-grain
 * first (i < j, ascending), then grain-wall in grain order, each with its unit normal, its
 * normal force by the pack's law (law.h: its pair setup and normal; a spring law at the pack's
 * meta kn) and the pack's history line for the pair. */
struct geo_contact {
	size_t i;
	long j;		/* grain index or PACK_WALL(w) */
	double h;	/* overlap (m) */
	double d;	/* centre distance; for a wall, distance centre-wall */
	double n[3];	/* unit normal, on i, from j to i */
	double P;	/* normal force by the pack's law (N; contact_law_of_pack) */
	long hist;	/* index into pack.c[] or -1 */
};

struct geo_contacts {
	size_t n, cap;
	struct geo_contact *c;
};

void contacts_init(struct geo_contacts *gc);
void contacts_free(struct geo_contacts *gc);
/* All contacts of p at p->x (see above); 0 or -1. */
int contacts_find(const struct pack *p, struct geo_contacts *gc);
/* The same with an enumerator the caller keeps over p (contact_enum_init on p->r and p->box,
 * any skin), brought up to p->x (rebuilt only when stale): the same contacts in the same order,
 * without building a new list each time (a frictional increment finds its contacts at every
 * start and commit of its settle passes; the functional's own enumerator serves).  0 or -1. */
int contacts_find_in(const struct pack *p, struct contact_enum *e, struct geo_contacts *gc);
/* Replace p->c by a line per touching contact with P0 the pack's law's normal force at the
 * current positions;
 * Q0 and M0 are carried over from the line of the same pair when keep_history is set (lines
 * of pairs that no longer touch are dropped), zero otherwise.  0 or -1. */
int contacts_store(struct pack *p, int keep_history);
/* contacts_store through the caller's enumerator e (contacts_find_in); NULL: a new one. */
int contacts_store_in(struct pack *p, struct contact_enum *e, int keep_history);
/* contacts_store_in that also hands the contacts it found to the caller (found, freed first):
 * the list contacts_find_in would give at the same positions now, each contact's hist its
 * new line.  A frictional increment's commit and the start of the next settle pass, at the
 * same positions, then walk the contacts once instead of twice.  0 or -1. */
int contacts_store_found(struct pack *p, struct contact_enum *e, int keep_history, struct geo_contacts *found);

#ifdef __cplusplus
}
#endif

#endif
