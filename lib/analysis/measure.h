/* SPDX-License-Identifier: GPL-3.0-or-later */
/* measure: what a pack says about itself (physics.md §7-8).
 *
 * Porosity, coordination (grain plus wall contacts per grain), grains under 4 contacts,
 * rattlers (the grains removed by iteratively removing every grain with fewer than 4 contacts
 * among the remaining ones and the walls, 2 in a frictional pack: measure_rattler_rule), radius
 * statistics, the largest overlap over the smaller radius; and, when contacts carry forces,
 * wall stresses (normal contact forces on the two walls of an axis, averaged, over the wall
 * area), the volume-averaged (Love-Weber) stress, normal-force statistics, the force-balance
 * residual (largest per-grain |F_i| / largest contact force on i, that force floored at
 * MEASURE_RESIDUAL_FLOOR times the mean normal contact force as the minimisers do (functional.h;
 * residual_strict has no floor), with moments |M_i|/R_i
 * counted the same way, its median over the grains, and the mean unbalanced-force ratio
 * mean|F_i| / mean|f_c|), the
 * sliding ratio from the contact history, and the fabric tensor <n n> of grain-grain
 * contacts with its anisotropy a = 15/2 sqrt(3/2 d:d), d = <n n> - I/3.
 *
 * The bulk (measure_bulk): the porosity and coordination of an inner box, the box shrunk by a
 * margin from each wall, because the walls order the grains next to them (a layer of looser
 * packing, fewer contacts) and the box values mix that layer in with the bulk.
 *
 * Public API (share/doc/library.md): the measures only read the pack.  A struct
 * geo_contacts (contact/contacts.h) is the caller's: contacts_init it once, pass it to
 * measure_pack (which fills it with the pack's contacts, reusing its memory) and
 * contacts_free it at the end.  The struct pack_measures is filled by value (no pointer in
 * it); has_forces says whether the force measures (stresses, forces, residual) mean
 * anything: without contacts carrying force, ignore them (packinfo prints them as absent),
 * and sliding_ratio and the bulk fields not computed are NaN.  Functions return
 * 0, or -1 with the error slot of base/msg.h set (out of memory). */
#ifndef QUSGM_MEASURE_H
#define QUSGM_MEASURE_H

#include "analysis/fabric.h"
#include "contact/contacts.h"
#include "pack/pack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Floor of a grain's largest contact force in the residual (contacts.h). */
#define MEASURE_RESIDUAL_FLOOR CONTACT_RESIDUAL_FLOOR

struct pack_measures {
	size_t grains, contacts_gg, contacts_gw, under4, rattlers, history, stale_history;
	double volume, porosity, coordination, coordination_nr;
	double r_mean, r_std, r_min, r_max, overlap_max;
	int has_forces;
	double sig_wall[3];	/* Pa, compression positive */
	double sig_lw[6];	/* xx yy zz xy xz yz */
	double sigma_c;		/* tr(sig_wall)/3 */
	double P_mean, P_max;
	double residual_max, residual_mean;
	double residual_strict;	/* residual_max without the floor */
	double residual_median;	/* the median over the grains of residual_max's ratio */
	double sliding_ratio;	/* NaN when no contact carries friction history */
	double fabric[6], fabric_anisotropy;
	unsigned rattler_min_contacts;	/* the rule of rattlers and coordination_nr: 4 or 2 */
	/* measure_bulk's, NaN (bulk_grains 0) until it runs or when the margin leaves no inner box */
	int has_bulk;
	double bulk_margin;	/* m, on each side with a wall */
	double bulk_box[6];	/* the inner box, xlo ylo zlo xhi yhi zhi (m) */
	double bulk_porosity;	/* 1 - (grain volume inside the inner box) / (its volume) */
	double bulk_coordination;	/* mean contacts of the grains centred in it; NaN without any */
	size_t bulk_grains;	/* grains whose centre is in the inner box */
};

/* The hydrate grains of a pack with the phase column (pack.h, pack-format.md "The phase
 * column"), what packinfo reports after the porosities: the count, their fraction of the grain
 * volume V_h / V_grains, the saturation S = V_h / (V_box - V_mineral) with the hydrate counted
 * as pore space (pack_hydrate_saturation), and the porosity that way, 1 - V_mineral / V_box.
 * Grain volumes as in pack_grain_volume, overlaps not subtracted.  Without the column,
 * has_phase 0 and every value NaN: the pack says nothing about its phases. */
struct hydrate_measures {
	int has_phase;
	double grains, volume_fraction, saturation, porosity_hydrate_as_pore;
};
void measure_hydrate(const struct pack *p, struct hydrate_measures *h);

/* Fills m, all but the bulk (measure_bulk); gc receives the contacts (may be reused by the
 * caller).  0 or -1. */
int measure_pack(const struct pack *p, struct geo_contacts *gc, struct pack_measures *m);
/* The same, finding the contacts through the caller's enumerator over p (contacts_find_in). */
int measure_pack_in(const struct pack *p, struct contact_enum *e, struct geo_contacts *gc, struct pack_measures *m);
/* Per-grain contact counts (grain + wall) over gc; counts has p->n entries. */
void measure_coordination(const struct pack *p, const struct geo_contacts *gc, unsigned *counts);
/* The fewest contacts a grain needs not to be a rattler in pack p.  Frictionless, 4: a sphere
 * held by normal forces alone, which all pass through its centre, needs d + 1 = 4 of them
 * (three balance only when they lie in one plane, and then nothing holds the grain across
 * it).  Frictional, 2: with tangential forces two contacts can hold a grain (two equal and
 * opposite forces along the line through the contact points, each within its friction cone)
 * and so can three, so the rule of 4 would call load-bearing grains rattlers; a grain with 0
 * or 1 contact carries no load in either kind.  A pack is frictional when one of its contact
 * lines carries a tangential force Q0 or a torsional couple M0: its equilibrium holds grains
 * by friction (frictionalize, loadtest).  A pack with mu > 0 whose lines carry only P0
 * (densify's) is held by normal forces alone: frictionless. */
unsigned measure_rattler_rule(const struct pack *p);
/* Marks rattlers (1) in flag[p->n]: the grains removed by iteratively removing every grain
 * with fewer than min_contacts contacts among the remaining ones and the walls.  Returns their
 * number. */
size_t measure_rattlers(const struct pack *p, const struct geo_contacts *gc, unsigned min_contacts, unsigned char *flag);
/* The bulk measures of m (measure.h's fields bulk_*) over the inner box: p's box shrunk by
 * margin (m, >= 0) on each side with a wall (none on a periodic axis), or by one mean grain
 * diameter 2 m->r_mean when margin is NaN.  gc and m are measure_pack's of p.  A margin of 0
 * is the box itself: bulk_porosity and bulk_coordination are then porosity and coordination
 * exactly (wall overlaps counted in, as there).  The grain volume is each sphere's exact
 * volume inside the inner box (measure_sphere_box_volume), overlaps between grains not
 * subtracted; bulk_coordination counts the contacts of the grains centred in the inner box as
 * coordination counts them, with their neighbours outside it and walls.  When the margin
 * leaves no inner box (twice the margin >= a box length between walls) has_bulk is 0 and the
 * fields but bulk_margin stay NaN.  0, or -1 (msg_seterr: out of memory, margin < 0). */
int measure_bulk(const struct pack *p, const struct geo_contacts *gc, double margin, struct pack_measures *m);
/* The volume (m^3) of the sphere of radius r about the origin inside the box lo[a] <= x_a <=
 * hi[a] (bounds relative to the centre; -INFINITY and INFINITY for an open side), to rounding
 * (1e-13 relative).  NaN (msg_seterr) when out of memory. */
double measure_sphere_box_volume(double r, const double lo[3], const double hi[3]);

/* What a pack with spheroplates (pack/shape.h) says about itself.  From the grains: its
 * packing fraction with the plates' volume, the spheroradius r and core side L, the
 * platyness eta = (R - r)/R and aspect ratio R/r under a convention for R (the pack's meta
 * plate-radius, pack_plate_radius), and the nematic order of the face normals.  Every
 * grain counts in the statistics (a sphere is a plate of side 0, eta 0, aspect 1); only
 * the plates (side > 0), whose face normal exists, count in the nematic order.
 *
 * From the interactions (contact/plate.h: the element contacts of a pair, or of a grain and
 * a wall, found as dem/engine finds them): the coordination Z, interactions per grain
 * (grain-grain counted at both ends, plus grain-wall), as the platy-particle paper's Fig. 12
 * counts it (an interaction of several element contacts is one); the floating grains, with
 * 0 or 1 interaction (P §IV: they carry no load); the element contacts, and the interactions
 * by their number m of elements (1: a point; 2: mostly a line, an edge along an edge or a
 * face; 3 or more: a face-face or edge-face overlap polygon).
 *
 * Forces, when the pack records its normal stiffness (meta kn, N/m: packgen writes it): each
 * element's elastic normal force k_n h (the dashpot is zero at rest) along the interaction's
 * normal, plus the tangential spring's force of the pair's contact line (Q0, engine_write_back;
 * zero without a line).  The wall stress is the normal force on the two walls of an axis,
 * averaged, over the wall area (NaN on a periodic axis); the Love-Weber stress sums
 * (x_i - x_j) (x) F over the pairs (j's nearest image) and (x_i - x_w) (x) F over the wall
 * contacts, x_w the element's foot on the wall plane (the tangential force at the
 * overlap-weighted foot), over the box volume, compression positive: it equals the wall
 * stress for a pack in equilibrium (its diagonal: the off-diagonal terms of an uneven wall
 * pressure have no wall counterpart).  As in the sphere report, force_mean and force_max are
 * the normal force P (the elements' k_n h summed) of an interaction, and residual_mean is
 * mean|F_i| over the grains with an interaction over the mean |F| of an interaction (packgen's
 * rest criterion takes the mean over all grains).
 *
 * Glued grains (the glued column, pack_set_glue: the shear's wall layers) are parts of the
 * walls: coordination and floating count every grain, coordination_free and floating_free the
 * free ones (interactions of a free grain with a free grain, a glued grain or a wall, counted
 * at the free grain's end: the shear's Z), and the descriptors (fabric) are over the pairs
 * of two free grains and the free plates' normals.  Without the column every grain is free. */
struct plate_measures {
	size_t grains, plates;
	double porosity, packing_fraction;
	double r_mean, r_std, r_min, r_max;		/* m */
	double side_mean, side_std, side_min, side_max;	/* m */
	double eta_mean, eta_min, eta_max;		/* min and max NaN when all grains share eta */
	double aspect_mean, aspect_min, aspect_max;	/* likewise */
	double nematic, director[3];			/* NaN without plates */
	size_t contacts_gg, contacts_gw, elements, floating;
	size_t by_elements[3];				/* interactions of 1, 2, >= 3 elements */
	double coordination, floating_fraction, elements_per_interaction;
	size_t glued, floating_free;			/* glued grains; free ones with 0 or 1 interaction */
	double coordination_free, floating_fraction_free;
	int has_forces;					/* meta kn present: the rest is set, else NaN */
	double sig_wall[3], sig_lw[6];			/* Pa, compression positive; xx yy zz xy xz yz */
	double force_mean, force_max;			/* normal force P of an interaction, N */
	double residual_mean;
	/* the platy-particle paper's descriptors (analysis/fabric.h) over the free pairs, under
	 * their own stress (P eq. 7, the pairs' branch (x) force over the box volume); a pair is
	 * at the Coulomb limit when |F_t| >= 0.99 mu F_n (mu the pack's).  Without forces the
	 * force descriptors, K_s, p, q and eq. 28 are NaN. */
	struct fabric_desc fabric;
};

int measure_plates(const struct pack *p, enum shape_radius conv, struct plate_measures *m);
/* Whether pack p is measured as plates (measure_plates) rather than as Hertz spheres
 * (measure_pack): 1 when it has a spheroplate or its law (contact_law_of_pack) is not
 * Hertz-Mindlin (the plate engine's 'linear', spheres at platyness 0 too), whose forces are
 * that law's; 0 otherwise; -1 (the error slot set) for a contact-law key no law has. */
int measure_is_plate_pack(const struct pack *p);

/* The measures grain by grain, for a viewer (analysis/view.h): what the reports sum over
 * the grains, kept per grain, and the contacts with their normal forces.  Spheres: the
 * contacts and forces of measure_pack (Hertz normal forces and the contact lines'
 * tangential forces and couples within Coulomb's limits); plates (measure_is_plate_pack):
 * the interactions and forces of measure_plates.  z counts contacts as coordination does
 * (a grain-grain contact at both ends, walls too; of plates the interactions); fmax is the
 * largest contact force |f| on the grain (normal plus tangential, N), 0 without contact;
 * residual the grain's unbalance over fmax floored at MEASURE_RESIDUAL_FLOOR times the mean
 * normal force, as residual_max takes it (spheres: max(|F_i|, |M_i|/R_i); plates: |F_i|),
 * NaN for a grain without contact or a pack without forces.  link: every contact, grain
 * pairs first (i < j) then walls (j = PACK_WALL(w)), as found, with its normal force P (N;
 * 0 without forces).  has_forces: the forces mean something (spheres: some contact
 * carries one; plates: the pack records its stiffness kn). */
struct measure_link {
	size_t i;
	long j;		/* grain index or PACK_WALL(w) */
	double P;	/* normal force (N) */
};

struct grain_forces {
	size_t n;
	unsigned *z;
	double *fmax, *residual;
	struct measure_link *link;
	size_t nlink, caplink;
	int has_forces;
};

/* Fills g (its arrays allocated here; grain_forces_free them).  0, or -1 (msg_seterr). */
int measure_grain_forces(const struct pack *p, struct grain_forces *g);
void grain_forces_free(struct grain_forces *g);
/* One interaction of measure_plates, for a force network (packexport's contacts of plates). */
struct plate_contact {
	size_t i;
	long j;			/* a grain index, or a wall PACK_WALL(w) */
	double a[3], b[3];	/* i's centre; j's centre (its nearest periodic image) or, for a wall,
				 * the overlap-weighted foot of the element contacts on its plane (m) */
	double n[3];		/* unit normal, from j to i */
	double P;		/* normal force on i along n: the elements' k_n h (N); NaN without meta kn */
	double Q[3];		/* tangential force on i, of the pair's contact line (N); NaN without */
	double overlap;		/* the largest element overlap h (m) */
	int elements;		/* element contacts */
};
/* The interactions that measure_plates counts, one by one, in the enumerator's order; the
 * caller frees *list.  0, or -1 (msg_seterr). */
int measure_plate_contact_list(const struct pack *p, struct plate_contact **list, size_t *n);
/* The nematic order of n unit vectors u (3 each): the largest eigenvalue S of
 * Q = <(3 u u - I)/2> (1 when all are parallel, 1/4 when they spread evenly over a plane,
 * of order 1/sqrt(n) for isotropic ones: see test_measure.c) and its unit eigenvector, the
 * director, signed so that its largest component is positive (u and -u are one axis).  A
 * degenerate largest eigenvalue leaves the director one of its eigenvectors.  0, or -1 with
 * msg_seterr (n = 0, GSL failure). */
int measure_nematic(const double *u, size_t n, double *S, double director[3]);

#ifdef __cplusplus
}
#endif

#endif
