/* frictionalize: phase (b) of making a pack (physics.md §9, F §3.2): friction is switched on
 * and the pack is loaded in uniaxial strain, increment by increment, until the fraction of
 * sliding contacts stops growing.
 *
 * Saturation: after at least `window` increments, the sliding ratio of the last `window`
 * increments spans less than sat_tol (max - min); the run then stops.  A run that reaches
 * max_inc increments without saturating is reported (status 2) so that the tool can refuse
 * or keep it.  Each increment's K and G come from hooke_fit of its stress and strain
 * increments (uniaxial strain determines both). */
#ifndef QUSGM_FRICTIONALIZE_H
#define QUSGM_FRICTIONALIZE_H

#include "hooke.h"
#include "loading.h"

struct fric_params {
	int axis;		/* loading axis 0..2 */
	double strain_step;	/* compression per increment along axis */
	long window, min_inc, max_inc;
	double sat_tol;
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

#endif
