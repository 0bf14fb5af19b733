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

/* The tangential spring xi (3 doubles of history): turned into the current tangent plane
 * with its length kept, advanced by the sliding velocity, its force clamped to the Coulomb
 * limit (the spring then set back to the force it carries). */
static void
dem_spring(double *xi, const double n[3], const double vt[3], double dt, double kt, double fmaxt, double ft[3])
{
	double xn = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2], old, now, s;
	int a;

	old = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	for (a = 0; a < 3; a++)
		xi[a] -= xn * n[a];
	now = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	s = now > 0 ? old / now : 0;
	for (a = 0; a < 3; a++) {
		xi[a] = xi[a] * s + vt[a] * dt;
		ft[a] = -kt * xi[a];
	}
	now = sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
	if (now > fmaxt && now > 0) {
		s = fmaxt / now;
		for (a = 0; a < 3; a++) {
			ft[a] *= s;
			xi[a] = -ft[a] / kt;
		}
	}
}

/* The DEM force for normal stiffness kn and elastic normal force fn0. */
static double
dem_damped(const struct contact_law *law, const struct law_dem_in *in, double kn, double fn0, double *hist,
    double ft[3], double *fel)
{
	double vn = in->vr[0] * in->n[0] + in->vr[1] * in->n[1] + in->vr[2] * in->n[2], vt[3], fn;
	int a;

	*fel = fn0;
	fn = fn0 - 2 * law->zeta * sqrt(in->meff * kn) * vn;
	if (fn < 0)
		fn = 0;
	for (a = 0; a < 3; a++)
		vt[a] = in->vr[a] - vn * in->n[a];
	dem_spring(hist, in->n, vt, in->dt, law->kt_ratio * kn, in->mu * fn, ft);
	return fn;
}

static double
hertz_dem_force(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_in *in, double *hist,
    double ft[3], double *fel)
{
	double kn = 2 * lp->Es * sqrt(lp->Rs * in->h);

	return dem_damped(law, in, kn, kn * in->h * (2.0 / 3.0), hist, ft, fel);
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
	return dem_damped(law, in, law->kn, law->kn * in->h, hist, ft, fel);
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
