/* law: the contact laws (see law.h). */
#include "contact/law.h"
#include "contact/hertz.h"

#include <math.h>
#include <string.h>

static double
shear_modulus(double E, double nu)
{
	return E / (2 * (1 + nu));
}

void
law_pair_from_pack(const struct contact_law *law, const struct pack *p, size_t i, long j, struct law_pair *lp)
{
	double Gi = shear_modulus(p->E[i], p->nu[i]), Gj, nuj;

	(void)law;
	if (PACK_IS_WALL(j)) {
		lp->Es = hertz_Estar(p->E[i], p->nu[i], p->wall_E, p->wall_nu);
		lp->Rs = p->r[i];
		Gj = shear_modulus(p->wall_E, p->wall_nu);
		nuj = p->wall_nu;
	} else {
		lp->Es = hertz_Estar(p->E[i], p->nu[i], p->E[j], p->nu[j]);
		lp->Rs = hertz_Rstar(p->r[i], p->r[j]);
		Gj = shear_modulus(p->E[j], p->nu[j]);
		nuj = p->nu[j];
	}
	lp->Ct = (2 - p->nu[i]) / Gi + (2 - nuj) / Gj;
	lp->Ctor = 1 / Gi + 1 / Gj;
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
	return 0.4 * f * h;	/* 8/15 E* sqrt(R*) h^(5/2) = 2/5 P h */
}

static void
mindlin_tangent(const struct contact_law *law, const struct law_pair *lp, double h, double P, double mu,
    struct law_tangent *t)
{
	double a = sqrt(lp->Rs * h);

	(void)law;
	t->k = 8 * a / lp->Ct;
	t->qmax = mu * P;
	t->kt = 16.0 / 3.0 * a * a * a / lp->Ctor;
	t->mmax = 3 * M_PI / 16 * a * mu * P;
}

static double
hertz_dem_force(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_in *in, double *hist,
    double ft[3], double *fel)
{
	return law_hertz_dem_force(law, lp, in, hist, ft, fel);
}

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
		*P = law->kn * h;
	if (k)
		*k = law->kn;
	return 0.5 * law->kn * h * h;
}

static void
linear_tangent(const struct contact_law *law, const struct law_pair *lp, double h, double P, double mu,
    struct law_tangent *t)
{
	(void)lp, (void)h;
	t->k = law->kt_ratio * law->kn;
	t->qmax = mu * P;
	t->kt = 0;
	t->mmax = 0;
}

static double
linear_dem_force(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_in *in, double *hist,
    double ft[3], double *fel)
{
	(void)lp;
	return law_dem_damped(law, in, law->kn, law->kn * in->h, hist, ft, fel);
}

/* kt_ratio 2(1-nu)/(2-nu) at nu = 0.2 (Mindlin stick over Hertz stiffness), zeta 0.3: the
 * DEM settling of packgen's loose packs (dem.h) */
const struct contact_law contact_law_hertz_mindlin = {
	"hertz-mindlin", 3, 0, 0.888888888888889, 0.3,
	law_pair_from_pack, hertz_normal, mindlin_tangent, hertz_dem_force,
};

const struct contact_law contact_law_linear = {
	"linear", 3, 1e5, 0.888888888888889, 0.3,
	law_pair_from_pack, linear_normal, linear_tangent, linear_dem_force,
};

const struct contact_law *
contact_law_find(const char *name)
{
	if (!strcmp(name, contact_law_hertz_mindlin.name))
		return &contact_law_hertz_mindlin;
	if (!strcmp(name, contact_law_linear.name))
		return &contact_law_linear;
	return NULL;
}
