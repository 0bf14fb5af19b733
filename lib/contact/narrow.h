/* SPDX-License-Identifier: GPL-3.0-or-later */
/* narrow: the narrow phase dispatched by shape pair, as YADE dispatches its geometry functors
 * by the pair of shapes: one table entry per ordered pair of pack/shape.h's kinds, and one per
 * kind against a wall.  The consumers (the DEM engine, the measures) ask the table for the
 * element contacts of an interaction (contact/plate.h's struct plate_interaction: a normal and
 * up to PLATE_MAX_ELEMENTS element contacts) and never test a grain's side.
 *
 * Two spheres: contact/sphere.c's exact element (h = r_i + r_j - |x_i - x_j|), their bounding
 * spheres being the shapes (bounds_exact: no prune, no cache, no frames).  A pair with a
 * spheroplate: contact/plate.c's element rules, a sphere being a core of side 0 there.
 *
 * A new shape adds its kind's row and column here (narrow_test in tests/unit/test_shape.c
 * checks that every entry is filled) and its functions in its own file. */
#ifndef QUSGM_NARROW_H
#define QUSGM_NARROW_H

#include "contact/plate.h"
#include "pack/shape.h"

/* The narrow phase of grains of kinds (a, b), i's first. */
struct narrow_pair {
	/* The element contacts of a (i) and b (j) with h > -gap (plate_interaction's contract). */
	int (*interaction)(const struct plate_body *a, const struct plate_body *b, double gap,
	    struct plate_interaction *out);
	/* The same at gap 0 through a cache word kept between steps (plate_interaction_cached's
	 * contract; a pair with bounds_exact keeps none and writes 0). */
	int (*cached)(const struct plate_body *a, const struct plate_body *b, double margin, unsigned *cache,
	    int build, struct plate_interaction *out);
	/* A lower bound on the distance of the cores (the neighbour list's prune at a build);
	 * NULL with bounds_exact. */
	double (*gap_bound)(const struct plate_body *a, const struct plate_body *b);
	/* 1 when the bounding spheres are the shapes: the list's overlap is the interaction's,
	 * the list needs no prune, the pair no cache and the bodies no frames. */
	int bounds_exact;
};

/* The element contacts of grain a with the wall plane through w0 with inward unit normal wn
 * (plate_wall_interaction's contract). */
typedef int (*narrow_wall_fn)(const struct plate_body *a, const double w0[3], const double wn[3], double gap,
    struct plate_interaction *out);

/* The entry of kinds (a, b) and the wall function of kind k (kinds of the shape table). */
const struct narrow_pair *narrow_pair_of(enum shape_kind a, enum shape_kind b);
narrow_wall_fn narrow_wall_of(enum shape_kind k);

/* Grains as the contact enumerator (contacts.h) sees them through their bounding spheres, in
 * one length unit: centres x (3n), rotations R (9n, body -> lab), half sides and spheroradii
 * (n), their shape kinds (n, enum shape_kind), the box lo, hi whose walls are the planes
 * x_a = lo_a, hi_a. */
struct narrow_grains {
	const double *x, *R, *half, *r;
	const unsigned char *kind;
	const double *lo, *hi;
};

/* The interaction of contact record c (a pair, or a grain and a wall, from an enumerator over
 * the bounding radii) among grains g, by the table: the pair's with j's centre at x_i - c->dx
 * (its nearest image, written into xj), or the wall's with the wall's plane; gap as there.
 * Returns m, 0 when the bounding spheres meet but the grains do not. */
int narrow_record_interaction(const struct narrow_grains *g, const struct contact *c, double gap,
    struct plate_interaction *out, double xj[3]);

/* contact/sphere.c: two spheres, and a sphere on a wall (its centre against the plane). */
int sphere_pair_interaction(const struct plate_body *a, const struct plate_body *b, double gap,
    struct plate_interaction *out);
int sphere_pair_cached(const struct plate_body *a, const struct plate_body *b, double margin, unsigned *cache,
    int build, struct plate_interaction *out);
int sphere_wall_interaction(const struct plate_body *a, const double w0[3], const double wn[3], double gap,
    struct plate_interaction *out);

#endif
