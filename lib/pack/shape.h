/* SPDX-License-Identifier: GPL-3.0-or-later */
/* shape: the grains' shapes, spheres and spheroplates (physics.md §12).
 *
 * A spheroplate is the Minkowski sum of a square plate (its core) of side L and a sphere of
 * radius r, the spheroradius; L = 0 is a sphere of radius r.  In a pack (pack-format.md) a
 * grain's radius column is r and its 'side' column L, so a sphere is a spheroplate of side 0
 * and every contact law sees r_i + r_j - d with d the distance of the cores.
 *
 * Platyness eta = (R - r)/R, aspect ratio lambda = R/r = 1/(1 - eta).  The platy-particle
 * paper's figure that defines the outer radius R is lost; two readings:
 *   SHAPE_R_EDGE   R reaches the middle of the core's outer edge: L = 2 (R - r);
 *   SHAPE_R_CORNER R reaches the core's corner:                   L = sqrt(2) (R - r).
 * The default is SHAPE_R_EDGE: under it the paper's initial grid spacing 2 sqrt(2) R is the
 * bounding diameter of a thin plate (r -> 0: the corner sits at sqrt(2) R), so that grid is
 * the densest on which randomly turned plates cannot overlap, which is why one would choose
 * it; under SHAPE_R_CORNER the bounding diameter is 2 R and the grid would be loose by
 * sqrt(2) for no reason; and packgen's compacted packs reach their densest near eta 0.3
 * under it, where P's Fig. 8 peaks, and near 0.4 under SHAPE_R_CORNER (share/doc/
 * spheroplates.md has the numbers).  A pack stores r and L, so it does not depend on the reading; only
 * converting eta (packgen --platyness, packinfo's report) does.
 *
 * Body frame: the core lies in the plane z = 0 with edges along x and y, |x|, |y| <= L/2;
 * the face normal is e3.  Moments of inertia about the centre, in the body frame: I_normal
 * about e3, I_inplane about e1 and e2 (equal by the square's symmetry).
 *
 * The shapes' table (SHAPES below, as contact/law.h's CONTACT_LAWS is the laws'): one row per
 * kind of grain, and per row the answers to every question that a consumer would otherwise
 * take by testing a grain's side: its name in a pack's shape column (pack-format.md), its
 * volume, principal moments, bounding radius, the body-frame box that holds it (drawing), and
 * whether its orientation is observable.  A grain's kind is pack_grain_shape (pack/pack.h);
 * the consumers ask shape_of(kind).  The narrow phase, a function of two shapes, is the
 * contact layer's table by shape pair (contact/narrow.h), indexed by these kinds. */
#ifndef QUSGM_SHAPE_H
#define QUSGM_SHAPE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum shape_radius { SHAPE_R_EDGE = 0, SHAPE_R_CORNER = 1 };

extern const char *const shape_radius_names[2];	/* "edge", "corner" */

/* The core side L and the spheroradius r of a plate of outer radius R and platyness eta in
 * [0, 1). */
double shape_plate_side(double R, double eta, enum shape_radius conv);
double shape_spheroradius(double R, double eta);
/* The outer radius R and the platyness of a grain of spheroradius r and side L. */
double shape_outer_radius(double r, double L, enum shape_radius conv);
double shape_platyness(double r, double L, enum shape_radius conv);
/* Radius of the smallest sphere about the centre that holds the grain: r + L / sqrt(2). */
double shape_bounding_radius(double r, double L);
/* Volume V = 2 r L^2 + 2 pi r^2 L + 4/3 pi r^3. */
double shape_volume(double r, double L);
/* Principal moments of inertia over the density (m^5):
 * I_normal/rho  = r L^4/3 + (2 pi/3) r^2 L^3 + (8/3 + 2 pi/3) r^3 L^2 + (3 pi/2) r^4 L + (8 pi/15) r^5,
 * I_inplane/rho = r L^4/6 + (pi/3) r^2 L^3 + (2 + pi/3) r^3 L^2 + (5 pi/4) r^4 L + (8 pi/15) r^5. */
void shape_inertia(double r, double L, double *Inormal, double *Iinplane);

/* The table of the shapes, one row each: X(ENUM, id), the kind SHAPE_ENUM and its row
 * shape_id (struct shape_ops), whose name is the kind's in a pack.  The first row is a
 * sphere, the kind of a grain of a pack without the shape columns. */
#define SHAPES(X) \
	X(SPHERE, sphere) \
	X(SPHEROPLATE, spheroplate)

#define SHAPE_KIND_ENUM(K, id) SHAPE_##K,
enum shape_kind { SHAPES(SHAPE_KIND_ENUM) SHAPE_NKINDS };
#undef SHAPE_KIND_ENUM

/* A shape's operations, of its spheroradius r and core side L (m, or any unit: each is
 * homogeneous in r and L). */
struct shape_ops {
	const char *name;	/* the kind's name in a pack's shape column and packgen --shape */
	enum shape_kind kind;
	/* 1 when its orientation is observable (a face normal: the nematic order, the fabric's
	 * normals, packview's tilt, packexport's boxes); 0 for a sphere, whose frame the DEM
	 * keeps as the lab's and whose pack orientation stays as it is. */
	int oriented;
	/* Its type in packexport's LAMMPS dump of a pack with plates (2 marks a sphere, for
	 * OVITO's per-type shape; the phase adds 2). */
	int lammps_type;
	/* Volume (m^3), principal moments over the density (m^5: about the body axis e3 and
	 * about e1, e2) and the radius of the smallest sphere about the centre that holds it. */
	double (*volume)(double r, double L);
	void (*inertia)(double r, double L, double *Inormal, double *Iinplane);
	double (*bounding_radius)(double r, double L);
	/* The half-extents along the body axes of the box that holds it (what packexport's VTK
	 * draws for it, and LAMMPS's shapex/y/z, twice these). */
	void (*extent)(double r, double L, double half[3]);
	/* Whether side L suits the kind (a sphere: L = 0; a spheroplate: L > 0), for the
	 * reader's check of a shape column against the side column. */
	int (*side_ok)(double L);
};

#define SHAPE_EXTERN(K, id) extern const struct shape_ops shape_##id;
SHAPES(SHAPE_EXTERN)
#undef SHAPE_EXTERN

/* The rows of the table, in its order (shape_table[k]->kind == k). */
extern const struct shape_ops *const shape_table[SHAPE_NKINDS];
/* The row of kind k (a kind of the table). */
const struct shape_ops *shape_of(enum shape_kind k);
/* The row named name ("sphere", "spheroplate"), NULL when none is. */
const struct shape_ops *shape_find(const char *name);
/* The kind of a grain of side L in a pack without a shape column (pack-format.md): a sphere
 * for L = 0, a spheroplate for L > 0.  The one place that reads a kind from a side. */
enum shape_kind shape_kind_of_side(double L);
/* The names of the table's kinds, "sphere, spheroplate", into buf (truncated to size). */
void shape_names(char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
