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
hertz_mindlin_pair(const struct contact_law *law, const struct law_pack *lk, size_t i, long j, struct law_pair *lp)
{
	const struct pack *p = lk->p;
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
	(void)law;
	lp->kn = lk->kn;
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

static double
hertz_overlap_of(const struct contact_law *law, const struct law_pair *lp, double P)
{
	(void)law;
	return hertz_overlap(lp->Es, lp->Rs, P);
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

/* The pack's mean Young's modulus and Poisson ratio: the mean grain of the DEM's units. */
static void
mean_material(const struct pack *p, double *Em, double *num)
{
	size_t i, n = p->n;

	*Em = *num = 0;
	for (i = 0; i < n; i++)
		*Em += p->E[i] / n, *num += p->nu[i] / n;
}

double
hertz_mean_Estar(const struct pack *p)
{
	double Em, num;

	mean_material(p, &Em, &num);
	return hertz_Estar(Em, num, Em, num);
}

/* The DEM's units: k0 = E* r0 of two mean grains (hertz_mean_Estar); the walls' E* with the
 * mean grain over it. */
static double
hertz_dem_units(const struct contact_law *law, const struct pack *p, double r0, double kn, struct law_pair *g,
    struct law_pair *w)
{
	double Em, num, Eg;

	(void)law, (void)kn;
	mean_material(p, &Em, &num);
	Eg = hertz_Estar(Em, num, Em, num);
	g->kn = w->kn = 1;
	g->Es = 1;
	w->Es = hertz_Estar_c(hertz_compliance(Em, num), p->wall_E > 0 ? hertz_compliance(p->wall_E, p->wall_nu) : 0) / Eg;
	return Eg * r0;
}

static double
hertz_stiffest(const struct contact_law *law, const struct law_pair *w, double r, double h)
{
	(void)law;
	return hertz_stiffness_t(w->Es, r, h);
}

/* kappa = (E* / sigma)^(2/3) (Agnolin and Roux's, with E* for their E / (1 - nu^2)). */
static double
hertz_kappa(const struct contact_law *law, const struct pack *p, double kn, double sigma)
{
	(void)law, (void)kn;
	return pow(hertz_mean_Estar(p) / sigma, 2.0 / 3.0);
}

static double
hertz_kappa_stress(const struct contact_law *law, const struct pack *p, double kn, double kappa)
{
	(void)law, (void)kn;
	return hertz_mean_Estar(p) / (kappa * sqrt(kappa));
}

/* The spring's stiffness kt_ratio times the elements' summed k_n (hertz_dem_interaction). */
static double
hertz_dem_kt(const struct law_pair *lp, const struct law_dem_elems *in)
{
	double ksum = 0;
	int k;

	for (k = 0; k < in->m; k++)
		ksum += hertz_stiffness_t(lp->Es, lp->Rs, in->h[k] > 0 ? in->h[k] : 0);
	return in->kt_ratio * ksum;
}

/* The history is the spring's displacement xi (law_dem_spring): its force is -k_t xi. */
static void
hertz_history_force(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double *hist, double Q[3])
{
	double kt = hertz_dem_kt(lp, in);
	int a;

	(void)law;
	for (a = 0; a < 3; a++)
		Q[a] = -kt * hist[a];
}

static void
hertz_history_set(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double Q[3], double *hist)
{
	double kt = hertz_dem_kt(lp, in);
	int a;

	(void)law;
	for (a = 0; a < 3; a++)
		hist[a] = kt > 0 ? -Q[a] / kt : 0;
}

static int
hertz_law_stress_in_range(const struct contact_law *law, const struct pack *p, double stress)
{
	(void)law;
	return hertz_stress_in_range(p, stress);
}

/* kt_ratio 2(1-nu)/(2-nu) at nu = 0.2 (Mindlin stick over Hertz stiffness), zeta 0.3: the
 * DEM settling of packgen's loose packs (dem.h) */
const struct contact_law contact_law_hertz_mindlin = {
	.name = "hertz-mindlin", .history = 3, .kn = 0, .kt_ratio = 0.888888888888889, .zeta = 0.3,
	.pair = hertz_mindlin_pair, .normal = hertz_normal, .overlap = hertz_overlap_of, .coulomb = law_coulomb_mu,
	.tangent = mindlin_tangent,
	.dem_interaction = hertz_mindlin_dem_interaction, .pack_key = "hertz", .stiffness = LAW_MODULI,
	.dem_units = hertz_dem_units, .stiffest = hertz_stiffest, .kappa = hertz_kappa, .kappa_stress = hertz_kappa_stress,
	.history_force = hertz_history_force, .history_set = hertz_history_set,
	.stress_in_range = hertz_law_stress_in_range,
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
