/* SPDX-License-Identifier: GPL-3.0-or-later */
/* export: packs in other programs' formats, and spheres from plain "x y z r" text.
 *
 * Owns the writers behind packexport and the reader behind packimport:
 *  - VTK XML PolyData (.vtp, ascii): grains as points with one vertex cell each, and
 *    contacts as two-point lines; a .vtm multiblock file that names the two; spheroplates
 *    as closed boxes of six quadrilaterals;
 *  - LAMMPS: a dump frame (ITEM: ... ATOMS id type x y z radius) and a data file
 *    (atom_style sphere);
 *  - YADE's SpherePack text: "x y z r" lines, optionally after "##PERIODIC:: Lx Ly Lz";
 *  - the reader of such "x y z r" text, strict like packio (file:line errors; through
 *    base/lines.h, so lines of any length, .gz works and a truncated .gz is an error).
 * Every number goes through num_format, so the output is a function of the pack alone.
 * Writers return 0, or -1 with the error slot set (a write error, a value the target format
 * cannot hold).  SI units throughout, as in the pack. */
#ifndef QUSGM_EXPORT_H
#define QUSGM_EXPORT_H

#include <stdio.h>
#include "pack/pack.h"

/* In the contacts .vtp, id2 of a grain-wall contact is the wall: -1 xlo, -2 xhi, -3 ylo,
 * -4 yhi, -5 zlo, -6 zhi (PACK_WALL(w) for w in pack.h's order). */
#define EXPORT_VTK_WALL_ID(w) PACK_WALL(w)

/* Grains: points at the centres, PointData id (Int64), radius, E, nu (Float64) and, for a
 * pack with the phase column, phase (Int32, 0 mineral, 1 hydrate), one vertex cell per
 * point. */
int export_vtp_grains(const struct pack *p, FILE *fp);
/* Spheroplates (pack/shape.h): each grain a closed box, 8 points and 6 quadrilaterals
 * (outward, counter-clockwise), the body-frame box |x|, |y| <= L/2 + r, |z| <= r turned by
 * R(q) about the centre: the plate's extent, L + 2 r wide and 2 r thick (a sphere, L = 0, is
 * its bounding cube).  CellData, one value per grain on each of its faces: id (Int64),
 * side, radius (r), E, nu and normal (R(q) e3, 3 components; Float64), phase (Int32)
 * for a pack with the phase column, and glued (Int32: 0 free, 1 + w glued to wall w) for a
 * pack with the glued column. */
int export_vtp_plates(const struct pack *p, FILE *fp);
/* Contacts found from the positions (contacts_find): a line from centre i to centre j, or
 * from the centre to the contact point on the wall; CellData id1, id2, normal_force (the
 * Hertz force P, N) and overlap (m). */
int export_vtp_contacts(const struct pack *p, FILE *fp);
/* The interactions of a plate pack (measure_plate_contact_list, the plate engine's element
 * contacts): a line from centre i to centre j (its nearest periodic image) or to the
 * overlap-weighted foot on a wall; CellData id1, id2 (a wall as above), normal (from j to i,
 * 3 components), and, when the pack records its stiffness (meta kn), normal_force (the
 * elements' k_n h, N), tangential_force (the contact line's Q0 on i, 3 components, N) and
 * its magnitude tangential_force_magnitude, force (the whole force on i, 3 components);
 * then overlap (the largest element overlap, m) and elements (Int32).  The force network of
 * a plate pack, for ParaView. */
int export_vtp_plate_contacts(const struct pack *p, FILE *fp);
/* Tables in the convention of share/doc/tables.md (a '# ' header of tab-separated names with
 * units in brackets, one row per line), for gnuplot, awk and numpy.  Grains: id x y z r E nu
 * rho, phase with the phase column, and contacts, the grain's contacts found from the
 * positions (grains and walls).  Contacts (contacts_find): id1 id2 (id2 a wall as in the
 * .vtp: -1 xlo .. -6 zhi), x1 y1 z1 the centre of grain 1, x2 y2 z2 the other end (the
 * centre of grain 2 as seen from grain 1, across a periodic boundary too, or the contact
 * point on the wall), normal_force (N) and overlap (m). */
int export_tsv_grains(const struct pack *p, FILE *fp);
int export_tsv_contacts(const struct pack *p, FILE *fp);
/* A vtkMultiBlockDataSet naming the two .vtp files, given relative to the .vtm. */
int export_vtm(FILE *fp, const char *grains_vtp, const char *contacts_vtp);

/* One LAMMPS dump frame; box bounds "ff ff ff" (walls).  Atom ids are the grain ids,
 * which LAMMPS wants positive: a pack holding id 0 is refused.  Spheres: "id type x y z
 * radius", type 1, or 2 for a hydrate grain (the phase column).  A pack with a spheroplate
 * (pack_first_plate): "id type x y z quatw quati quatj quatk shapex shapey shapez", the
 * quaternion as stored and the full extents L + 2 r, L + 2 r, 2 r along the body axes; type 1
 * for a plate, 2 for a sphere (L = 0), 2 more for a hydrate grain. */
int export_lammps_dump(const struct pack *p, FILE *fp, long timestep);
/* A LAMMPS data file for atom_style sphere: "id type diameter density x y z", type 1; a pack
 * with the phase column has 2 atom types, type 2 a hydrate grain. */
int export_lammps_data(const struct pack *p, FILE *fp);

/* "x y z r" lines, nothing else; with periodic, a first line "##PERIODIC:: Lx Ly Lz" with
 * the box lengths (YADE's periodic cell). */
int export_xyzr(const struct pack *p, FILE *fp, int periodic);

/* Read "x y z r" lines (blank lines and '#' comments allowed) from fp into p, initialised
 * here: ids 1..N in file order, E = nu = rho = 0 for the caller to fill.  With box NULL,
 * p->box is the tightest box holding every sphere; otherwise it is box, and every centre must
 * lie in it.  YADE's cell line "##PERIODIC:: Lx Ly Lz" makes every axis periodic, the box of
 * those lengths (with box NULL: [0, L] where it holds the centres, else one from the lowest
 * centre, so that export_xyzr writes the same lengths back; with box, its lengths must be
 * those).  0, or -1 with "name:line: what" in the slot. */
int xyzr_read(FILE *fp, const char *name, const double *box, struct pack *p);

#endif
