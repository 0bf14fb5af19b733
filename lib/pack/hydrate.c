/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hydrate: tagging the smallest grains (see hydrate.h). */
#include "pack/hydrate.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>

static const double *sort_r;	/* the radii qsort compares by (one sort at a time) */

static int
cmp_radius(const void *a, const void *b)
{
	size_t i = *(const size_t *)a, j = *(const size_t *)b;

	if (sort_r[i] != sort_r[j])
		return sort_r[i] < sort_r[j] ? -1 : 1;
	return i < j ? -1 : i > j;
}

int
pack_tag_hydrate(struct pack *p, double F, const struct material *hyd, gsl_rng *rng, size_t *ntag,
    double *reached)
{
	size_t *ord, i, k, m;
	double total = 0, sum = 0;

	if (!(F >= 0 && F < 1)) {
		msg_seterr("hydrate volume fraction %g is not in [0, 1)", F);
		return -1;
	}
	if (pack_require_spheres(p, "the hydrate tagging"))
		return -1;
	if (pack_set_phases(p))
		return -1;
	if (!(ord = malloc((p->n ? p->n : 1) * sizeof *ord))) {
		msg_seterr("out of memory");
		return -1;
	}
	for (i = 0; i < p->n; i++)
		ord[i] = i;
	sort_r = p->r;
	qsort(ord, p->n, sizeof *ord, cmp_radius);
	/* the total in the same order as the prefix sums: the last prefix is the total to the
	 * bit, so F < 1 always stops inside the pack */
	for (k = 0; k < p->n; k++)
		total += p->r[ord[k]] * p->r[ord[k]] * p->r[ord[k]];
	for (m = 0; m < p->n && !(sum >= F * total); m++) {
		i = ord[m];
		sum += p->r[i] * p->r[i] * p->r[i];
		p->phase[i] = PHASE_HYDRATE;
	}
	free(ord);
	/* the hydrate's moduli drawn in index order, so that a seed fixes them */
	for (i = 0; i < p->n; i++)
		if (p->phase[i] == PHASE_HYDRATE) {
			material_sample(hyd, rng, &p->E[i], &p->nu[i]);
			p->rho[i] = hyd->rho;
		}
	if (ntag)
		*ntag = m;
	if (reached)
		*reached = total > 0 ? sum / total : 0;
	return 0;
}
