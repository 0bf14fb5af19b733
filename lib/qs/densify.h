/* SPDX-License-Identifier: GPL-3.0-or-later */
/* densify: phase (a) of making a pack (physics.md §9, S §2.4): frictionless isotropic
 * compaction of a loose pack.
 *
 * Rounds: every grain with fewer than min_coord contacts (grain plus wall) is expanded until
 * it touches min_coord neighbours or walls (at most max_growth of its radius per round), the
 * box is shrunk by strain_step while the confining stress is below the onset, and the pack is
 * brought to equilibrium.  The rounds end when the stress has reached the onset (the pack has
 * jammed); that box becomes the reference box for strains.  Then the box is compressed
 * isotropically (a secant on sigma_c^(2/3), which Hertz contacts make nearly linear in strain)
 * until sigma_c is within stress_tol of the target, and every grain that is (or falls) under
 * min_coord contacts is grown at each step as in the rounds; the compaction ends with the
 * target stress, no grain under min_coord and a full equilibrium.  A growth round only
 * decides which grains grow next: it is minimised to the looser grow_tol in at most
 * grow_max_iter iterations (not an error).  Near jamming a full-tolerance minimisation slows
 * critically (70k L-BFGS iterations in the jamming round of a 1e4-grain pack).
 *
 * Below the onset the residual's force floor is what a contact carries at the onset (an
 * unjammed pack has no load to balance).  A compaction step that moves the box or grows grains
 * is minimised like a growth round, to grow_tol in at most grow_max_iter iterations
 * (loose_steps): it only brings the pack nearer the target.  The step that stays at the target
 * (sigma_c within stress_tol) with no grain to grow is the full equilibrium, and only a full
 * step ends the compaction, judged again on its own stress.  Why these choices, with the
 * measurements: bench/densify.md.
 *
 * Every minimisation here runs in chunks of release_after iterations; between chunks the
 * grains with 1-3 contacts, which frictionless equilibrium holds only once those contacts
 * have opened, are moved to where they just touch (qs_release_unbraced).  The minimiser
 * opens such a contact only asymptotically (the Hertz stiffness vanishes as h^(1/2)): a
 * 1e5-grain pack's second compaction step stood at a largest residual near 1 after 99k
 * L-BFGS iterations, held by hundreds of grains with one contact left (bench/densify.md).
 *
 * After a release the minimiser starts afresh (release_keep 0, the default): keeping its
 * memory (release_keep 1: the L-BFGS pairs survive, qs_minimizer_moved) was slower on every
 * pack tried (bench/densify.md), since the stored pairs describe the curvature before the
 * release moved the grains. */
#ifndef QUSGM_DENSIFY_H
#define QUSGM_DENSIFY_H

#include "qs/minimize.h"
#include "pack/pack.h"

struct densify_params {
	double stress;		/* target confining stress sigma_c (Pa) */
	double onset;		/* stress that marks the reference box (Pa); 0: densify_onset_default */
	double stress_tol;	/* relative tolerance on the final sigma_c */
	double strain_step;	/* largest isotropic strain per step */
	double max_growth;	/* largest relative growth of a radius per round */
	double grow_tol;	/* residual target of growth rounds and loose compaction steps */
	long grow_max_iter;	/* iteration limit of those */
	long release_after;	/* minimiser iterations between releases of unbraced grains; 0: never */
	int release_keep;	/* between releases, keep the minimiser's memory (1) or restart it (0) */
	int loose_steps;	/* compaction steps that move the box or grow grains: to grow_tol in grow_max_iter (1), or full (0) */
	unsigned min_coord;
	long max_rounds;
	int nsub;		/* sub-increments per strain step */
	long k_inc;		/* minimiser iterations between sub-increments */
	double skin;		/* Verlet skin / smallest radius */
	struct qs_min_params min;
};

struct densify_stage {
	const char *stage;	/* "relax", "grow", "compact" */
	long round;
	double sigma_c, porosity, coordination;
	size_t under4;
	size_t under_min;	/* grains under min_coord contacts (under4 when min_coord is 4) */
	double growth;		/* mean relative radius growth so far */
	long iterations;
	double res_max, res_mean;
	int min_status;
};

typedef void (*densify_log_fn)(const struct densify_stage *st, void *ctx);

/* Where a run stands after a stage (a checkpoint): with the pack's centres, radii, box and
 * reference box it is everything the run carries from one stage to the next, so a run
 * resumed from it goes on exactly, to the bit, as the run that wrote it would have (every
 * stage starts its minimiser afresh and rebuilds what it needs from the positions).  Long
 * runs (1e6 grains: hours) can so be split into jobs that fit a cluster's time limit. */
struct densify_resume {
	int phase;		/* the stage just ended: 0 the relaxation, 1 a growth round, 2 a compaction step */
	long round;
	double scale;		/* the growth rounds' squeeze and growth factor (halved by a retry) */
	double r0sum;		/* the input radii's sum: growth is counted from it */
	double skin;		/* the Verlet skin (m), set from the input's smallest radius */
	double e_prev, y_prev;	/* the compaction secant's last point (NaN before the first step) */
	int full;		/* the last stage was minimised to the full tolerance */
	int have_ref;		/* p->refbox holds the reference box (set in phase (a)) */
	int limit_hit;
	struct densify_stage st;	/* the stage's measures, as logged */
};

/* Called after every stage with the pack's centres in p->x; nonzero stops the run (densify_run
 * returns 2), -1 is an error. */
typedef int (*densify_checkpoint_fn)(const struct pack *p, const struct densify_resume *at, void *ctx);

/* The default onset for a target stress: 1e5 Pa, or a tenth of the target below 1 MPa.
 * Just above jamming the minimisations slow critically as the stress falls (the Hessian's
 * soft modes): at 1e4 Pa a 1e4-grain pack spent 100k+ L-BFGS iterations per round and did
 * not finish in an hour, at 1e5 Pa it reached 4 MPa in 227 s; a 2740-grain pack took 49 s
 * and 26 s, ending at porosity 0.3859 and 0.3843.  The price: strains count from a box
 * (1e5/4e6)^(2/3) = 8.5 % of the Hertz strain to 4 MPa past the first contact forces. */
double densify_onset_default(double stress);

void densify_params_default(struct densify_params *dp);
/* Densify p in place (positions, radii, box, refbox, contacts).  0 on success; 1 when a
 * minimisation hit its iteration limit (p holds the state reached); -1 on error. */
int densify_run(struct pack *p, const struct densify_params *dp, densify_log_fn fn, void *ctx,
    struct densify_stage *last);
/* densify_run, with ck called after every stage, and from (NULL: the start) a checkpoint to
 * go on from, p then holding the checkpoint's pack.  2 when ck stopped the run. */
int densify_run_resumable(struct pack *p, const struct densify_params *dp, densify_log_fn fn, void *ctx,
    densify_checkpoint_fn ck, const struct densify_resume *from, struct densify_stage *last);

/* The checkpoint as header meta lines of the pack (keys "densify-..."), and back: the state
 * numbers written to round-trip exactly, the reference box when p does not carry it yet, run
 * (what the caller needs to recognise its own run: options, input) and the log rows so far
 * (one per line).  densify_resume_get returns 0 with *at, *run and *rows filled (the caller
 * frees the strings) and the meta removed, 1 when p holds no checkpoint, -1 on a malformed
 * one (message in msg_geterr). */
int densify_resume_put(struct pack *p, const struct densify_resume *at, const char *run, const char *rows);
int densify_resume_get(struct pack *p, struct densify_resume *at, char **run, char **rows);
void densify_resume_clear(struct pack *p);
/* Whether the checkpoint at was written by a run from input with dp (its radii's sum and the
 * skin, which follow from them): 0, or -1 with the message set. */
int densify_resume_check_input(const struct pack *input, const struct densify_params *dp,
    const struct densify_resume *at);

#include <stdio.h>

/* The log: one TSV header, one row per stage; its last column, elapsed[s], is the wall time
 * since the run started (over every call of a run resumed from checkpoints). */
void densify_log_header(FILE *fp);
void densify_log_row(FILE *fp, const struct densify_stage *st, double elapsed);

#endif
