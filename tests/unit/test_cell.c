/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_cell: the cell grid finds exactly the pairs an O(N^2) search finds.
 *
 * Random polydisperse packs (radii uniform in 0.7-1.3) at several volume fractions, from a
 * sparse gas (where the grid coarsens its cells) to heavily overlapping packs, with a few
 * grains placed outside the grid's box (clamped into the boundary cells).  A pair is "close"
 * when d^2 < (r_i + r_j + skin)^2, computed the same way in both searches, so the sets must be
 * identical: no tolerance.  Each pair must come once, as i < j, with dx = x_i - x_j. */
#include "contact/cell.h"
#include "unit.h"

#include <gsl/gsl_rng.h>
#include <stdlib.h>
#include <string.h>

struct seen {
	size_t n;
	unsigned char *hits;	/* n * n counts */
	const double *x;
	long calls, bad_order, bad_dx;
};

static int
on_pair(size_t i, size_t j, double dx[3], double d2, void *vctx)
{
	struct seen *s = vctx;
	int a;
	double e2 = 0;

	s->calls++;
	if (!(i < j) || j >= s->n) {
		s->bad_order++;
		return 0;
	}
	for (a = 0; a < 3; a++) {
		if (dx[a] != s->x[3 * i + a] - s->x[3 * j + a])
			s->bad_dx++;
		e2 += dx[a] * dx[a];
	}
	if (e2 != d2)
		s->bad_dx++;
	if (s->hits[i * s->n + j] < 255)
		s->hits[i * s->n + j]++;
	return 0;
}

static int
stop_at_third(size_t i, size_t j, double dx[3], double d2, void *vctx)
{
	long *n = vctx;

	(void)i, (void)j, (void)dx, (void)d2;
	return ++*n == 3;
}

static void
one_case(gsl_rng *rng, size_t n, double phi, double outside, double skin)
{
	double *x = malloc(3 * n * sizeof *x), *r = malloc(n * sizeof *r);
	double vol = 0, side, lo[3], hi[3], rmax = 0;
	struct cell_grid g;
	struct seen s;
	size_t i, j, missing = 0, extra = 0, twice = 0, expected = 0;
	long visited;
	int a;

	for (i = 0; i < n; i++) {
		r[i] = 0.7 + 0.6 * gsl_rng_uniform(rng);
		vol += 4.0 / 3.0 * 3.141592653589793 * r[i] * r[i] * r[i];
		rmax = r[i] > rmax ? r[i] : rmax;
	}
	side = cbrt(vol / phi);
	for (a = 0; a < 3; a++) {
		lo[a] = -0.25 * side + a;	/* not at the origin, and not a cube */
		hi[a] = lo[a] + side * (1 + 0.1 * a);
	}
	for (i = 0; i < n; i++)
		for (a = 0; a < 3; a++) {
			double len = hi[a] - lo[a];
			/* a fraction 'outside' of the grains lies up to a third of the box outside it */
			double u = gsl_rng_uniform(rng) < outside ? gsl_rng_uniform(rng) * 1.6 - 0.3
								    : gsl_rng_uniform(rng);
			x[3 * i + a] = lo[a] + u * len;
		}

	cell_init(&g);
	memset(&s, 0, sizeof s);
	s.n = n;
	s.x = x;
	s.hits = calloc(n * n, 1);
	CHECK(cell_build(&g, x, n, lo, hi, 2 * rmax + skin, NULL) == 0, "cell_build n=%zu phi=%g", n, phi);
	visited = cell_for_pairs(&g, x, r, skin, on_pair, &s);
	for (i = 0; i < n; i++)
		for (j = i + 1; j < n; j++) {
			double d[3], d2, cut = r[i] + r[j] + skin;
			for (a = 0; a < 3; a++)
				d[a] = x[3 * i + a] - x[3 * j + a];
			d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
			if (d2 < cut * cut) {
				expected++;
				if (s.hits[i * n + j] == 0)
					missing++;
				else if (s.hits[i * n + j] > 1)
					twice++;
			} else if (s.hits[i * n + j]) {
				extra++;
			}
		}
	CHECK(expected > 0 && missing == 0 && extra == 0,
	    "n=%zu phi=%g outside=%g skin=%g: the same %zu pairs as the O(N^2) search (%zu missing, %zu extra, cells %d %d %d)",
	    n, phi, outside, skin, expected, missing, extra, g.nc[0], g.nc[1], g.nc[2]);
	CHECK(twice == 0 && s.bad_order == 0, "n=%zu phi=%g skin=%g: each pair once, as i < j (%zu twice, %ld not i < j)",
	    n, phi, skin, twice, s.bad_order);
	CHECK(s.bad_dx == 0, "n=%zu phi=%g skin=%g: dx = x_i - x_j and d2 = |dx|^2 (%ld wrong)", n, phi, skin, s.bad_dx);
	CHECK(visited == s.calls && (size_t)visited == expected, "n=%zu phi=%g skin=%g: returns the number of pairs (%ld)",
	    n, phi, skin, visited);
	{
		/* the threads' split (nlist_build): disjoint runs of cells that cover the grid
		 * meet every pair exactly once between them */
		size_t cuts[4] = {0, g.ncells / 3, 2 * g.ncells / 3, g.ncells}, q;
		size_t again = 0, lost = 0;
		long split = 0;
		unsigned char *first = s.hits;

		s.hits = calloc(n * n, 1);
		for (q = 0; q < 3; q++)
			split += cell_for_pairs_in(&g, cuts[q], cuts[q + 1], x, r, skin, on_pair, &s);
		for (i = 0; i < n * n; i++) {
			again += s.hits[i] > 1;
			lost += first[i] != s.hits[i];
		}
		CHECK(split == visited && again == 0 && lost == 0,
		    "n=%zu phi=%g skin=%g: three runs of cells meet the same %ld pairs once (%ld met, %zu twice, %zu differ)",
		    n, phi, skin, visited, split, again, lost);
		free(first);
	}
	cell_free(&g);
	free(s.hits);
	free(x);
	free(r);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	static const double phis[] = {0.005, 0.1, 0.45, 0.64, 1.2, 3.0};
	size_t k;

	gsl_rng_set(rng, 20240611);
	for (k = 0; k < sizeof phis / sizeof phis[0]; k++) {
		one_case(rng, 1500, phis[k], 0.05, 0);
		one_case(rng, 1500, phis[k], 0.05, 0.35);
	}
	/* small and degenerate grids: a box smaller than one cell, two grains, all outside */
	one_case(rng, 40, 2.0, 0.0, 0.1);
	one_case(rng, 2, 0.3, 0.0, 10.0);
	one_case(rng, 300, 0.5, 1.0, 0.2);
	{
		/* a callback error stops the walk and is reported as -1 */
		double x[12] = {0, 0, 0, 0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5}, r[4] = {1, 1, 1, 1};
		double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
		struct cell_grid g;
		long calls = 0, ret;

		cell_init(&g);
		cell_build(&g, x, 4, lo, hi, 2, NULL);
		ret = cell_for_pairs(&g, x, r, 0, stop_at_third, &calls);
		CHECK(ret == -1 && calls == 3, "callback error: -1 after the third pair (%ld, %ld calls)", ret, calls);
		cell_free(&g);
	}
	gsl_rng_free(rng);
	return unit_summary();
}
