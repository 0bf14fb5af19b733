/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hertz: the Hertz-Mindlin contact law through the interface of law.h, from the kernels of
 * hertz.h (see there and law.h). */
#include "contact/hertz.h"

#include "base/msg.h"

#include <math.h>

static double
shear_modulus(double E, double nu)
{
	return E / (2 * (1 + nu));
}

void
hertz_mindlin_pair(const struct contact_law *law, const struct pack *p, size_t i, long j, struct law_pair *lp)
{
	double Gi = shear_modulus(p->E[i], p->nu[i]), Gj, nuj;

	hertz_pair_moduli(p, i, j, &lp->Es, &lp->Rs);
	if (PACK_IS_WALL(j)) {
		Gj = shear_modulus(p->wall_E, p->wall_nu);
		nuj = p->wall_nu;
	} else {
		Gj = shear_modulus(p->E[j], p->nu[j]);
		nuj = p->nu[j];
	}
	lp->Ct = (2 - p->nu[i]) / Gi + (2 - nuj) / Gj;
	lp->Ctor = 1 / Gi + 1 / Gj;
	lp->mu = pack_contact_mu(p, j);
	lp->kn = law->kn;
}

static double
hertz_normal(const struct contact_law *law, const struct law_pair *lp, double h, double *P, double *k)
{
	double f = hertz_force(lp->Es, lp->Rs, h);

	(void)law;
	if (P)
		*P = f;
	if (k)
		*k = hertz_stiffness(lp->Es, lp->Rs, h);
	return hertz_energy_P(f, h);
}

static void
mindlin_tangent(const struct contact_law *law, const struct law_pair *lp, double h, double P, struct law_tangent *t)
{
	double a = hertz_radius(lp->Rs, h);

	(void)law;
	t->k = mindlin_stiffness(a, lp->Ct);
	t->qmax = law_coulomb_limit(lp->mu, P);
	t->kt = mindlin_twist_stiffness(a, lp->Ctor);
	t->mmax = mindlin_twist_limit(a, lp->mu, P);
}

static double
hertz_mindlin_dem_interaction(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    double *hist, double *fk, double ft[3], double *fel)
{
	(void)law;
	return hertz_dem_interaction(lp, in, hist, fk, ft, fel);
}

/* kt_ratio 2(1-nu)/(2-nu) at nu = 0.2 (Mindlin stick over Hertz stiffness), zeta 0.3: the
 * DEM settling of packgen's loose packs (dem.h) */
const struct contact_law contact_law_hertz_mindlin = {
	"hertz-mindlin", 3, 0, 0.888888888888889, 0.3,
	hertz_mindlin_pair, hertz_normal, mindlin_tangent, hertz_mindlin_dem_interaction, "hertz",
};

int
hertz_stress_in_range(const struct pack *p, double stress)
{
	size_t i, soft = 0;

	for (i = 0; i < p->n; i++)
		if (p->E[i] < p->E[soft])
			soft = i;
	if (p->n && stress >= 0.01 * p->E[soft]) {
		msg_seterr("%g Pa is beyond the small-strain range of Hertz contacts (E/100 = %g Pa, E of grain %ld, the softest)",
		    stress, 0.01 * p->E[soft], p->id[soft]);
		return -1;
	}
	return 0;
}
