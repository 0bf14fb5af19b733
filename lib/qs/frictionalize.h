/* SPDX-License-Identifier: GPL-3.0-or-later */
/* frictionalize: phase (b) of making a pack (physics.md §9, F §3.2): friction is switched on
 * and the pack is loaded in uniaxial strain, increment by increment, until the fraction of
 * sliding contacts stops growing.
 *
 * Saturation: after at least min_inc and 2 `window` increments, the mean sliding ratio of the
 * last `window` increments differs from the mean of the `window` before them by less than
 * sat_tol times itself (relative: the level the ratio saturates at depends on mu and on the
 * pack); the run then stops.  Means, not the span of the values: the ratio of a small pack
 * jumps by one contact in a few hundred from increment to increment, and the span of a long
 * window grows with its length even when the trend is flat.  The strain that
 * mobilises friction at a contact scales with its normal overlap (Q_max / k* is about
 * mu h, physics.md §4), so the window is widened to cover at least window_overlap times the
 * mean overlap / radius of the starting pack in strain: a fixed count of increments that
 * is right at 4 MPa stops a 41 MPa pack at a transient plateau (0.054 of 300 grains'
 * contacts sliding, then 0.08 in the test that followed, with G still falling).  A run that reaches
 * max_inc increments without saturating is reported (status 2) so that the tool can refuse
 * or keep it.  Each increment's K and G come from hooke_fit of its stress and strain
 * increments (uniaxial strain determines both). */
#ifndef QUSGM_FRICTIONALIZE_H
#define QUSGM_FRICTIONALIZE_H

#include "analysis/hooke.h"
#include "qs/loading.h"

/* FRIC_UNTIL_SLIDING: the sliding ratio has saturated (above); FRIC_UNTIL_SHEAR: the shear
 * modulus has passed its minimum, the mean G of the last window above that of the window
 * before (F §3.2: phase (b) is complete "once frictional loads are well-developed, the moduli
 * increase with sigma_c").  Both with the same windows. */
enum fric_until { FRIC_UNTIL_SLIDING, FRIC_UNTIL_SHEAR };

struct fric_params {
	enum fric_until until;
	int axis;		/* loading axis 0..2 */
	double strain_step;	/* compression per increment along axis */
	long window, min_inc, max_inc;
	double sat_tol;
	double window_overlap;	/* window strain >= this x mean overlap / radius (0: off) */
	struct load_params lp;
};

typedef void (*fric_row_fn)(const struct load_row *row, const struct hooke *hk, void *ctx);

void fric_params_default(struct fric_params *fp);
/* Frictionalize p in place.  fn (may be NULL) gets the starting row (inc 0, no moduli) and
 * then one row per increment.  Returns 0 when saturated, 1 when a minimisation hit its
 * iteration limit, 2 when max_inc passed without saturation, -1 on error; last gets the last
 * row. */
int frictionalize_run(struct pack *p, const struct fric_params *fp, fric_row_fn fn, void *ctx,
    struct load_row *last);
/* The window (increments) frictionalize_run uses on p: window, widened by window_overlap. */
long fric_window(const struct pack *p, const struct fric_params *fp);

#endif
