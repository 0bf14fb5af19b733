/* SPDX-License-Identifier: GPL-3.0-or-later */
/* narrow: the shape-pair table of the narrow phase (narrow.h). */
#include "contact/narrow.h"

#include <string.h>

/* Every ordered pair of kinds, rows i's kind, columns j's (the shape table's order). */
static const struct narrow_pair narrow_pairs[SHAPE_NKINDS][SHAPE_NKINDS] = {
	[SHAPE_SPHERE] = {
		[SHAPE_SPHERE] = {sphere_pair_interaction, sphere_pair_cached, NULL, 1},
		[SHAPE_SPHEROPLATE] = {plate_interaction, plate_interaction_cached, plate_core_gap_bound, 0},
	},
	[SHAPE_SPHEROPLATE] = {
		[SHAPE_SPHERE] = {plate_interaction, plate_interaction_cached, plate_core_gap_bound, 0},
		[SHAPE_SPHEROPLATE] = {plate_interaction, plate_interaction_cached, plate_core_gap_bound, 0},
	},
};

static const narrow_wall_fn narrow_walls[SHAPE_NKINDS] = {
	[SHAPE_SPHERE] = sphere_wall_interaction,
	[SHAPE_SPHEROPLATE] = plate_wall_interaction,
};

const struct narrow_pair *
narrow_pair_of(enum shape_kind a, enum shape_kind b)
{
	return &narrow_pairs[a][b];
}

narrow_wall_fn
narrow_wall_of(enum shape_kind k)
{
	return narrow_walls[k];
}

static void
grain_body(const struct narrow_grains *g, size_t i, const double *x, struct plate_body *b)
{
	memcpy(b->x, x, sizeof b->x);
	memcpy(b->R, g->R + 9 * i, sizeof b->R);
	b->half = g->half[i];
	b->r = g->r[i];
}

int
narrow_record_interaction(const struct narrow_grains *g, const struct contact *c, double gap,
    struct plate_interaction *out, double xj[3])
{
	struct plate_body a, b;
	size_t j;
	int k;

	grain_body(g, c->i, g->x + 3 * c->i, &a);
	if (PACK_IS_WALL(c->j)) {
		int w = PACK_WALL_INDEX(c->j), ax = w / 2;
		double w0[3] = {0, 0, 0}, wn[3] = {0, 0, 0};

		w0[ax] = w % 2 ? g->hi[ax] : g->lo[ax];
		wn[ax] = w % 2 ? -1 : 1;
		return narrow_wall_of(g->kind[c->i])(&a, w0, wn, gap, out);
	}
	j = (size_t)c->j;
	for (k = 0; k < 3; k++)
		xj[k] = g->x[3 * c->i + k] - c->dx[k];
	grain_body(g, j, xj, &b);
	return narrow_pair_of(g->kind[c->i], g->kind[j])->interaction(&a, &b, gap, out);
}
