/* SPDX-License-Identifier: GPL-3.0-or-later */
/* linear: the linear spring law through the interface of law.h, from the kernels of linear.h
 * (see there and law.h). */
#include "contact/linear.h"
#include "contact/hertz.h"

static double
linear_normal(const struct contact_law *law, const struct law_pair *lp, double h, double *P, double *k)
{
	(void)lp;
	if (h <= 0) {
		if (P)
			*P = 0;
		if (k)
			*k = 0;
		return 0;
	}
	if (P)
		*P = linear_force(law->kn, h);
	if (k)
		*k = law->kn;
	return linear_energy(law->kn, h);
}

static void
linear_tangent(const struct contact_law *law, const struct law_pair *lp, double h, double P, struct law_tangent *t)
{
	(void)h;
	t->k = law->kt_ratio * law->kn;
	t->qmax = law_coulomb_limit(lp->mu, P);
	t->kt = 0;
	t->mmax = 0;
}

static double
linear_law_dem_force(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_in *in,
    double *hist, double ft[3], double *fel)
{
	return linear_dem_force(law->zeta, law->kt_ratio, law->kn, lp, in, hist, ft, fel);
}

/* the pair setup is Hertz-Mindlin's (hertz_mindlin_pair): of it the law reads mu */
const struct contact_law contact_law_linear = {
	"linear", 3, 1e5, 0.888888888888889, 0.3,
	hertz_mindlin_pair, linear_normal, linear_tangent, linear_law_dem_force, "linear",
};
