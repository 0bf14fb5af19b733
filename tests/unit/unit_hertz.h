/* SPDX-License-Identifier: GPL-3.0-or-later */
/* unit_hertz: the contact geometry of the O(N^2) Hertz references, written independently of
 * lib/qs/functional.c, and the Hertz part of the central-difference tolerances, shared by
 * test_functional, test_friction, test_lattice and test_lattice_moduli. */
#ifndef QUSGM_UNIT_HERTZ_H
#define QUSGM_UNIT_HERTZ_H

#include <math.h>
#include <stddef.h>
#include "contact/hertz.h"
#include "pack/pack.h"

/* Grains i and j of p at positions x: d = x_i - x_j, its length *dist and the overlap
 * *h = r_i + r_j - *dist; nonzero when they touch (|d|^2 < (r_i + r_j)^2). */
static int __attribute__((unused))
unit_pair_overlap(const struct pack *p, const double *x, size_t i, size_t j, double d[3], double *dist, double *h)
{
	double dd = 0, S = p->r[i] + p->r[j];
	int a;

	for (a = 0; a < 3; a++) {
		d[a] = x[3 * i + a] - x[3 * j + a];
		dd += d[a] * d[a];
	}
	*dist = sqrt(dd);
	*h = S - *dist;
	return !(dd >= S * S);
}

/* Grain i of p at positions x against wall w (normal to axis w / 2, the upper one when w is
 * odd): returns the overlap r_i - distance, positive in contact, and then sets the contact
 * modulus *Es and the Hertz force *P (R* = r_i). */
static double __attribute__((unused))
unit_wall_contact(const struct pack *p, const double *x, size_t i, int w, double *Es, double *P)
{
	int a = w / 2;
	double dist = w % 2 ? p->box[3 + a] - x[3 * i + a] : x[3 * i + a] - p->box[a], h = p->r[i] - dist;

	if (h > 0) {
		*Es = hertz_Estar(p->E[i], p->nu[i], p->wall_E, p->wall_nu);
		*P = hertz_force(*Es, p->r[i], h);
	}
	return h;
}

/* The Hertz part of the tolerance of a central difference of step hs of the energy at x
 * (test_functional's analysis): for every grain i,
 *  - trunc[i] += the bound on |U'''| of its contacts: 3P/(4h^2) + 9P/(2hd) + 3P/d^2 for a
 *    grain-grain contact at centre distance d, 3P/(4h^2) for a wall contact;
 *  - excl[i] = 1 when one of its contacts or near contacts lies within 50 hs of h = 0, where
 *    Hertz is not C3;
 *  - *rsum += 4 P S (S the radii sum) once per grain-grain contact, 4 P r_i per wall contact;
 *  - unless sabs is NULL, *sabs += 0.4 P h (the contact's energy) likewise. */
static void __attribute__((unused))
unit_hertz_fd_bounds(const struct pack *p, const double *x, double hs, double *trunc, char *excl, double *rsum,
    double *sabs)
{
	size_t i, j, n = p->n;
	int w;

	for (i = 0; i < n; i++) {
		for (j = 0; j < n; j++) {
			double dv[3], d, h, P;
			if (j == i)
				continue;
			unit_pair_overlap(p, x, i, j, dv, &d, &h);
			if (fabs(h) < 50 * hs)
				excl[i] = 1;
			if (h <= 0)
				continue;
			P = hertz_force(hertz_Estar(p->E[i], p->nu[i], p->E[j], p->nu[j]), hertz_Rstar(p->r[i], p->r[j]), h);
			trunc[i] += 0.75 * P / (h * h) + 4.5 * P / (h * d) + 3 * P / (d * d);
			if (i < j) {
				*rsum += 4 * P * (p->r[i] + p->r[j]);
				if (sabs)
					*sabs += 0.4 * P * h;
			}
		}
		for (w = 0; w < NWALLS; w++) {
			double Es, P, h = unit_wall_contact(p, x, i, w, &Es, &P);
			if (fabs(h) < 50 * hs)
				excl[i] = 1;
			if (h <= 0)
				continue;
			trunc[i] += 0.75 * P / (h * h);
			*rsum += 4 * P * p->r[i];
			if (sabs)
				*sabs += 0.4 * P * h;
		}
	}
}

#endif
