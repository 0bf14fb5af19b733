/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_lattice_moduli: moduli of Hertz lattices of identical spheres (radius R, E, nu; E* = E /
 * (2 (1 - nu^2)) between two grains, R* = R/2), frictionless unless said otherwise, against
 * moduli derived here.  Strains are compression positive and measured against the touching
 * lattice: a box length L = L_ref (1 - eps); a strain increment de changes sigma by dsigma,
 * C_ab = dsigma_a / deps_b.  The loader (lib/qs/loading.h, as loadtest uses it) applies the
 * increments and measures the wall stresses; lib/analysis/hooke.c fits K and G to each increment.
 *
 * Comparisons.  A step de = 1e-4 from eps0 = 1e-3 is not small (r = de/eps = 0.1), so the
 * measured secant dsigma/de is compared with the secant of the exact Hertz stress at the two
 * states (finite-strain geometry included), which leaves only the minimiser's residual: tol
 * 1e-11 makes the stresses good to ~1e-11 (times the number of layers, 4-5, along a chain),
 * and dsigma/sigma = 1.5 r = 0.15 turns that into ~5e-10 of the secant: tolerance 1e-8.  The
 * tangent moduli derived below are then checked against the measured secants with the
 * tolerance the finite step implies: sigma ~ eps^(3/2) gives secant / tangent =
 * (2/3)((1+r)^(3/2) - 1)/r = 1 + r/4 - r^2/24 + ..., and the tangents drop terms of relative
 * order eps (area changes, prestress; up to 5 eps, see fcc_lattice_case), so
 * |secant / tangent - 1| <= |r|/4 + r^2/4 + 5 eps.
 * Any factor 2 or sign error is far outside either tolerance.
 *
 * SIMPLE CUBIC (SC), m^3 grains at spacing 2R, walls touching the outer layers.  Every
 * contact lies along an axis, so a chain along a carries one force P(h_a) and sigma_aa =
 * m^2 P(h_a) / (L_b L_c).  With rigid walls a wall contact at overlap h/2 carries exactly
 * P_gg(h) (E*_gw = 2 E*, R*_gw = R: 4/3 2E* sqrt(R) (h/2)^(3/2) = 4/3 E* sqrt(R/2) h^(3/2)):
 * the wall is a mirror and the affine state is the equilibrium, h_a = 2R eps_a, so
 *     P_a = 4/3 E* sqrt(R/2) (2R eps_a)^(3/2) = 8/3 E* R^2 eps_a^(3/2),
 *     sigma_aa = P_a / (4R^2 (1-eps_b)(1-eps_c)) = 2/3 E* eps_a^(3/2) / ((1-eps_b)(1-eps_c)).
 * With walls of finite stiffness (E_w = 100 E) a wall contact at h_w carries P_gg(h_w / kappa),
 * kappa = (E* sqrt(R/2) / (E*_gw sqrt R))^(2/3), and the chain of m grains must fit the box:
 * (m-1) h + 2 kappa h = 2mR - L = 2mR eps, so h_a = 2R s eps_a with s = m / (m - 1 + 2 kappa)
 * (the closed form of test_lattice.c): the outer layers move, the equilibrium is non-affine,
 * and sigma_aa is the rigid-wall law at s eps_a.  Tangent moduli, dropping the O(eps) area terms:
 *     C11 = d sigma_aa / d eps_a = E* s^(3/2) sqrt(eps_a),
 *     C12 = d sigma_aa / d eps_b = sigma_aa / (1 - eps_b) ~ 2/3 eps C11 ~ 0: a strain along b does
 *           not change the chains along a, only the area they act on;
 *     C44 = O(sigma): an axis-aligned contact resists a shear only through its prestress.
 * The Hooke fit of a uniaxial increment (d sigma = (C11, C12, C12) de) gives K = (C11 + 2 C12)/3
 * = C11/3 and G = (C11 - C12)/2 = C11/2; an isotropic one K = (C11 + 2 C12)/3 = C11/3.
 *
 * FACE-CENTRED CUBIC (FCC), conventional cell a0 = 2 sqrt2 R (touching), 4 grains and 24
 * contacts per cell, 4 in each of the 6 bond classes b0 = (a0/2)(1,+-1,0), (1,0,+-1), (0,1,+-1),
 * l0 = 2R, V0 = a0^3 = 16 sqrt2 R^3.  Under the affine map F = I - eps, a bond becomes b = F b0,
 * h = 2R - |b|, and the Love-Weber stress of the infinite lattice is exactly
 *     sigma = (4 / (det F a0^3)) sum_classes P(h) b (x) b / |b|.
 * Linearised (dh = l0 n.eps.n, k = dP/dh = 2 E* sqrt(R/2 h0) = 2 E* R sqrt(eps0) at h0 = 2R eps0),
 *     C_abcd = (4/V0) k l0^2 sum_classes n_a n_b n_c n_d = (k / (sqrt2 R)) sum_classes n_a n_b n_c n_d,
 * and with n = (1,1,0)/sqrt2 etc.: sum n_x^4 = 4 (1/4) = 1, sum n_x^2 n_y^2 = 2 (1/4) = 1/2, so
 *     C11 = sqrt2 E* sqrt(eps0),   C12 = C44 = C11/2   (Cauchy relation, central forces),
 *     K = (C11 + 2 C12)/3 = 2/3 C11,  G from normal strains = (C11 - C12)/2 = C11/4 (= C44/2:
 * the lattice is anisotropic, 2 C44 / (C11 - C12) = 2), isotropic check: sigma = 4 sqrt2 / 3 E*
 * eps^(3/2), d sigma / d eps = 2 sqrt2 E* sqrt(eps) = C11 + 2 C12.
 * Walls cannot reproduce the infinite lattice: a face grain misses 4 diagonal contacts that one
 * normal wall contact would have to replace (test_lattice.c), so a walled FCC block is
 * non-affine and its wall-stress moduli differ from the lattice's by an amount set by the block
 * size (63 grains, rigid walls: K 0.617 GPa against the lattice's 1.14, G 0.300 against 0.408,
 * printed as a '#' line).  So the FCC lattice moduli are measured where lib computes the lattice's own stress:
 * measure_pack's Love-Weber sum over an affinely deformed block with the walls out of reach,
 * scaled from the block's contacts to the cell's (each class has the same count N in a block
 * with the cube's symmetry: sigma_lattice = sigma_LW V_box 4 / (N V_cell)); C44 from an affine
 * shear.  The walled FCC block goes through the loader as well and is compared with a Newton
 * reference (unit_lattice.h: the exact Hessian of an O(N^2) Hertz energy, as in test_lattice.c). */
#include "contact/contacts.h"
#include "contact/hertz.h"
#include "analysis/hooke.h"
#include "qs/loading.h"
#include "analysis/measure.h"
#include "base/msg.h"
#include "pack/pack.h"
#include "unit.h"
#include "unit_lattice.h"

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define R_ ldexp(1.0, -13)	/* 122 um */
#define E_ 7e10
#define NU 0.2
#define EPS0 1e-3		/* isotropic precompression */
#define DE 1e-4			/* the increments */
#define MIN_TOL 1e-11		/* the minimiser's residual (largest |F_i| / largest contact force) */
#define TOL_SEC 1e-8		/* measured secant against the exact one (see the top) */

/* The path: precompression from the touching lattice, then increments of each kind. */
enum { NSTEP = 6 };
static const double path_de[NSTEP][3] = {
    {EPS0, EPS0, EPS0}, {DE, 0, 0}, {0, DE, 0}, {0, 0, DE}, {DE, DE, DE}, {0, 0, -DE},
};
static const char *const path_name[NSTEP] = {
    "isotropic precompression", "uniaxial x", "uniaxial y", "uniaxial z", "isotropic", "uniaxial z unloading",
};

static double worst_sec;	/* largest secant error seen, for the closing line */

static double
Egg(void)
{
	return hertz_Estar(E_, NU, E_, NU);
}

/* ---------- lattices ---------- */

static void
lattice(struct pack *p, int kind, int m, double wall_E, double wall_nu)
{
	lattice_pack(p, kind, m, R_, E_, NU, wall_E, wall_nu);
	memcpy(p->refbox, p->box, sizeof p->box);
	p->has_refbox = 1;
	p->mu = p->wall_mu = 0;
}

/* ---------- the loader on a path ---------- */

/* Run the path; rows[k] and the box lengths L[k] after step k.  0 when every step converged. */
static int
run_path(struct pack *p, int friction, struct load_row rows[NSTEP], double L[NSTEP][3], const char *tag)
{
	struct loader ld;
	struct load_params lp;
	int k, a, bad = 0;
	long iters = 0;

	load_params_default(&lp);
	lp.friction = friction;
	lp.min.tol = MIN_TOL;
	lp.min.max_iter = 100000;
	if (loader_open(&ld, p, &lp)) {
		CHECK(0, "%s: loader_open", tag);
		return -1;
	}
	for (k = 0; k < NSTEP; k++) {
		int st = loader_step(&ld, path_de[k], &rows[k]);
		double derr = 0;
		for (a = 0; a < 3; a++) {
			L[k][a] = pack_box_length(p->box, a);
			derr = fmax(derr, fabs(rows[k].eps[a] - (k ? rows[k - 1].eps[a] : 0) - path_de[k][a]));
		}
		/* loader_step's de is the change of eps against the reference box: the strains
		 * of the rows, (L_ref - L) / L_ref, step by de to their rounding (1e-16 each) */
		if (derr > 1e-15) {
			CHECK(0, "%s %s: the rows' strains changed by de to %.3g", tag, path_name[k], derr);
			bad = 1;
		}
		if (st != 0 || !(rows[k].res_max <= MIN_TOL)) {
			CHECK(0, "%s %s: loader_step status %d, residual %.3g (%s)", tag, path_name[k], st, rows[k].res_max,
			    st < 0 ? msg_geterr() : "-");
			bad = 1;
		}
	}
	for (k = 0; k < NSTEP; k++)
		iters += rows[k].iterations;
	CHECK(!bad, "%s: every increment converged to residual %g (%ld minimiser iterations in all)", tag, MIN_TOL, iters);
	loader_close(&ld);
	return bad ? -1 : 0;
}

/* ---------- comparing an increment ---------- */

/* Step k of a path: measured stresses s0 -> s1 at strains e0 -> e1, reference stresses
 * r0 -> r1 at the same states.  The secants C_a = dsigma_a / de (de the largest strain
 * change) against the reference's; the Hooke fits of both increments. */
static void
check_increment(const char *tag, int k, const double e0[3], const double e1[3], const double s0[3], const double s1[3],
    const double r0[3], const double r1[3], struct hooke *hk_meas)
{
	double de[3], ds[3], dr[3], scale = 0, err = 0, dmax = 0;
	struct hooke hr;
	int a;

	for (a = 0; a < 3; a++) {
		de[a] = e1[a] - e0[a];
		ds[a] = s1[a] - s0[a];
		dr[a] = r1[a] - r0[a];
		scale = fmax(scale, fabs(dr[a]));
		if (fabs(de[a]) > fabs(dmax))
			dmax = de[a];
	}
	for (a = 0; a < 3; a++)
		err = fmax(err, fabs(ds[a] - dr[a]) / scale);
	worst_sec = fmax(worst_sec, err);
	CHECK(err <= TOL_SEC,
	    "%s %s: secants d sig / d eps = %.10g %.10g %.10g GPa = exact %.10g %.10g %.10g (error %.3g of the largest)", tag,
	    path_name[k], ds[0] / dmax / 1e9, ds[1] / dmax / 1e9, ds[2] / dmax / 1e9, dr[0] / dmax / 1e9, dr[1] / dmax / 1e9,
	    dr[2] / dmax / 1e9, err);
	/* Hooke fits: the measured increment's against the exact increment's (the same strains) */
	hooke_fit((const double(*)[3])&de, (const double(*)[3])&ds, 1, hk_meas);
	hooke_fit((const double(*)[3])&de, (const double(*)[3])&dr, 1, &hr);
	CHECK(hk_meas->has_K == hr.has_K && hk_meas->has_G == hr.has_G && unit_close(hk_meas->K, hr.K, TOL_SEC, 0) &&
	    (!hr.has_G || unit_close(hk_meas->G, hr.G, TOL_SEC, 0)),
	    "%s %s: Hooke fit K %.10g G %.10g GPa = exact increment's %.10g %.10g", tag, path_name[k], hk_meas->K / 1e9,
	    hk_meas->G / 1e9, hr.K / 1e9, hr.G / 1e9);
}

/* The measured fit against tangent moduli at the state before the step; r = de / eps of the
 * loaded axis (see the top for the tolerance). */
static void
check_tangent(const char *tag, int k, const struct hooke *hk, double K_t, double G_t, double r)
{
	double tol = fabs(r) / 4 + r * r / 4 + 5 * EPS0;

	CHECK(unit_close(hk->K, K_t, tol, 0) && (isnan(G_t) ? isnan(hk->G) : unit_close(hk->G, G_t, tol, 0)),
	    "%s %s: K %.6g G %.6g GPa against the tangent moduli %.6g %.6g GPa (ratios %.5f %.5f, tol %.3g for r = %.3g)", tag,
	    path_name[k], hk->K / 1e9, hk->G / 1e9, K_t / 1e9, G_t / 1e9, hk->K / K_t, hk->G / G_t, tol, r);
}

/* ---------- SC ---------- */

/* Exact stresses of the SC block (see the top) for box lengths L. */
static void
sc_sigma(int m, double wall_E, double wall_nu, const double L[3], double sig[3])
{
	double Es = Egg(), Ew = hertz_Estar(E_, NU, wall_E, wall_nu);
	double kappa = cbrt(pow(Es * sqrt(0.5) / Ew, 2));
	int a;

	for (a = 0; a < 3; a++) {
		double h = (2 * m * R_ - L[a]) / (m - 1 + 2 * kappa);
		sig[a] = m * m * hertz_force(Es, R_ / 2, h) / (L[(a + 1) % 3] * L[(a + 2) % 3]);
	}
}

static void
sc_case(int m, double wall_E, double wall_nu, int friction, const char *tag, struct load_row out[NSTEP])
{
	struct pack p;
	struct load_row rows[NSTEP];
	double L[NSTEP][3], ref[NSTEP][3], s;
	double Ew = hertz_Estar(E_, NU, wall_E, wall_nu), kappa = cbrt(pow(Egg() * sqrt(0.5) / Ew, 2));
	int k, a;

	s = m / (m - 1 + 2 * kappa);
	lattice(&p, SC, m, wall_E, wall_nu);
	if (friction) {
		/* grain-grain friction only: a grain on an x wall does move along z relative to
		 * it under a z strain, so wall friction would change the stresses; no grain-grain
		 * contact slides, since grains of a layer normal to a move alike along a */
		p.mu = 0.3;
		p.wall_mu = 0;
	}
	if (run_path(&p, friction, rows, L, tag)) {
		pack_free(&p);
		return;
	}
	for (k = 0; k < NSTEP; k++)
		sc_sigma(m, wall_E, wall_nu, L[k], ref[k]);
	/* the precompressed state itself: sigma = 2/3 E* (s eps0)^(3/2) / (1 - eps0)^2 */
	{
		double e = 0;
		for (a = 0; a < 3; a++)
			e = fmax(e, fabs(rows[0].sig[a] - ref[0][a]) / ref[0][a]);
		CHECK(e <= 1e-9 && unit_close(ref[0][0], 2.0 / 3 * Egg() * pow(s * EPS0, 1.5) / pow(1 - EPS0, 2), 1e-12, 0),
		    "%s: precompressed to %.10g MPa = 2/3 E* (s eps0)^(3/2) / (1-eps0)^2 (s = %.6f; error %.3g)", tag,
		    rows[0].sig[0] / 1e6, s, e);
	}
	for (k = 1; k < NSTEP; k++) {
		struct hooke hk;
		int ax = path_de[k][0] && path_de[k][1] ? -1 : path_de[k][0] ? 0 : path_de[k][1] ? 1 : 2;
		double e_ax = rows[k - 1].eps[ax < 0 ? 0 : ax], C11 = Egg() * pow(s, 1.5) * sqrt(e_ax);

		check_increment(tag, k, rows[k - 1].eps, rows[k].eps, rows[k - 1].sig, rows[k].sig, ref[k - 1], ref[k], &hk);
		/* the tangents: uniaxial K = C11/3, G = C11/2; isotropic K = C11/3, no G */
		check_tangent(tag, k, &hk, C11 / 3, ax < 0 ? NAN : C11 / 2, path_de[k][ax < 0 ? 0 : ax] / e_ax);
		if (ax >= 0) {
			/* C12 = 0 but for the area the chains along b act on: d sig_bb / d eps_a =
			 * sig_bb / (1 - eps_a) = 2/3 (eps_b / eps_a)^(1/2) eps_b C11 <= 1.3 eps0 C11 on this
			 * path (eps <= 1.2 eps0); a contact term would be O(C11) */
			int b = (ax + 1) % 3;
			double C12 = (rows[k].sig[b] - rows[k - 1].sig[b]) / (rows[k].eps[ax] - rows[k - 1].eps[ax]);
			CHECK(fabs(C12) <= EPS0 * 1.3 * C11 && fabs(C12) > 0,
			    "%s %s: C12 = %.4g GPa = %.3g C11: the area term only, no contact term", tag,
			    path_name[k], C12 / 1e9, C12 / C11);
		}
	}
	if (out)
		memcpy(out, rows, sizeof rows);
	pack_free(&p);
}

/* ---------- FCC: the infinite lattice ---------- */

static const int fcc_bond[6][3] = {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}};

static double
det3(const double F[3][3])
{
	return F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) - F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
	    F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
}

/* Exact Love-Weber stress (xx yy zz xy xz yz) of the infinite FCC lattice under F. */
static void
fcc_sigma(const double F[3][3], double sig[6])
{
	static const int ia[6] = {0, 1, 2, 0, 0, 1}, ib[6] = {0, 1, 2, 1, 2, 2};
	double a0 = 2 * sqrt(2.0) * R_, V = det3(F) * a0 * a0 * a0;
	int c, a, q;

	memset(sig, 0, 6 * sizeof *sig);
	for (c = 0; c < 6; c++) {
		double b[3], l = 0, P;
		for (a = 0; a < 3; a++) {
			b[a] = 0;
			for (q = 0; q < 3; q++)
				b[a] += F[a][q] * 0.5 * a0 * fcc_bond[c][q];
			l += b[a] * b[a];
		}
		l = sqrt(l);
		P = hertz_force(Egg(), R_ / 2, 2 * R_ - l);
		for (q = 0; q < 6; q++)
			sig[q] += 4 * P * b[ia[q]] * b[ib[q]] / l / V;
	}
}

/* F = I - eps for the symmetric strain (xx yy zz xy xz yz). */
static void
strain_F(const double e[6], double F[3][3])
{
	F[0][0] = 1 - e[0], F[1][1] = 1 - e[1], F[2][2] = 1 - e[2];
	F[0][1] = F[1][0] = -e[3];
	F[0][2] = F[2][0] = -e[4];
	F[1][2] = F[2][1] = -e[5];
}

/* sigma_xx of the lattice under isotropic strain e. */
static double
fcc_sigma_iso(double e)
{
	double ev[6] = {e, e, e, 0, 0, 0}, F[3][3], s[6];

	strain_F(ev, F);
	fcc_sigma(F, s);
	return s[0];
}

/* Love-Weber stress of an M^3-site FCC block mapped by F about its centre, walls out of
 * reach, scaled to the lattice: sigma_LW V_box 4 / (N V_cell).  N from the block's pairs. */
static int
fcc_block_sigma(int M, const double F[3][3], double sig[6], size_t *ncls, size_t *ngg)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures mm;
	double a0 = 2 * sqrt(2.0) * R_, c = R_ + 0.5 * (M - 1) * sqrt(2.0) * R_, Vcell = det3(F) * a0 * a0 * a0;
	size_t cnt[6] = {0}, i, j;
	int *site, a, q, rc;

	lattice(&p, FCC, M, INFINITY, 0.495);
	site = malloc(3 * p.n * sizeof *site);
	for (i = 0; i < p.n; i++) {
		double x0[3];
		for (a = 0; a < 3; a++) {
			site[3 * i + a] = (int)lround((p.x[3 * i + a] - R_) / (sqrt(2.0) * R_));
			x0[a] = p.x[3 * i + a] - c;
		}
		for (a = 0; a < 3; a++) {
			p.x[3 * i + a] = c;
			for (q = 0; q < 3; q++)
				p.x[3 * i + a] += F[a][q] * x0[q];
		}
	}
	/* the bond classes of the block's nearest-neighbour pairs */
	for (i = 0; i < p.n; i++)
		for (j = i + 1; j < p.n; j++) {
			int d[3], s = 1, cl;
			for (a = 0; a < 3; a++)
				d[a] = site[3 * j + a] - site[3 * i + a];
			if (abs(d[0]) + abs(d[1]) + abs(d[2]) != 2 || abs(d[0]) > 1 || abs(d[1]) > 1 || abs(d[2]) > 1)
				continue;
			if (d[0] < 0 || (d[0] == 0 && d[1] < 0))
				s = -1;	/* orient as the class representative */
			for (cl = 0; cl < 6; cl++)
				if (s * d[0] == fcc_bond[cl][0] && s * d[1] == fcc_bond[cl][1] && s * d[2] == fcc_bond[cl][2])
					cnt[cl]++;
		}
	*ncls = cnt[0];
	for (a = 1; a < 6; a++)
		if (cnt[a] != cnt[0])
			*ncls = 0;
	/* walls far away: 4R beyond the block on every side */
	for (a = 0; a < 3; a++) {
		p.box[a] = -4 * R_;
		p.box[3 + a] = 2 * c + 4 * R_;
	}
	contacts_init(&gc);
	rc = measure_pack(&p, &gc, &mm);
	*ngg = mm.contacts_gg;
	if (rc == 0 && *ncls > 0 && mm.contacts_gw == 0)
		for (q = 0; q < 6; q++)
			sig[q] = mm.sig_lw[q] * pow(2 * c + 8 * R_, 3) * 4 / ((double)*ncls * Vcell);
	else
		rc = -1;
	contacts_free(&gc);
	free(site);
	pack_free(&p);
	return rc;
}

static void
fcc_lattice_case(void)
{
	/* states: A isotropic eps0; from A: uniaxial x, isotropic, shear eps_xy */
	static const double eA[6] = {EPS0, EPS0, EPS0, 0, 0, 0};
	static const struct {
		const char *name;
		double de[6];
	} st[3] = {
	    {"uniaxial x", {DE, 0, 0, 0, 0, 0}},
	    {"isotropic", {DE, DE, DE, 0, 0, 0}},
	    {"shear xy", {0, 0, 0, DE / 2, 0, 0}},
	};
	double F[3][3], sA[6], rA[6], e[6], s1[6], r1[6], C11 = sqrt(2.0) * Egg() * sqrt(EPS0), err;
	size_t ncls, ngg;
	int k, q, rc;

	/* the derivation's tangents against the exact lattice stress by a central difference
	 * (1e-9 strain: truncation ~1e-12, rounding ~1e-16/1e-9 of sigma ~ 1e-9).  They agree
	 * to the terms the linearisation drops: the (1-eps)^-2 of the deformed cell in the
	 * contact term (2 eps0 C11) and the prestress terms (volume and bond-direction changes
	 * times sigma, sigma = 4/3 eps0 C11, with coefficients up to 1.5 here): in all below
	 * 5 eps0 C11 (measured: C11 +0.13 %, C12 +0.27 % of C11, C44 -1e-6) */
	{
		double ep[6], em[6], Fp[3][3], Fm[3][3], sp[6], sm[6], hstep = 1e-9, c11, c12, c44;
		memcpy(ep, eA, sizeof ep), memcpy(em, eA, sizeof em);
		ep[0] += hstep, em[0] -= hstep;
		strain_F(ep, Fp), strain_F(em, Fm);
		fcc_sigma(Fp, sp), fcc_sigma(Fm, sm);
		c11 = (sp[0] - sm[0]) / (2 * hstep);
		c12 = (sp[1] - sm[1]) / (2 * hstep);
		memcpy(ep, eA, sizeof ep), memcpy(em, eA, sizeof em);
		ep[3] += hstep, em[3] -= hstep;
		strain_F(ep, Fp), strain_F(em, Fm);
		fcc_sigma(Fp, sp), fcc_sigma(Fm, sm);
		c44 = (sp[3] - sm[3]) / (2 * 2 * hstep);	/* sigma_xy = 2 C44 eps_xy */
		CHECK(unit_close(c11, C11, 5 * EPS0, C11) && unit_close(c12, C11 / 2, 5 * EPS0, C11) &&
		    unit_close(c44, C11 / 2, 5 * EPS0, C11),
		    "FCC lattice: exact-stress derivatives C11 %.6g C12 %.6g C44 %.6g GPa = sqrt2 E* sqrt(eps0) = %.6g, C11/2, C11/2 "
		    "(to O(eps0))",
		    c11 / 1e9, c12 / 1e9, c44 / 1e9, C11 / 1e9);
		CHECK(unit_close(fcc_sigma_iso(EPS0), 4 * sqrt(2.0) / 3 * Egg() * pow(EPS0, 1.5) / pow(1 - EPS0, 2), 1e-12, 0),
		    "FCC lattice: isotropic sigma = 4 sqrt2/3 E* eps^(3/2) (1-eps)^-2 (%.10g MPa)", fcc_sigma_iso(EPS0) / 1e6);
	}

	strain_F(eA, F);
	fcc_sigma(F, rA);
	rc = fcc_block_sigma(5, F, sA, &ncls, &ngg);
	CHECK(rc == 0 && ncls > 0 && ngg == 6 * ncls,
	    "FCC 63-grain block: each of the 6 bond classes has %zu contacts, %zu in all, no wall contact", ncls, ngg);
	if (rc)
		return;
	/* rounding of the positions (2e-19 m against overlaps of 2e-7 m) moves a force by ~1e-12 */
	err = 0;
	for (q = 0; q < 3; q++)
		err = fmax(err, fabs(sA[q] - rA[q]) / rA[q]);
	CHECK(err <= 1e-10 && fabs(sA[3]) + fabs(sA[4]) + fabs(sA[5]) <= 1e-10 * rA[0],
	    "FCC lattice at eps0: Love-Weber %.10g MPa = exact %.10g MPa (error %.3g), no shear stress", sA[0] / 1e6, rA[0] / 1e6,
	    err);
	for (k = 0; k < 3; k++) {
		struct hooke hk;
		double ds[6], dr[6], scale = 0, d3[3], s3[3], C44;
		for (q = 0; q < 6; q++)
			e[q] = eA[q] + st[k].de[q];
		strain_F(e, F);
		fcc_sigma(F, r1);
		if (fcc_block_sigma(5, F, s1, &ncls, &ngg)) {
			CHECK(0, "FCC lattice %s: block measure", st[k].name);
			continue;
		}
		for (q = 0; q < 6; q++) {
			ds[q] = s1[q] - sA[q];
			dr[q] = r1[q] - rA[q];
			scale = fmax(scale, fabs(dr[q]));
		}
		err = 0;
		for (q = 0; q < 6; q++)
			err = fmax(err, fabs(ds[q] - dr[q]) / scale);
		worst_sec = fmax(worst_sec, err);
		/* stresses to 1e-12 over a change of 0.15 (0.03 for the shear) of sigma: 1e-9 */
		CHECK(err <= 1e-9, "FCC lattice %s: Love-Weber stress change %.6g %.6g %.6g %.6g MPa = exact (error %.3g)", st[k].name,
		    ds[0] / 1e6, ds[1] / 1e6, ds[2] / 1e6, ds[3] / 1e6, err);
		if (k < 2) {
			for (q = 0; q < 3; q++) {
				d3[q] = st[k].de[q];
				s3[q] = ds[q];
			}
			hooke_fit((const double(*)[3])&d3, (const double(*)[3])&s3, 1, &hk);
			/* uniaxial: K = (C11 + 2 C12)/3 = 2/3 C11, G = (C11 - C12)/2 = C11/4;
			 * isotropic: K = 2/3 C11, no G */
			check_tangent("FCC lattice", k == 0 ? 1 : 4, &hk, 2.0 / 3 * C11, k == 0 ? C11 / 4 : NAN, DE / EPS0);
		} else {
			/* sigma_xy is odd in eps_xy: the secant from the unsheared state is the tangent
			 * to O(r^2) and the O(eps0) terms above (5 eps0 + r^2, r = eps_xy / eps0).  The
			 * normal stresses change only to second order: the (1,1,0) and (1,-1,0) bonds
			 * change their overlaps by +-r, P ~ h^(3/2) gains 3/8 r^2 on average, and they
			 * carry half of sigma_xx: |d sigma_xx| ~ 3/16 r^2 sigma, bounded by r^2 sigma / 2
			 * (a first-order coupling would be C11 eps_xy ~ 40 times that) */
			double r = st[k].de[3] / EPS0;
			C44 = ds[3] / (2 * st[k].de[3]);
			CHECK(unit_close(C44, C11 / 2, 5 * EPS0 + r * r, 0) && fabs(ds[0]) <= 0.5 * r * r * rA[0] &&
			    fabs(ds[2]) <= 0.5 * r * r * rA[0],
			    "FCC lattice shear: C44 = d sig_xy / (2 d eps_xy) = %.6g GPa = C11/2 = %.6g GPa (ratio %.5f); normal "
			    "stresses change by %.3g of sigma, second order",
			    C44 / 1e9, C11 / 2e9, C44 / (C11 / 2), fabs(ds[0]) / rA[0]);
		}
	}
}

/* ---------- FCC between walls: the Newton reference ---------- */

/* Newton from x (in place) to rounding; the wall stresses of the solution into sig. */
static void
newton(const struct pack *p, double *x, double sig[3])
{
	double *g = malloc(3 * p->n * sizeof *g), wf[NWALLS];

	lattice_newton(p, x, 1e-15 * R_);
	lattice_ref_eval(p, x, g, NULL, wf);
	lattice_wall_stress(p->box, wf, sig);
	free(g);
}

static void
fcc_walled_case(void)
{
	const int M = 5;
	struct pack p, q;
	struct load_row rows[NSTEP];
	double L[NSTEP][3], ref[NSTEP][3], *xr, oldbox[6], C11, Kw = NAN, Gw = NAN;
	int k, a;
	size_t i;

	lattice(&p, FCC, M, INFINITY, 0.495);
	/* the reference's copy: its own positions, the loader's boxes */
	lattice(&q, FCC, M, INFINITY, 0.495);
	xr = malloc(3 * q.n * sizeof *xr);
	memcpy(xr, q.x, 3 * q.n * sizeof *xr);
	if (run_path(&p, 0, rows, L, "FCC 63 rigid walls")) {
		free(xr), pack_free(&p), pack_free(&q);
		return;
	}
	/* replay the boxes: the previous reference mapped affinely into the next box, then
	 * Newton.  (The boxes are recomputed from the strains, as the loader made them.) */
	for (k = 0; k < NSTEP; k++) {
		double e = 0;
		memcpy(oldbox, q.box, sizeof oldbox);
		for (a = 0; a < 3; a++) {
			double c = 0.5 * (q.refbox[a] + q.refbox[3 + a]);
			q.box[a] = c - 0.5 * L[k][a];
			q.box[3 + a] = c + 0.5 * L[k][a];
		}
		for (i = 0; i < q.n; i++)
			for (a = 0; a < 3; a++)
				xr[3 * i + a] = q.box[a] + (xr[3 * i + a] - oldbox[a]) * L[k][a] / (oldbox[3 + a] - oldbox[a]);
		newton(&q, xr, ref[k]);
		for (a = 0; a < 3; a++)
			e = fmax(e, fabs(rows[k].sig[a] - ref[k][a]) / ref[k][a]);
		CHECK(e <= 1e-9, "FCC 63 rigid walls %s: wall stresses %.10g %.10g %.10g MPa = Newton reference (error %.3g)",
		    path_name[k], rows[k].sig[0] / 1e6, rows[k].sig[1] / 1e6, rows[k].sig[2] / 1e6, e);
	}
	for (k = 1; k < NSTEP; k++) {
		struct hooke hk;
		check_increment("FCC 63 rigid walls", k, rows[k - 1].eps, rows[k].eps, rows[k - 1].sig, rows[k].sig, ref[k - 1],
		    ref[k], &hk);
		if (k == 1)
			Gw = hk.G;
		if (k == 4)
			Kw = hk.K;
	}
	/* information: the walled block against the infinite lattice at eps0 (not a check; the
	 * difference is the walls' non-affinity, see the top) */
	C11 = sqrt(2.0) * Egg() * sqrt(EPS0);
	printf("# FCC 63 grains, rigid walls: K (isotropic step at %.3g) %.4g GPa, G (uniaxial x at %.3g) %.4g GPa; "
	       "infinite lattice tangents K = 2/3 C11 = %.4g, G = C11/4 = %.4g GPa\n",
	    rows[3].eps[0], Kw / 1e9, EPS0, Gw / 1e9, 2.0 / 3 * C11 * sqrt(rows[3].eps[0] / EPS0) / 1e9, C11 / 4e9);
	free(xr);
	pack_free(&p);
	pack_free(&q);
}

int
main(void)
{
	struct load_row fl[NSTEP], fr[NSTEP];
	int k, a;

	sc_case(4, INFINITY, 0.495, 0, "SC 4^3 rigid walls", NULL);
	sc_case(4, 100 * E_, 0.495, 0, "SC 4^3 walls E_w = 100 E", fl);
	/* friction mu = 0.3 between grains (6N unknowns): under these paths no grain-grain
	 * contact has a tangential displacement (a layer normal to a moves as one along a, the
	 * outer layers included), so the stresses are the frictionless ones, to the residual
	 * (1e-11, times the chain's 4 layers: 1e-9).  Walls of finite stiffness, so that the
	 * minimiser has to move the outer layers (with rigid walls the affine guess is exact) */
	sc_case(4, 100 * E_, 0.495, 1, "SC 4^3 walls E_w = 100 E, mu = 0.3", fr);
	{
		double e = 0, sl = 0;
		for (k = 0; k < NSTEP; k++) {
			for (a = 0; a < 3; a++)
				e = fmax(e, fabs(fr[k].sig[a] - fl[k].sig[a]) / fl[k].sig[a]);
			sl = fmax(sl, fr[k].sliding_ratio);
		}
		CHECK(e <= 1e-9 && sl == 0, "SC 4^3 walls E_w = 100 E, mu = 0.3: the frictionless stresses on every step (largest difference %.3g), "
		    "no sliding contact", e);
	}
	fcc_lattice_case();
	fcc_walled_case();
	printf("# largest secant error %.3g\n", worst_sec);
	return unit_summary();
}
