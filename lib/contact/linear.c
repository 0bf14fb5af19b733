/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linear: the linear spring law through the interface of law.h, from the kernels of linear.h
 * (see there and law.h). */
#include "contact/linear.h"
#include "contact/hertz.h"

static double
linear_normal(const struct contact_law *law, const struct law_pair *lp, double h, double *P, double *k)
{
	(void)law;
	if (h <= 0) {
		if (P)
			*P = 0;
		if (k)
			*k = 0;
		return 0;
	}
	if (P)
		*P = linear_force(lp->kn, h);
	if (k)
		*k = lp->kn;
	return linear_energy(lp->kn, h);
}

static void
linear_tangent(const struct contact_law *law, const struct law_pair *lp, double h, double P, struct law_tangent *t)
{
	(void)h;
	t->k = law->kt_ratio * lp->kn;
	t->qmax = law_coulomb_limit(lp->mu, P);
	t->kt = 0;
	t->mmax = 0;
}

static double
linear_law_dem_interaction(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    double *hist, double *fk, double ft[3], double *fel)
{
	(void)law;
	return linear_dem_interaction(lp, in, hist, fk, ft, fel);
}

/* the pair setup is Hertz-Mindlin's (hertz_mindlin_pair): of it the law reads mu and kn */
const struct contact_law contact_law_linear = {
	"linear", 3, 1e5, 0.888888888888889, 0.3,
	hertz_mindlin_pair, linear_normal, linear_tangent, linear_law_dem_interaction, "linear",
};
