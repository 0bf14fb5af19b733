/* fabric: the platy-particle paper's descriptors in the shear plane (see fabric.h). */
#include "analysis/fabric.h"

#include <math.h>
#include <string.h>

void
fabric_planar(const double t[6], double *a, double *theta)
{
	double tr = t[0] + t[1], hd = 0.5 * (t[0] - t[1]), r = sqrt(hd * hd + t[3] * t[3]), th;

	if (!(tr > 0)) {
		*a = *theta = NAN;
		return;
	}
	*a = 2 * (2 * r) / tr;	/* T1 - T3 = 2 r, T1 + T3 = tr */
	th = 0.5 * atan2(t[3], hd) * 180 / M_PI;
	*theta = th < 0 ? th + 180 : th;
}

/* t += w sym(u v) */
static void
add_sym(double t[6], const double u[3], const double v[3], double w)
{
	t[0] += w * u[0] * v[0];
	t[1] += w * u[1] * v[1];
	t[2] += w * u[2] * v[2];
	t[3] += w * 0.5 * (u[0] * v[1] + u[1] * v[0]);
	t[4] += w * 0.5 * (u[0] * v[2] + u[2] * v[0]);
	t[5] += w * 0.5 * (u[1] * v[2] + u[2] * v[1]);
}

static double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double
harmonic(double a, double th, double ts)
{
	return a * cos(2 * (th - ts) * M_PI / 180);
}

void
fabric_describe(const struct fabric_interaction *it, size_t n, const double *m, size_t np, const double sig[6],
    struct fabric_desc *d)
{
	double M[6] = {0}, Fn[6] = {0}, cln[6] = {0}, cl[6] = {0}, cfn[6] = {0}, cf[6] = {0}, A;
	size_t k, slide = 0;

	memset(d, 0, sizeof *d);
	d->interactions = n, d->particles = np;
	for (k = 0; k < np; k++)
		add_sym(M, m + 3 * k, m + 3 * k, 1.0 / np);
	for (k = 0; k < n; k++) {
		const struct fabric_interaction *e = &it[k];

		add_sym(Fn, e->n, e->n, 1.0 / n);
		add_sym(cln, e->n, e->n, dot(e->l, e->n) / n);
		add_sym(cl, e->n, e->l, 1.0 / n);
		add_sym(cfn, e->n, e->n, dot(e->F, e->n) / n);
		add_sym(cf, e->n, e->F, 1.0 / n);
		slide += e->sliding != 0;
	}
	fabric_planar(M, &d->a_m, &d->theta_m);
	if (np == 0)
		d->a_m = d->theta_m = NAN;
	fabric_planar(Fn, &d->a_n, &d->theta_n);
	fabric_planar(cln, &A, &d->theta_ln);
	d->a_ln = A - d->a_n;
	fabric_planar(cl, &A, &d->theta_lt);
	d->a_lt = A - d->a_n - d->a_ln;
	fabric_planar(cfn, &A, &d->theta_fn);
	d->a_fn = A - d->a_n;
	fabric_planar(cf, &A, &d->theta_ft);
	d->a_ft = A - d->a_n - d->a_fn;
	d->K_s = n ? (double)slide / n : NAN;
	if (n == 0) {
		d->a_n = d->theta_n = d->a_ln = d->theta_ln = d->a_lt = d->theta_lt = NAN;
		d->a_fn = d->theta_fn = d->a_ft = d->theta_ft = NAN;
	}
	d->p = d->q = d->qp = d->theta_sigma = d->qp_harmonic = NAN;
	if (sig) {
		double hd = 0.5 * (sig[0] - sig[1]), ts;

		d->p = 0.5 * (sig[0] + sig[1]);
		d->q = sqrt(hd * hd + sig[3] * sig[3]);
		d->qp = d->p > 0 ? d->q / d->p : NAN;
		ts = 0.5 * atan2(sig[3], hd) * 180 / M_PI;
		d->theta_sigma = ts < 0 ? ts + 180 : ts;
		ts = d->theta_sigma;
		d->qp_harmonic = 0.5 * (harmonic(d->a_n, d->theta_n, ts) + harmonic(d->a_ln, d->theta_ln, ts) +
		    harmonic(d->a_lt, d->theta_lt, ts) + harmonic(d->a_fn, d->theta_fn, ts) + harmonic(d->a_ft, d->theta_ft, ts));
	}
}
