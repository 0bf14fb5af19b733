/* unit_min: minimising a copy of a start and comparing two equilibria, shared by the unit
 * tests of the minimisers (test_minimize, test_hessian). */
#ifndef QUSGM_UNIT_MIN_H
#define QUSGM_UNIT_MIN_H

#include <math.h>
#include <string.h>
#include "qs/functional.h"
#include "qs/minimize.h"

/* Minimise from x0 (copied into x) by method m to tol (max_iter, and cap when > 0, else the
 * defaults); each grain's contacts at the end into cnt unless NULL.  Returns the energy. */
static double __attribute__((unused))
energy_from(struct pack *p, const double *x0, enum qs_method m, long max_iter, double tol, double cap, double *x,
    struct qs_min_report *rep, unsigned *cnt)
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
