/* SPDX-License-Identifier: GPL-3.0-or-later */
/* unit_pack: a random polydisperse pack with controlled overlaps, shared by the unit tests
 * of the functional and the minimisers. */
#ifndef QUSGM_UNIT_PACK_H
#define QUSGM_UNIT_PACK_H

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include "pack/pack.h"

/* n grains, radii uniform in scale * [0.7, 1.3], E normal about 70 GPa (sd 10 %), nu uniform
 * in [0.15, 0.25], uniformly placed in a box of nominal solid fraction phi (not at the origin,
 * not a cube), walls 100 x stiffer; then sweeps of pairwise separation push every overlap back
 * below ovmax times the pair's mean radius (a random target below it, so that overlaps spread
 * over (0, ovmax]); grain-wall overlaps likewise below ovmax R. */
static void __attribute__((unused))
random_pack(struct pack *p, gsl_rng *rng, size_t n, double scale, double phi, double ovmax)
{
	double vol = 0, L;
	size_t i, j;
	int a, sweep;

	pack_init(p);
	for (i = 0; i < n; i++) {
		double x[3] = {0, 0, 0}, r = scale * (0.7 + 0.6 * gsl_rng_uniform(rng));
		double E = 7e10 * (1 + 0.1 * gsl_ran_gaussian(rng, 1.0));
		pack_add_grain(p, (long)i, x, r, E, 0.15 + 0.1 * gsl_rng_uniform(rng), 2420);
		vol += 4.0 / 3.0 * M_PI * r * r * r;
	}
	L = cbrt(vol / phi);
	for (a = 0; a < 3; a++) {
		p->box[a] = (a - 1) * 0.37 * L;
		p->box[3 + a] = p->box[a] + L * (1 + 0.05 * a);
	}
	p->wall_E = 7e12;
	p->wall_nu = 0.495;
	for (i = 0; i < n; i++)
		for (a = 0; a < 3; a++)
			p->x[3 * i + a] = p->box[a] + p->r[i] + gsl_rng_uniform(rng) * (p->box[3 + a] - p->box[a] - 2 * p->r[i]);
	for (sweep = 0; sweep < 4000; sweep++) {
		long moved = 0;
		for (i = 0; i < n; i++) {
			double *xi = p->x + 3 * i;
			for (j = i + 1; j < n; j++) {
				double *xj = p->x + 3 * j, d[3], dd = 0, sum = p->r[i] + p->r[j], dist, ov, lim, push;
				for (a = 0; a < 3; a++) {
					d[a] = xi[a] - xj[a];
					dd += d[a] * d[a];
				}
				if (dd >= sum * sum)
					continue;
				dist = sqrt(dd);
				ov = sum - dist;
				lim = ovmax * sum / 2;
				if (ov <= lim)
					continue;
				push = (ov - lim * gsl_rng_uniform(rng)) / 2;
				for (a = 0; a < 3; a++) {
					double u = dist > 0 ? d[a] / dist : (a == 0);
					xi[a] += push * u;
					xj[a] -= push * u;
				}
				moved++;
			}
			for (a = 0; a < 3; a++) {
				double lim = (1 - ovmax) * p->r[i];
				if (xi[a] - p->box[a] < lim) {
					xi[a] = p->box[a] + p->r[i] * (1 - ovmax * gsl_rng_uniform(rng));
					moved++;
				}
				if (p->box[3 + a] - xi[a] < lim) {
					xi[a] = p->box[3 + a] - p->r[i] * (1 - ovmax * gsl_rng_uniform(rng));
					moved++;
				}
			}
		}
		if (!moved)
			break;
	}
}

#endif
