/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pack: the data model every tool shares.
 *
 * A pack is N grains in a rectangular box bounded by six walls (or periodic), the reference box
 * against which strains are measured, the contacts that carry history (normal force P0,
 * tangential force Q0 on the first grain, torsional couple M0, all at the last committed
 * equilibrium), and provenance (one history line per program that touched it).
 * Units are SI: m, Pa, kg/m^3, N, N m.  Grains are stored as parallel arrays so that the
 * minimisers can work on x[] directly.
 *
 * Grains are spheres unless the pack carries the shape columns (has_shapes): then each is of
 * a kind of pack/shape.h's table (shape[i], pack_grain_shape: a sphere or a spheroplate) of
 * spheroradius r[i], core side side[i] (0: a sphere) and orientation q[4 i .. 4 i + 3]
 * (base/quat.h), and only a tool that knows plates may use it (pack_require_spheres).
 *
 * Public API (share/doc/library.md): a struct pack is a value the caller owns.  pack_init
 * makes an empty one, pack_free releases everything in it (and leaves it empty, so freeing
 * twice is harmless), pack_copy deep-copies; the pointers of the struct (x, r, c, history,
 * meta ...) belong to the pack and stay valid until the next function that adds to it
 * (pack_add_grain, pack_add_contact, ...) or pack_free.  Functions returning int give 0 on
 * success and -1 with the error slot of base/msg.h set; those returning an index give
 * (size_t)-1; a returned long * (pack_history_keys) is the caller's to free(). */
#ifndef QUSGM_PACK_H
#define QUSGM_PACK_H

#include <stddef.h>
#include "pack/shape.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PACK_FORMAT_NAME "qusgm-pack"
#define PACK_FORMAT_VERSION 2	/* the newest version read and written */

/* Walls: index w = 2 * axis + side (side 0 = low, 1 = high). */
enum { WALL_XLO, WALL_XHI, WALL_YLO, WALL_YHI, WALL_ZLO, WALL_ZHI, NWALLS };
/* In a contact, j >= 0 is a grain index and j < 0 a wall: j = PACK_WALL(w). */
#define PACK_WALL(w) (-1 - (long)(w))
#define PACK_IS_WALL(j) ((j) < 0)
#define PACK_WALL_INDEX(j) ((int)(-1 - (j)))

extern const char *const pack_wall_names[NWALLS];

/* Distance from a grain centre xi to wall w of box (lo[3], hi[3]), positive inside: the
 * grain touches the wall when it is below the radius. */
static inline double
pack_wall_distance(const double box[6], const double *xi, int w)
{
	int a = w / 2;

	return w % 2 ? box[3 + a] - xi[a] : xi[a] - box[a];
}

struct pack_contact {
	size_t i;	/* grain index */
	long j;		/* grain index, or PACK_WALL(w) */
	double P0;	/* normal force at the last equilibrium (N) */
	double Q0[3];	/* tangential force on grain i (N) */
	double M0;	/* torsional couple on i about the normal from j to i (N m) */
};

/* The history force of line c as the force on grain i, one of the two grains it names.  A
 * line may name its pair either way, 'i j' or 'j i' (pack-format.md); its Q0 acts on the
 * first grain named, so the force on the other is -Q0 (action and reaction).  M0 is the
 * same either way: the couple on j about the normal from i to j equals the couple on i about
 * the normal from j to i.  This is the one place that applies the rule. */
static inline void
pack_contact_q0_on(const struct pack_contact *c, size_t i, double Q[3])
{
	double s = c->i == i ? 1.0 : -1.0;

	Q[0] = c->Q0[0] * s, Q[1] = c->Q0[1] * s, Q[2] = c->Q0[2] * s;
}

struct pack_meta {
	char *key;
	char *value;
};

struct pack {
	size_t n, cap;
	long *id;	/* user-visible grain ids, unique, >= 0 */
	double *x;	/* centres, 3n (m) */
	double *r;	/* radii (m) */
	double *E;	/* Young's moduli (Pa) */
	double *nu;	/* Poisson ratios */
	double *rho;	/* densities (kg/m^3) */
	/* The shape columns of format 2 (pack-format.md), all or none: has_shapes says which.
	 * side: L >= 0 of the square core (m), 0 for a sphere; q: 4n, the unit quaternion
	 * (w x y z) turning the grain's body frame (core in its z = 0 plane, edges along x and
	 * y) into the lab frame; shape: n, each grain's enum shape_kind (the shape column, or
	 * from its side for a pack without one: shape_kind_of_side).  NULL without the columns,
	 * which keeps every sphere-only pack and its output as they were.  A grain's side and
	 * kind go together: pack_set_grain_shape sets both, and a caller that writes side[i]
	 * itself sets shape[i] to agree (pack_validate checks that they do). */
	int has_shapes;
	double *side;
	double *q;
	unsigned char *shape;
	/* The phase column of format 2 (pack-format.md, "The phase column"): has_phase says
	 * whether the pack has it; phase[i] is PHASE_MINERAL or PHASE_HYDRATE.  What a grain
	 * is made of is told by this tag, never guessed from its density or moduli (hydrate
	 * dissociation, physics.md section 11, acts on the hydrate grains only).  NULL without
	 * the column. */
	int has_phase;
	unsigned char *phase;
	/* The glued column of format 2 (pack-format.md, "The glued column"): has_glue says
	 * whether the pack has it; glue[i] is 0 for a free grain or 1 + w for a grain glued to
	 * wall w (the shear's wall layers, which move with their wall as a part of it), so that
	 * the descriptors of a snapshot can leave them out.  NULL without the column. */
	int has_glue;
	unsigned char *glue;

	double box[6];		/* xlo ylo zlo xhi yhi zhi (m) */
	/* The boundary along each axis: 0, the two box faces are rigid walls (every pack of
	 * format 1); 1, periodic with the box length as the period, and no walls on that axis.
	 * The contact enumerator (contact/contacts.h) is the one place that acts on it. */
	int periodic[3];
	double refbox[6];	/* reference box for strains */
	int has_refbox;
	double wall_E, wall_nu;	/* wall moduli (Pa, -) */
	double mu, wall_mu;	/* friction coefficients grain-grain, grain-wall */

	size_t nc, ccap;
	struct pack_contact *c;

	size_t nhist, hist_cap;	/* hist_cap, meta_cap: the room, grown by doubling */
	char **history;
	size_t nmeta, meta_cap;
	struct pack_meta *meta;
};

void pack_init(struct pack *p);
void pack_free(struct pack *p);
int pack_reserve(struct pack *p, size_t n);
/* Append a grain; returns its index or (size_t)-1 when out of memory.  With the shape
 * columns it is a sphere (side 0, q = (1, 0, 0, 0)) until pack_set_grain_shape. */
size_t pack_add_grain(struct pack *p, long id, const double x[3], double r, double E, double nu,
    double rho);
/* Give p the shape columns, every grain a sphere (side 0, q the identity): what a tool that
 * makes plates calls first, and what the reader calls for a columns line that names them.
 * Nothing happens when p has them already.  0, or -1 (msg_seterr) when out of memory. */
int pack_set_shapes(struct pack *p);
/* The grain phases of the phase column.  PHASE_MINERAL is every grain of a pack without it. */
enum pack_phase { PHASE_MINERAL = 0, PHASE_HYDRATE = 1, PACK_NPHASES };
/* Give p the phase column, every grain PHASE_MINERAL: what packgen --hydrate-volume calls
 * first, and what the reader calls for a columns line that names it.  Nothing happens when p
 * has it already.  0, or -1 (msg_seterr) when out of memory. */
int pack_set_phases(struct pack *p);
/* Grain i's phase: PHASE_MINERAL when p has no phase column. */
static inline int
pack_grain_phase(const struct pack *p, size_t i)
{
	return p->has_phase ? p->phase[i] : (int)PHASE_MINERAL;
}
/* Give p the glued column, every grain free (0): what the shear's snapshots call, and what
 * the reader calls for a columns line that names it.  Nothing happens when p has it already.
 * 0, or -1 (msg_seterr) when out of memory. */
int pack_set_glue(struct pack *p);
/* Whether grain i is glued to a wall: 0 when p has no glued column. */
static inline int
pack_grain_glued(const struct pack *p, size_t i)
{
	return p->has_glue && p->glue[i] != 0;
}
/* The number of hydrate grains and their volume (m^3, overlaps not subtracted). */
size_t pack_hydrate_grains(const struct pack *p, double *volume);
/* Hydrate saturation S = V_hydrate / V_pores with the hydrate counted as pore space
 * (physics.md section 11): V_pores = V_box - V_mineral, grain volumes as in
 * pack_grain_volume (overlaps not subtracted).  0 for a pack without hydrate grains. */
double pack_hydrate_saturation(const struct pack *p);
/* Grain i's core side L (m) and orientation (a unit quaternion, copied), its kind the one of
 * its side (shape_kind_of_side: a spheroplate when L > 0); p has the shape columns.  The
 * reader and pack_validate check the values. */
void pack_set_grain_shape(struct pack *p, size_t i, double side, const double q[4]);
/* Grain i's kind (a row of pack/shape.h's table); p has the shape columns.  The reader of a
 * shape column sets it after pack_set_grain_shape; pack_validate checks it against the side
 * (struct shape_ops's side_ok). */
void pack_set_grain_kind(struct pack *p, size_t i, enum shape_kind kind);
/* The kind of grain i: its shape column's, SHAPE_SPHERE for a pack without shape columns.
 * (A struct pack that has side but not shape, as a test may make, gets the kind of its
 * side.)  What a consumer asks instead of testing side > 0: shape_of(pack_grain_shape(p, i))
 * answers for the grain's shape. */
enum shape_kind pack_grain_shape(const struct pack *p, size_t i);
/* How far from 1 the norm of a stored quaternion may be (pack-format.md, "Grain lines"). */
#define PACK_QUAT_TOL 1e-6
/* The box lies within [-PACK_BOX_MAX, PACK_BOX_MAX] m on each axis (a pack of grains: a 1e300 m box
 * was read) */
#define PACK_BOX_MAX 1e3
/* The index of the first grain that is not a sphere (pack_grain_shape), or (size_t)-1 when
 * every grain is a sphere: no shape columns, or every kind a sphere. */
size_t pack_first_plate(const struct pack *p);
/* The check of every tool that runs the sphere physics: 0 when every grain is a sphere;
 * otherwise -1 with "grain ID is a spheroplate (side > 0); WHO handles spheres only" in the
 * slot, for the tool to prefix with its input's name.  WHO names the tool (or its mode). */
int pack_require_spheres(const struct pack *p, const char *who);
int pack_add_contact(struct pack *p, const struct pack_contact *c);
/* dst (uninitialised) becomes a deep copy of src: grains, columns, box, contacts, history,
 * meta.  For a tool that tries something on a pack and keeps the original (dissociate's
 * probe of the bulk modulus).  0, or -1 (msg_seterr; dst freed) when out of memory. */
int pack_copy(struct pack *dst, const struct pack *src);
/* The friction-coefficient rule, the one place that says it: a contact of a grain with grain j
 * slides at p->mu, with a wall (j = PACK_WALL(w)) at p->wall_mu.  The laws' pair setup
 * (contact/law.h, struct law_pair's mu) and every check of a history line ask it. */
static inline double
pack_contact_mu(const struct pack *p, long j)
{
	return PACK_IS_WALL(j) ? p->wall_mu : p->mu;
}
/* The history lines as sorted keys: three longs per line, (a, b, line) with a < b for a grain
 * pair (either order in the file: 'i j' and 'j i' name one pair) and (grain, wall) for a wall,
 * ascending in a, then b, then line.  For finding a pair's line and a pair named twice.
 * NULL (msg_seterr) when out of memory; the caller frees. */
long *pack_history_keys(const struct pack *p);
/* The first line of pair (i, j) in keys (p->nc of them): i < j for grains, or j a wall; -1
 * when the pack has none. */
long pack_history_lookup(const long *keys, size_t n, size_t i, long j);
int pack_add_history(struct pack *p, const char *line);
int pack_set_meta(struct pack *p, const char *key, const char *value);
/* Append key's line without looking for the key first: for a caller that knows it is new
 * (the reader, which checks every key once against a hash of those before; pack_copy).
 * pack_set_meta looks through every line, so a header of N meta lines read through it took
 * N^2/2 comparisons (160000 lines: over 2 minutes).  0, or -1 when out of memory. */
int pack_append_meta(struct pack *p, const char *key, const char *value);
const char *pack_get_meta(const struct pack *p, const char *key);
/* Remove key's line (the others keep their order); nothing when it is absent. */
void pack_unset_meta(struct pack *p, const char *key);
/* The meta value of key as a finite number: 0 with *v set, or -1 (absent or not a number). */
int pack_get_meta_double(const struct pack *p, const char *key, double *v);
/* The convention for a plate's outer radius R (pack/shape.h) under which this pack's
 * platyness is given: meta 'plate-radius', 'edge' or 'corner', and SHAPE_R_EDGE when the key
 * is absent.  A pack stores r and L, so only converting to and from the platyness needs it.
 * 0, or -1 with msg_seterr for another value. */
#define PACK_META_PLATE_RADIUS "plate-radius"
int pack_plate_radius(const struct pack *p, enum shape_radius *conv);

/* Box geometry: wall w's inward normal and position along its axis. */
double pack_box_length(const double box[6], int axis);
/* Wrap n centres x (3n) into [lo, hi) along the axes where periodic is set. */
void pack_wrap_centres(double *x, size_t n, const double lo[3], const double hi[3], const int periodic[3]);
double pack_box_volume(const double box[6]);
/* The wall stress along axis a of the box [lo, hi]: force, the normal force on both walls of
 * the axis together (N), over twice the area of one, (hi - lo) along the other two axes
 * (Pa, compression positive).  The one formula of every consumer: the functional's
 * qs_wall_stress, packinfo's measures, the DEM compactions and their servo. */
double pack_wall_stress(const double lo[3], const double hi[3], int a, double force);
/* The sum of the grains' volumes, spheres and spheroplates (shape_volume), overlaps not
 * subtracted (m^3). */
double pack_grain_volume(const struct pack *p);
/* Index of the grain with the given id, or (size_t)-1 (binary search over a cached sort). */
size_t pack_find_id(const struct pack *p, long id, size_t *scratch_sorted);

/* What identifies a pack's grains for a checkpoint (cli_run_identity): "grains N crc32 X",
 * X the CRC-32 of the ids, centres and radii (and sides and orientations when it has them),
 * into buf (64 bytes are enough). */
void pack_checksum(const struct pack *p, char *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif
