/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_lattice: compressed lattices of identical spheres between walls, brought to equilibrium
 * by qs_minimize (CG and FIRE), against solutions known independently of lib/.
 *
 * Simple cubic (SC), NL^3 grains of radius R at spacing 2R, walls touching the outer layers.
 * After a strain the box lengths are L_a; by symmetry every row along axis a is a chain whose
 * contacts all lie along a, and equilibrium of each grain along a makes all grain-grain
 * forces of the chain equal, P_gg(h_a), and the wall force P_gw(h_w) = P_gg(h_a).  Hertz
 * is homogeneous, so h_w = kappa h_a with
 *     kappa = (E*_gg sqrt(R/2) / (E*_gw sqrt(R)))^(2/3),
 * and the chain must fit the box: 2 NL R - L_a = (NL - 1) h_a + 2 kappa h_a, so
 *     h_a = (2 NL R - L_a) / (NL - 1 + 2 kappa),
 *     x_a(i) = lo_a + R - kappa h_a + i (2R - h_a),
 *     sig_aa = NL^2 P_gg(h_a) / (L_b L_c)   (NL^2 contacts per wall, the force on both walls
 *                                            of the axis being equal).
 * With rigid walls (E_w = inf) E*_gw = E/(1-nu^2) = 2 E*_gg and kappa = 1/2: the wall is a
 * mirror, half a grain-grain contact (P_gw(h/2) = P_gg(h)), and the affine state is exact.
 * With the papers' walls (E_w = 100 E, nu_w = 0.495) kappa is about 0.63 and the outer layers
 * must move: a non-affine equilibrium, still in closed form.  Transverse stability: a grain
 * moved sideways by y feels -P y / d from its two axial contacts and 2 E* a y from the
 * transverse ones; E* a / (P/d) ~ d / h >> 1, so the lattice is a strict minimum.
 *
 * Face-centred cubic (FCC), conventional cubic cell (edge a = 2 sqrt2 R), sites (i, j, k) a/2
 * with i + j + k even, 0 <= i, j, k < M (M odd: the block has the full cubic symmetry), walls
 * at R from the outer layers.  Here no wall makes the affine state exact: a face grain has
 * 4 diagonal contacts pushing it into the wall (need P_w = 2 sqrt2 P_gg), an edge grain 3, and
 * affinity gives h_w = h/2 for every wall contact, so the equilibrium is non-affine and has no
 * closed form.  The reference is Newton's method with the exact Hessian of an O(N^2) Hertz
 * energy written in unit_lattice.h (independent of lib/qs/functional.c and lib/qs/minimize.c), converged to
 * rounding; the same solver reproduces the SC closed form, which validates it.  Checks that
 * need no reference: sig_xx = sig_yy = sig_zz under isotropic strain (cubic symmetry), and the
 * force on a wall equals the force carried across every plane between two layers (balance of
 * each slab of grains). */
#include "qs/functional.h"
#include "contact/hertz.h"
#include "qs/loading.h"
#include "qs/minimize.h"
#include "pack/pack.h"
#include "unit.h"
#include "unit_lattice.h"

#include <float.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define R_ ldexp(1.0, -13)	/* 122 um */
#define E_ 7e10
#define NU 0.2
#define EPS1 1e-3		/* isotropic strain */
#define EPS2 1e-3		/* then uniaxial strain along z */

static double worst_sig, worst_pos;	/* achieved errors, for the closing line */

/* ---------- the SC closed form ---------- */

static void
sc_solution(const struct pack *p, int nl, double *x, double sig[3], double hgg[3])
{
	double Egg = hertz_Estar(E_, NU, E_, NU), Egw = hertz_Estar(E_, NU, p->wall_E, p->wall_nu);
	double kappa = cbrt(pow(Egg * sqrt(0.5) / Egw, 2)), L[3];
	int i, j, k, a;

	for (a = 0; a < 3; a++) {
		L[a] = p->box[3 + a] - p->box[a];
		hgg[a] = (2 * nl * R_ - L[a]) / (nl - 1 + 2 * kappa);
	}
	for (k = 0; k < nl; k++)
		for (j = 0; j < nl; j++)
			for (i = 0; i < nl; i++) {
				int idx[3] = {i, j, k};
				size_t g = (size_t)i + nl * ((size_t)j + nl * (size_t)k);
				for (a = 0; a < 3; a++)
					x[3 * g + a] = p->box[a] + R_ - kappa * hgg[a] + idx[a] * (2 * R_ - hgg[a]);
			}
	for (a = 0; a < 3; a++)
		sig[a] = nl * nl * hertz_force(Egg, R_ / 2, hgg[a]) / (L[(a + 1) % 3] * L[(a + 2) % 3]);
}

/* ---------- one case ---------- */

/* Largest |x - xr| over all coordinates. */
static double
maxdiff(const double *x, const double *xr, size_t n3)
{
	double m = 0;
	size_t k;

	for (k = 0; k < n3; k++)
		m = fmax(m, fabs(x[k] - xr[k]));
	return m;
}

/* Force carried across the plane between layers l and l+1 normal to z: sum of P n_z over the
 * contacts whose centres lie on either side. */
static double
plane_force(const struct pack *p, const double *x, double zc)
{
	double F = 0;
	size_t i, j;
	int a;

	for (i = 0; i < p->n; i++)
		for (j = 0; j < p->n; j++) {
			double d[3], dd = 0, S = 2 * R_, dist;
			if (!(x[3 * i + 2] < zc && x[3 * j + 2] > zc))
				continue;
			for (a = 0; a < 3; a++) {
				d[a] = x[3 * j + a] - x[3 * i + a];
				dd += d[a] * d[a];
			}
			if (dd >= S * S)
				continue;
			dist = sqrt(dd);
			F += hertz_force(hertz_Estar(E_, NU, E_, NU), R_ / 2, S - dist) * d[2] / dist;
		}
	return F;
}

static void
one_case(gsl_rng *rng, int kind, int m, double wall_E, double wall_nu, const struct qs_method_type *method, const char *tag)
{
	struct pack p;
	struct qs_system s;
	struct qs_min_params mp;
	struct qs_min_report rep;
	double *x, *xr, *g, sig[3], sigr[3], hgg[3], wf[NWALLS], de[3], hmin;
	size_t n, n3, k;
	int stage, a;

	lattice_pack(&p, kind, m, R_, E_, NU, wall_E, wall_nu);
	n = p.n;
	n3 = 3 * n;
	x = malloc(n3 * sizeof *x);
	xr = malloc(n3 * sizeof *xr);
	g = malloc(n3 * sizeof *g);
	memcpy(x, p.x, n3 * sizeof *x);
	CHECK(qs_init(&s, &p, 0.3) == 0, "%s: qs_init", tag);
	qs_min_params_default(&mp);
	mp.method = method;
	/* the residual is the largest |F_i| / (largest contact force on i).  Its floor is set by
	 * the spacing of doubles near the centres, not by the force sums: ulp(1.2e-3 m) = 2.2e-19 m
	 * is 0.9e-12 of the overlap h = 2.4e-7 m, which moves a Hertz force by 1.4e-12 of itself.
	 * 1e-11 is above that floor by a factor 7; CG stalls between 1e-12 and 6e-12. */
	mp.tol = 1e-11;
	mp.max_iter = 20000;
	for (stage = 0; stage < 2; stage++) {
		char name[160];
		double esig = 0, epos;

		de[0] = de[1] = stage ? 0 : EPS1;
		de[2] = stage ? EPS2 : EPS1;
		load_strain_box(p.box, x, n, de);
		/* the reference, from the affine state */
		memcpy(xr, x, n3 * sizeof *x);
		if (kind == SC) {
			double xn[3 * 125], stepn;
			sc_solution(&p, m, xr, sigr, hgg);
			hmin = fmin(hgg[0], fmin(hgg[1], hgg[2]));
			if (n <= 125) {
				/* the Newton reference reproduces the closed form: it is validated here
				 * before it is trusted for FCC; to rounding of positions, 1e-15 R */
				memcpy(xn, x, n3 * sizeof *x);
				stepn = lattice_newton(&p, xn, 1e-15 * R_);
				snprintf(name, sizeof name, "%s %s: Newton reference = SC closed form", tag, stage ? "uniaxial" : "isotropic");
				CHECK(maxdiff(xn, xr, n3) <= 1e-8 * hmin && stepn < 1e-14 * R_, "%s (%.3g of the overlap)", name,
				    maxdiff(xn, xr, n3) / hmin);
			}
		} else {
			lattice_newton(&p, xr, 1e-15 * R_);
			lattice_ref_eval(&p, xr, g, NULL, wf);
			lattice_wall_stress(p.box, wf, sigr);
			/* smallest grain-grain overlap of the affine state, as the position scale: the
			 * (1,1,0) contacts keep 2R EPS1 under the uniaxial stage */
			hmin = 2 * R_ * EPS1;
		}
		/* a random start near the affine state, so that the minimiser has work to do */
		for (k = 0; k < n3; k++)
			x[k] += 0.1 * hmin * (2 * gsl_rng_uniform(rng) - 1);
		qs_minimize(&s, x, &mp, &rep);
		snprintf(name, sizeof name, "%s %s: converged (status %d, %s, %ld iterations, residual %.3g)", tag,
		    stage ? "uniaxial" : "isotropic", rep.status, rep.stopped_by ? rep.stopped_by : "-", rep.iter,
		    rep.res_max);
		CHECK(rep.status == 0 && rep.res_max <= mp.tol, "%s", name);
		/* wall stress of the minimiser's last evaluation against the reference */
		qs_wall_stress(&s, sig);
		for (a = 0; a < 3; a++)
			esig = fmax(esig, fabs(sig[a] - sigr[a]) / sigr[a]);
		epos = maxdiff(x, xr, n3) / hmin;
		worst_sig = fmax(worst_sig, esig);
		worst_pos = fmax(worst_pos, epos);
		/* a residual of 1e-11 leaves forces off by about 1e-11 P and positions by 1e-11 P / k
		 * = 1e-11 h; the Hertz law turns that into 1.5e-11 of the stress, amplified along
		 * the chains by at most the number of layers (5): 1e-9 holds with a margin of 10 */
		snprintf(name, sizeof name, "%s %s: wall stresses %.10g %.10g %.10g Pa = reference (largest error %.3g)",
		    tag, stage ? "uniaxial" : "isotropic", sig[0], sig[1], sig[2], esig);
		CHECK(esig <= 1e-9, "%s", name);
		snprintf(name, sizeof name, "%s %s: positions = reference (largest error %.3g of the overlap %.3g m)", tag,
		    stage ? "uniaxial" : "isotropic", epos, hmin);
		CHECK(epos <= 1e-9, "%s", name);
		if (kind == FCC && stage == 0) {
			/* cubic symmetry: the three stresses agree to the residual */
			double sd = fmax(fabs(sig[0] - sig[2]), fabs(sig[1] - sig[2])) / sig[2];
			CHECK(sd <= 1e-9, "%s isotropic: sig_xx = sig_yy = sig_zz by symmetry (%.3g)", tag, sd);
		}
		if (kind == FCC) {
			/* the force on zlo equals the force across each plane between two layers */
			double dev = 0;
			int l;
			for (l = 0; l + 1 < m; l++) {
				/* midway between layers l and l+1, mapped affinely from the unstrained box */
				double zc = p.box[2] + (R_ + (l + 0.5) * sqrt(2.0) * R_) * (p.box[5] - p.box[2]) /
				    (2 * R_ + (m - 1) * sqrt(2.0) * R_);
				dev = fmax(dev, fabs(plane_force(&p, x, zc) - s.wall_force[WALL_ZLO]) / s.wall_force[WALL_ZLO]);
			}
			dev = fmax(dev, fabs(s.wall_force[WALL_ZHI] - s.wall_force[WALL_ZLO]) / s.wall_force[WALL_ZLO]);
			CHECK(dev <= 1e-9, "%s %s: the force on each z wall = the force across every layer plane (%.3g)", tag,
			    stage ? "uniaxial" : "isotropic", dev);
		}
		if (kind == SC && stage == 1) {
			/* the uniaxial stage carries the isotropic one: h_z = 2R (1 - (1-e1)(1-e2)) when kappa
			 * = 1/2; with kappa != 1/2 the closed form already checked covers it */
			double Egg = hertz_Estar(E_, NU, E_, NU);
			CHECK(sigr[2] > sigr[0] && sigr[0] == sigr[1],
			    "%s uniaxial: sig_zz %.6g > sig_xx = sig_yy %.6g (Pa; P_gg(h_z) = %.6g N)", tag, sigr[2], sigr[0],
			    hertz_force(Egg, R_ / 2, hgg[2]));
		}
	}
	qs_free(&s);
	free(x), free(xr), free(g);
	pack_free(&p);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	double Egg = hertz_Estar(E_, NU, E_, NU), Egw = hertz_Estar(E_, NU, INFINITY, 0.495), h = 1e-7;
	/* the papers' two methods */
	const struct qs_method_type *const methods[] = {&qs_method_cg, &qs_method_fire};
	size_t k;

	gsl_rng_set(rng, 4242);
	/* a rigid wall is half a grain-grain contact: P_gw(h/2) = P_gg(h); the compliances are
	 * (1-nu^2)/E + 0 against twice that, so only rounding separates them */
	CHECK_CLOSE(hertz_force(Egw, R_, h / 2), hertz_force(Egg, R_ / 2, h), 1e-14,
	    "rigid wall: P_gw(h/2) = P_gg(h), so the affine SC state is exact");
	for (k = 0; k < sizeof methods / sizeof *methods; k++) {
		const struct qs_method_type *method = methods[k];
		char tag[64];
		snprintf(tag, sizeof tag, "SC 4^3 rigid walls %s", method->name);
		one_case(rng, SC, 4, INFINITY, 0.495, method, tag);
		snprintf(tag, sizeof tag, "SC 5^3 walls E_w = 100 E %s", method->name);
		one_case(rng, SC, 5, 100 * E_, 0.495, method, tag);
		snprintf(tag, sizeof tag, "FCC 63 rigid walls %s", method->name);
		one_case(rng, FCC, 5, INFINITY, 0.495, method, tag);
		snprintf(tag, sizeof tag, "FCC 63 walls E_w = 100 E %s", method->name);
		one_case(rng, FCC, 5, 100 * E_, 0.495, method, tag);
	}
	printf("# achieved: wall stress relative error %.3g, positions %.3g of the overlap\n", worst_sig, worst_pos);
	gsl_rng_free(rng);
	return unit_summary();
}
