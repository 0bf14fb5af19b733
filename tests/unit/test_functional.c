/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_functional: lib/qs/functional.c (Hertz energy, gradient, wall forces) and the neighbour
 * list behind it, against closed forms, finite differences and O(N^2) searches.
 *
 *  - one grain-grain and one grain-wall contact on exactly representable geometry: U, P, the
 *    direction and sign of the gradient, wall forces and wall stress (a few ulps);
 *  - central finite differences of Pi on random polydisperse packs, every coordinate, with a
 *    tolerance from the truncation/rounding analysis, and a check that the tolerance rejects
 *    a gradient 1 % too large;
 *  - Newton's third law: the grain-grain forces cancel in pairs, so sum_i dPi/dx_i equals
 *    the reaction on the walls;
 *  - the contacts found through the Verlet list equal an O(N^2) search, before and after
 *    moves small, near the skin, adversarial (a pair just outside the list driven into
 *    contact), large, and after box changes and radius growth;
 *  - qs_release_unbraced: on built geometry, grains with one, two or three contacts move by
 *    the closed-form u (u.n_c = h_c for each contact) and touch nothing after, a grain with
 *    four contacts stays, and so does one squeezed between opposite walls; on random packs
 *    every moved grain ends without contacts and Pi falls. */
#include "qs/functional.h"
#include "base/par.h"
#include "qs/layout.h"
#include "contact/hertz.h"
#include "qs/loading.h"
#include "pack/pack.h"
#include "unit.h"
#include "unit_hertz.h"
#include "unit_pack.h"

#include <float.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------- random packs ---------- */

/* ---------- O(N^2) reference ---------- */

struct ref {
	double E;		/* energy */
	double *g;		/* gradient (3n) */
	double *fsum;		/* sum of contact force magnitudes on each grain (n) */
	double *fbig;		/* largest contact force on each grain (n) */
	unsigned *cnt;		/* contacts per grain (n) */
	double wf[NWALLS];	/* normal force on each wall */
	size_t ngg, ngw;
	double hmin_abs;	/* not used by every caller */
};

static void
ref_alloc(struct ref *rf, size_t n)
{
	memset(rf, 0, sizeof *rf);
	rf->g = malloc(3 * n * sizeof *rf->g);
	rf->fsum = malloc(n * sizeof *rf->fsum);
	rf->fbig = malloc(n * sizeof *rf->fbig);
	rf->cnt = malloc(n * sizeof *rf->cnt);
}

static void
ref_free(struct ref *rf)
{
	free(rf->g);
	free(rf->fsum);
	free(rf->fbig);
	free(rf->cnt);
}

/* Every pair and every grain-wall pair, with hertz.h's closed forms. */
static void
ref_eval(const struct pack *p, const double *x, struct ref *rf)
{
	size_t i, j, n = p->n;
	int a, w;

	rf->E = 0;
	rf->ngg = rf->ngw = 0;
	memset(rf->g, 0, 3 * n * sizeof *rf->g);
	memset(rf->fsum, 0, n * sizeof *rf->fsum);
	memset(rf->fbig, 0, n * sizeof *rf->fbig);
	memset(rf->cnt, 0, n * sizeof *rf->cnt);
	memset(rf->wf, 0, sizeof rf->wf);
	for (i = 0; i < n; i++) {
		for (j = i + 1; j < n; j++) {
			double d[3], dist, h, Es, Rs, P;
			if (!unit_pair_overlap(p, x, i, j, d, &dist, &h))
				continue;
			Es = hertz_Estar(p->E[i], p->nu[i], p->E[j], p->nu[j]);
			Rs = hertz_Rstar(p->r[i], p->r[j]);
			P = hertz_force(Es, Rs, h);
			rf->E += hertz_energy(Es, Rs, h);
			for (a = 0; a < 3; a++) {
				rf->g[3 * i + a] -= P * d[a] / dist;
				rf->g[3 * j + a] += P * d[a] / dist;
			}
			rf->fsum[i] += P;
			rf->fsum[j] += P;
			rf->fbig[i] = fmax(rf->fbig[i], P);
			rf->fbig[j] = fmax(rf->fbig[j], P);
			rf->cnt[i]++;
			rf->cnt[j]++;
			rf->ngg++;
		}
		for (w = 0; w < NWALLS; w++) {
			double Es, P, h = unit_wall_contact(p, x, i, w, &Es, &P);
			if (h <= 0)
				continue;
			a = w / 2;
			rf->E += hertz_energy(Es, p->r[i], h);
			rf->g[3 * i + a] += w % 2 ? P : -P;
			rf->fsum[i] += P;
			rf->fbig[i] = fmax(rf->fbig[i], P);
			rf->cnt[i]++;
			rf->wf[w] += P;
			rf->ngw++;
		}
	}
}

/* ---------- one contact ---------- */

/* Two grains whose centre distance and overlap are exact in binary: radii 2^-13 and 3 2^-15
 * (sum 7 2^-15), centres c +- t (1, 3/2, 3) with t = 2^-15 - 2^-24, so x_i - x_j = t (2, 3, 6),
 * |x_i - x_j| = 7 t exactly and h = 7 2^-24 (0.42 um, 0.8 % of R*).  The only rounding is in
 * the force law (E*, sqrt R*, h^(3/2)): a few ulps, so 1e-13 relative is a safe bound that
 * still catches any wrong constant. */
static void
test_pair(void)
{
	struct pack p;
	struct qs_system s;
	double R1 = ldexp(1, -13), R2 = 3 * ldexp(1, -15), t = ldexp(1, -15) - ldexp(1, -24), c = ldexp(1, -8);
	double u[3] = {2.0 / 7, 3.0 / 7, 6.0 / 7}, x[6], g[6], fm[2], h = 7 * ldexp(1, -24);
	double Es = 1 / ((1 - 0.2 * 0.2) / 7e10 + (1 - 0.15 * 0.15) / 1e11), Rs = 1 / (1 / R1 + 1 / R2);
	double Uex = 8.0 / 15.0 * Es * sqrt(Rs) * pow(h, 2.5), Pex = 4.0 / 3.0 * Es * sqrt(Rs) * pow(h, 1.5);
	double E, E2, gn = 0, gl = 0, perp = 0;
	int a;

	pack_init(&p);
	{
		double x1[3] = {c + t, c + 1.5 * t, c + 3 * t}, x2[3] = {c - t, c - 1.5 * t, c - 3 * t};
		pack_add_grain(&p, 0, x1, R1, 7e10, 0.2, 2420);
		pack_add_grain(&p, 1, x2, R2, 1e11, 0.15, 2650);
	}
	for (a = 0; a < 3; a++) {
		p.box[a] = 0;
		p.box[3 + a] = 2 * c;
	}
	p.wall_E = 7e11;
	memcpy(x, p.x, sizeof x);
	CHECK(R1 + R2 - sqrt((x[0] - x[3]) * (x[0] - x[3]) + (x[1] - x[4]) * (x[1] - x[4]) + (x[2] - x[5]) * (x[2] - x[5])) ==
	    h, "pair: the geometry is exact (h = 7 2^-24)");
	CHECK(qs_init(&s, &p, 0.3) == 0, "pair: qs_init");
	E = qs_energy(&s, x, g, fm);
	CHECK_CLOSE(E, Uex, 1e-13, "pair: Pi = 8/15 E* sqrt(R*) h^(5/2)");
	CHECK(s.ncontacts == 1, "pair: one contact (%zu)", s.ncontacts);
	CHECK_CLOSE(s.sum_force, Pex, 1e-13, "pair: contact force = 4/3 E* sqrt(R*) h^(3/2)");
	CHECK_CLOSE(fm[0], Pex, 1e-13, "pair: largest contact force on grain 0");
	CHECK(fm[1] == fm[0], "pair: largest contact force on grain 1 is the same");
	for (a = 0; a < 3; a++) {
		gn += g[a] * u[a];
		gl += g[a] * g[a];
	}
	for (a = 0; a < 3; a++)
		perp = fmax(perp, fabs(g[a] - gn * u[a]));
	CHECK_CLOSE(sqrt(gl), Pex, 1e-13, "pair: |dPi/dx_0| = P");
	/* the sign: dPi/dx_0 . n = -P (n from grain 1 to grain 0), so moving grain 0 away lowers Pi */
	CHECK_CLOSE(gn, -Pex, 1e-13, "pair: dPi/dx_0 . n = -P (energy falls as the grains separate)");
	CHECK(perp <= 1e-13 * Pex, "pair: the gradient lies along the normal (off-normal part %.3g N)", perp);
	CHECK(g[3] == -g[0] && g[4] == -g[1] && g[5] == -g[2], "pair: dPi/dx_1 = -dPi/dx_0 exactly");
	/* a separation of 1e-3 h along n changes Pi by about -P 1e-3 h, far above rounding */
	for (a = 0; a < 3; a++)
		x[a] += 1e-3 * h * u[a];
	E2 = qs_energy(&s, x, NULL, NULL);
	CHECK(E2 < E, "pair: Pi falls when the grains move apart (%.6g < %.6g)", E2, E);
	for (a = 0; a < 3; a++)
		x[a] -= 2e-3 * h * u[a];
	E2 = qs_energy(&s, x, NULL, NULL);
	CHECK(E2 > E, "pair: Pi rises when the grains move together");
	for (a = 0; a < NWALLS; a++)
		if (s.wall_force[a] != 0)
			break;
	CHECK(a == NWALLS, "pair: no wall force");
	qs_free(&s);
	pack_free(&p);
}

/* Two grains, each on one wall: grain 0 (radius 2^-13) on zlo with overlap 2^-22, grain 1
 * (radius 3 2^-15) on xhi with overlap 2^-21; R* = R_i, E* from the grain and pack.wall_E,
 * wall_nu.  Exact geometry again, so 1e-13. */
static void
test_walls(void)
{
	struct pack p;
	struct qs_system s;
	double R0 = ldexp(1, -13), R1 = 3 * ldexp(1, -15), h0 = ldexp(1, -22), h1 = ldexp(1, -21), L = ldexp(1, -7);
	double Ew = 3e11, nuw = 0.3, E0 = 7e10, nu0 = 0.2, E1 = 1e11, nu1 = 0.15, x[6], g[6], sig[3];
	double Es0 = 1 / ((1 - nu0 * nu0) / E0 + (1 - nuw * nuw) / Ew), Es1 = 1 / ((1 - nu1 * nu1) / E1 + (1 - nuw * nuw) / Ew);
	double P0 = 4.0 / 3.0 * Es0 * sqrt(R0) * pow(h0, 1.5), P1 = 4.0 / 3.0 * Es1 * sqrt(R1) * pow(h1, 1.5);
	double U = 8.0 / 15.0 * (Es0 * sqrt(R0) * pow(h0, 2.5) + Es1 * sqrt(R1) * pow(h1, 2.5)), E;
	int w, others = 0;

	pack_init(&p);
	{
		double x0[3] = {L / 4, L / 4, R0 - h0}, x1[3] = {L - R1 + h1, L / 4, L / 2};
		pack_add_grain(&p, 0, x0, R0, E0, nu0, 2420);
		pack_add_grain(&p, 1, x1, R1, E1, nu1, 2650);
	}
	for (w = 0; w < 3; w++) {
		p.box[w] = 0;
		p.box[3 + w] = L;
	}
	p.box[4] = L / 2;	/* y: not a cube, so the wall areas differ */
	p.wall_E = Ew;
	p.wall_nu = nuw;
	memcpy(x, p.x, sizeof x);
	CHECK(qs_init(&s, &p, 0.3) == 0, "walls: qs_init");
	E = qs_energy(&s, x, g, NULL);
	CHECK_CLOSE(E, U, 1e-13, "walls: Pi = sum of 8/15 E*_w sqrt(R_i) h^(5/2)");
	CHECK(s.ncontacts == 2, "walls: two contacts (%zu)", s.ncontacts);
	/* zlo pushes grain 0 up (+z): dPi/dz_0 = -P0; xhi pushes grain 1 towards -x: dPi/dx_1 = +P1 */
	CHECK_CLOSE(g[2], -P0, 1e-13, "walls: dPi/dz = -P on the low z wall (energy falls moving away from it)");
	CHECK_CLOSE(g[3], P1, 1e-13, "walls: dPi/dx = +P on the high x wall");
	CHECK(g[0] == 0 && g[1] == 0 && g[4] == 0 && g[5] == 0, "walls: no tangential gradient");
	CHECK_CLOSE(s.wall_force[WALL_ZLO], P0, 1e-13, "walls: force on zlo = P0");
	CHECK_CLOSE(s.wall_force[WALL_XHI], P1, 1e-13, "walls: force on xhi = P1");
	for (w = 0; w < NWALLS; w++)
		others += w != WALL_ZLO && w != WALL_XHI && s.wall_force[w] != 0;
	CHECK(others == 0, "walls: no force on the other four walls");
	qs_wall_stress(&s, sig);
	/* (force on the two walls of an axis) / 2 / area: areas Ly Lz = L^2/2 for x, Lx Ly = L^2/2 for z */
	CHECK_CLOSE(sig[0], P1 / 2 / (L * L / 2), 1e-13, "walls: sig_xx = (F_xlo + F_xhi) / (2 Ly Lz)");
	CHECK_CLOSE(sig[2], P0 / 2 / (L * L / 2), 1e-13, "walls: sig_zz = (F_zlo + F_zhi) / (2 Lx Ly)");
	CHECK(sig[1] == 0, "walls: sig_yy = 0");
	qs_free(&s);
	pack_free(&p);
}

/* ---------- finite differences ---------- */

/* Central differences of Pi for every coordinate of a random pack.
 *
 * Step hs = 1e-5 of the mean radius (1e-9 m for 0.1 mm grains; overlaps are 0.1-4 % of R,
 * i.e. 1e2-4e3 hs).  Error of (Pi(x + hs e_k) - Pi(x - hs e_k)) / 2hs against dPi/dx_k:
 *  - truncation hs^2/6 |Pi'''|; per contact, with h(xi) = S - d(xi), |dh/dxi| <= 1,
 *    |d2h/dxi2| <= 1/d, |d3h/dxi3| <= 3/d^2, and P = c h^(3/2), P' = 3P/2h, P'' = 3P/4h^2:
 *    |U'''| <= 3P/(4h^2) + 9P/(2hd) + 3P/d^2.  Summed over grain i's contacts.
 *  - rounding: each Pi is a sum of M terms, each off by a few ulps plus the cancellation in
 *    h = S - d (an error of order eps S in h, eps S P in U); the sum adds at most M eps |Pi|
 *    (worst case; typically sqrt(M)).  So |dPi| <= eps (M |Pi| + 4 sum P S) per evaluation and
 *    the difference quotient is off by |dPi| / hs.
 * The tolerance of coordinate k is 2 (truncation + rounding): the analysis is a bound, and the
 * factor 2 covers the few-ulp terms left out; it comes to about 1e-7 of the largest force on the
 * grain.  Coordinates of grains with a contact (or a near contact) within 50 hs of h = 0, where
 * Hertz is not C3 and the truncation bound does not hold, are left out and counted.  A gradient
 * scaled by 1.01 must fail this tolerance on nearly every coordinate (|0.01 g_k| is 1e5 times
 * the tolerance unless g_k nearly cancels), so the check can fail. */
static void
test_fd(gsl_rng *rng, size_t n, double scale, double phi, const char *tag)
{
	struct pack p;
	struct qs_system s;
	struct ref rf;
	double *x, *g, *fm, *trunc, Pi, hs, Mterms, rsum = 0, worst = 0, worst_f = 0;
	char *excl;
	size_t i, k, tested = 0, bad = 0, scaled_fail = 0, excluded = 0;
	unsigned with_contacts = 0, with_wall = 0;
	int a, w;

	random_pack(&p, rng, n, scale, phi, 0.04);
	x = malloc(3 * n * sizeof *x);
	g = malloc(3 * n * sizeof *g);
	fm = malloc(n * sizeof *fm);
	trunc = calloc(n, sizeof *trunc);
	excl = calloc(n, 1);
	memcpy(x, p.x, 3 * n * sizeof *x);
	ref_alloc(&rf, n);
	ref_eval(&p, x, &rf);
	for (i = 0; i < n; i++) {
		with_contacts += rf.cnt[i] > 0;
		for (a = 0; a < 3; a++)
			with_wall += (x[3 * i + a] - p.box[a] < p.r[i]) + (p.box[3 + a] - x[3 * i + a] < p.r[i]);
	}
	CHECK(with_contacts >= 8 * n / 10 && with_wall >= 10,
	    "fd %s: the pack is dense (%u of %zu grains in contact, %u wall contacts, %zu grain-grain)", tag,
	    with_contacts, n, with_wall, rf.ngg);
	CHECK(qs_init(&s, &p, 0.3) == 0, "fd %s: qs_init", tag);
	Pi = qs_energy(&s, x, g, fm);
	hs = 1e-5 * scale;
	/* per grain: truncation bound and exclusion */
	unit_hertz_fd_bounds(&p, x, hs, trunc, excl, &rsum, NULL);
	for (i = 0; i < n; i++)
		trunc[i] *= hs * hs / 6;
	Mterms = (double)(rf.ngg + rf.ngw);
	for (k = 0; k < 3 * n; k++) {
		double save = x[k], ep, em, fd, tol, err;
		i = k / 3;
		if (excl[i]) {
			excluded++;
			continue;
		}
		if (!(fm[i] > 0))
			continue;	/* no contact: the gradient is 0 and so is the difference */
		x[k] = save + hs;
		ep = qs_energy(&s, x, NULL, NULL);
		x[k] = save - hs;
		em = qs_energy(&s, x, NULL, NULL);
		x[k] = save;
		fd = (ep - em) / (2 * hs);
		tol = 2 * (trunc[i] + DBL_EPSILON * (Mterms * fabs(Pi) + rsum) / hs);
		err = fabs(g[k] - fd);
		tested++;
		if (!(err <= tol))
			bad++;
		if (fabs(1.01 * g[k] - fd) > tol)
			scaled_fail++;
		worst = fmax(worst, err / tol);
		worst_f = fmax(worst_f, err / fm[i]);
	}
	CHECK(tested >= 300, "fd %s: %zu coordinates tested (%zu left out within 50 hs of h = 0)", tag, tested, excluded);
	CHECK(bad == 0, "fd %s: dPi/dx_k = central difference on every coordinate (%zu outside; worst error %.3g of the "
	    "tolerance, %.3g of the grain's largest force)", tag, bad, worst, worst_f);
	CHECK(scaled_fail >= 95 * tested / 100,
	    "fd %s: a gradient scaled by 1.01 fails the same tolerance on %zu of %zu coordinates", tag, scaled_fail, tested);

	/* Newton's third law: every grain-grain force enters g_i and g_j as the same number with
	 * opposite signs, so sum_i g_i is the reaction on the walls, -sum_w F_w n_w, with n_w the
	 * inward normal: component a is F_(a,hi) - F_(a,lo).  Rounding: each g_i adds at most a few
	 * tens of terms and the sum over grains n more, each term at most the total force, so the
	 * bound is (n + 64) eps sum|P|. */
	{
		double sum[3] = {0, 0, 0}, dev = 0, bound = (double)(n + 64) * DBL_EPSILON * 2 * s.sum_force, wdev = 0;
		qs_energy(&s, x, g, NULL);
		for (i = 0; i < n; i++)
			for (a = 0; a < 3; a++)
				sum[a] += g[3 * i + a];
		for (a = 0; a < 3; a++)
			dev = fmax(dev, fabs(sum[a] - (s.wall_force[2 * a + 1] - s.wall_force[2 * a])));
		CHECK(dev <= bound, "fd %s: sum_i dPi/dx_i = wall reaction (deviation %.3g N, bound %.3g N, total force %.3g N)",
		    tag, dev, bound, s.sum_force);
		/* the wall forces themselves against the O(N^2) sums: the same terms, maybe in another
		 * order: a few ulps of the total */
		for (w = 0; w < NWALLS; w++)
			wdev = fmax(wdev, fabs(s.wall_force[w] - rf.wf[w]));
		CHECK(wdev <= 1e-13 * s.sum_force, "fd %s: wall forces = O(N^2) sums (deviation %.3g N)", tag, wdev);
		CHECK(rf.wf[0] > 0 && rf.wf[5] > 0, "fd %s: walls are loaded (xlo %.3g N, zhi %.3g N)", tag, rf.wf[0],
		    rf.wf[5]);
	}
	ref_free(&rf);
	qs_free(&s);
	free(x), free(g), free(fm), free(trunc), free(excl);
	pack_free(&p);
}

/* ---------- neighbour list ---------- */

static int
listed(const struct nlist *nl, size_t i, size_t j)
{
	size_t lo = nl->first[i], hi = nl->first[i + 1];

	while (lo < hi) {
		size_t m = (lo + hi) / 2;
		if (nl->nbr[m] == j)
			return 1;
		if (nl->nbr[m] < j)
			lo = m + 1;
		else
			hi = m;
	}
	return 0;
}

/* Compare one evaluation with the O(N^2) reference.  Energies: the same terms in another
 * order, so at most M eps |Pi| apart; 1e-12 relative holds for M < 4500 contacts.  Gradient:
 * a few terms per grain, compared against 1e-12 of the sum of the contact forces on the
 * grain.  Counts, contact numbers and the pair set: exact. */
static void
compare(struct qs_system *s, const double *x, struct ref *rf, const char *what, long want_rebuild)
{
	const struct pack *p = s->p;
	size_t n = s->n, i, j, missing = 0, cdiff = 0;
	double *g = malloc(3 * n * sizeof *g), *fm = malloc(n * sizeof *fm), E, gdev = 0;
	unsigned *cnt = malloc(n * sizeof *cnt);
	long builds = s->ce.nl.builds;
	size_t fbad = 0;
	int a;

	E = qs_energy(s, x, g, fm);
	ref_eval(p, x, rf);
	qs_coordination(s, x, cnt);
	for (i = 0; i < n; i++) {
		cdiff += cnt[i] != rf->cnt[i];
		/* each grain's largest contact force (the residual's scale): the same Hertz force of
		 * the same pair, so equal to a few ulps; a walk that kept the first or the last force
		 * instead of the largest fails it */
		fbad += !(fabs(fm[i] - rf->fbig[i]) <= 1e-12 * rf->fbig[i]);
		for (a = 0; a < 3; a++)
			gdev = fmax(gdev, fabs(g[3 * i + a] - rf->g[3 * i + a]) / fmax(rf->fsum[i], 1e-300));
		for (j = i + 1; j < n; j++) {
			double dd = 0, S = p->r[i] + p->r[j];
			for (a = 0; a < 3; a++)
				dd += (x[3 * i + a] - x[3 * j + a]) * (x[3 * i + a] - x[3 * j + a]);
			if (dd < S * S && !listed(&s->ce.nl, i, j))
				missing++;
		}
	}
	CHECK_CLOSE(E, rf->E, 1e-12, what);
	CHECK(missing == 0 && cdiff == 0 && s->ncontacts == rf->ngg + rf->ngw,
	    "%s: the same contacts as the O(N^2) search (%zu + %zu; %zu overlapping pairs missing from the list, %zu "
	    "grains with other counts, %zu found)", what, rf->ngg, rf->ngw, missing, cdiff, s->ncontacts);
	CHECK(gdev <= 1e-12, "%s: gradient = O(N^2) gradient (%.3g of the grain's force sum)", what, gdev);
	CHECK(fbad == 0, "%s: every grain's largest contact force = the O(N^2) one (%zu differ)", what, fbad);
	if (want_rebuild >= 0)
		CHECK((s->ce.nl.builds > builds) == (want_rebuild > 0), "%s: the list was %s (as intended)", what,
		    s->ce.nl.builds > builds ? "rebuilt" : "reused");
	free(g), free(fm), free(cnt);
}

/* Random displacements of length up to amp (uniform direction and length), kept inside the box. */
static void
jiggle(gsl_rng *rng, const struct pack *p, double *x, double amp)
{
	size_t i;
	int a;

	for (i = 0; i < p->n; i++) {
		double v[3], l = amp * gsl_rng_uniform(rng);
		gsl_ran_dir_3d(rng, v, v + 1, v + 2);
		for (a = 0; a < 3; a++) {
			double y = x[3 * i + a] + l * v[a], lo = p->box[a] + 0.5 * p->r[i], hi = p->box[3 + a] - 0.5 * p->r[i];
			x[3 * i + a] = y < lo ? lo : y > hi ? hi : y;
		}
	}
}

static void
test_nlist(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	struct ref rf;
	size_t n = 250, i, j, bi = 0, bj = 0;
	double *x, skin, gbest = INFINITY;
	int a;

	random_pack(&p, rng, n, 1e-4, 0.6, 0.04);
	x = malloc(3 * n * sizeof *x);
	memcpy(x, p.x, 3 * n * sizeof *x);
	ref_alloc(&rf, n);
	CHECK(qs_init(&s, &p, 0.3) == 0, "nlist: qs_init");
	skin = s.skin;
	compare(&s, x, &rf, "nlist: first evaluation", 1);
	CHECK(rf.ngg > n, "nlist: the pack has many contacts (%zu grain-grain, %zu wall)", rf.ngg, rf.ngw);

	/* moves that keep 2 max|u| below the skin: the list is reused and must still hold every contact */
	jiggle(rng, &p, x, 1e-3 * p.r[0]);
	compare(&s, x, &rf, "nlist: moves of 1e-3 R", 0);
	memcpy(x, s.ce.nl.xb, 3 * n * sizeof *x);
	jiggle(rng, &p, x, 0.45 * skin);
	compare(&s, x, &rf, "nlist: moves up to 0.45 skin", 0);
	jiggle(rng, &p, x, 0.8 * skin);
	compare(&s, x, &rf, "nlist: further moves up to 0.8 skin", -1);

	/* adversarial: the unlisted pair with the smallest gap g (>= skin) is driven into contact,
	 * each grain moving g/2 (1 + 1e-3) towards the other.  Each moves only just over skin/2:
	 * a staleness test that forgot that two grains close a gap together would keep the list
	 * and miss this contact. */
	memcpy(x, s.ce.nl.xb, 3 * n * sizeof *x);
	for (i = 0; i < n; i++)
		for (j = i + 1; j < n; j++) {
			double dd = 0, gap;
			if (listed(&s.ce.nl, i, j))
				continue;
			for (a = 0; a < 3; a++)
				dd += (x[3 * i + a] - x[3 * j + a]) * (x[3 * i + a] - x[3 * j + a]);
			gap = sqrt(dd) - p.r[i] - p.r[j];
			if (gap < gbest) {
				gbest = gap;
				bi = i;
				bj = j;
			}
		}
	CHECK(gbest >= skin && gbest < 1.5 * skin, "nlist: the nearest unlisted pair has a gap of %.3g skin", gbest / skin);
	{
		double d[3], dd = 0, m;
		for (a = 0; a < 3; a++) {
			d[a] = x[3 * bj + a] - x[3 * bi + a];
			dd += d[a] * d[a];
		}
		m = gbest / 2 * (1 + 1e-3) / sqrt(dd);
		for (a = 0; a < 3; a++) {
			x[3 * bi + a] += m * d[a];
			x[3 * bj + a] -= m * d[a];
		}
	}
	compare(&s, x, &rf, "nlist: nearest unlisted pair driven into contact", 1);

	jiggle(rng, &p, x, 3 * p.r[0]);
	compare(&s, x, &rf, "nlist: moves up to 3 R", 1);

	/* box changes: z wall moved in by 3 % with the grains left in place (non-affine) */
	{
		double de[3] = {0, 0, 0};
		p.box[5] -= 0.03 * (p.box[5] - p.box[2]);
		compare(&s, x, &rf, "nlist: z box shortened 3 %, grains fixed", -1);
		/* affine 3 % along x: the affine shortening of the longest listed pair, 3 % of
		 * 2 rmax + skin, is below the skin, so the list may be kept */
		de[0] = 0.03;
		load_strain_box(p.box, x, n, de);
		compare(&s, x, &rf, "nlist: x box shortened 3 %, affine", 0);
		/* affine 15 % along y: now pairs beyond the skin can close */
		de[0] = 0;
		de[1] = 0.15;
		load_strain_box(p.box, x, n, de);
		compare(&s, x, &rf, "nlist: y box shortened 15 %, affine", 1);
		/* expansion with the grains fixed */
		de[1] = -0.05;
		p.box[0] -= 0.05 * (p.box[3] - p.box[0]);
		compare(&s, x, &rf, "nlist: x box lengthened 5 %, grains fixed", -1);
		jiggle(rng, &p, x, 0.3 * skin);
		compare(&s, x, &rf, "nlist: then moves up to 0.3 skin", -1);
	}
	/* radius growth: qs_radii_changed makes the next evaluation rebuild */
	for (i = 0; i < n; i++)
		p.r[i] *= 1.03;
	qs_radii_changed(&s);
	compare(&s, x, &rf, "nlist: radii grown 3 %", 1);
	ref_free(&rf);
	qs_free(&s);
	free(x);
	pack_free(&p);
}


/* ---------- release of unbraced grains ---------- */

static void
release_grain(struct pack *p, const double c[3], double R)
{
	pack_add_grain(p, (long)p->n, c, R, 7e10, 0.2, 2500);
}

/* Built geometry in a 1 mm cube, radii 0.1 mm, overlaps of a few um:
 *  0: on the xlo wall (1 um), the yhi wall (2 um) and grain 6 (3 um) along
 *     d = (0.36, -0.48, 0.8): three normals (1,0,0), (0,-1,0), -d, not orthogonal, so
 *     u = (1, -2, -5.4) um solves u.n_c = h_c (the 3x3 Gram solve);
 *  1: on the ylo wall (2 um) and against grain 2 along x (1 um): u = (-1, 2, 0) um;
 *  2: on the ylo wall, with grains 1, 3, 4, 5: five contacts, then four once 1 has gone:
 *     it stays;
 *  3, 4, 5: one contact each, with 2, along (0.8, 0.6, 0), (0, 0.6, 0.8), (0, 0.6, -0.8), overlaps
 *     1.5, 0.5, 2.5 um: each moves by its overlap along its normal (they do not touch each other:
 *     their normals are 69 degrees or more apart);
 *  6: grain 0's partner: its one contact has opened when its turn comes, so it stays.
 * u is exact to rounding, and scaled by 1 + 1e-8 so that the contacts open: 1e-12 m.
 * Then a grain in a box 2 um narrower than its diameter (two opposite wall contacts): it can
 * be balanced and must stay. */
static void
test_release(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	struct ref rf;
	double L = 1e-3, R = 1e-4, um = 1e-6, *x, x0[21], E0, E1;
	double dir[3][3] = {{0.8, 0.6, 0}, {0, 0.6, 0.8}, {0, 0.6, -0.8}}, ov[3] = {1.5 * um, 0.5 * um, 2.5 * um};
	double d6[3] = {0.36, -0.48, 0.8}, uexp[7][3] = {{1 * um, -2 * um, -5.4 * um}, {-1 * um, 2 * um, 0}, {0, 0, 0}};
	size_t i, n, nmoved;
	long moved;
	int a, k, ok;

	pack_init(&p);
	{
		double c0[3] = {R - 1 * um, L - R + 2 * um, 0.5 * L}, c6[3];
		double c2[3] = {0.5 * L, R - 2 * um, 0.5 * L};
		double c1[3] = {0.5 * L - 2 * R + 1 * um, R - 2 * um, 0.5 * L};
		release_grain(&p, c0, R);
		release_grain(&p, c1, R);
		release_grain(&p, c2, R);
		for (k = 0; k < 3; k++) {
			double c[3];
			for (a = 0; a < 3; a++) {
				c[a] = c2[a] + (2 * R - ov[k]) * dir[k][a];
				uexp[3 + k][a] = ov[k] * dir[k][a];
			}
			release_grain(&p, c, R);
		}
		for (a = 0; a < 3; a++) {
			c6[a] = c0[a] + (2 * R - 3 * um) * d6[a];
			uexp[6][a] = 0;
		}
		release_grain(&p, c6, R);
	}
	for (a = 0; a < 3; a++) {
		p.box[a] = 0;
		p.box[3 + a] = L;
	}
	p.wall_E = 7e10;
	p.wall_nu = 0.2;
	n = p.n;
	x = malloc(3 * n * sizeof *x);
	memcpy(x, p.x, 3 * n * sizeof *x);
	memcpy(x0, x, sizeof x0);
	ref_alloc(&rf, n);
	ref_eval(&p, x, &rf);
	CHECK(rf.cnt[0] == 3 && rf.cnt[1] == 2 && rf.cnt[2] == 5 && rf.cnt[3] == 1 && rf.cnt[4] == 1 && rf.cnt[5] == 1 &&
	        rf.cnt[6] == 1,
	    "release: built contacts 3 2 5 1 1 1 1 (%u %u %u %u %u %u %u)", rf.cnt[0], rf.cnt[1], rf.cnt[2], rf.cnt[3],
	    rf.cnt[4], rf.cnt[5], rf.cnt[6]);
	CHECK(qs_init(&s, &p, 0.3) == 0, "release: qs_init");
	moved = qs_release_unbraced(&s, x);
	CHECK(moved == 5, "release: 5 grains moved (%ld)", moved);
	ok = 1;
	for (i = 0; i < n; i++)
		for (a = 0; a < 3; a++) {
			double u = x[3 * i + a] - x0[3 * i + a];
			if (!(fabs(u - uexp[i][a]) <= 1e-6 * um)) {
				ok = 0;
				printf("# release: grain %zu axis %d: u %.17g, expected %.17g\n", i, a, u, uexp[i][a]);
			}
		}
	CHECK(ok, "release: each move is the closed form (two walls and an oblique grain; a wall and a grain at right angles; one contact; none for four contacts or an opened one) within 1e-12 m");
	ref_eval(&p, x, &rf);
	CHECK(rf.cnt[0] + rf.cnt[1] + rf.cnt[3] + rf.cnt[4] + rf.cnt[5] + rf.cnt[6] == 0 && rf.cnt[2] == 1,
	    "release: the moved grains touch nothing; grain 2 keeps its wall (%u %u %u %u %u %u)", rf.cnt[0],
	    rf.cnt[1], rf.cnt[2], rf.cnt[3], rf.cnt[4], rf.cnt[5]);
	qs_free(&s);
	pack_free(&p);

	/* squeezed between the xlo and xhi walls: balanced by two opposite contacts */
	pack_init(&p);
	{
		double c[3] = {R - um, 0.5 * L, 0.5 * L};
		release_grain(&p, c, R);
	}
	for (a = 0; a < 3; a++) {
		p.box[a] = 0;
		p.box[3 + a] = L;
	}
	p.box[3] = 2 * R - 2 * um;
	p.wall_E = 7e10;
	p.wall_nu = 0.2;
	memcpy(x, p.x, 3 * sizeof *x);
	CHECK(qs_init(&s, &p, 0.3) == 0, "release: qs_init (squeezed)");
	moved = qs_release_unbraced(&s, x);
	CHECK(moved == 0 && memcmp(x, p.x, 3 * sizeof *x) == 0, "release: a grain between opposite walls stays (%ld moved)", moved);
	qs_free(&s);
	pack_free(&p);
	ref_free(&rf);
	free(x);

	/* random overlapping packs: every moved grain ends without contacts; Pi falls */
	for (k = 0; k < 3; k++) {
		random_pack(&p, rng, 300, 1e-4, 0.62, 0.04);
		n = p.n;
		x = malloc(3 * n * sizeof *x);
		memcpy(x, p.x, 3 * n * sizeof *x);
		ref_alloc(&rf, n);
		ref_eval(&p, x, &rf);
		E0 = rf.E;
		CHECK(qs_init(&s, &p, 0.3) == 0, "release: qs_init (random)");
		moved = qs_release_unbraced(&s, x);
		ref_eval(&p, x, &rf);
		E1 = rf.E;
		ok = 1;
		nmoved = 0;
		for (i = 0; i < n; i++)
			if (memcmp(x + 3 * i, p.x + 3 * i, 3 * sizeof *x)) {
				nmoved++;
				ok &= rf.cnt[i] == 0;
			}
		CHECK(moved > 0 && (size_t)moved == nmoved && ok && E1 < E0,
		    "release: random pack %d: %ld moved (%zu changed), all now without contacts: %s; Pi %.6g -> %.6g", k,
		    moved, nmoved, ok ? "yes" : "no", E0, E1);
		qs_free(&s);
		ref_free(&rf);
		free(x);
		pack_free(&p);
	}
}

/* qs_residual walks two grains at a time in lanes; here the scalar walk it replaced, the
 * larger of a grain's two lengths from two square roots, by the same blocks of grains. */
static void
residual_scalar(const struct qs_system *s, const double *g, const double *fbig, double floor_rel, double *res_max,
    double *res_mean)
{
	double rmax = 0, sum = 0, fl = s->ncontacts ? floor_rel * s->sum_force / s->ncontacts : 0;
	size_t n = s->n, bl = par_block(n), i, q, nf = 0;

	if (s->force_floor > fl)
		fl = s->force_floor;
	for (q = 0; q * bl < n; q++) {
		double t = 0;
		for (i = q * bl; i < n && i < (q + 1) * bl; i++) {
			const double *a = g + 3 * i, *o = s->layout.rotations ? g + 3 * n + 3 * i : NULL;
			double f = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), rel;
			if (!(fbig[i] > 0))
				continue;
			if (o)
				f = max_or_num(f, sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
			rel = f / max_or_num(fbig[i], fl);
			if (rel > rmax)
				rmax = rel;
			t += f;
			nf++;
		}
		sum += t;
	}
	*res_max = rmax;
	*res_mean = nf && s->ncontacts ? (sum / nf) / (s->sum_force / s->ncontacts) : 0;
}

/* The residual in lanes to the bit: random vectors over 7 orders of magnitude, with and
 * without rotations, odd and even counts, grains with no contact (fbig 0 or NaN), forces
 * below the floor, a translation and rotation of equal squares, NaNs in the vector. */
static void
test_residual(gsl_rng *rng)
{
	size_t sizes[] = {1, 2, 7, 300, 301}, z;
	long bad = 0, cases = 0;

	for (z = 0; z < sizeof sizes / sizeof sizes[0]; z++) {
		int rot;
		for (rot = 0; rot < 2; rot++) {
			struct qs_system s;
			size_t n = sizes[z], k;
			double *g = malloc(6 * n * sizeof *g), *fb = malloc(n * sizeof *fb), a1, b1, a2, b2;

			memset(&s, 0, sizeof s);
			s.n = n;
			layout_set(&s.layout, n, rot);
			s.ncontacts = 3 * n;
			s.sum_force = 1.7 * (double)s.ncontacts;
			s.force_floor = rot ? 0 : 0.05;
			for (k = 0; k < 6 * n; k++)
				g[k] = (gsl_rng_uniform(rng) - 0.5) * pow(10, -7 * gsl_rng_uniform(rng));
			for (k = 0; k < n; k++)
				fb[k] = k % 5 == 1 ? 0 : k % 11 == 3 ? NAN : k % 7 == 2 ? 1e-9 : gsl_rng_uniform(rng);
			if (n > 9 && rot) {
				/* equal squares: translation and rotation of the same length */
				memcpy(g + 3 * n + 3 * 4, g + 3 * 4, 3 * sizeof *g);
				/* grains with contacts (fbig > 0): a NaN translation, a NaN rotation, both */
				g[3 * 2 + 1] = NAN;
				g[3 * n + 3 * 8] = NAN;
				g[3 * 9] = g[3 * n + 3 * 9 + 2] = NAN;
			}
			qs_residual(&s, g, fb, 1e-3, &a1, &b1);
			residual_scalar(&s, g, fb, 1e-3, &a2, &b2);
			bad += memcmp(&a1, &a2, sizeof a1) != 0 || memcmp(&b1, &b2, sizeof b1) != 0;
			cases++;
			free(g), free(fb);
		}
	}
	CHECK(bad == 0, "residual: the two-grain lanes give the scalar walk's largest and mean to the bit (%ld of %ld cases differ)",
	    bad, cases);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);

	gsl_rng_set(rng, 77031);
	test_pair();
	test_walls();
	test_fd(rng, 300, 1e-4, 0.62, "0.1 mm, n=300");
	test_fd(rng, 120, 1e-3, 0.64, "1 mm, n=120");
	test_nlist(rng);
	test_release(rng);
	test_residual(rng);
	gsl_rng_free(rng);
	return unit_summary();
}
