/* SPDX-License-Identifier: GPL-3.0-or-later */
/* engine: the explicit DEM engine of every shape (pack/shape.h: spheres and spheroplates)
 * under every contact law of the table (contact/law.h); packgen's compactions (dem/dem.h
 * for spheres, dem/platepack.h for plates) and the shear test (dem/plateshear.h) run on it.
 * The platy-particle paper's engine (P §II B, App. A; physics.md §12).
 *
 * An interaction is the element contacts of contact/plate.h, found by contact/narrow.h's table
 * of shape pairs (one for a pair of spheres or a sphere and a wall), sharing its normal.  The law gives them their forces (its
 * dem_interaction: each element's normal force at its own contact point, never attractive,
 * and the interaction's one tangential force at the overlap-weighted centre of the
 * elements), and keeps law->history doubles per interaction in the enumerator's slot (a
 * tangential spring's 3, none for a law without one).  The law's formulas are the law's
 * (contact/linear.h: P eqs. 2-4; contact/hertz.h); the engine sets what they share: the
 * damping ratio zeta of a restitution coefficient e, whose collision returns e with the
 * never-attractive force (engine.c: Schwager and Poschel's closed form, not the classical
 * exp(-pi zeta/...)), and the tangential over normal stiffness ratio.  The law also gives
 * the engine's units and time step (dem_units, stiffest) and its history's force (what a
 * pack's Q0 lines carry: engine_write_back, engine_read_history).
 *
 * Integration: leapfrog translations; rotations by Euler's equations in the principal
 * (body) frame, P eq. A2, with the angular velocity at the full step taken as the mean of
 * the two half steps (the implicit midpoint rule, solved by fixed-point iteration): P's A2
 * needs Omega_t, which a leapfrog does not have, and the midpoint keeps the kinetic energy
 * and |L| of a free body exactly.  The quaternion then turns by P's eq. A4 step
 * (quat_step_body).  A sphere's orientation is not observable: its frame is kept as the
 * lab's, and its isotropic Euler equations are w' = t / J.  Optionally Cundall's local
 * damping and a viscous loss (P uses neither; packgen uses them to reach rest sooner: they
 * remove kinetic energy, not the equilibrium).
 *
 * The list holds the pairs whose bounding spheres are within the skin and, of plates, whose
 * cores may be (pruned at its build by a gap bound; it goes stale on turns as well as moves).
 * The narrow phase is kept between steps: per listed pair, the features (vertex-square, edge
 * pairs) that can be within reach while the pair's cores move against each other by less
 * than cache_margin (contact/plate.h's plate_interaction_cached; the same elements to the
 * bit as computing them all).  The force pass runs on the library's threads (base/par.h):
 * blocks of rows compute their interactions (each thread a run of blocks of about equal list
 * pairs), each grain gathers its column's in a fixed order, so the bytes are the same for any
 * thread count.
 *
 * A pack of spheres only takes the sphere pass (engine_spheres.c): no narrow phase, a pair's
 * force into both grains as the walk meets it, Hertz pairs two at a time in lanes; the same
 * integrator, sums and law entry.
 *
 * Units inside: length r0 (the mean spheroradius), mass rho0 r0^3, stiffness k0 (the law's
 * dem_units: a spring law's k_n; Hertz's E* r0 of two mean grains), so time
 * sqrt(rho0 r0^3 / k0) and stress k0 / r0; the pack (SI) is converted in and out. */
#ifndef QUSGM_ENGINE_H
#define QUSGM_ENGINE_H

#include <stddef.h>
#include <stdio.h>
#include "contact/contacts.h"
#include "contact/law.h"
#include "contact/narrow.h"
#include "pack/pack.h"

struct engine_params {
	const struct contact_law *law;	/* the contact law (contact/law.h's table): linear, P's, by default */
	double kn, kt;		/* linear law: normal, tangential stiffness (N/m); kt / kn is the
				 * tangential over normal stiffness ratio of either law */
	double hertz_overlap;	/* Hertz law: the largest overlap / smallest spheroradius the time
				 * step is made for */
	double viscous;		/* fraction of the velocities lost per step (0: none) */
	double mu, wall_mu;	/* friction grain-grain, grain-wall (during the dynamics) */
	double restitution;	/* of a binary collision, [0.21, 1] (below exp(-pi/2): overdamped) */
	double damping;		/* Cundall local damping, [0, 1) */
	double dt_factor;	/* dt = dt_factor sqrt(m_min / k_n) */
};

/* A pair's share for its grain j in a pass of engine_forces: the force on i (j gets its
 * opposite) and the torque on j about its centre. */
struct engine_xrec;
struct engine_rec {
	double F[3], Tj[3];
};

/* A pair's narrow-phase cache: the word of plate_interaction_cached, and the branch vector,
 * the sum of the two grains' turns when it was made, for list `list` (engine.cache_list). */
struct engine_cache {
	double dx[3], turn;
	unsigned word;
	long list;
};

/* A block of rows' share of a pass's sums (added in block order). */
struct engine_sums {
	double wallf[NWALLS], wallF[NWALLS][3], sig[6], sum_f;
	size_t ninter, nwall, nelem, zends;
};

struct engine {
	size_t n;
	double *x, *v;		/* centres, velocities (3n) */
	double *q;		/* orientations (4n), body -> lab */
	double *w;		/* angular velocities in the body frame (3n), at half steps */
	double *f, *t;		/* forces, torques in the lab frame (3n) */
	double *R;		/* rotation matrices of q (9n), refreshed by engine_forces */
	double *m, *J;		/* masses (n), principal moments (3n: in-plane, in-plane, normal) */
	double *r, *half;	/* spheroradii, half sides (n) */
	unsigned char *kind;	/* shape kinds (n, enum shape_kind: the narrow phase's table, narrow.h) */
	double *rb;		/* bounding radii (n): what the enumerator sees */
	double lo[3], hi[3];
	int periodic[3];
	struct contact_enum ce;
	double kt_ratio, mu, wall_mu, zeta, damping, viscous, dt;
	/* the contact law, and its pair physics (scaled) of two grains and of a grain and a wall,
	 * R* set per interaction: the linear law's k_n = 1; Hertz's E* = 1 between two grains */
	const struct contact_law *law;
	struct law_pair lp_grain, lp_wall;
	/* the mobilities dt / m and dt / J (interleaved per grain), made for the step mob_dt */
	double *mob, mob_dt;
	/* every grain a sphere: the sphere pass (engine_spheres.c), no narrow phase, and each
	 * sphere's frame kept as the lab's (its orientation is not observable); pair_lanes: its
	 * Hertz pairs two at a time in lanes (the same bytes) */
	int spheres, pair_lanes;
	/* the sphere pass on threads: block sums, and the records of the pairs that cross from one
	 * thread's rows to a later one's, for x_team threads on the list of rebuild x_builds */
	struct engine_xrec *xrec;
	size_t *xslot, *xin_first, x_team;
	long stamp, x_builds;
	/* the last engine_forces: elastic normal force on each wall, interactions with at least one
	 * element (nwall of them with a wall), elements, sum of interaction force magnitudes */
	double wallf[NWALLS];
	size_t ninter, nwall, nelem;
	double sum_f;
	/* ... and the whole force of each wall on the grains, and the sum over the grain pairs of
	 * branch vector (x_i - x_j, nearest image) (x) the force on i (xx yy zz xy xz yz): the
	 * Love-Weber stress times the volume */
	double wallF[NWALLS][3];
	double sig[6];
	/* (both kept when stress is set, the shear's; the compactions read neither: without stress
	 * sig is 0, and so is wallF in the sphere pass of a pack without glue) */
	int stress;
	/* ... and the interactions' ends on free grains (Z of the free grains = zends / their
	 * number); a pair of two glued grains is part of a wall: it is in none of the sums above */
	size_t zends;
	/* Moving walls and grains glued to them (plateshear): glue is NULL or, per grain, 0 for a
	 * free grain or 1 + w for one glued to wall w, which moves at the wall's velocity
	 * wallv[w] without turning and has no contact with that wall (it is part of it); a
	 * wall's velocity also enters the relative velocity of the grains that touch it.  The
	 * caller moves the planes (lo, hi) itself. */
	unsigned char *glue;
	double wallv[NWALLS][3];
	/* The narrow phase kept between steps (plate_interaction_cached): per listed pair its
	 * cache (struct engine_cache), remade when the pair's cores may have moved against each
	 * other by cache_margin since it was made: the change of their branch vector plus what
	 * their turns move a corner.  A grain's turn is the sum over the passes of what its turn
	 * from one pass to the next (from q0, its orientation at the last pass) can move a point
	 * of its core (2 |q - q0| half sqrt 2, the nearer of q0 and -q0, which bounds |R - R0|
	 * times the core's radius); a cache keeps the sum of its two grains' turns when it was
	 * made.  The caches of a pair listed again when the list is rebuilt are kept; cache_list
	 * is the list the caches are of (0: none yet, the turns start afresh).  Set cache_margin
	 * to 0 to compute every feature at every step (the same bytes). */
	struct engine_cache *pcache;
	size_t pcap;
	long cache_list, cache_builds;
	double cache_margin;
	double *q0, *turn;
	int q0_set;		/* q0 holds the orientations of the last pass (0: the turns start afresh) */
	/* The contact list's broad phase at its build (contacts.h: contact_enum_prune): a pair
	 * whose bounding spheres are within the skin is listed only when its cores may be (their
	 * six frame axes' gap bound, plate_core_gap_bound, below r_i + r_j + skin); turn_list is
	 * each grain's turn since the build, which the list's staleness adds to its displacement,
	 * so that a pair left out cannot touch before the next build.  A shear at eta 0.8 lists
	 * 2.6 times fewer pairs than the bounding spheres meet.  Plates only. */
	double *turn_list;
	struct contact_prune prune;
	/* engine_forces' records: a pair's share for j and whether it holds this pass's
	 * interaction (ptouch), both by the pair's place in the enumerator's columns
	 * (contact_enum_columns' col_pos), which the gather reads in order; each grain's force
	 * and torque from its own row (frow, 6n), the block sums, the lab-frame angular
	 * velocities (3n), and whether the passes run on threads */
	struct engine_rec *prec;
	unsigned char *ptouch;
	double *frow;
	size_t rcap;
	long rec_builds;
	struct engine_sums *sums;
	size_t sums_cap;
	double *wl;
	int threads;
	/* the scales: SI value = scaled value times these */
	double u_len, u_mass, u_time, u_force;
};

/* The default cache margin (scaled units, r0): features within r_i + r_j + 0.03 r0 are kept;
 * a pair's cache lasts while its cores move against each other by less than that.  The
 * elements do not depend on it, the cost does: a wider one keeps more features per pair, a
 * narrower one remakes caches more often; a shear at I = 1e-3 at eta 0.8 cost least at
 * 0.03-0.05 (bench/plates.md). */
#define ENGINE_CACHE_MARGIN 0.03

/* The cache margin for a slow shear of d's grains: 0.0075 times the plates' mean core
 * half-side, within [0.005, ENGINE_CACHE_MARGIN].  Small cores have their features close
 * together, so a margin keeps more of them per pair: 8000 plates sheared at I = 1e-3 cost
 * least near 0.005 at eta 0.14 (half-side 0.16 r0), 0.005-0.01 at eta 0.5 (1 r0) and 0.03 at
 * eta 0.8 (4 r0) (bench/plates.md).  ENGINE_CACHE_MARGIN for spheres only. */
double engine_shear_cache_margin(const struct engine *d);

void engine_params_default(struct engine_params *pp);
/* pp set for law: the law, and for a law other than the linear one (whose kn and kt are the
 * caller's, N/m) the law's own tangential over normal stiffness ratio (kt / kn = the law's
 * kt_ratio, as packgen's sphere DEM takes it). */
void engine_params_law(struct engine_params *pp, const struct contact_law *law);
/* E* of two grains of pack p's mean Young's modulus and Poisson ratio (Pa): the Hertz law's
 * stiffness unit in the engine, over r0. */
double engine_mean_Estar(const struct pack *p);
/* The stiffness number kappa of a normal stress sigma (Pa) on pack p under pp's law: the
 * mean spheroradius r0 over the typical overlap that sigma makes, up to a factor of order
 * one, so that 1 / kappa is the contacts' strain whatever the law.  Linear law:
 * kappa = k_n / (sigma r0) (P eq. 6).  Hertz: kappa = (E* / sigma)^(2/3), E* of
 * engine_mean_Estar (Agnolin and Roux's, with E* for their E / (1 - nu^2), which is 2 E*).
 * The overlaps follow from the Love-Weber stress sigma = Z phi <F> / (4 pi r0^2) of spheres
 * (Z about 4.5, phi about 0.6): a mean overlap of 4.7 r0 / kappa under the linear law and
 * 2.9 r0 / kappa under Hertz (R* = r0 / 2). */
double engine_kappa(const struct pack *p, const struct engine_params *pp, double sigma);
/* Its inverse: the stress (Pa) of stiffness number kappa. */
double engine_kappa_stress(const struct pack *p, const struct engine_params *pp, double kappa);
/* The largest overlap over the smallest spheroradius likely at stiffness number kappa, what
 * a Hertz time step is made for (hertz_overlap): ENGINE_OVERLAP_KAPPA / kappa.  The mean
 * overlap of engine_kappa is 2.9 r0 / kappa; over the smallest radius (0.7 r0 in packgen's
 * default radii) and at the tail of a pack's forces it is several times that: 300 spheres
 * sheared at kappa 1e3 (tests/tools/shear.sh) had their largest at 13 / kappa.  The time
 * step goes as the overlap^(-1/4): a factor 2 in it moves the step by 19 %. */
#define ENGINE_OVERLAP_KAPPA 20.0
/* The arrays of an engine for n grains, zeroed, for a caller that fills them itself (x, r,
 * half, rb, m, J, q; packgen's sphere compaction, dem.c) and then calls engine_start.  0 or -1. */
int engine_alloc(struct engine *d, size_t n);
/* After the grains are set: the per-shape arrays, the time step's mobilities, and the contact
 * list of the bounding radii rb with that skin (scaled), periodic along d->periodic.  The
 * caller has set the law, its pair physics and the DEM coefficients.  0 or -1. */
int engine_start(struct engine *d, double skin);
/* An interaction into a pass's sums: grain i with grain j (branch vector br = x_i - x_j, the
 * nearest image) or a wall (br unused), its whole force Fc on i, elastic normal force fel, m
 * elements.  A pair of two glued grains is part of a
 * wall: in none of the sums. */
CONTACT_INLINE void
engine_count(const struct engine *d, size_t i, long j, const double br[3], const double Fc[3], double fel, int m,
    struct engine_sums *sums)
{
	int wall = PACK_IS_WALL(j), gi = d->glue ? d->glue[i] : 0, gj = d->glue && !wall ? d->glue[j] : 0, a;

	if (!wall && gi && gj)	/* inside a wall body: applied, not counted */
		return;
	sums->zends += (gi ? 0 : 1) + (wall || gj ? 0 : 1);
	if (!wall && d->stress) {
		sums->sig[0] += br[0] * Fc[0], sums->sig[1] += br[1] * Fc[1], sums->sig[2] += br[2] * Fc[2];
		sums->sig[3] += 0.5 * (br[0] * Fc[1] + br[1] * Fc[0]);
		sums->sig[4] += 0.5 * (br[0] * Fc[2] + br[2] * Fc[0]);
		sums->sig[5] += 0.5 * (br[1] * Fc[2] + br[2] * Fc[1]);
	} else if (wall) {
		int w = PACK_WALL_INDEX(j);

		sums->wallf[w] += fel;
		for (a = 0; a < 3; a++)
			sums->wallF[w][a] += Fc[a];
		sums->nwall++;
	}
	sums->ninter++;
	sums->nelem += (size_t)m;
	sums->sum_f += sqrt(Fc[0] * Fc[0] + Fc[1] * Fc[1] + Fc[2] * Fc[2]);
}
/* The first block of thread t's share of nb blocks of bl grains among T threads (t = T: nb),
 * for both passes: runs of whole blocks of about equal work, measured by list nl's pairs.
 * Which thread takes a block changes no byte. */
size_t engine_blocks_share(const struct nlist *nl, size_t bl, size_t nb, size_t T, size_t t);
/* Room for nb blocks' sums (0 or -1), and their total in block order into the engine's. */
int engine_sums_fit(struct engine *d, size_t nb);
void engine_sums_total(struct engine *d, size_t nb);
/* The sphere pass of engine_forces (engine_spheres.c). */
int engine_sphere_forces(struct engine *d);
/* The engine for pack p (SI): scaled copies of its grains and box, at rest, the boundary of
 * the pack.  0 or -1 (msg_seterr). */
int engine_init(struct engine *d, const struct pack *p, const struct engine_params *pp);
void engine_free(struct engine *d);
/* Forces and torques at the current state (the contact list brought up to date). 0 or -1. */
int engine_forces(struct engine *d);
/* Calls fn for every interaction of the current state that has element contacts (a pair, or
 * a grain and a wall: j = PACK_WALL(w)), in the enumerator's order (contacts.h), with j's
 * centre xj (its nearest image; NULL for a wall), the interaction in scaled units and its
 * tangential spring hist (3 doubles: minus the spring's force on i), which fn may set.  The
 * list is rebuilt first when rebuild is set, else brought up to date.  0, or -1 (msg_seterr,
 * or fn returned nonzero). */
typedef int (*engine_interaction_fn)(const struct engine *d, size_t i, long j, const double *xj,
    const struct plate_interaction *it, double *hist, void *ctx);
int engine_foreach_interaction(struct engine *d, int rebuild, engine_interaction_fn fn, void *ctx);
/* One leapfrog step from the forces of engine_forces. */
void engine_integrate(struct engine *d);
/* Kinetic energy (translation + rotation) and total angular momentum about the origin, lab
 * frame, into L unless NULL (scaled units). */
double engine_kinetic(const struct engine *d, double L[3]);
/* Mean |net force| over the grains over the mean interaction force (INFINITY without one). */
double engine_unbalanced(const struct engine *d);
/* Wrap the centres into the box along the periodic axes. */
void engine_wrap(struct engine *d);
/* Replace the walls of the axes set in periodic by periodic boundaries, the box lengths kept
 * as the periods: a new enumerator (the pairs across the boundary appear; the tangential
 * springs start again from zero).  -1 (msg_seterr) when an axis is shorter than three
 * interaction distances (the enumerator's cell grid needs them): "use more grains". */
int engine_make_periodic(struct engine *d, const int periodic[3]);
/* Positions, orientations, box and frictional history (one contact line per interaction:
 * P0 its elastic normal force, Q0 its tangential spring's force on i, M0 0) back into p
 * (SI), replacing p's contact lines, and with glued grains (glue) the glued column
 * (pack_set_glue).  0 or -1. */
int engine_write_back(struct engine *d, struct pack *p);
/* Set the tangential springs from p's contact lines (engine_write_back's), for the
 * interactions that touch now; the others start from zero.  0 or -1. */
int engine_read_history(struct engine *d, struct pack *p);

/* The engine's state between two steps, for a checkpoint: the grains' centres, velocities,
 * orientations, angular velocities and glue, the box and the walls' velocities, and the
 * tangential springs that hold something (contacts.h: contact_enum_history_get), every
 * number as a C99 hex float, so that it reads back to the bit.  What the engine rebuilds (the
 * contact list, the narrow-phase caches, the forces of the next pass) is not saved: the
 * contacts, their order and their elements do not depend on when those were made, so the run
 * going on from it is the same bytes as the run that wrote it.  Lines:
 *     pdem-state 1 N
 *     box LO0 LO1 LO2 HI0 HI1 HI2 PX PY PZ
 *     wallv 18 numbers (NWALLS x 3)
 *     N lines: X0 X1 X2 V0 V1 V2 QW QX QY QZ W0 W1 W2 GLUE
 *     springs M, then M lines: I J H0 H1 H2 (J < 0: a wall, PACK_WALL)
 * engine_state_write returns 0 or -1 (a write error: msg_seterr).  engine_state_read reads them
 * from in into d, an engine made by engine_init for the same grains (and made periodic as the
 * run that wrote it was), and builds its list: 0, or -1 with the file:line message. */
struct lines;
int engine_state_write(const struct engine *d, FILE *fp);
int engine_state_read(struct engine *d, struct lines *in);

#endif
