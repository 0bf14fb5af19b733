/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cell: uniform grid neighbour search (see cell.h). */
#include "contact/cell.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
cell_init(struct cell_grid *g)
{
	memset(g, 0, sizeof *g);
}

void
cell_free(struct cell_grid *g)
{
	free(g->start);
	free(g->idx);
	free(g->cell_of);
	memset(g, 0, sizeof *g);
}

static int
clampi(long v, int n)
{
	return v < 0 ? 0 : v >= n ? n - 1 : (int)v;
}

/* The cell index of coordinate v along axis a: clamped into the grid, or wrapped on a
 * periodic axis. */
static int
cell_coord(const struct cell_grid *g, int a, double v)
{
	long c = (long)floor((v - g->lo[a]) * g->inv[a]);

	if (g->periodic[a]) {
		c %= g->nc[a];
		return (int)(c < 0 ? c + g->nc[a] : c);
	}
	return clampi(c, g->nc[a]);
}

int
cell_build(struct cell_grid *g, const double *x, size_t n, const double lo[3], const double hi[3], double edge,
    const int *periodic)
{
	size_t ncells = 1, k;
	int a;

	for (a = 0; a < 3; a++) {
		g->periodic[a] = periodic && periodic[a];
		g->len[a] = hi[a] - lo[a];
	}

	for (;;) {
		ncells = 1;
		for (a = 0; a < 3; a++) {
			double len = hi[a] - lo[a];
			double m = floor(len / edge);

			if (!(m >= 1))
				m = 1;
			if (m > 2048)
				m = 2048;
			g->nc[a] = (int)m;
			g->lo[a] = lo[a];
			g->inv[a] = m / (len > 0 ? len : 1);
			ncells *= (size_t)m;
		}
		/* a sparse pack in a large box: coarser cells keep memory O(N) */
		if ((double)ncells <= 8.0 * (double)n + 4096)
			break;
		edge *= 1.25;
	}
	for (a = 0; a < 3; a++)
		if (g->periodic[a] && g->nc[a] < 3) {
			/* no unit: the DEM engines call this in their scaled units */
			msg_seterr("the box is too short along periodic axis %c (length %.6g) for grains of this size: it "
			    "must hold three interaction distances", "xyz"[a], g->len[a]);
			return -1;
		}
	if (ncells != g->ncells || !g->start) {
		free(g->start);
		g->start = malloc((ncells + 1) * sizeof *g->start);
		g->ncells = ncells;
	}
	if (n > g->cap) {
		free(g->idx);
		free(g->cell_of);
		g->idx = malloc(n * sizeof *g->idx);
		g->cell_of = malloc(n * sizeof *g->cell_of);
		g->cap = n;
	}
	if (!g->start || (n && (!g->idx || !g->cell_of))) {
		msg_seterr("out of memory for the neighbour grid");
		return -1;
	}
	g->n = n;
	memset(g->start, 0, (ncells + 1) * sizeof *g->start);
	for (k = 0; k < n; k++) {
		int c[3];
		for (a = 0; a < 3; a++)
			c[a] = cell_coord(g, a, x[3 * k + a]);
		g->cell_of[k] = ((size_t)c[2] * (size_t)g->nc[1] + (size_t)c[1]) * (size_t)g->nc[0] + (size_t)c[0];
		g->start[g->cell_of[k] + 1]++;
	}
	for (k = 0; k < ncells; k++)
		g->start[k + 1] += g->start[k];
	{
		size_t *fill = malloc(ncells * sizeof *fill);
		if (!fill) {
			msg_seterr("out of memory for the neighbour grid");
			return -1;
		}
		memcpy(fill, g->start, ncells * sizeof *fill);
		for (k = 0; k < n; k++)
			g->idx[fill[g->cell_of[k]]++] = k;
		free(fill);
	}
	return 0;
}

static void
min_image(const struct cell_grid *g, double d[3])
{
	int a;

	for (a = 0; a < 3; a++)
		if (g->periodic[a] && !(2 * fabs(d[a]) < g->len[a] && d[a] != 0))	/* as contact_min_image */
			d[a] -= g->len[a] * nearbyint(d[a] / g->len[a]);
}

long
cell_for_pairs(const struct cell_grid *g, const double *x, const double *r, double skin, cell_pair_fn fn,
    void *ctx)
{
	return cell_for_pairs_in(g, 0, g->ncells, x, r, skin, fn, ctx);
}

long
cell_for_pairs_in(const struct cell_grid *g, size_t c0, size_t c1, const double *x, const double *r, double skin,
    cell_pair_fn fn, void *ctx)
{
	long visited = 0;
	int any_periodic = g->periodic[0] || g->periodic[1] || g->periodic[2];
	int nx = g->nc[0], ny = g->nc[1], nz = g->nc[2];
	size_t c;

	for (c = c0; c < c1 && c < g->ncells; c++) {
		int cx = (int)(c % (size_t)nx), cy = (int)(c / (size_t)nx % (size_t)ny), cz = (int)(c / ((size_t)nx * ny));
		int dz, dy, dx;

		/* half stencil: this cell and the 13 neighbours "after" it */
		for (dz = 0; dz <= 1; dz++)
			for (dy = (dz ? -1 : 0); dy <= 1; dy++)
				for (dx = (dz || dy ? -1 : 0); dx <= 1; dx++) {
					int ox = cx + dx, oy = cy + dy, oz = cz + dz;
					size_t o, p, q;

					if (g->periodic[0])
						ox = (ox + nx) % nx;
					if (g->periodic[1])
						oy = (oy + ny) % ny;
					if (g->periodic[2])
						oz = oz % nz;
					if (ox < 0 || oy < 0 || ox >= nx || oy >= ny || oz >= nz)
						continue;
					o = ((size_t)oz * ny + oy) * nx + ox;
					for (p = g->start[c]; p < g->start[c + 1]; p++) {
						size_t i = g->idx[p];
						size_t q0 = o == c ? p + 1 : g->start[o];
						for (q = q0; q < g->start[o + 1]; q++) {
							size_t j = g->idx[q];
							double d[3], d2, cut;
							d[0] = x[3 * i] - x[3 * j];
							d[1] = x[3 * i + 1] - x[3 * j + 1];
							d[2] = x[3 * i + 2] - x[3 * j + 2];
							if (any_periodic)
								min_image(g, d);
							d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
							cut = r[i] + r[j] + skin;
							if (d2 >= cut * cut)
								continue;
							visited++;
							if (i < j) {
								if (fn(i, j, d, d2, ctx))
									return -1;
							} else {
								d[0] = -d[0];
								d[1] = -d[1];
								d[2] = -d[2];
								if (fn(j, i, d, d2, ctx))
									return -1;
							}
						}
					}
				}
	}
	return visited;
}
