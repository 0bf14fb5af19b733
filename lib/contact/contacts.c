/* contacts: geometric contact detection (see contacts.h). */
#include "contact/contacts.h"
#include "contact/cell.h"
#include "contact/hertz.h"
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

void
contacts_moduli(const struct pack *p, const struct geo_contact *c, double *Es, double *Rs)
{
	size_t i = c->i;

	if (PACK_IS_WALL(c->j)) {
		*Es = hertz_Estar(p->E[i], p->nu[i], p->wall_E, p->wall_nu);
		*Rs = p->r[i];
	} else {
		size_t j = (size_t)c->j;
		*Es = hertz_Estar(p->E[i], p->nu[i], p->E[j], p->nu[j]);
		*Rs = hertz_Rstar(p->r[i], p->r[j]);
	}
}

void
contacts_wall_plane(const struct pack *p, int w, double n[3], double *pos)
{
	int axis = w / 2, high = w % 2;

	n[0] = n[1] = n[2] = 0;
	n[axis] = high ? -1.0 : 1.0;
	*pos = p->box[axis + 3 * high];
}

struct find_ctx {
	const struct pack *p;
	struct geo_contacts *gc;
};

static int
on_pair(size_t i, size_t j, double dx[3], double d2, void *vctx)
{
	struct find_ctx *ctx = vctx;
	const struct pack *p = ctx->p;
	struct geo_contact c;
	double d = sqrt(d2), Es, Rs;

	c.i = i;
	c.j = (long)j;
	c.h = p->r[i] + p->r[j] - d;
	if (!(c.h > 0) || d == 0)
		return 0;
	c.d = d;
	c.n[0] = dx[0] / d;
	c.n[1] = dx[1] / d;
	c.n[2] = dx[2] / d;
	c.hist = -1;
	contacts_moduli(p, &c, &Es, &Rs);
	c.P = hertz_force(Es, Rs, c.h);
	return push(ctx->gc, &c);
}

static int
cmp_gc(const void *a, const void *b)
{
	const struct geo_contact *x = a, *y = b;

	if (x->i != y->i)
		return x->i < y->i ? -1 : 1;
	return x->j < y->j ? -1 : x->j > y->j;
}

static int
cmp_hist(const void *a, const void *b)
{
	const long *x = a, *y = b;

	if (x[0] != y[0])
		return x[0] < y[0] ? -1 : 1;
	return x[1] < y[1] ? -1 : x[1] > y[1];
}

/* Attach history lines to geometric contacts by pair. */
static int
match_history(const struct pack *p, struct geo_contacts *gc)
{
	long *t;
	size_t k;

	if (p->nc == 0)
		return 0;
	t = malloc(p->nc * 3 * sizeof *t);
	if (!t) {
		msg_seterr("out of memory");
		return -1;
	}
	for (k = 0; k < p->nc; k++) {
		long i = (long)p->c[k].i, j = p->c[k].j;
		if (j >= 0 && j < i) {
			long s = i;
			i = j;
			j = s;
		}
		t[3 * k] = i;
		t[3 * k + 1] = j;
		t[3 * k + 2] = (long)k;
	}
	qsort(t, p->nc, 3 * sizeof *t, cmp_hist);
	for (k = 0; k < gc->n; k++) {
		size_t lo = 0, hi = p->nc;
		long key[2] = {(long)gc->c[k].i, gc->c[k].j};
		while (lo < hi) {
			size_t mid = (lo + hi) / 2;
			if (cmp_hist(t + 3 * mid, key) < 0)
				lo = mid + 1;
			else
				hi = mid;
		}
		if (lo < p->nc && cmp_hist(t + 3 * lo, key) == 0)
			gc->c[k].hist = t[3 * lo + 2];
	}
	free(t);
	return 0;
}

int
contacts_find(const struct pack *p, struct geo_contacts *gc)
{
	struct cell_grid g;
	struct find_ctx ctx = {p, gc};
	double rmax = 0, lo[3], hi[3];
	size_t i, ngg;
	int a, w;

	gc->n = 0;
	for (i = 0; i < p->n; i++)
		if (p->r[i] > rmax)
			rmax = p->r[i];
	for (a = 0; a < 3; a++) {
		lo[a] = p->box[a];
		hi[a] = p->box[a + 3];
	}
	cell_init(&g);
	if (cell_build(&g, p->x, p->n, lo, hi, 2 * rmax) ||
	    cell_for_pairs(&g, p->x, p->r, 0, on_pair, &ctx) < 0) {
		cell_free(&g);
		return -1;
	}
	cell_free(&g);
	ngg = gc->n;
	if (ngg > 1)	/* qsort(NULL, 0, ...) is undefined; gc->c is NULL before the first contact */
		qsort(gc->c, ngg, sizeof *gc->c, cmp_gc);
	for (i = 0; i < p->n; i++)
		for (w = 0; w < NWALLS; w++) {
			struct geo_contact c;
			double n[3], pos, Es, Rs;
			int axis = w / 2;

			contacts_wall_plane(p, w, n, &pos);
			c.d = (p->x[3 * i + axis] - pos) * n[axis];
			c.h = p->r[i] - c.d;
			if (!(c.h > 0))
				continue;
			c.i = i;
			c.j = PACK_WALL(w);
			memcpy(c.n, n, sizeof n);
			c.hist = -1;
			contacts_moduli(p, &c, &Es, &Rs);
			c.P = hertz_force(Es, Rs, c.h);
			if (push(gc, &c))
				return -1;
		}
	return match_history(p, gc);
}

int
contacts_store(struct pack *p, int keep_history)
{
	struct geo_contacts gc;
	struct pack_contact *old = NULL;
	size_t k, nold = 0;

	contacts_init(&gc);
	if (contacts_find(p, &gc))
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
			memcpy(c.Q0, old[g->hist].Q0, sizeof c.Q0);
			if (old[g->hist].i != g->i) {	/* the old line named the pair "j i" */
				c.Q0[0] = -c.Q0[0];
				c.Q0[1] = -c.Q0[1];
				c.Q0[2] = -c.Q0[2];
			}
			c.M0 = old[g->hist].M0;
		}
		if (pack_add_contact(p, &c))
			goto fail;
	}
	free(old);
	contacts_free(&gc);
	return 0;
fail:
	free(old);
	contacts_free(&gc);
	return -1;
}
