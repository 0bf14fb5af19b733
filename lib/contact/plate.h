/* SPDX-License-Identifier: GPL-3.0-or-later */
/* plate: the element contacts of an interaction between two spheroplates, or between a
 * spheroplate and a wall (physics.md §12, the platy-particle paper's §II B).
 *
 * A spheroplate (pack/shape.h) is a square core of side L swept by a sphere of radius r.
 * Two of them interact when the distance between their cores is below r_i + r_j.  The
 * interaction is made of element contacts (vertex-vertex, vertex-edge, vertex-face,
 * edge-edge, and the corners of a face-face or edge-face overlap); the interaction's
 * force is the sum of theirs (P eq. 5).  Each element contact k has the overlap
 * h_k = r_i + r_j - d_k, d_k the distance of the closest points of its two elements, and a
 * contact point; all share the interaction's unit normal n (from j to i), the direction of
 * the closest points of the two cores.
 *
 * The rules are non-redundant (plate.c states them; redundant ones give ~4.5 element contacts
 * per interaction where strict ones give 1.6, and make the interaction's stiffness jump in
 * multiples of k_n): a face-face or edge-face overlap gives the corners of its overlap
 * polygon, a line contact its two ends, anything else one element, and the closest pair of
 * the cores always has an element.  When the two cores themselves intersect (d = 0, or below
 * 1e-9 of the pair's size: the normal is then not defined by closest points) the penetration
 * depth and direction come from libccd (MPR) on the two spheroplates, as one element contact
 * of kind PLATE_CORE_OVERLAP.
 *
 * A sphere (half = 0) is a point core, its centre its one vertex: against a plate it gives one
 * element, the centre against the square (PLATE_FACE_VERTEX, PLATE_EDGE_VERTEX or
 * PLATE_VERTEX_VERTEX when j is the sphere; the mirrored kinds when i is); two spheres give
 * one PLATE_SPHERE element with exactly h = r_i + r_j - |x_i - x_j| and n along x_i - x_j
 * (e3 when the centres coincide): contact/sphere.c's, to which contact/narrow.h's table of shape
 * pairs, the consumers' way here, gives two spheres (plate_interaction on two cores of side 0
 * finds that element too, to round-off, by the rules for cores).
 *
 * Everything is in the caller's length unit.  No allocation; thread-safe. */
#ifndef QUSGM_PLATE_H
#define QUSGM_PLATE_H

#include "contact/contacts.h"

/* The most element contacts one interaction can have (two coplanar squares overlapping in an
 * octagon: 8 corners; with margin). */
#define PLATE_MAX_ELEMENTS 16

/* A spheroplate placed in the lab frame. */
struct plate_body {
	double x[3];	/* centre */
	double R[9];	/* rotation body -> lab, row-major (quat_to_matrix); column 2 is the face normal */
	double half;	/* L / 2, half the core's side (0: a sphere) */
	double r;	/* spheroradius */
};

enum plate_element_kind {
	PLATE_VERTEX_VERTEX, PLATE_VERTEX_EDGE, PLATE_EDGE_VERTEX, PLATE_VERTEX_FACE, PLATE_FACE_VERTEX,
	PLATE_EDGE_EDGE, PLATE_CORE_OVERLAP, PLATE_SPHERE	/* cores intersect (libccd); sphere-sphere */
};

struct plate_element {
	double h;	/* overlap r_i + r_j - d_k (> 0 for a contact) */
	double pi[3];	/* closest point on i's core (PLATE_CORE_OVERLAP: a point common to both cores) */
	double pj[3];	/* closest point on j's core (on the wall plane for a wall; as pi for a core overlap) */
	double p[3];	/* contact point, halfway between the two surfaces along n:
			 * (pi + pj)/2 + (r_j - r_i)/2 n (r_j = 0 for a wall), the centre of the lens
			 * when pi - pj is along n; for PLATE_CORE_OVERLAP, libccd's contact position */
	int kind;	/* enum plate_element_kind, i's element first */
};

/* Element e's contact point along n, halfway between the two surfaces:
 * (pi + pj)/2 + (r_j - r_i)/2 n (r_j = 0 for a wall); every shape's narrow phase sets it so. */
static inline void
plate_element_point(struct plate_element *e, const double n[3], double ri, double rj)
{
	int k;

	for (k = 0; k < 3; k++)
		e->p[k] = 0.5 * (e->pi[k] + e->pj[k]) + 0.5 * (rj - ri) * n[k];
}

struct plate_interaction {
	double n[3];	/* unit normal, from j to i (out of the wall for a wall) */
	double d;	/* distance of the two cores (0 when they intersect); for a wall, the signed
			 * distance of the core's nearest point, negative when it crosses the plane.
			 * When m = 0 it may be only a lower bound above r_i + r_j + gap (a separating
			 * axis told the pair apart without computing the distance). */
	int m;		/* element contacts, 0 .. PLATE_MAX_ELEMENTS */
	struct plate_element e[PLATE_MAX_ELEMENTS];
};

/* The element contacts between plates a (i) and b (j); b's centre is taken as given (the
 * caller applies the nearest periodic image).  Only elements with h > -gap are kept (gap >= 0:
 * 0 for contacts, a positive margin to see near ones).  Returns m (>= 0). */
int plate_interaction(const struct plate_body *a, const struct plate_body *b, double gap,
    struct plate_interaction *out);

/* The narrow phase kept between steps (the DEM's persistent element pairs, as Rockable and
 * exaDEM keep theirs): a cache word per pair names the features worth computing, bits 0-3
 * a's vertices against b's square, 4-7 b's against a's, 8 + 4 i + j a's edge i against b's
 * edge j, and PLATE_CACHE_CROSS when the cores were near enough to meet.  With build set the
 * interaction is computed from every feature and *cache made: the features nearer than
 * r_a + r_b + margin.  Without, only the cached features are computed, which gives
 * plate_interaction's elements (gap 0) to the bit as long as no point of either core has
 * moved, since the cache was made, by more than margin in all (the caller's bound: centre
 * displacement plus the turn's; plate.c says why).  Returns m. */
#define PLATE_CACHE_FEATURES 0xffffffu
#define PLATE_CACHE_CROSS (1u << 24)
int plate_interaction_cached(const struct plate_body *a, const struct plate_body *b, double margin, unsigned *cache,
    int build, struct plate_interaction *out);

/* The element contacts of plate a with the wall plane through point w0 with inward unit normal
 * wn (the wall's side is where wn points away from): the core's points nearest the plane,
 * i.e. the corners (a face or an edge lying on the wall gives its 4 or 2 corners, which is the
 * overlap polygon), each with h = r - (signed distance to the plane), kind PLATE_VERTEX_FACE;
 * a sphere gives its centre, kind PLATE_SPHERE.  n = wn.  Returns m. */
int plate_wall_interaction(const struct plate_body *a, const double w0[3], const double wn[3], double gap,
    struct plate_interaction *out);

/* A lower bound on the distance between the cores of a and b, from the six axes of their
 * frames (each face normal and edge direction: the gap between the cores' projections on
 * it), at about a tenth of plate_interaction's cost; 0 when no axis separates them.  Two
 * spheres: their centres' distance along the lab axes' largest. */
double plate_core_gap_bound(const struct plate_body *a, const struct plate_body *b);

/* The distance between the cores of a and b (0 when they intersect; an overlap of two coplanar
 * squares is found as a vertex in the other square, at distance 0 up to round-off) and the
 * closest points,
 * into pa and pb unless NULL: the reference the element rules are checked against. */
double plate_core_distance(const struct plate_body *a, const struct plate_body *b, double pa[3], double pb[3]);

#endif
