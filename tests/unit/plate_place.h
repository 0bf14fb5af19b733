/* SPDX-License-Identifier: GPL-3.0-or-later */
/* plate_place.h: a pair of spheroplates at a chosen core distance, for test_plate and the
 * plate-contact benchmark (tests/bench/platecontact.c). */
#ifndef QUSGM_TEST_PLATE_PLACE_H
#define QUSGM_TEST_PLATE_PLACE_H

#include "contact/plate.h"
#include <math.h>

/* b along the unit vector dir from a where the cores are target apart, by bisection on the
 * ray (their distance only grows along it): 56 halvings of a few R are below round-off. */
static void
plate_place(const struct plate_body *a, struct plate_body *b, const double dir[3], double target)
{
	double lo = 0, hi = target + M_SQRT2 * (a->half + b->half) + 1e-3;
	int it, k;

	for (it = 0; it < 56; it++) {
		double mid = 0.5 * (lo + hi);
		for (k = 0; k < 3; k++)
			b->x[k] = a->x[k] + mid * dir[k];
		if (plate_core_distance(a, b, NULL, NULL) < target)
			lo = mid;
		else
			hi = mid;
	}
	for (k = 0; k < 3; k++)
		b->x[k] = a->x[k] + hi * dir[k];
}

#endif
