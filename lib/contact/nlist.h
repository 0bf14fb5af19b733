/* SPDX-License-Identifier: GPL-3.0-or-later */
/* nlist: Verlet neighbour lists of polydisperse spheres, built in O(N) with the cell grid.
 *
 * A list holds every pair i < j closer than r_i + r_j + skin at the positions and box of
 * the last build, as rows (CSR) sorted by j.  It stays exact while no pair can have closed
 * the skin since: twice the largest non-affine displacement plus the affine shortening of
 * the longest listed pair below the skin (positions that follow a changing box affinely do
 * not count as displacement).  nlist_stale() answers that; the caller rebuilds.
 *
 * A caller whose grains are not spheres may leave out, at the build, the pairs whose shapes
 * (not just their bounding spheres) stay farther apart than the skin (a keep function), and
 * then counts in the staleness what each grain's points may have moved beyond its centre
 * since the build (extra: turning). */
#ifndef QUSGM_NLIST_H
#define QUSGM_NLIST_H

#include <stddef.h>
#include <stdint.h>
#include "contact/cell.h"

#ifdef __cplusplus
extern "C" {
#endif

struct nlist {
	size_t n;
	size_t *first;		/* n + 1 row offsets */
	uint32_t *nbr;		/* neighbour j of each pair, rows sorted (4 bytes: the walks over the
				 * list read it every evaluation and DEM step; nlist_build refuses
				 * packs of 2^32 grains or more) */
	size_t npairs, cap;
	double skin, rmax;
	double *xb;		/* positions at the build */
	double blo[3], bhi[3];	/* box at the build */
	struct cell_grid grid;
	unsigned *tcnt;		/* the threads' pair counts per row (nlist.c), tcap of them */
	size_t tcap;
	long builds;
};

void nlist_init(struct nlist *nl);
void nlist_free(struct nlist *nl);
/* Whether pair i < j (dx = x_i - x_j, its nearest image), whose spheres are within the skin,
 * is listed: called from the build's threads, twice per pair, with the same answer each time. */
typedef int (*nlist_keep_fn)(void *ctx, size_t i, size_t j, const double dx[3]);
/* Build for n spheres at x with radii r (largest rmax) in the box [lo, hi], periodic along
 * the axes flagged in periodic (NULL: none; see cell_build); keep (NULL: every pair) leaves
 * pairs out.  0 or -1. */
int nlist_build(struct nlist *nl, const double *x, const double *r, size_t n, const double lo[3],
    const double hi[3], double rmax, double skin, const int *periodic, nlist_keep_fn keep, void *keep_ctx);
/* 1 when a pair may have come within range since the build: twice the largest of a grain's
 * non-affine displacement plus extra[i] (NULL: 0), plus the affine shortening, over the skin. */
int nlist_stale(const struct nlist *nl, const double *x, const double lo[3], const double hi[3],
    const double *extra);

#ifdef __cplusplus
}
#endif

#endif
