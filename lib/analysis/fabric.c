/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fabric: the platy-particle paper's descriptors in the shear plane (see fabric.h). */
#include "analysis/fabric.h"

#include <gsl/gsl_eigen.h>
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

/* The eigenvalues of the symmetric 3x3 tensor t (xx yy zz xy xz yz), largest first; -1 when
 * the solver fails (it allocates). */
static int
eigenvalues3(const double t[6], double ev[3])
{
	double A[9] = {t[0], t[3], t[4], t[3], t[1], t[5], t[4], t[5], t[2]}, x;
	gsl_matrix_view m = gsl_matrix_view_array(A, 3, 3);
	gsl_vector_view v = gsl_vector_view_array(ev, 3);
	gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc(3);
	int st = !w || gsl_eigen_symm(&m.matrix, &v.vector, w) ? -1 : 0, i, j;

	gsl_eigen_symm_free(w);
	for (i = 0; i < 3; i++)	/* sort, largest first */
		for (j = i + 1; j < 3; j++)
			if (ev[j] > ev[i])
				x = ev[i], ev[i] = ev[j], ev[j] = x;
	return st;
}

/* A traceless (in the plane) tangential tensor's anisotropy against the trace of its normal
 * companion: 2 (T1 - T3) / tr_xy(normal), and T1's direction (fabric.h, "direct"). */
static void
tangential_direct(const double t[6], const double normal[6], double *a, double *theta)
{
	double hd = 0.5 * (t[0] - t[1]), r = sqrt(hd * hd + t[3] * t[3]), tr = normal[0] + normal[1], th;

	if (!(tr > 0)) {
		*a = *theta = NAN;
		return;
	}
	*a = 2 * (2 * r) / tr;
	th = 0.5 * atan2(t[3], hd) * 180 / M_PI;
	*theta = th < 0 ? th + 180 : th;
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
	double M[6] = {0}, Fn[6] = {0}, cln[6] = {0}, clt[6] = {0}, cl[6], cfn[6] = {0}, cft[6] = {0}, cf[6], A, ev[3];
	size_t k, slide = 0;
	int a;

	memset(d, 0, sizeof *d);
	d->interactions = n, d->particles = np;
	for (k = 0; k < np; k++)
		add_sym(M, m + 3 * k, m + 3 * k, 1.0 / np);
	for (k = 0; k < n; k++) {
		const struct fabric_interaction *e = &it[k];
		double fn = dot(e->F, e->n), t[3], ft;

		for (a = 0; a < 3; a++)
			t[a] = e->F[a] - fn * e->n[a];
		ft = sqrt(dot(t, t));
		add_sym(Fn, e->n, e->n, 1.0 / n);
		add_sym(cln, e->n, e->n, dot(e->l, e->n) / n);
		add_sym(cfn, e->n, e->n, fn / n);
		if (ft > 0) {	/* t, the direction of the tangential force (P eq. 20) */
			for (a = 0; a < 3; a++)
				t[a] /= ft;
			add_sym(clt, e->n, t, dot(e->l, t) / n);
			add_sym(cft, e->n, t, ft / n);
		}
		slide += e->sliding != 0;
	}
	for (a = 0; a < 6; a++)
		cl[a] = cln[a] + clt[a], cf[a] = cfn[a] + cft[a];
	fabric_planar(M, &d->a_m, &d->theta_m);
	d->a_m_3d = d->m1_m3 = d->nematic_S = NAN;
	if (np == 0)
		d->a_m = d->theta_m = NAN;
	else if (eigenvalues3(M, ev) == 0) {
		d->m1_m3 = ev[0] - ev[2];
		d->a_m_3d = 2 * d->m1_m3;
		d->nematic_S = (3 * ev[0] - 1) / 2;
	}
	fabric_planar(Fn, &d->a_n, &d->theta_n);
	fabric_planar(cln, &A, &d->theta_ln);
	d->a_ln = A - d->a_n;
	fabric_planar(cl, &A, &d->theta_lt);
	d->a_lt = A - d->a_n - d->a_ln;
	fabric_planar(cfn, &A, &d->theta_fn);
	d->a_fn = A - d->a_n;
	fabric_planar(cf, &A, &d->theta_ft);
	d->a_ft = A - d->a_n - d->a_fn;
	tangential_direct(clt, cln, &d->a_lt_direct, &d->theta_lt_direct);
	tangential_direct(cft, cfn, &d->a_ft_direct, &d->theta_ft_direct);
	d->K_s = n ? (double)slide / n : NAN;
	if (n == 0) {
		d->a_n = d->theta_n = d->a_ln = d->theta_ln = d->a_lt = d->theta_lt = NAN;
		d->a_fn = d->theta_fn = d->a_ft = d->theta_ft = NAN;
		d->a_lt_direct = d->theta_lt_direct = d->a_ft_direct = d->theta_ft_direct = NAN;
	}
	d->p = d->q = d->qp = d->theta_sigma = d->qp_harmonic = d->qp_harmonic_direct = NAN;
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
		d->qp_harmonic_direct = 0.5 * (harmonic(d->a_n, d->theta_n, ts) + harmonic(d->a_ln, d->theta_ln, ts) +
		    harmonic(d->a_lt_direct, d->theta_lt_direct, ts) + harmonic(d->a_fn, d->theta_fn, ts) +
		    harmonic(d->a_ft_direct, d->theta_ft_direct, ts));
	}
}
