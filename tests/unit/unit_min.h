/* SPDX-License-Identifier: GPL-3.0-or-later */
/* unit_min: minimising a copy of a start and comparing two equilibria, shared by the unit
 * tests of the minimisers (test_minimize, test_hessian). */
#ifndef QUSGM_UNIT_MIN_H
#define QUSGM_UNIT_MIN_H

#include <math.h>
#include <string.h>
#include "qs/functional.h"
#include "qs/loading.h"
#include "qs/minimize.h"
#include "unit_pack.h"

/* Minimise from x0 (copied into x) by method m to tol (max_iter, and cap when > 0, else the
 * defaults); each grain's contacts at the end into cnt unless NULL.  Returns the energy. */
static double __attribute__((unused))
energy_from(struct pack *p, const double *x0, const struct qs_method_type *m, long max_iter, double tol, double cap,
    double *x, struct qs_min_report *rep, unsigned *cnt)
{
	struct qs_system s;
	struct qs_min_params mp;

	memcpy(x, x0, 3 * p->n * sizeof *x);
	qs_init(&s, p, 0.3);
	qs_min_params_default(&mp);
	mp.method = m;
	mp.max_iter = max_iter;
	mp.tol = tol;
	if (cap > 0)
		mp.cap = cap;
	qs_minimize(&s, x, &mp, rep);
	if (cnt) {
		qs_energy(&s, x, NULL, NULL);
		qs_coordination(&s, x, cnt);
	}
	qs_free(&s);
	return rep->energy;
}

/* The minimisers' common start (test_minimize, test_hessian): p a random 200-grain pack
 * (seed 31337, overlaps up to 4 %), its CG equilibrium to 1e-6 (CG's report into rep, each
 * grain's contacts into cnt, the positions into xeq unless NULL), then x0 = that
 * equilibrium strained 1e-4 along z (p's box too) and perturbed by 1e-5 of the mean
 * radius per coordinate.  Returns the grains with at least 4 contacts at the equilibrium. */
static size_t __attribute__((unused))
strained_start(struct pack *p, gsl_rng *rng, double *x0, double *xeq, struct qs_min_report *rep, unsigned *cnt)
{
	size_t n = 200, i, k, braced = 0;
	double de[3] = {0, 0, 1e-4}, rmean = 0;

	gsl_rng_set(rng, 31337);
	random_pack(p, rng, n, 1e-4, 0.66, 0.04);
	for (i = 0; i < n; i++)
		rmean += p->r[i] / n;
	energy_from(p, p->x, &qs_method_cg, 200000, 1e-6, 0, x0, rep, cnt);
	for (i = 0; i < n; i++)
		braced += cnt[i] >= 4;
	if (xeq)
		memcpy(xeq, x0, 3 * n * sizeof *xeq);
	load_strain_box(p->box, x0, n, de);
	for (k = 0; k < 3 * n; k++)
		x0[k] += 1e-5 * rmean * (2 * gsl_rng_uniform(rng) - 1);
	return braced;
}

/* The largest coordinate difference of two equilibria xa, xb over each grain's radius,
 * leaving out (and counting into *rattlers) the grains without contacts in either. */
static double __attribute__((unused))
equilibria_apart(const struct pack *p, const double *xa, const double *xb, const unsigned *ca, const unsigned *cb,
    unsigned *rattlers)
{
	double dpos = 0;
	size_t i;
	int a;

	*rattlers = 0;
	for (i = 0; i < p->n; i++) {
		if (ca[i] == 0 || cb[i] == 0) {
			(*rattlers)++;
			continue;
		}
		for (a = 0; a < 3; a++)
			dpos = fmax(dpos, fabs(xa[3 * i + a] - xb[3 * i + a]) / p->r[i]);
	}
	return dpos;
}

#endif
