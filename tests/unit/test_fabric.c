/* SPDX-License-Identifier: GPL-3.0-or-later */
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
	/* the tangential tensors on their own: co-axial with the fabric here, so the direct
	 * anisotropies are eqs. 19 and 27's, |c|/(1 + ab/2) (fabric.h), along theta0 for c > 0
	 * and across it (theta0 + 90) for c < 0 */
	CHECK_CLOSE(d.a_lt_direct, fabs(s->c) / den, 1e-7, "fabric: a_lt_direct = |c|/(1 + ab/2)");
	CHECK_CLOSE(d.a_ft_direct, fabs(s->cf) / denf, 1e-7, "fabric: a_ft_direct = |cf|/(1 + ab/2)");
	CHECK(fabs(d.theta_lt_direct - fmod(s->theta0 + (s->c < 0 ? 90 : 0), 180)) <= 1e-5 &&
	    fabs(d.theta_ft_direct - fmod(s->theta0 + (s->cf < 0 ? 90 : 0), 180)) <= 1e-5,
	    "%s: the direct directions %.9g %.9g", name, d.theta_lt_direct, d.theta_ft_direct);
	CHECK_CLOSE(d.qp_harmonic_direct, d.qp_harmonic, 1e-7, "fabric: co-axial, eq. 28 direct = eq. 28");
	CHECK(d.K_s == (double)slide / N, "%s: K_s %g", name, d.K_s);
	CHECK_CLOSE(d.p, p, 1e-14, "fabric: p = (s1 + s3)/2");
	CHECK_CLOSE(d.q, q, 1e-9, "fabric: q = (s1 - s3)/2");
	CHECK(fabs(d.theta_sigma - ts) <= 1e-9, "%s: theta_sigma %.12g = %g", name, d.theta_sigma, ts);
	want = 0.5 * cos(2 * (s->theta0 - ts) * M_PI / 180) * (d.a_n + d.a_ln + d.a_lt + d.a_fn + d.a_ft);
	CHECK_CLOSE(d.qp_harmonic, want, 1e-9, "fabric: P eq. 28 with every direction theta0");
	free(it);
	free(m);
}

/* Three interactions in the xy plane whose tensors are worked out by hand (sym(u v) the
 * symmetric part of u_a v_b, e_x and e_y the axes):
 *   1: n = e_x, F = (2, 1, 0): F_n 2, t = e_y, F_t 1;  l = (1, 0.5, 0): l_n 1, l_t 0.5
 *   2: n = e_y, F = (1, 1, 0): F_n 1, t = e_x, F_t 1;  l = (0.2, 2, 0): l_n 2, l_t 0.2
 *   3: n = e_x, F = (1, 0, 0): F_n 1, no F_t;         l = (1, 0, 0):   l_n 1
 * F = diag(2/3, 1/3): a_n = 2 (1/3) / 1 = 2/3, theta_n 0.
 * chi_ln = (1/3) diag(1 + 1, 2) = diag(2/3, 2/3): isotropic, a_ln = 0 - 2/3.
 * chi_lt: sym(e_x e_y) and sym(e_y e_x) both have xy = 1/2, so xy = (0.5 0.5 + 0.2 0.5)/3
 *   = 0.35/3 (xx = yy = 0): T1 - T3 = 0.7/3, a_lt_direct = 2 (0.7/3) / (4/3) = 0.35 at 45 deg;
 *   chi_l = chi_ln + chi_lt: a = 4 (0.35/3) / (4/3) = 0.35 at 45, a_lt = 0.35 - 2/3 + 2/3.
 * chi_fn = (1/3) diag(2 + 1, 1) = diag(1, 1/3): a = 2 (2/3) / (4/3) = 1, a_fn = 1/3, at 0.
 * chi_ft: xy = (1 0.5 + 1 0.5)/3 = 1/3: T1 - T3 = 2/3, a_ft_direct = 2 (2/3)/(4/3) = 1 at 45;
 *   chi_f = [[1, 1/3], [1/3, 1/3]]: half-difference 1/3, xy 1/3, r = sqrt(2)/3, trace 4/3,
 *   a = 4 r / (4/3) = sqrt 2 at (1/2) atan2(1/3, 1/3) = 22.5 deg: a_ft = sqrt 2 - 2/3 - 1/3,
 *   not co-axial with chi_ft (eq. 27 reports sqrt 2 - 1 = 0.414 of the tangential tensor's 1).
 * Under sigma = [[1, 0.5], [0.5, 1]] (p 1, q 0.5, theta_sigma 45): the terms along 0 deg
 * vanish (cos 90 = 0), so eq. 28 = (1/2)(0.35 + (sqrt 2 - 1) cos 45) = (0.35 + 1 - 1/sqrt 2)/2
 * and the direct one (1/2)(0.35 + 1) = 0.675. */
static void
hand_set(void)
{
	struct fabric_interaction it[3] = {
		{{1, 0, 0}, {1, 0.5, 0}, {2, 1, 0}, 0},
		{{0, 1, 0}, {0.2, 2, 0}, {1, 1, 0}, 1},
		{{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, 0},
	};
	double sig[6] = {1, 1, 0, 0.5, 0, 0};
	struct fabric_desc d;

	fabric_describe(it, 3, NULL, 0, sig, &d);
	CHECK(fabs(d.a_n - 2.0 / 3) <= 1e-15 && d.theta_n == 0, "hand set: a_n %.17g = 2/3 at %g = 0", d.a_n, d.theta_n);
	CHECK(fabs(d.a_ln + 2.0 / 3) <= 1e-15, "hand set: a_ln %.17g = -2/3", d.a_ln);
	CHECK(fabs(d.a_lt - 0.35) <= 1e-14 && fabs(d.theta_lt - 45) <= 1e-12, "hand set: a_lt %.17g = 0.35 at %.15g = 45",
	    d.a_lt, d.theta_lt);
	CHECK(fabs(d.a_lt_direct - 0.35) <= 1e-14 && fabs(d.theta_lt_direct - 45) <= 1e-12,
	    "hand set: a_lt_direct %.17g = 0.35 at %.15g = 45", d.a_lt_direct, d.theta_lt_direct);
	CHECK(fabs(d.a_fn - 1.0 / 3) <= 1e-15 && d.theta_fn == 0, "hand set: a_fn %.17g = 1/3 at %g = 0", d.a_fn, d.theta_fn);
	CHECK(fabs(d.a_ft - (sqrt(2) - 1)) <= 1e-14 && fabs(d.theta_ft - 22.5) <= 1e-12,
	    "hand set: eq. 27 a_ft %.17g = sqrt 2 - 1 at %.15g = 22.5", d.a_ft, d.theta_ft);
	CHECK(fabs(d.a_ft_direct - 1) <= 1e-15 && fabs(d.theta_ft_direct - 45) <= 1e-12,
	    "hand set: a_ft_direct %.17g = 1 at %.15g = 45", d.a_ft_direct, d.theta_ft_direct);
	CHECK(d.p == 1 && d.q == 0.5 && fabs(d.theta_sigma - 45) <= 1e-12, "hand set: p 1, q 0.5, theta_sigma 45");
	CHECK(fabs(d.qp_harmonic - (1.35 - 1 / sqrt(2)) / 2) <= 1e-14, "hand set: eq. 28 %.17g = (1.35 - 1/sqrt 2)/2",
	    d.qp_harmonic);
	CHECK(fabs(d.qp_harmonic_direct - 0.675) <= 1e-14, "hand set: eq. 28 direct %.17g = 0.675", d.qp_harmonic_direct);
	CHECK(d.K_s == 1.0 / 3 && isnan(d.a_m) && isnan(d.a_m_3d) && isnan(d.nematic_S), "hand set: K_s 1/3, no plates");
	/* l_t is the projection on the force's tangent, not the branch's whole tangential part:
	 * with interaction 1's tangential force along z (F = (2, 0, 1), t = e_z) its branch
	 * (1, 0.5, 0) has l_t = 0, so chi_lt's xy is interaction 2's alone, 0.2 0.5 / 3: a_lt =
	 * a_lt_direct = 4 (0.1/3) / (4/3) = 0.1 (the whole tangential branch would give 0.35 again),
	 * and chi_ft's xy block 1 0.5 / 3: a_ft_direct = 2 (1/3) / (4/3) = 0.5 */
	it[0].F[1] = 0, it[0].F[2] = 1;
	fabric_describe(it, 3, NULL, 0, sig, &d);
	CHECK(fabs(d.a_lt - 0.1) <= 1e-14 && fabs(d.a_lt_direct - 0.1) <= 1e-14 && fabs(d.a_ft_direct - 0.5) <= 1e-14,
	    "hand set: the force's tangent along z: a_lt %.17g = a_lt_direct %.17g = 0.1, a_ft_direct %.17g = 0.5", d.a_lt,
	    d.a_lt_direct, d.a_ft_direct);
}

/* Face normals of known 3D nematic tensors:
 *   e_z, e_z, e_x, e_y: M = diag(1/4, 1/4, 1/2): M1 - M3 = 1/4, a_m_3d 1/2,
 *     S = (3/2 - 1)/2 = 1/4; the xy block diag(1/4, 1/4) is isotropic: planar a_m 0.
 *   e_x three times, e_y once: M = diag(3/4, 1/4, 0): M1 - M3 = 3/4, a_m_3d 3/2,
 *     S = (9/4 - 1)/2 = 5/8; planar a_m = 2 (1/2) / 1 = 1 at 0.
 *   (e_x + e_y)/sqrt 2 twice: M1 = 1, M3 = 0: a_m_3d 2, S 1, planar a_m 2 at 45. */
static void
nematic_3d(void)
{
	const double m1[12] = {0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 1, 0}, m2[12] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0};
	const double h = sqrt(0.5), m3[6] = {h, h, 0, h, h, 0};
	struct fabric_desc d;

	fabric_describe(NULL, 0, m1, 4, NULL, &d);
	CHECK(fabs(d.m1_m3 - 0.25) <= 1e-15 && fabs(d.a_m_3d - 0.5) <= 1e-15 && fabs(d.nematic_S - 0.25) <= 1e-15 &&
	    fabs(d.a_m) <= 1e-15, "nematic: M diag(1/4, 1/4, 1/2): M1-M3 %.17g, a_m_3d %.17g, S %.17g, a_m %.3g", d.m1_m3,
	    d.a_m_3d, d.nematic_S, d.a_m);
	fabric_describe(NULL, 0, m2, 4, NULL, &d);
	CHECK(fabs(d.m1_m3 - 0.75) <= 1e-15 && fabs(d.a_m_3d - 1.5) <= 1e-15 && fabs(d.nematic_S - 0.625) <= 1e-15 &&
	    fabs(d.a_m - 1) <= 1e-15 && d.theta_m == 0, "nematic: M diag(3/4, 1/4, 0): M1-M3 %.17g, a_m_3d %.17g, S %.17g, a_m %.17g",
	    d.m1_m3, d.a_m_3d, d.nematic_S, d.a_m);
	fabric_describe(NULL, 0, m3, 2, NULL, &d);
	CHECK(fabs(d.a_m_3d - 2) <= 1e-14 && fabs(d.nematic_S - 1) <= 1e-14 && fabs(d.a_m - 2) <= 1e-14 &&
	    fabs(d.theta_m - 45) <= 1e-12, "nematic: parallel normals at 45: a_m_3d %.17g, S %.17g, a_m %.17g at %.15g",
	    d.a_m_3d, d.nematic_S, d.a_m, d.theta_m);
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
	hand_set();
	nematic_3d();
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
