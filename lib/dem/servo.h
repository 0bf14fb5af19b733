/* SPDX-License-Identifier: GPL-3.0-or-later */
/* servo: what the DEM compactions share (dem.c for spheres, platepack.c for spheroplates):
 * the wall servo, under which each axis with walls strains its box towards a target stress
 * and the grain centres follow the box affinely, and the rest criterion's unbalanced force. */
#ifndef QUSGM_SERVO_H
#define QUSGM_SERVO_H

#include <stddef.h>

/* One step: along each wall axis a (periodic[a] == 0, or periodic NULL) the mean normal force
 * of its two walls over their area gives the ratio to ptarget, and the box strains by
 * clamp(1 - ratio, -1, 1) times rate about its centre (proportional control: full rate far
 * from the target, slowing near it); the n centres x (3n) are mapped along.  Returns the mean
 * ratio over the wall axes (0 without one). */
double dem_servo(double lo[3], double hi[3], const double wallf[6], double ptarget, double rate, const int *periodic,
    double *x, size_t n);

/* The mean |net force| over the n grains (f, 3n) over the mean contact force sum_f / ncontacts:
 * 0 in static equilibrium; INFINITY without contacts or force. */
double dem_unbalanced(const double *f, size_t n, double sum_f, size_t ncontacts);

#endif
