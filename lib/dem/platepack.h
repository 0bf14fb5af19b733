/* SPDX-License-Identifier: GPL-3.0-or-later */
/* platepack: packs of spheroplates by DEM, as the platy-particle paper makes them (P §II C).
 *
 * The grains (radius column = spheroradius, side, any orientation) are put on the nodes of a
 * cubic grid of spacing 2 sqrt(2) R, R the outer radius, each turned at random (a uniform
 * random rotation): under either reading of R the spacing exceeds the bounding diameter, so no
 * two grains overlap however they are turned.  Spheres (and any grain) may also be moved off
 * their nodes (jitter): a grid of turned spheres is still a simple cubic crystal, which an
 * isotropic compaction keeps (packing pi/6, a little more with the overlaps).  The six walls then close in under servo
 * control to the isotropic stress sigma_0 until static equilibrium (the mean unbalanced force
 * below rest_tol of the mean interaction force, the wall stress within 5 % of sigma_0).  As in
 * the sphere DEM (dem.h) the centres follow the box affinely while it closes, which only
 * shortens the gas phase.  Then, as an option, the walls of some axes are replaced by
 * periodic boundaries (P's lateral walls, for the shear test) and the pack relaxes again at
 * the stress of the remaining walls, the periodic lengths kept.
 *
 * Friction during the compaction: P gives neither whether friction acts during the
 * compaction nor sigma_0.  Both are options.  The default compacts with P's friction, 0.58,
 * so the pack the shear test starts from has carried the test's friction throughout.
 * Frictionless compaction (mu 0) gives a denser pack but no quick rest: frictionless plates
 * keep sliding into denser arrangements at the target stress (125 plates at eta 0.5: at
 * rest after 17100 steps, packing 0.538, with friction; 177000 steps, packing 0.692, still
 * creeping by 1e-4 per 1000 steps before rest, without).  The walls' friction (dyn.wall_mu)
 * is the caller's: with it the walls carry shear and the grains' stress departs from the
 * isotropic target (packgen's --dem-wall-friction, 0 by default).  sigma_0 defaults to
 * kappa = k_n / (sigma_0 r) = 1e4, ten
 * times P's lower bound of 1e3 for the rigid limit. */
#ifndef QUSGM_PLATEPACK_H
#define QUSGM_PLATEPACK_H

#include <gsl/gsl_rng.h>
#include "dem/engine.h"
#include "pack/pack.h"

struct platepack_params {
	struct engine_params dyn;	/* the contact law and the step (mu: friction during compaction) */
	double spacing;		/* grid spacing (m): 2 sqrt(2) R */
	double jitter;		/* off the nodes, in [0, 1] of the room each cell leaves (0: on them) */
	double sigma0;		/* target isotropic stress (Pa) */
	double rest_tol;	/* static: mean |net force| / mean interaction force below this */
	double rate;		/* largest strain of the box per step */
	long max_steps;		/* for each stage */
	int periodic[3];	/* axes whose walls become periodic boundaries after compaction */
};

struct platepack_status {
	long step;
	int stage;		/* 1: compaction by six walls; 2: relaxation with periodic axes */
	double phi;		/* packing fraction */
	double p_ratio;		/* mean wall stress over sigma_0 */
	double z;		/* interactions per grain */
	double elements;	/* element contacts per interaction */
	double unbalanced;
	int at_rest;
	/* dimensionless groups of P eq. 6 for the compaction: kappa = k_n / (sigma_0 r) and the
	 * inertial number I = (strain rate) r sqrt(rho / sigma_0) at the servo's full rate */
	double kappa, inertial;
};

typedef void (*platepack_progress_fn)(const struct platepack_status *s, void *ctx);

/* Defaults: P's contact law (engine.h) and friction 0.58, Cundall damping 0.3 (removes
 * kinetic energy, so rest comes sooner; the equilibrium condition is the same), rest_tol
 * 1e-3, rate 1e-4. */
void platepack_params_default(struct platepack_params *pp);
/* Place p's grains (r, side set by the caller) on the grid with random orientations, set the
 * box, compact, and write back the static pack (ids kept, grains in grid order).  0 or -1
 * (msg_seterr; also when a stage reaches max_steps). */
int platepack_make(struct pack *p, const struct platepack_params *pp, gsl_rng *rng, platepack_progress_fn fn,
    void *ctx, struct platepack_status *final);

/* Steps of engine d under the wall servo (dem_servo at pp->rate, the periodic axes fixed)
 * until static: the mean unbalanced force below pp->rest_tol of the mean interaction force
 * and the wall stress within 5 % of target (scaled units, k_n / r0), checked every 100
 * steps, at most pp->max_steps; st (stage as given) is filled, fn called every 1000 steps.
 * The damping is d's own.  0 or -1 (msg_seterr).  Stage 1 and 2 of platepack_make, and the
 * shear's relaxation before its strain (plateshear.h). */
int platepack_settle(struct engine *d, const struct platepack_params *pp, double target, int stage, platepack_progress_fn fn,
    void *ctx, struct platepack_status *st);

#endif
