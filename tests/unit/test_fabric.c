/* test_fabric: the platy-particle paper's descriptors (analysis/fabric.h) on synthetic sets of
 * interactions whose anisotropies are known in closed form.
 *
 * The normals lie in the xy plane at angles theta_k drawn from P_n(theta) = (1 + a cos 2(theta
 * - theta0)) / pi by stratified inversion (theta_k = CDF^-1((k + 1/2)/N)): the mean of a smooth
 * function over them is a midpoint rule in the CDF's variable, exact to O(1/N^2), so with N =
 * 20000 the moments are within 1e-8 and the tolerances below are 1e-7.  On them: normal branch
 * lengths L (1 + b cos 2 phi), tangential ones L c sin 2 phi along t = (sin theta, -cos theta)
 * (phi = theta - theta0), and likewise forces.  Then (fabric.h) a(chi_ln) = (a + b)/(1 + a b/2)
 * and a(chi_l) = (a + b + c)/(1 + a b/2), so a_ln = (a + b)/(1 + a b/2) - a and
 * a_lt = c/(1 + a b/2): the exact values of P's first-order formulas. */
#include "unit.h"
#include "analysis/fabric.h"

#include <stdlib.h>
#include <string.h>

#define N 20000

/* phi in [0, pi) with (phi + (a/2) sin 2 phi)/pi = u, by bisection (the CDF is increasing
 * for |a| < 1). */
static double
cdf_inverse(double a, double u)
{
	double lo = 0, hi = M_PI;
	int it;

	for (it = 0; it < 80; it++) {
		double mid = 0.5 * (lo + hi);
		if ((mid + 0.5 * a * sin(2 * mid)) / M_PI < u)
			lo = mid;
		else
			hi = mid;
	}
	return 0.5 * (lo + hi);
}

struct synth {
	double a, theta0;	/* fabric */
	double L, b, c;		/* branch: normal and tangential anisotropies */
	double F, bf, cf;	/* force */
	double mu;		/* sliding: |F_t| >= mu F_n */
};

static size_t
make_set(const struct synth *s, struct fabric_interaction *it, double *m)
{
	double t0 = s->theta0 * M_PI / 180;
	size_t k, slide = 0;
	int a;

	for (k = 0; k < N; k++) {
		double phi = cdf_inverse(s->a, (k + 0.5) / N), th = t0 + phi;
		double n[3] = {cos(th), sin(th), 0}, t[3] = {sin(th), -cos(th), 0};
		double ln = s->L * (1 + s->b * cos(2 * phi)), lt = s->L * s->c * sin(2 * phi);
		double fn = s->F * (1 + s->bf * cos(2 * phi)), ft = s->F * s->cf * sin(2 * phi);

		for (a = 0; a < 3; a++) {
			it[k].n[a] = n[a];
			it[k].l[a] = ln * n[a] + lt * t[a];
			it[k].F[a] = fn * n[a] + ft * t[a];
			m[3 * k + a] = n[a];
		}
		it[k].sliding = fabs(ft) >= s->mu * fn;
		slide += (size_t)it[k].sliding;
	}
	return slide;
}

static void
check_set(const char *name, const struct synth *s)
{
	struct fabric_interaction *it = malloc(N * sizeof *it);
	double *m = malloc(3 * N * sizeof *m), sig[6] = {0}, den = 1 + s->a * s->b / 2, denf = 1 + s->a * s->bf / 2;
	double p = 2e6, q = 7e5, ts = 120, w = 2 * ts * M_PI / 180, want;
	struct fabric_desc d;
	size_t slide = make_set(s, it, m);

	/* a stress with p, q and its major direction ts in the xy plane */
	sig[0] = p + q * cos(w), sig[1] = p - q * cos(w), sig[3] = q * sin(w), sig[2] = p;
	fabric_describe(it, N, m, N, sig, &d);
	CHECK(d.interactions == N && d.particles == N, "%s: counts", name);
	CHECK_CLOSE(d.a_n, s->a, 1e-7, "fabric: a_n");
	CHECK_CLOSE(d.a_m, s->a, 1e-7, "fabric: a_m of face normals along the same set");
	CHECK(fabs(d.theta_n - s->theta0) <= 1e-5 && fabs(d.theta_m - s->theta0) <= 1e-5, "%s: theta_n %.9g, theta_m %.9g = %g",
	    name, d.theta_n, d.theta_m, s->theta0);
	CHECK_CLOSE(d.a_ln, (s->a + s->b) / den - s->a, 1e-7, "fabric: a_ln = (a + b)/(1 + ab/2) - a");
	CHECK_CLOSE(d.a_lt, s->c / den, 1e-7, "fabric: a_lt = c/(1 + ab/2)");
	CHECK_CLOSE(d.a_fn, (s->a + s->bf) / denf - s->a, 1e-7, "fabric: a_fn");
	CHECK_CLOSE(d.a_ft, s->cf / denf, 1e-7, "fabric: a_ft");
	CHECK(fabs(d.theta_ln - s->theta0) <= 1e-5 && fabs(d.theta_fn - s->theta0) <= 1e-5 &&
	    fabs(d.theta_lt - s->theta0) <= 1e-5 && fabs(d.theta_ft - s->theta0) <= 1e-5,
	    "%s: the branch and force directions are theta0 (%.9g %.9g %.9g %.9g)", name, d.theta_ln, d.theta_lt,
	    d.theta_fn, d.theta_ft);
	CHECK(d.K_s == (double)slide / N, "%s: K_s %g", name, d.K_s);
	CHECK_CLOSE(d.p, p, 1e-14, "fabric: p = (s1 + s3)/2");
	CHECK_CLOSE(d.q, q, 1e-9, "fabric: q = (s1 - s3)/2");
	CHECK(fabs(d.theta_sigma - ts) <= 1e-9, "%s: theta_sigma %.12g = %g", name, d.theta_sigma, ts);
	want = 0.5 * cos(2 * (s->theta0 - ts) * M_PI / 180) * (d.a_n + d.a_ln + d.a_lt + d.a_fn + d.a_ft);
	CHECK_CLOSE(d.qp_harmonic, want, 1e-9, "fabric: P eq. 28 with every direction theta0");
	free(it);
	free(m);
}

int
main(void)
{
	static const struct synth sets[] = {
		{0.4, 135, 1e-7, 0.2, 0.1, 1e-6, 0.3, 0.25, 0.2},	/* P's orders at eta 0 */
		{0.9, 110, 2e-7, -0.2, -0.4, 3e-6, 0.3, 0.7, 0.5},	/* near eta 0.8 (a_n 1.2 there is no density) */
		{0.0, 0, 1e-7, 0.3, 0, 1e-6, 0, 0, 0.5},		/* isotropic fabric: a_ln is b exactly */
	};
	struct fabric_interaction e;
	struct fabric_desc d;
	double t[6] = {1, 0, 0, 0, 0, 0}, a, th;
	size_t k;

	for (k = 0; k < sizeof sets / sizeof sets[0]; k++) {
		char name[40];
		snprintf(name, sizeof name, "fabric set %zu", k + 1);
		if (sets[k].a > 0)
			check_set(name, &sets[k]);
	}
	{
		/* the isotropic fabric: theta_n is undefined, a_ln = b with nothing subtracted */
		struct fabric_interaction *it = malloc(N * sizeof *it);
		double *m = malloc(3 * N * sizeof *m);

		make_set(&sets[2], it, m);
		fabric_describe(it, N, m, N, NULL, &d);
		CHECK(fabs(d.a_n) <= 1e-7, "fabric: isotropic normals, a_n %g", d.a_n);
		CHECK_CLOSE(d.a_ln, 0.3, 1e-7, "fabric: isotropic normals, a_ln = b");
		CHECK(isnan(d.p) && isnan(d.qp_harmonic), "fabric: no stress, no p or eq. 28");
		free(it);
		free(m);
	}
	/* tensors of known eigenvectors */
	fabric_planar(t, &a, &th);
	CHECK(a == 2 && th == 0, "fabric_planar: all along x: a 2, theta 0 (%g, %g)", a, th);
	t[0] = 0.5, t[1] = 0.5, t[3] = 0.5;	/* all along (1, 1)/sqrt 2 */
	fabric_planar(t, &a, &th);
	CHECK(fabs(a - 2) <= 1e-15 && fabs(th - 45) <= 1e-12, "fabric_planar: all along 45 degrees (%g, %.15g)", a, th);
	t[3] = -0.5;
	fabric_planar(t, &a, &th);
	CHECK(fabs(th - 135) <= 1e-12, "fabric_planar: along 135 degrees, in [0, 180) (%.15g)", th);
	memset(t, 0, sizeof t);
	t[2] = 1;	/* all along z: nothing in the plane */
	fabric_planar(t, &a, &th);
	CHECK(isnan(a) && isnan(th), "fabric_planar: normals along z have no planar anisotropy");
	/* no interactions */
	fabric_describe(&e, 0, NULL, 0, NULL, &d);
	CHECK(isnan(d.a_n) && isnan(d.a_fn) && isnan(d.K_s) && isnan(d.a_m), "fabric: nothing to describe is NaN");
	return unit_summary();
}
