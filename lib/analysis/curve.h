/* SPDX-License-Identifier: GPL-3.0-or-later */
/* curve: moduli along a stress-strain curve (physics.md §8), the physics behind the moduli
 * tool.
 *
 * A curve is loadtest's table: rows of strains eps_ll and stresses sig_ll (compression
 * positive) in increment order, grouped in path segments.  An interval is a block of k
 * consecutive increments within one segment (the increment into a row belongs to that row's
 * segment; a shorter block ends a segment; with pool the blocks run across segments, so
 * that the three uniaxial segments of a probe along x, y and z are fitted together and
 * their moduli average the axes); its moduli are the least-squares Hooke fit of its
 * increments (hooke_fit): K and G where the path determines them, NaN where not. */
#ifndef QUSGM_CURVE_H
#define QUSGM_CURVE_H

#include "analysis/hooke.h"
#include "base/table.h"

struct curve_cols {
	int eps[3], sig[3], sigma_c, sig_lat, seg, inc;	/* column indices; seg, inc, sig_lat may be -1 */
	int from_sig;		/* 1: sigma_c and sig_lat are computed from the sig columns */
	int pool;		/* 1: intervals run across segments (0 from curve_columns) */
};

struct curve_interval {
	int seg;
	long inc_from, inc_to, n;
	size_t row_to;		/* table row of the interval's end */
	double sigma_c, sig_lat;	/* means of the interval's two end rows */
	struct hooke hk;
	/* a negative K or G is no modulus (a frictionless pack without shear rigidity on the
	 * path, or noise in a fit of too few increments): it is kept here, and hk has NaN for it,
	 * its standard error and what follows from it (lambda, E, nu) */
	double K_negative, G_negative;	/* the fitted value when negative, else NaN */
};

/* Find the columns; stress_prefix "sig" (wall stresses) or "sig_lw" (volume-averaged).
 * With "sig" the interval's sigma_c and sig_lat are the table's columns (the wall
 * stresses' mean, and that of the two lateral walls); with any other prefix they are
 * computed from that prefix's stresses the same way, the lateral axes being the two other
 * than the interval's largest strain increment (the loading axis of a uniaxial or triaxial
 * interval; for an isotropic one any choice gives sigma_c).  0, or -1 with msg_seterr naming
 * the missing column. */
int curve_columns(const struct table *t, const char *display, const char *stress_prefix, struct curve_cols *c);
/* Check the row order (inc strictly increasing; a segment-0 row repeating the previous
 * increment, the start row of a continued test, is skipped) and fit every interval of k
 * increments.  *out is malloc'd; 0, or -1 with msg_seterr("display:line: ..."). */
int curve_moduli(const struct table *t, const struct curve_cols *c, const char *display, long k,
    struct curve_interval **out, size_t *nout);

#endif
