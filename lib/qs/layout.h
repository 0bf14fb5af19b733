/* SPDX-License-Identifier: GPL-3.0-or-later */
/* layout: the unknowns of a quasi-static equilibrium, and the one place that knows their order.
 *
 * Frictionless: the grain centres, 3N lengths (m), grain i at 3i.  With friction: the centres
 * followed by the small rotation vectors of the increment times the radius, R_i Omega_i (3N
 * lengths, m), grain i's at 3N + 3i.  Everything that walks a vector of unknowns grain by
 * grain (the minimisers' step cap, the residual, the terms' gradients) goes through these. */
#ifndef QUSGM_LAYOUT_H
#define QUSGM_LAYOUT_H

#include <math.h>
/* lanes.h is the library's own (law.h says why): not in a user's program */
#ifdef QUSGM_BUILD
#include "base/lanes.h"
#endif
#include "base/vec3.h"
#include <stddef.h>

struct qs_layout {
	size_t n;	/* grains */
	int rotations;	/* the scaled rotations follow the centres */
	size_t dim;	/* 3n or 6n */
};

static inline void
layout_set(struct qs_layout *l, size_t n, int rotations)
{
	l->n = n;
	l->rotations = rotations;
	l->dim = (rotations ? 6 : 3) * n;
}

/* Grain i's centre (or its translation, or its force) in a vector of unknowns v. */
static inline double *
layout_centre(const struct qs_layout *l, double *v, size_t i)
{
	(void)l;
	return v + 3 * i;
}

/* Grain i's scaled rotation R_i Omega_i (or its moment over R_i); NULL without rotations. */
static inline double *
layout_rotation(const struct qs_layout *l, double *v, size_t i)
{
	return l->rotations ? v + 3 * l->n + 3 * i : NULL;
}

static inline const double *
layout_rotation_c(const struct qs_layout *l, const double *v, size_t i)
{
	return l->rotations ? v + 3 * l->n + 3 * i : NULL;
}

/* Grain i's part of v as one length: its translation, or with rotations the larger of its
 * translation and its scaled rotation.  One square root, of the larger square: a correctly
 * rounded sqrt is monotone, so this is the larger of the two lengths to the bit (and a NaN
 * square is dropped for the other as max_or_num drops a NaN length). */
static inline double
layout_grain_len_sq(const struct qs_layout *l, const double *v, size_t i)
{
	const double *t = v + 3 * i, *o = layout_rotation_c(l, v, i);
	double sq = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];

	if (o)
		sq = max_or_num(sq, o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
	return sq;
}

static inline double
layout_grain_len(const struct qs_layout *l, const double *v, size_t i)
{
	return sqrt(layout_grain_len_sq(l, v, i));
}

#if defined(QUSGM_BUILD) && LANES_OK
/* The lengths of grains i and i + 1, one square root instruction for both (lanes.h). */
static inline v2d
layout_grain_len_pair(const struct qs_layout *l, const double *v, size_t i)
{
	return V2_SQRT(((v2d){layout_grain_len_sq(l, v, i), layout_grain_len_sq(l, v, i + 1)}));
}
#endif

/* x += f v on grain i's unknowns. */
static inline void
layout_grain_axpy(const struct qs_layout *l, double *x, const double *v, size_t i, double f)
{
	size_t k;

	for (k = 3 * i; k < 3 * i + 3; k++)
		x[k] += f * v[k];
	if (l->rotations)
		for (k = 3 * l->n + 3 * i; k < 3 * l->n + 3 * i + 3; k++)
			x[k] += f * v[k];
}

#endif
