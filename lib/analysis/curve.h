/* curve: moduli along a stress-strain curve (physics.md §8), the physics behind the moduli
 * tool.
 *
 * A curve is loadtest's table: rows of strains eps_ll and stresses sig_ll (compression
 * positive) in increment order, grouped in path segments.  An interval is a block of k
 * consecutive increments within one segment (the increment into a row belongs to that row's
 * segment; a shorter block ends a segment); its moduli are the least-squares Hooke fit of
 * its increments (hooke_fit): K and G where the path determines them, NaN where not. */
#ifndef QUSGM_CURVE_H
#define QUSGM_CURVE_H

#include "analysis/hooke.h"
#include "base/table.h"

struct curve_cols {
	int eps[3], sig[3], sigma_c, sig_lat, seg, inc;	/* column indices; seg, inc, sig_lat may be -1 */
};

struct curve_interval {
	int seg;
	long inc_from, inc_to, n;
	size_t row_to;		/* table row of the interval's end */
	double sigma_c, sig_lat;	/* means of the interval's two end rows */
	struct hooke hk;
};

/* Find the columns; stress_prefix "sig" (wall stresses) or "sig_lw" (volume-averaged).
 * 0, or -1 with msg_seterr naming the missing column. */
int curve_columns(const struct table *t, const char *display, const char *stress_prefix, struct curve_cols *c);
/* Check the row order (inc strictly increasing; a segment-0 row repeating the previous
 * increment, the start row of a continued test, is skipped) and fit every interval of k
 * increments.  *out is malloc'd; 0, or -1 with msg_seterr("display:line: ..."). */
int curve_moduli(const struct table *t, const struct curve_cols *c, const char *display, long k,
    struct curve_interval **out, size_t *nout);

#endif
