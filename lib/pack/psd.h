/* SPDX-License-Identifier: GPL-3.0-or-later */
/* psd: grain-size (radius) distributions for packgen.
 *
 * Specs: "uniform:RMIN,RMAX" (m), "lognormal:MEDIAN,SIGMA[,RMIN,RMAX]" (SIGMA of ln r,
 * optional truncation, default [median/5, 5 median]), "table:FILE" (lines "r [weight]",
 * sampled with probability proportional to weight, default 1; # comments and blank lines
 * allowed; read through base/lines.h, so lines of any length, plain or gzip, and errors as
 * "file:line: what").  Draws use the GSL RNG. */
#ifndef QUSGM_PSD_H
#define QUSGM_PSD_H

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <stddef.h>

struct psd {
	enum { PSD_UNIFORM, PSD_LOGNORMAL, PSD_TABLE } kind;
	double a, b, lo, hi;
	double *table;
	size_t ntable;
	gsl_ran_discrete_t *disc;
};

int psd_parse(const char *spec, struct psd *d);	/* 0 or -1 with the slot set */
double psd_draw(const struct psd *d, gsl_rng *rng);
void psd_free(struct psd *d);

#endif
