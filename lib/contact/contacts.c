/* SPDX-License-Identifier: GPL-3.0-or-later */
/* contacts: geometric contact detection (see contacts.h). */
#include "contact/contacts.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
contacts_init(struct geo_contacts *gc)
{
	memset(gc, 0, sizeof *gc);
}

void
contacts_free(struct geo_contacts *gc)
{
	free(gc->c);
	memset(gc, 0, sizeof *gc);
}

static int
push(struct geo_contacts *gc, const struct geo_contact *c)
{
	if (gc->n == gc->cap) {
		size_t cap = gc->cap ? 2 * gc->cap : 1024;
		struct geo_contact *q = realloc(gc->c, cap * sizeof *q);
		if (!q) {
			msg_seterr("out of memory for contacts");
			return -1;
		}
		gc->c = q;
		gc->cap = cap;
	}
	gc->c[gc->n++] = *c;
	return 0;
}

int
contact_enum_init(struct contact_enum *e, size_t n, const double *r, const double *lo, const double *hi,
    const int *periodic, double skin, unsigned hsize)
{
	size_t i;
	int a;

	memset(e, 0, sizeof *e);
	e->n = n;
	e->r = r;
	e->lo = lo;
	e->hi = hi;
	for (a = 0; a < 3; a++) {
		e->periodic[a] = periodic && periodic[a];
		e->any_periodic |= e->periodic[a];
	}
	for (i = 0; i < n; i++)
		e->rmax = fmax(e->rmax, r[i]);
	e->skin = skin;
	e->hsize = hsize;
	nlist_init(&e->nl);
	nlist_init(&e->prev);
	if (hsize) {
		e->hwall = calloc((n ? n : 1) * NWALLS * hsize, sizeof *e->hwall);
		e->hwall_set = calloc(n ? n : 1, 1);
		if (!e->hwall || !e->hwall_set) {
			free(e->hwall), free(e->hwall_set);
			e->hwall = NULL, e->hwall_set = NULL;
			msg_seterr("out of memory for the contact history");
			return -1;
		}
	}
	return 0;
}

void
contact_enum_free(struct contact_enum *e)
{
	nlist_free(&e->nl);
	nlist_free(&e->prev);
	free(e->hpair[0]), free(e->hpair[1]), free(e->hwall), free(e->hwall_set);
	free(e->full_first), free(e->full_nbr);
	free(e->col_first), free(e->col_nbr), free(e->col_k), free(e->col_pos);
	memset(e, 0, sizeof *e);
}

void
contact_enum_prune(struct contact_enum *e, struct contact_prune *pr)
{
	e->prune = pr;
	e->stale = 1;
}

void
contact_enum_radii_changed(struct contact_enum *e)
{
	size_t i;

	e->rmax = 0;
	for (i = 0; i < e->n; i++)
		e->rmax = fmax(e->rmax, e->r[i]);
	e->stale = 1;
}

/* The history slots of the new list: a pair listed before keeps its slot's values. */
static int
carry_history(struct contact_enum *e)
{
	const struct nlist *old = &e->prev, *nl = &e->nl;
	int nx = 1 - e->hcur;
	size_t i, k, h = e->hsize;

	if (nl->npairs > e->hcap[nx] || !e->hpair[nx]) {
		size_t cap = nl->npairs + nl->npairs / 4 + 16;
		free(e->hpair[nx]);
		e->hpair[nx] = malloc(h * cap * sizeof *e->hpair[nx]);
		if (!e->hpair[nx]) {
			msg_seterr("out of memory for the contact history");
			return -1;
		}
		e->hcap[nx] = cap;
	}
	for (i = 0; i < e->n; i++) {
		size_t o = old->first ? old->first[i] : 0, oe = old->first ? old->first[i + 1] : 0;
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			double *to = e->hpair[nx] + h * k;
			while (o < oe && old->nbr[o] < nl->nbr[k])
				o++;
			if (o < oe && old->nbr[o] == nl->nbr[k])
				memcpy(to, e->hpair[e->hcur] + h * o, h * sizeof *to);
			else
				memset(to, 0, h * sizeof *to);
		}
	}
	e->hcur = nx;
	return 0;
}

size_t
contact_enum_history_get(const struct contact_enum *e, long *ij, double *h)
{
	const struct nlist *nl = &e->nl;
	size_t i, k, m = 0, hs = e->hsize;
	int w;

	if (!hs || !nl->first)
		return 0;
	for (i = 0; i < e->n; i++)
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			const double *s = e->hpair[e->hcur] + hs * k;
			if (!row_nonzero(s, hs))
				continue;
			if (ij) {
				ij[2 * m] = (long)i, ij[2 * m + 1] = (long)nl->nbr[k];
				memcpy(h + hs * m, s, hs * sizeof *h);
			}
			m++;
		}
	for (i = 0; i < e->n; i++)
		for (w = 0; w < NWALLS; w++) {
			const double *s = e->hwall + hs * (NWALLS * i + (size_t)w);
			if (!row_nonzero(s, hs))
				continue;
			if (ij) {
				ij[2 * m] = (long)i, ij[2 * m + 1] = PACK_WALL(w);
				memcpy(h + hs * m, s, hs * sizeof *h);
			}
			m++;
		}
	return m;
}

int
contact_enum_history_set(struct contact_enum *e, const double *x, size_t m, const long *ij, const double *h)
{
	const struct nlist *nl = &e->nl;
	size_t s = 0, i, k, hs = e->hsize;

	if (contact_enum_update(e, x, 1))
		return -1;
	if (!hs)
		return m ? (msg_seterr("the enumerator keeps no history"), -1) : 0;
	memset(e->hpair[e->hcur], 0, hs * nl->npairs * sizeof *e->hpair[e->hcur]);
	memset(e->hwall, 0, hs * NWALLS * e->n * sizeof *e->hwall);
	memset(e->hwall_set, 0, e->n);
	/* the pairs: both sequences ascend by (i, j) */
	for (i = 0; i < e->n; i++)
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			while (s < m && !PACK_IS_WALL(ij[2 * s + 1]) &&
			       (ij[2 * s] < (long)i || (ij[2 * s] == (long)i && ij[2 * s + 1] < (long)nl->nbr[k])))
				s++;
			if (s < m && ij[2 * s] == (long)i && ij[2 * s + 1] == (long)nl->nbr[k])
				memcpy(e->hpair[e->hcur] + hs * k, h + hs * s, hs * sizeof *h);
		}
	while (s < m && !PACK_IS_WALL(ij[2 * s + 1]))
		s++;
	for (; s < m; s++) {
		long g = ij[2 * s], j = ij[2 * s + 1];
		if (!PACK_IS_WALL(j) || g < 0 || (size_t)g >= e->n) {
			msg_seterr("history slot %zu: not a grain and a wall after the pairs", s);
			return -1;
		}
		memcpy(e->hwall + hs * (NWALLS * (size_t)g + (size_t)PACK_WALL_INDEX(j)), h + hs * s, hs * sizeof *h);
		e->hwall_set[g] |= (unsigned char)(1u << PACK_WALL_INDEX(j));
	}
	return 0;
}

void
contact_enum_skin_auto(struct contact_enum *e, double skin_max)
{
	e->skin_max = skin_max;
	e->skin = skin_max / 6;
}

int
contact_enum_update(struct contact_enum *e, const double *x, int force)
{
	e->updates++;
	if (!force && !e->stale && e->nl.first && !nlist_stale(&e->nl, x, e->lo, e->hi, e->prune ? e->prune->extra : NULL))
		return 0;
	/* a list that went stale soon: the next one with twice the skin (contact_enum_skin_auto) */
	if (!force && !e->stale && e->nl.first && e->skin < e->skin_max && e->updates - e->updates_built < CONTACT_SKIN_GROW)
		e->skin = fmin(2 * e->skin, e->skin_max);
	e->updates_built = e->updates;
	if (e->hsize) {	/* the last list stays, for carrying the history over */
		struct nlist t = e->prev;
		e->prev = e->nl;
		e->nl = t;
	}
	if (e->prune && e->prune->prepare)
		e->prune->prepare(e->prune->ctx);
	if (nlist_build(&e->nl, x, e->r, e->n, e->lo, e->hi, e->rmax, e->skin, e->periodic, e->prune ? e->prune->keep : NULL,
	    e->prune ? e->prune->ctx : NULL))
		return -1;
	e->stale = 0;
	e->rebuilds++;
	return e->hsize ? carry_history(e) : 0;
}

/* Both directions of the half list, rows ascending (i's lower neighbours, from their rows
 * in grain order, then its own row). */
static int
full_rows(struct contact_enum *e)
{
	const struct nlist *nl = &e->nl;
	size_t i, k, n = e->n, *fill;

	free(e->full_first), free(e->full_nbr);
	e->full_first = calloc(n + 1, sizeof *e->full_first);
	e->full_nbr = malloc((2 * nl->npairs + 1) * sizeof *e->full_nbr);
	fill = calloc(n ? n : 1, sizeof *fill);
	if (!e->full_first || !e->full_nbr || !fill) {
		free(fill);
		msg_seterr("out of memory");
		return -1;
	}
	for (i = 0; i < n; i++)
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			e->full_first[i + 1]++;
			e->full_first[nl->nbr[k] + 1]++;
		}
	for (i = 0; i < n; i++)
		e->full_first[i + 1] += e->full_first[i];
	for (i = 0; i < n; i++)
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			size_t j = nl->nbr[k];
			e->full_nbr[e->full_first[i] + fill[i]++] = j;
			e->full_nbr[e->full_first[j] + fill[j]++] = i;
		}
	free(fill);
	e->full_builds = e->rebuilds;
	return 0;
}

int
contact_enum_columns(struct contact_enum *e)
{
	const struct nlist *nl = &e->nl;
	size_t i, k, n = e->n, *fill;

	if (e->col_first && e->col_builds == e->rebuilds)
		return 0;
	free(e->col_first), free(e->col_nbr), free(e->col_k), free(e->col_pos);
	e->col_first = calloc(n + 1, sizeof *e->col_first);
	e->col_nbr = malloc((nl->npairs + 1) * sizeof *e->col_nbr);
	e->col_k = malloc((nl->npairs + 1) * sizeof *e->col_k);
	e->col_pos = malloc((nl->npairs + 1) * sizeof *e->col_pos);
	fill = calloc(n ? n : 1, sizeof *fill);
	if (!e->col_first || !e->col_nbr || !e->col_k || !e->col_pos || !fill) {
		free(fill);
		free(e->col_first), free(e->col_nbr), free(e->col_k), free(e->col_pos);
		e->col_first = e->col_nbr = e->col_k = e->col_pos = NULL;
		msg_seterr("out of memory");
		return -1;
	}
	for (k = 0; k < nl->npairs; k++)
		e->col_first[nl->nbr[k] + 1]++;
	for (i = 0; i < n; i++)
		e->col_first[i + 1] += e->col_first[i];
	for (i = 0; i < n; i++)	/* rows in ascending i: each column fills ascending */
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			size_t j = nl->nbr[k], q = e->col_first[j] + fill[j]++;
			e->col_nbr[q] = i;
			e->col_k[q] = k;
			e->col_pos[k] = q;
		}
	free(fill);
	e->col_builds = e->rebuilds;
	return 0;
}

/* The record of grain i and wall w at x; 1 when it is visited in mode (never on a periodic
 * axis). */
static int
contact_wall(const struct contact_enum *e, const double *x, size_t i, int w, int mode, struct contact *c)
{
	int a = w / 2;
	double dist;

	if (e->periodic[a]) {
		c->hist = NULL;
		return 0;
	}
	dist = w % 2 ? e->hi[a] - x[3 * i + a] : x[3 * i + a] - e->lo[a];
	c->i = i;
	c->j = PACK_WALL(w);
	c->ri = e->r[i];
	c->rj = 0;
	c->h = e->r[i] - dist;
	c->hist = e->hsize ? e->hwall + (size_t)e->hsize * (NWALLS * i + (size_t)w) : NULL;
	if (mode == CONTACT_TOUCHING && c->h <= 0)
		return 0;
	c->d = dist;
	c->dx[0] = c->dx[1] = c->dx[2] = 0;
	c->dx[a] = w % 2 ? -dist : dist;
	return 1;
}

long
contact_foreach_grain(struct contact_enum *e, const double *x, size_t i, int mode, contact_fn fn, void *ctx)
{
	struct contact c;
	size_t k;
	long calls = 0;
	double len[3];
	int w;

	contact_periods(e, len);
	if ((!e->full_first || e->full_builds != e->rebuilds) && full_rows(e))
		return -2;
	for (k = e->full_first[i]; k < e->full_first[i + 1]; k++) {
		size_t j = e->full_nbr[k];
		double sum = e->r[i] + e->r[j];
		double dd = contact_branch_in(len, &c, x[3 * i], x[3 * i + 1], x[3 * i + 2], x, j, e->any_periodic);

		if (mode == CONTACT_TOUCHING && dd >= sum * sum)
			continue;
		c.i = i;
		c.j = (long)j;
		c.ri = e->r[i];
		c.rj = e->r[j];
		c.d = sqrt(dd);
		c.h = sum - c.d;
		c.hist = NULL;
		if (fn(&c, ctx))
			return -1;
		calls++;
	}
	for (w = 0; w < NWALLS; w++) {
		if (!contact_wall(e, x, i, w, mode, &c))
			continue;
		c.hist = NULL;
		if (fn(&c, ctx))
			return -1;
		calls++;
	}
	return calls;
}

void
contact_between(const struct pack *p, const double *x, size_t i, long j, struct contact *c)
{
	c->i = i;
	c->j = j;
	c->hist = NULL;
	if (PACK_IS_WALL(j)) {
		int w = PACK_WALL_INDEX(j), a = w / 2;
		c->d = pack_wall_distance(p->box, x + 3 * i, w);
		c->h = p->r[i] - c->d;
		c->dx[0] = c->dx[1] = c->dx[2] = 0;
		c->dx[a] = w % 2 ? -c->d : c->d;
		return;
	}
	c->dx[0] = x[3 * i] - x[3 * j], c->dx[1] = x[3 * i + 1] - x[3 * j + 1], c->dx[2] = x[3 * i + 2] - x[3 * j + 2];
	for (int a = 0; a < 3; a++)
		if (p->periodic[a]) {
			double L = p->box[3 + a] - p->box[a];
			c->dx[a] -= L * nearbyint(c->dx[a] / L);
		}
	c->d = sqrt(c->dx[0] * c->dx[0] + c->dx[1] * c->dx[1] + c->dx[2] * c->dx[2]);
	c->h = p->r[i] + p->r[j] - c->d;
}

/* Contact (i, j) before (k, l) in the enumerator's order: the grain pairs (i < j) by i then
 * j, then the walls by grain, then wall index (xlo xhi ylo yhi zlo zhi). */
static int
enum_before(size_t i, long j, size_t k, long l)
{
	if (PACK_IS_WALL(j) != PACK_IS_WALL(l))
		return PACK_IS_WALL(l);
	if (i != k)
		return i < k;
	return PACK_IS_WALL(j) ? PACK_WALL_INDEX(j) < PACK_WALL_INDEX(l) : j < l;
}

/* Whether p's history lines are strictly in the enumerator's order, each pair named i < j:
 * what a commit writes (contacts_store), so the lines and the contacts can be matched by one
 * merge instead of sorting the lines (the sort was 7 % of a frictional increment, which
 * matches the history after every settle pass).  Strictly ascending also means no pair twice,
 * so the merge finds the same line as pack_history_lookup. */
static int
history_in_enum_order(const struct pack *p)
{
	size_t k;

	for (k = 0; k < p->nc; k++) {
		const struct pack_contact *c = &p->c[k];
		if (!PACK_IS_WALL(c->j) && (size_t)c->j <= c->i)
			return 0;
		if (k > 0 && !enum_before(p->c[k - 1].i, p->c[k - 1].j, c->i, c->j))
			return 0;
	}
	return 1;
}

/* Attach history lines to geometric contacts by pair (gc in the enumerator's order). */
static int
match_history(const struct pack *p, struct geo_contacts *gc)
{
	long *t;
	size_t k, line = 0;

	if (p->nc == 0)
		return 0;
	if (history_in_enum_order(p)) {
		for (k = 0; k < gc->n; k++) {
			const struct geo_contact *g = &gc->c[k];
			while (line < p->nc && enum_before(p->c[line].i, p->c[line].j, g->i, g->j))
				line++;
			gc->c[k].hist = line < p->nc && p->c[line].i == g->i && p->c[line].j == g->j ? (long)line : -1;
		}
		return 0;
	}
	t = pack_history_keys(p);
	if (!t)
		return -1;
	for (k = 0; k < gc->n; k++)
		gc->c[k].hist = pack_history_lookup(t, p->nc, gc->c[k].i, gc->c[k].j);
	free(t);
	return 0;
}

/* The touching contacts of p at p->x, in the enumerator's order: grain-grain pairs are
 * collected first and the grain-wall ones after them, which is the order of the network. */
struct find_ctx {
	const struct pack *p;
	const struct contact_law *law;	/* the pack's: each contact's normal force */
	struct law_pack lk;
	struct geo_contacts *gc, walls;
};

static int
on_contact(const struct contact *c, void *vctx)
{
	struct find_ctx *ctx = vctx;
	struct geo_contact g;
	struct law_pair lp;

	/* a contact of the network carries a positive overlap and has a normal */
	if (!(c->h > 0) || c->d == 0)
		return 0;
	g.i = c->i;
	g.j = c->j;
	g.h = c->h;
	g.d = c->d;
	contact_normal(c, g.n);
	g.hist = -1;
	ctx->law->pair(ctx->law, &ctx->lk, g.i, g.j, &lp);
	ctx->law->normal(ctx->law, &lp, g.h, &g.P, NULL);
	return push(PACK_IS_WALL(c->j) ? &ctx->walls : ctx->gc, &g);
}

int
contacts_find_in(const struct pack *p, struct contact_enum *e, struct geo_contacts *gc)
{
	struct find_ctx ctx;
	size_t k;
	int rc = -1;

	gc->n = 0;
	ctx.p = p;
	ctx.gc = gc;
	if (!(ctx.law = contact_law_of_pack(p)))
		return -1;
	law_pack_bind(ctx.law, p, &ctx.lk);
	contacts_init(&ctx.walls);
	if (contact_enum_update(e, p->x, 0) || contact_foreach(e, p->x, CONTACT_TOUCHING, on_contact, &ctx) < 0)
		goto out;
	for (k = 0; k < ctx.walls.n; k++)
		if (push(gc, &ctx.walls.c[k]))
			goto out;
	rc = match_history(p, gc);
out:
	contacts_free(&ctx.walls);
	return rc;
}

int
contacts_find(const struct pack *p, struct geo_contacts *gc)
{
	struct contact_enum e;
	int rc = -1;

	if (contact_enum_init(&e, p->n, p->r, p->box, p->box + 3, p->periodic, 0, 0) == 0)
		rc = contacts_find_in(p, &e, gc);
	contact_enum_free(&e);
	return rc;
}

int
contacts_store(struct pack *p, int keep_history)
{
	return contacts_store_in(p, NULL, keep_history);
}

int
contacts_store_in(struct pack *p, struct contact_enum *e, int keep_history)
{
	return contacts_store_found(p, e, keep_history, NULL);
}

int
contacts_store_found(struct pack *p, struct contact_enum *e, int keep_history, struct geo_contacts *found)
{
	struct geo_contacts gc;
	struct pack_contact *old = NULL;
	size_t k, nold = 0;

	contacts_init(&gc);
	if (e ? contacts_find_in(p, e, &gc) : contacts_find(p, &gc))
		goto fail;
	if (keep_history && p->nc) {
		nold = p->nc;
		old = malloc(nold * sizeof *old);
		if (!old) {
			msg_seterr("out of memory");
			goto fail;
		}
		memcpy(old, p->c, nold * sizeof *old);
	}
	p->nc = 0;
	for (k = 0; k < gc.n; k++) {
		const struct geo_contact *g = &gc.c[k];
		struct pack_contact c = {g->i, g->j, g->P, {0, 0, 0}, 0};
		if (old && g->hist >= 0) {
			pack_contact_q0_on(&old[g->hist], g->i, c.Q0);
			c.M0 = old[g->hist].M0;
		}
		if (pack_add_contact(p, &c))
			goto fail;
	}
	free(old);
	if (found) {
		/* line k is contact k's: what match_history finds in the lines just written */
		for (k = 0; k < gc.n; k++)
			gc.c[k].hist = (long)k;
		contacts_free(found);
		*found = gc;
		return 0;
	}
	contacts_free(&gc);
	return 0;
fail:
	free(old);
	contacts_free(&gc);
	return -1;
}
