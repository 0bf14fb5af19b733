/* SPDX-License-Identifier: GPL-3.0-or-later */
/* nlist: Verlet lists over the cell grid (see nlist.h). */
#include "contact/nlist.h"
#include "base/par.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
nlist_init(struct nlist *nl)
{
	memset(nl, 0, sizeof *nl);
	cell_init(&nl->grid);
}

void
nlist_free(struct nlist *nl)
{
	free(nl->first);
	free(nl->nbr);
	free(nl->xb);
	free(nl->tcnt);
	cell_free(&nl->grid);
	memset(nl, 0, sizeof *nl);
}

/* The build, on T threads (one below PAR_MIN grains): each thread meets the pairs of its own
 * run of cells (cell_for_pairs_in) and counts them per row in its own column of tcnt (no two
 * threads write one counter); the rows' offsets are the columns' sums, a thread's place in a
 * row the counts of the threads before it, and the rows are sorted afterwards, so the list is
 * the same bytes for any thread count. */
struct pass_ctx {
	struct nlist *nl;
	unsigned *cnt;		/* this thread's column of tcnt */
	int pass;
	nlist_keep_fn keep;
	void *keep_ctx;
};

static int
on_pair(size_t i, size_t j, double dx[3], double d2, void *vctx)
{
	struct pass_ctx *c = vctx;

	(void)d2;
	if (c->keep && !c->keep(c->keep_ctx, i, j, dx))
		return 0;
	if (c->pass == 0)
		c->cnt[i]++;
	else
		c->nl->nbr[c->nl->first[i] + c->cnt[i]++] = (uint32_t)j;
	return 0;
}

static int
find_pairs(struct nlist *nl, const double *x, const double *r, double skin, int T, nlist_keep_fn keep, void *keep_ctx)
{
	size_t n = nl->n, i, need = (size_t)T * (n ? n : 1);
	int fail = 0;

	if (need > nl->tcap) {
		free(nl->tcnt);
		nl->tcnt = malloc(need * sizeof *nl->tcnt);
		nl->tcap = nl->tcnt ? need : 0;
		if (!nl->tcnt) {
			msg_seterr("out of memory for the neighbour list");
			return -1;
		}
	}
	memset(nl->tcnt, 0, need * sizeof *nl->tcnt);
#pragma omp parallel num_threads(T) if (T > 1)
	{
		/* the team OpenMP gave, which may be smaller than asked for: its threads cover the cells */
		size_t TT = (size_t)par_team(), t = (size_t)par_tid(), nc = nl->grid.ncells;
		struct pass_ctx c = {nl, nl->tcnt + t * n, 0, keep, keep_ctx};
		size_t c0 = nc * t / TT, c1 = nc * (t + 1) / TT, k;

		cell_for_pairs_in(&nl->grid, c0, c1, x, r, skin, on_pair, &c);
#pragma omp barrier
#pragma omp single
		{
			for (i = 0; i < n; i++) {
				size_t sum = 0;
				for (k = 0; k < TT; k++) {
					unsigned v = nl->tcnt[k * n + i];
					nl->tcnt[k * n + i] = (unsigned)sum;	/* the place of thread k in row i */
					sum += v;
				}
				nl->first[i + 1] = nl->first[i] + sum;
			}
			if (nl->first[n] > nl->cap || !nl->nbr) {
				size_t cap = nl->first[n] + nl->first[n] / 4 + 16;
				free(nl->nbr);
				nl->nbr = malloc(cap * sizeof *nl->nbr);
				nl->cap = nl->nbr ? cap : 0;
				fail = !nl->nbr;
			}
		}
		if (!fail) {
			c.pass = 1;
			cell_for_pairs_in(&nl->grid, c0, c1, x, r, skin, on_pair, &c);
		}
	}
	if (fail) {
		msg_seterr("out of memory for the neighbour list");
		return -1;
	}
	return 0;
}

int
nlist_build(struct nlist *nl, const double *x, const double *r, size_t n, const double lo[3], const double hi[3],
    double rmax, double skin, const int *periodic, nlist_keep_fn keep, void *keep_ctx)
{
	size_t i, k;
	int threads = n >= PAR_MIN ? par_threads() : 1;

	if (n > UINT32_MAX) {
		msg_seterr("%zu grains: the neighbour list holds at most 2^32 - 1", n);
		return -1;
	}
	if (n != nl->n || !nl->first) {
		free(nl->first), free(nl->xb);
		nl->first = malloc((n + 1) * sizeof *nl->first);
		nl->xb = malloc(3 * n * sizeof *nl->xb);
		nl->n = n;
		if (!nl->first || !nl->xb) {
			msg_seterr("out of memory for the neighbour list");
			return -1;
		}
	}
	nl->skin = skin;
	nl->rmax = rmax;
	if (cell_build(&nl->grid, x, n, lo, hi, 2 * rmax + skin, periodic))
		return -1;
	nl->first[0] = 0;
	if (find_pairs(nl, x, r, skin, threads, keep, keep_ctx))
		return -1;
	/* rows sorted by j: deterministic order of summation, and merges of two lists */
#pragma omp parallel for schedule(static) private(k) if (threads > 1)
	for (i = 0; i < n; i++)
		for (k = nl->first[i] + 1; k < nl->first[i + 1]; k++) {
			size_t v = nl->nbr[k], q = k;
			while (q > nl->first[i] && nl->nbr[q - 1] > v) {
				nl->nbr[q] = nl->nbr[q - 1];
				q--;
			}
			nl->nbr[q] = (uint32_t)v;
		}
	nl->npairs = nl->first[n];
	memcpy(nl->xb, x, 3 * n * sizeof *x);
	memcpy(nl->blo, lo, sizeof nl->blo);
	memcpy(nl->bhi, hi, sizeof nl->bhi);
	nl->builds++;
	return 0;
}

int
nlist_stale(const struct nlist *nl, const double *x, const double lo[3], const double hi[3], const double *extra)
{
	double maxm = 0, shrink = 0, s[3];
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		s[a] = (hi[a] - lo[a]) / (nl->bhi[a] - nl->blo[a]);
		shrink = fmax(shrink, 1 - s[a]);
	}
	/* a largest value is exact in any order: threads (base/par.h) cannot change it.  Without
	 * extra, the squares are compared and one root taken; with it, a root per grain. */
#pragma omp parallel for schedule(static) reduction(max : maxm) if (nl->n >= PAR_MIN)
	for (i = 0; i < nl->n; i++) {
		double e2 = 0, m;
		int b;
		for (b = 0; b < 3; b++) {
			double ref = lo[b] + (nl->xb[3 * i + b] - nl->blo[b]) * s[b];
			double e = x[3 * i + b] - ref;
			e2 += e * e;
		}
		m = extra ? sqrt(e2) + extra[i] : e2;
		if (m > maxm)
			maxm = m;
	}
	if (!extra)
		maxm = sqrt(maxm);
	return 2 * maxm + shrink * (2 * nl->rmax + nl->skin) > nl->skin;
}
