/* SPDX-License-Identifier: GPL-3.0-or-later */
/* dem: explicit discrete-element dynamics that makes packgen's loose packs.
 *
 * The papers start from a loose DEM pack in which grains touch their neighbours and many
 * have fewer than 4 contacts.  We make one by random sequential placement of the grains in
 * a large box (packing fraction phi0), then isotropic frictional compaction: the six walls
 * close in under servo control, positions follow the box affinely, and the grains relax by
 * explicit dynamics with Hertz normal contacts, Coulomb-limited tangential springs,
 * viscous normal damping and Cundall's local damping, until the wall stresses reach a
 * small target pressure and the pack is at rest.  No gravity: the stress is uniform, so
 * densify does not have to erase a depth gradient (physics.md §9).
 *
 * The dynamics run in scaled units (mean radius 1, grain-grain E* 1, density 1): the
 * geometry at rest depends only on the friction and on p/E*, which the target mean overlap
 * fixes (overlap/r ~ (p/E*)^(2/3)), not on the real material. */
#ifndef QUSGM_DEM_H
#define QUSGM_DEM_H

#include <gsl/gsl_rng.h>
#include "pack/pack.h"

struct dem_params {
	double mu;		/* friction coefficient during compaction */
	double overlap;		/* target mean overlap / radius at rest */
	double damping;		/* Cundall local damping, 0..1 */
	double phi0;		/* packing fraction of the random placement */
	double aspect[3];	/* box side ratios */
	double rest_tol;	/* at rest: mean |net force| / mean contact force below this */
	double preload;		/* jam at this multiple of the target stress, then unload */
	double viscous;		/* fraction of the velocity lost per step */
	double rate;		/* largest strain of the box per step */
	double dt_safety;	/* time step over sqrt(m_eff / k) of the stiffest likely contact */
	long max_steps;
	int pair_lanes;		/* 1 (default): grain pairs' forces two at a time in lanes; 0: one at
				 * a time.  The same bytes either way (tests/unit/test_dem.c) */
};

struct dem_status {
	long step;
	double phi;		/* packing fraction */
	double p_ratio;		/* mean wall stress / target */
	double coordination;
	double unbalanced;
	double max_overlap;	/* largest overlap / smaller radius */
	int stage;		/* 1: jamming at the preload, 2: unloading to the target */
	int at_rest;
};

typedef void (*dem_progress_fn)(const struct dem_status *s, void *ctx);

void dem_params_default(struct dem_params *dp);

/* Place p's grains (radii set by the caller, in metres) and set the box: on return the
 * grains are at rest in the fitted box, renumbered (ids 1..N) in spatial order.  0 on success; -1 with the error slot set (also
 * when max_steps is reached before rest). */
int dem_loose_pack(struct pack *p, const struct dem_params *dp, gsl_rng *rng, dem_progress_fn fn,
    void *ctx, struct dem_status *final);

#endif
