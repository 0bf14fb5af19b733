/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cell: a uniform grid of cells for finding overlapping spheres in O(N).
 *
 * The cell edge is at least the largest interaction distance (2 r_max + skin), so every
 * pair closer than that lies in the same or an adjacent cell.  Polydisperse radii are
 * handled by sizing cells for the largest pair; for the papers' 0.07-0.13 mm radii that
 * costs under a factor 2 against per-size grids.  Grains outside the grid's box are
 * clamped into the boundary cells, so a grain that has moved out of the box is still found.
 * The grid stores grain indices sorted by cell (counting sort): memory is O(N + cells). */
#ifndef QUSGM_CELL_H
#define QUSGM_CELL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

struct cell_grid {
	double lo[3], inv[3];	/* origin and 1/cell edge per axis */
	int periodic[3];	/* wrap along this axis: cells, and branch vectors to the nearest image */
	double len[3];		/* box lengths (the periods) */
	int nc[3];		/* cells per axis */
	size_t ncells;
	size_t *start;		/* ncells + 1 offsets into idx */
	size_t *idx;		/* grain indices sorted by cell */
	size_t *cell_of;	/* cell of each grain */
	size_t n, cap;
};

void cell_init(struct cell_grid *g);
void cell_free(struct cell_grid *g);
/* Bin n points x[3n] in the box [lo, hi] with cells no smaller than edge; periodic (3 flags,
 * or NULL) wraps the axes where it is set, and such an axis must hold at least three cells
 * (a box length of three interaction distances), so that no pair is met twice.  0 on
 * success, -1 with msg_seterr. */
int cell_build(struct cell_grid *g, const double *x, size_t n, const double lo[3], const double hi[3],
    double edge, const int *periodic);

/* Calls fn(i, j, ctx) once for every pair i < j whose centres are closer than cut(i, j),
 * where cut = r_i + r_j + skin, with dx = x_i - x_j (its nearest image on periodic axes).  Returns the number of pairs visited, or -1 on fn error. */
typedef int (*cell_pair_fn)(size_t i, size_t j, double dx[3], double d2, void *ctx);
long cell_for_pairs(const struct cell_grid *g, const double *x, const double *r, double skin,
    cell_pair_fn fn, void *ctx);
/* The same for the pairs found from cells c0 <= c < c1 (linear index, x fastest) with the
 * half stencil: a pair is met from the cell of one of its grains only, so disjoint ranges
 * that cover the grid meet every pair once (the threads of nlist_build). */
long cell_for_pairs_in(const struct cell_grid *g, size_t c0, size_t c1, const double *x, const double *r,
    double skin, cell_pair_fn fn, void *ctx);

#ifdef __cplusplus
}
#endif

#endif
