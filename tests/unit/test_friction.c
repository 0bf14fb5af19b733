/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_friction: lib/qs/friction.c, the Mindlin-Deresiewicz tangential force and torsion of
 * physics.md §3-6, against closed forms, the papers' Fig. 2 loop and finite differences.
 *
 *  1. Fig. 2 of the frictional paper: one grain-grain contact (grain 0 orbiting grain 1 at
 *     a fixed centre distance, so the overlap and the normal force stay fixed) and one
 *     grain-wall contact (a grain sliding along the zlo wall) driven increment by increment
 *     (fr_begin, impose the displacement on x, qs_energy, fr_commit) through loading,
 *     unloading and reloading: slope k* from zero, plateau mu P, unloading slope k*, a
 *     closed loop of the parallelogram's area; the same for torsion through the rotation
 *     block (slope k*_t, plateau M_max); both sliding rules (they coincide in one dimension).
 *  2. |Q| <= Q_max and |M| <= M_max on every contact after every evaluation of every test.
 *  3. The gradient of Pi (6N unknowns) against central differences on random packs where a
 *     good share of the contacts slide, with the frozen quantities (n, lever arms, k*, Q_max,
 *     k*_t, M_max) of every contact checked against physics.md, and Pi against the work of its
 *     gradient along a path through the slip transitions (an energy offset on the sliding
 *     branch is invisible to differences); FR_PAPER at the same point.
 *  4. mu = 0: the frictional engine gives the frictionless energy and gradient.
 *  5. Two-grain shear: sliding at exactly Q = mu P; a push across the reference force.
 *  6. History: commit and begin (Q0 turned into the new tangent plane, magnitude kept),
 *     stale lines, opened contacts, clamping, fr_check_history's limit, and the orientation
 *     of a line listed as "j i" (which the pack format allows: Q0 is then the force on j).
 *     The evaluation's two-lane kernel equals the one-contact walk to the bit.
 *  7. A rigid translation and a rigid rotation of a wall-free pack change no tangential
 *     force or couple. */
#include "contact/contacts.h"
#include "qs/friction.h"
#include "qs/functional.h"
#include "qs/minimize.h"
#include "contact/hertz.h"
#include "base/msg.h"
#include "pack/pack.h"
#include "unit.h"
#include "unit_hertz.h"
#include "unit_pack.h"
#include "base/vec3.h"

#include <float.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EPS DBL_EPSILON

/* CHECK_CLOSE with a formatted name: |a - b| <= tol |b|. */
static void check_rel(double a, double b, double tol, const char *fmt, ...) __attribute__((format(printf, 4, 5)));

static void
check_rel(double a, double b, double tol, const char *fmt, ...)
{
	char name[256];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(name, sizeof name, fmt, ap);
	va_end(ap);
	unit_report(unit_close(a, b, tol, 0), "%s: %.17g vs %.17g (rel %.3g, tol %.3g)", name, a, b,
	    fabs(a - b) / (fabs(b) > 0 ? fabs(b) : 1), tol);
}

/* ---------- closed forms of physics.md §2-5 ---------- */

struct ref_contact {
	double P, a, k, kt, qmax, mmax;
};

/* Contact of grain (Ei, nui, Ri) with grain (Ej, nuj, Rj), or with a wall when Rj <= 0, at
 * overlap h with friction coefficient mu. */
static void
ref_contact(double Ei, double nui, double Ri, double Ej, double nuj, double Rj, double h, double mu,
    struct ref_contact *r)
{
	double Rs = Rj > 0 ? Ri * Rj / (Ri + Rj) : Ri;
	double Es = 1 / ((1 - nui * nui) / Ei + (1 - nuj * nuj) / Ej);
	double Gi = Ei / (2 * (1 + nui)), Gj = Ej / (2 * (1 + nuj));

	r->P = 4.0 / 3.0 * Es * sqrt(Rs) * pow(h, 1.5);
	r->a = sqrt(Rs * h);
	r->k = 8 * r->a / ((2 - nui) / Gi + (2 - nuj) / Gj);
	r->kt = 16.0 / 3.0 * pow(r->a, 3) / (1 / Gi + 1 / Gj);
	r->qmax = mu * r->P;
	r->mmax = 3 * M_PI / 16 * r->a * mu * r->P;
}

static void
ref_of(const struct pack *p, size_t i, long j, double h, struct ref_contact *r)
{
	if (PACK_IS_WALL(j))
		ref_contact(p->E[i], p->nu[i], p->r[i], p->wall_E, p->wall_nu, 0, h, p->wall_mu, r);
	else
		ref_contact(p->E[i], p->nu[i], p->r[i], p->E[j], p->nu[j], p->r[j], h, p->mu, r);
}

/* Q_max and M_max of a history line at its own P0 (a = sqrt(R* h(P0))). */
static void
line_limits(const struct pack *p, const struct pack_contact *c, double P, double *qmax, double *mmax)
{
	int wall = PACK_IS_WALL(c->j);
	double Ei = p->E[c->i], nui = p->nu[c->i], Ej = wall ? p->wall_E : p->E[c->j], nuj = wall ? p->wall_nu : p->nu[c->j];
	double Es = 1 / ((1 - nui * nui) / Ei + (1 - nuj * nuj) / Ej);
	double Rs = wall ? p->r[c->i] : p->r[c->i] * p->r[c->j] / (p->r[c->i] + p->r[c->j]);
	double mu = wall ? p->wall_mu : p->mu, h = hertz_overlap(Es, Rs, P);

	*qmax = mu * P;
	*mmax = 3 * M_PI / 16 * sqrt(Rs * h) * mu * P;
}

/* ---------- test 2: the sliding limits after every evaluation ---------- */

/* |Q| = Q_max q / |q| is off its limit by the rounding of |q|, of the division and product and
 * of the norm taken here: a few ulps.  16 eps (3.6e-15) is round-off, far below any error of
 * the rule itself (a paper-rule root or a clamp gone wrong is off by O(1)).  The couple is
 * clamped by assignment (M = +-M_max), so it may not exceed M_max at all; the same 16 eps
 * is used for symmetry. */
#define BOUND_TOL (16 * EPS)

static struct {
	long evals, checks, viol;
	double worst_q, worst_m;	/* largest |Q| / Q_max - 1 and |M| / M_max - 1 */
	char first[256];
} bnd = {0, 0, 0, -INFINITY, -INFINITY, ""};

static void
bounds_record(const struct qs_friction *f, const char *where)
{
	size_t k;

	bnd.evals++;
	for (k = 0; k < f->n; k++) {
		const struct fr_contact *c = &f->c[k];
		double qn = vec3_norm(c->Q), m = fabs(c->M);
		int bad = !(qn <= c->qmax * (1 + BOUND_TOL)) || !(m <= c->mmax * (1 + BOUND_TOL));

		bnd.checks++;
		if (c->qmax > 0)
			bnd.worst_q = fmax(bnd.worst_q, qn / c->qmax - 1);
		if (c->mmax > 0)
			bnd.worst_m = fmax(bnd.worst_m, m / c->mmax - 1);
		if (bad && bnd.viol++ == 0)
			snprintf(bnd.first, sizeof bnd.first, "%s: contact %zu-%ld |Q| = %.17g Q_max = %.17g |M| = %.17g M_max = %.17g",
			    where, c->i, c->j, qn, c->qmax, m, c->mmax);
	}
}

/* Every evaluation of the tests goes through here. */
static double
eval(struct qs_system *s, const double *x, double *g, const char *where)
{
	double E = qs_energy(s, x, g, NULL);

	if (fr_attached(s))
		bounds_record(fr_attached(s), where);
	return E;
}

static int
begin(struct qs_friction *f, struct qs_system *s, double *x, const char *where)
{
	int r = fr_begin(f, s);

	if (r == 0) {
		memcpy(x, s->p->x, 3 * s->n * sizeof *x);
		memset(x + 3 * s->n, 0, 3 * s->n * sizeof *x);
		bounds_record(f, where);	/* Q = Q^p, M = M^p after the clamp */
	}
	return r;
}

static int
commit(struct qs_friction *f, struct qs_system *s, double *x, const char *where)
{
	int r = fr_commit(f, s, x);

	bounds_record(f, where);
	return r;
}

static long
find_contact(const struct qs_friction *f, size_t i, long j)
{
	size_t k;

	for (k = 0; k < f->n; k++)
		if (f->c[k].i == i && f->c[k].j == j)
			return (long)k;
	return -1;
}

static struct pack_contact *
find_line(const struct pack *p, size_t i, long j)
{
	size_t k;

	for (k = 0; k < p->nc; k++)
		if ((p->c[k].i == i && p->c[k].j == j) || (j >= 0 && p->c[k].i == (size_t)j && p->c[k].j == (long)i))
			return &p->c[k];
	return NULL;
}

/* ---------- the two-contact pack ---------- */

/* Grain 1 (radius 3 2^-15, E 1e11, nu 0.15) at the origin and grain 0 (radius 2^-13, E 7e10,
 * nu 0.2) at t (2, 3, 6), t = 2^-15 - 2^-24: |x0 - x1| = 7 t and h = 7 2^-24 exactly (0.42 um,
 * 0.8 % of R*).  Grain 2 (radius 2^-13, E 7e10, nu 0.25) on the zlo wall of the box
 * [-2^-10, 2^-10]^3 with overlap 2^-22, exact too.  Walls E 7e11, nu 0.3.  mu = 0.3 and
 * wall_mu = 0.4 differ, so that a mix-up of the two is caught. */
#define PAIR_T (ldexp(1, -15) - ldexp(1, -24))
#define PAIR_H (7 * ldexp(1, -24))
#define WALL_H ldexp(1, -22)
static const double n0[3] = {2.0 / 7, 3.0 / 7, 6.0 / 7};

static void
pair_pack(struct pack *p)
{
	double t = PAIR_T, L = ldexp(1, -10);
	double xa[3] = {2 * t, 3 * t, 6 * t}, xb[3] = {0, 0, 0};
	double xc[3] = {ldexp(1, -11), ldexp(1, -11), -L + ldexp(1, -13) - WALL_H};
	int a;

	pack_init(p);
	pack_add_grain(p, 0, xa, ldexp(1, -13), 7e10, 0.2, 2420);
	pack_add_grain(p, 1, xb, 3 * ldexp(1, -15), 1e11, 0.15, 2650);
	pack_add_grain(p, 2, xc, ldexp(1, -13), 7e10, 0.25, 2420);
	for (a = 0; a < 3; a++) {
		p->box[a] = -L;
		p->box[3 + a] = L;
	}
	p->wall_E = 7e11;
	p->wall_nu = 0.3;
	p->mu = 0.3;
	p->wall_mu = 0.4;
}

/* A unit tangent of the pair, t0 . n0 = 0, and b0 = n0 x t0. */
static void
pair_frame(double t0[3], double b0[3])
{
	double s = sqrt(13.0);

	t0[0] = 3 / s;
	t0[1] = -2 / s;
	t0[2] = 0;
	vec3_cross(n0, t0, b0);
}

/* Grain 0 on the circle of radius 7 t about grain 1 in the plane (n0, t0), at angle th. */
static void
orbit(double *x0, double th, const double t0[3])
{
	double d = 7 * PAIR_T;
	int a;

	for (a = 0; a < 3; a++)
		x0[a] = d * (cos(th) * n0[a] + sin(th) * t0[a]);
}

/* ---------- test 1: Fig. 2 ---------- */

/* Fig. 2 as physics.md §4-5 has it: from the branch's start (Sb, Fb) the force falls with
 * slope k as the displacement grows (it opposes the motion), clamped to [-lim, lim]. */
static double
loop_model(double S, double Sb, double Fb, double k, double lim)
{
	double F = Fb - k * (S - Sb);

	return F > lim ? lim : (F < -lim ? -lim : F);
}

#define NLOAD 25	/* steps of lim / (10 k): loading to 2.5 lim / k */
#define NSTEP (NLOAD + 4 * NLOAD)

struct loop_rec {
	const char *name;
	double k, lim;		/* closed forms */
	double S[NSTEP + 1], F[NSTEP + 1];
	double off;		/* largest force component off the line of motion / lim */
};

/* The checks of one contact's loop.  Tolerances:
 *  - against the model, 1e-10 of the limit: per increment the force moves by k* times the
 *    rounding of the coordinates (ulp 3e-20 m for the orbit, 1e-19 m on the wall; k* u ~ 1e-14
 *    N against limits of 3e-2 N) and the frozen k*, Q_max are off by the rounding of h
 *    (ulp(d) / h = 7e-14); 125 increments accumulate at most a few 1e-12.  A factor-2 error
 *    in k* or a sign error is off by O(1);
 *  - slopes (k* from zero, k* after the reversal), 1e-10 relative, the same rounding over a
 *    force change of about the limit;
 *  - plateau, 1e-12 of the limit: the limit is recomputed from the (rounded) overlap at each
 *    increment, 1.5 ulp(d) / h = 1e-13;
 *  - the loop closes: after unloading and reloading the same distance the state is the one
 *    at the first reversal (the orbit returns to the same angle, the wall grain to the same
 *    point: identical positions), 1e-10 of the limit;
 *  - dissipation per cycle -oint F dS (trapezoids; the kinks fall on the steps, so exact but
 *    for rounding) against the parallelogram 4 lim (S1 - lim / k*), 1e-9. */
static void
loop_check(const struct loop_rec *L, const char *tag)
{
	double Sb = 0, Fb = 0, worst = 0, plat = 0, slope_l, slope_u, area = 0, area_ex, S1 = L->S[NLOAD];
	int k, last_stick = 0, last_stick_u = 0, nplat = 0;

	for (k = 1; k <= NSTEP; k++) {
		double m;
		if (k == NLOAD + 1 || k == 3 * NLOAD + 1) {	/* reversal: the branch starts at the model's point */
			Fb = loop_model(L->S[k - 1], Sb, Fb, L->k, L->lim);
			Sb = L->S[k - 1];
		}
		m = loop_model(L->S[k], Sb, Fb, L->k, L->lim);
		worst = fmax(worst, fabs(L->F[k] - m) / L->lim);
		if (fabs(m) >= L->lim) {
			plat = fmax(plat, fabs(fabs(L->F[k]) - L->lim) / L->lim);
			nplat++;
		}
		if (k <= NLOAD && fabs(m) < L->lim)
			last_stick = k;
		if (k > NLOAD && k <= 3 * NLOAD && fabs(m) < L->lim)
			last_stick_u = k;
		if (k > NLOAD)
			area -= 0.5 * (L->F[k] + L->F[k - 1]) * (L->S[k] - L->S[k - 1]);
	}
	slope_l = -(L->F[last_stick] - L->F[0]) / (L->S[last_stick] - L->S[0]);
	slope_u = -(L->F[last_stick_u] - L->F[NLOAD]) / (L->S[last_stick_u] - L->S[NLOAD]);
	area_ex = 4 * L->lim * (S1 - L->lim / L->k);
	CHECK(last_stick >= 8 && last_stick_u >= NLOAD + 18 && nplat >= 50,
	    "%s %s: the loop has stick stretches (%d and %d increments) and plateaus (%d increments)", tag, L->name,
	    last_stick, last_stick_u - NLOAD, nplat);
	CHECK(worst <= 1e-10, "%s %s: force = Fig. 2 model (slope k, plateau at +-limit) at all %d increments (worst %.3g of the limit)",
	    tag, L->name, NSTEP, worst);
	check_rel(slope_l, L->k, 1e-10, "%s %s: loading slope from zero = k (physics.md)", tag, L->name);
	check_rel(slope_u, L->k, 1e-10, "%s %s: unloading slope after the reversal = k", tag, L->name);
	CHECK(plat <= 1e-12, "%s %s: plateau at mu P (M_max): worst | |F| - limit | = %.3g of the limit", tag, L->name, plat);
	CHECK(fabs(L->S[NSTEP] - S1) <= 1e-12 * S1 && fabs(L->F[NSTEP] - L->F[NLOAD]) <= 1e-10 * L->lim,
	    "%s %s: the loop closes (S %.17g vs %.17g, F %.17g vs %.17g)", tag, L->name, L->S[NSTEP], S1, L->F[NSTEP],
	    L->F[NLOAD]);
	check_rel(area, area_ex, 1e-9, "%s %s: dissipation per cycle = 4 limit (S1 - limit/k), the parallelogram", tag, L->name);
	CHECK(L->off <= 1e-12, "%s %s: the force stays on the line of motion (off %.3g of the limit)", tag, L->name, L->off);
}

static void
test_loop(enum fr_rule rule, int twist)
{
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	struct ref_contact rp, rw;
	struct loop_rec Lp, Lw;
	double x[18], g[18], t0[3], b0[3], ew[3] = {0.6, 0.8, 0}, nw[3] = {0, 0, 1}, x2[3], dsp, dsw, dth;
	double R0, R1, R2, d = 7 * PAIR_T;
	char tag[64];
	int k, kpos = 0, a, ok = 1;

	snprintf(tag, sizeof tag, "loop %s %s", twist ? "torsion" : "shear", fr_rule_name(rule));
	pair_pack(&p);
	R0 = p.r[0];
	R1 = p.r[1];
	R2 = p.r[2];
	memcpy(x2, p.x + 6, sizeof x2);
	pair_frame(t0, b0);
	ref_of(&p, 0, 1, PAIR_H, &rp);
	ref_of(&p, 2, PACK_WALL(WALL_ZLO), WALL_H, &rw);
	memset(&Lp, 0, sizeof Lp);
	memset(&Lw, 0, sizeof Lw);
	Lp.name = "grain-grain";
	Lw.name = "grain-wall";
	Lp.k = twist ? rp.kt : rp.k;
	Lp.lim = twist ? rp.mmax : rp.qmax;
	Lw.k = twist ? rw.kt : rw.k;
	Lw.lim = twist ? rw.mmax : rw.qmax;
	dsp = Lp.lim / Lp.k / 10;
	dsw = Lw.lim / Lw.k / 10;
	dth = asin(dsp / d);
	CHECK(contacts_store(&p, 0) == 0 && qs_init(&s, &p, 0.3) == 0, "%s: set up", tag);
	fr_init(&f, rule);
	for (k = 1; k <= NSTEP && ok; k++) {
		int dir = k <= NLOAD ? 1 : (k <= 3 * NLOAD ? -1 : 1);
		double xold0[3], nref[3], tref[3], du[3], us[3], dn, th_old = kpos * dth, xold2[3];
		long cp, cw;

		if (begin(&f, &s, x, tag) || f.n != 2) {
			ok = 0;
			break;
		}
		cp = find_contact(&f, 0, 1);
		cw = find_contact(&f, 2, PACK_WALL(WALL_ZLO));
		if (cp < 0 || cw < 0) {
			ok = 0;
			break;
		}
		memcpy(xold0, x, sizeof xold0);
		memcpy(xold2, x + 6, sizeof xold2);
		kpos += dir;
		if (!twist) {
			/* the reference normal and tangent of the orbit at the start of the increment */
			double nn = vec3_norm(xold0);
			for (a = 0; a < 3; a++) {
				nref[a] = xold0[a] / nn;
				tref[a] = -sin(th_old) * n0[a] + cos(th_old) * t0[a];
			}
			orbit(x, kpos * dth, t0);
			for (a = 0; a < 3; a++)
				x[6 + a] = x2[a] + kpos * dsw * ew[a];
		} else {
			/* grains 0 and 1 turn by +-dOmega/2 about the normal, grain 2 by dOmega about n_w */
			double dO = dir * dsp, dOw = dir * dsw;
			for (a = 0; a < 3; a++) {
				x[9 + a] = R0 * 0.5 * dO * n0[a];
				x[12 + a] = -R1 * 0.5 * dO * n0[a];
				x[15 + a] = R2 * dOw * nw[a];
			}
		}
		eval(&s, x, g, tag);
		if (!twist) {
			const double *Q = f.c[cp].Q, *Qw = f.c[cw].Q;
			double off[3];
			for (a = 0; a < 3; a++)
				du[a] = x[a] - xold0[a];
			dn = vec3_dot(du, nref);
			for (a = 0; a < 3; a++)
				us[a] = du[a] - dn * nref[a];
			Lp.S[k] = Lp.S[k - 1] + vec3_dot(us, tref);
			Lp.F[k] = vec3_dot(Q, tref);
			for (a = 0; a < 3; a++)
				off[a] = Q[a] - Lp.F[k] * tref[a];
			Lp.off = fmax(Lp.off, vec3_norm(off) / Lp.lim);
			for (a = 0; a < 3; a++)
				du[a] = x[6 + a] - xold2[a];
			Lw.S[k] = Lw.S[k - 1] + vec3_dot(du, ew);
			Lw.F[k] = vec3_dot(Qw, ew);
			for (a = 0; a < 3; a++)
				off[a] = Qw[a] - Lw.F[k] * ew[a];
			Lw.off = fmax(Lw.off, vec3_norm(off) / Lw.lim);
			/* torsion stays zero */
			Lp.off = fmax(Lp.off, fabs(f.c[cp].M) / rp.mmax);
			Lw.off = fmax(Lw.off, fabs(f.c[cw].M) / rw.mmax);
		} else {
			Lp.S[k] = Lp.S[k - 1] + dir * dsp;
			Lp.F[k] = f.c[cp].M;
			Lw.S[k] = Lw.S[k - 1] + dir * dsw;
			Lw.F[k] = f.c[cw].M;
			/* the tangential force stays zero (Omega parallel to n and to the lever arm) */
			Lp.off = fmax(Lp.off, vec3_norm(f.c[cp].Q) / rp.qmax);
			Lw.off = fmax(Lw.off, vec3_norm(f.c[cw].Q) / rw.qmax);
		}
		if (k == 1) {
			/* the frozen quantities of the first increment against the closed forms: the geometry is exact */
			const struct fr_contact *c = &f.c[cp], *cwl = &f.c[cw];
			CHECK(fabs(c->k / rp.k - 1) <= 1e-13 && fabs(c->qmax / rp.qmax - 1) <= 1e-13 &&
			          fabs(c->kt / rp.kt - 1) <= 1e-13 && fabs(c->mmax / rp.mmax - 1) <= 1e-13,
			    "%s: grain-grain k* %.6g N/m, Q_max %.6g N, k*_t %.6g N m, M_max %.6g N m as physics.md (1e-13)", tag, c->k,
			    c->qmax, c->kt, c->mmax);
			CHECK(fabs(cwl->k / rw.k - 1) <= 1e-13 && fabs(cwl->qmax / rw.qmax - 1) <= 1e-13 &&
			          fabs(cwl->kt / rw.kt - 1) <= 1e-13 && fabs(cwl->mmax / rw.mmax - 1) <= 1e-13,
			    "%s: grain-wall k* %.6g N/m, Q_max = wall_mu P %.6g N, k*_t, M_max as physics.md (1e-13)", tag, cwl->k,
			    cwl->qmax);
		}
		if (commit(&f, &s, x, tag)) {
			ok = 0;
			break;
		}
	}
	CHECK(ok, "%s: %d increments begun, evaluated and committed", tag, NSTEP);
	if (ok) {
		loop_check(&Lp, tag);
		loop_check(&Lw, tag);
	}
	fr_free(&f);
	qs_free(&s);
	pack_free(&p);
}

/* ---------- test 5: two-grain shear ---------- */

/* u_s of grain 0 against the fixed grain 1: T (x - xs) with the reference normal n. */
static void
tangential(const double *x, const double *xs, const double n[3], double us[3])
{
	double du[3], dn;
	int a;

	for (a = 0; a < 3; a++)
		du[a] = x[a] - xs[a];
	dn = vec3_dot(du, n);
	for (a = 0; a < 3; a++)
		us[a] = du[a] - dn * n[a];
}

/* Grain 0 pushed along the tangent t0 by alpha Q_max / k* in one increment from Q0 = 0:
 * |Q| = min(alpha, 1) mu P, against the force opposing the motion; fr_sliding counts the
 * contact only beyond the limit; at alpha = 3 the gradient's translation and rotation blocks
 * of both grains are checked against -Q, the Hertz force and the lever arms.  Tolerances:
 * 1e-12..1e-13 against the closed forms (exact geometry; the rounding of the force law and
 * of the moved coordinates); 16 eps against the engine's own Q_max.  Then a second increment
 * from the slid state, pushed across the reference force, where the two rules differ. */
static void
test_shear(enum fr_rule rule)
{
	static const double alpha[] = {0.5, 0.999999, 1.000001, 3};
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	struct ref_contact rp;
	double x[18], g[18], t0[3], b0[3], xs[18];
	char tag[64];
	size_t m;
	int a;

	snprintf(tag, sizeof tag, "shear %s", fr_rule_name(rule));
	pair_pack(&p);
	pair_frame(t0, b0);
	ref_of(&p, 0, 1, PAIR_H, &rp);
	CHECK(qs_init(&s, &p, 0.3) == 0, "%s: qs_init", tag);
	fr_init(&f, rule);
	CHECK(begin(&f, &s, x, tag) == 0, "%s: fr_begin", tag);
	memcpy(xs, x, sizeof xs);
	for (m = 0; m < sizeof alpha / sizeof alpha[0]; m++) {
		long cp = find_contact(&f, 0, 1);
		const struct fr_contact *c = &f.c[cp < 0 ? 0 : cp];
		double u = alpha[m] * rp.qmax / rp.k, Qt, qn, expect = fmin(alpha[m], 1) * rp.qmax;
		size_t nsl;

		memcpy(x, xs, sizeof x);
		for (a = 0; a < 3; a++)
			x[a] += u * t0[a];
		eval(&s, x, g, tag);
		nsl = fr_sliding(&f);
		qn = vec3_norm(c->Q);
		Qt = vec3_dot(c->Q, t0);
		CHECK(cp >= 0 && fabs(qn - expect) <= 1e-12 * rp.qmax && fabs(Qt + qn) <= 1e-13 * rp.qmax,
		    "%s: push %.6g Q_max/k*: Q = -%.17g t0 (expected %.17g, mu P %.17g)", tag, alpha[m], qn, expect, rp.qmax);
		CHECK(nsl == (alpha[m] > 1), "%s: push %.6g Q_max/k*: fr_sliding = %zu", tag, alpha[m], nsl);
		if (alpha[m] > 2) {
			/* the gradient: grain 0 feels -Q and the Hertz force P n along the current normal,
			 * grain 1 the opposite; the couples are -(R_01 x Q) / R0 and +(R_10 x Q) / R1 with the
			 * lever arms of physics.md §3 at the reference (exact geometry); grain 2 (on the
			 * wall, at rest) has no couple.  1e-12 of P: the rounding of the current h. */
			double d = 7 * PAIR_T, R0 = p.r[0], R1 = p.r[1], dc = vec3_norm(x), Pc, l0, l1, A2, m0[3], m1[3], li[3], lj[3];
			double dev = 0, devr = 0;
			Pc = hertz_force(hertz_Estar(p.E[0], p.nu[0], p.E[1], p.nu[1]), hertz_Rstar(R0, R1), R0 + R1 - dc);
			A2 = (d - R0 + R1) * (d + R0 - R1) * (R0 + R1 - d) * (R0 + R1 + d) / (4 * d * d);
			l0 = sqrt(R0 * R0 - A2);
			l1 = sqrt(R1 * R1 - A2);
			CHECK(fabs(qn - c->qmax) <= BOUND_TOL * c->qmax, "%s: sliding at |Q| = Q_max to round-off (%.3g)", tag,
			    qn / c->qmax - 1);
			check_rel(qn, p.mu * rp.P, 1e-13, "%s: sliding |Q| = mu P (Hertz P of the exact overlap)", tag);
			for (a = 0; a < 3; a++) {
				dev = fmax(dev, fabs(g[a] - (-c->Q[a] - Pc * x[a] / dc)));
				dev = fmax(dev, fabs(g[3 + a] - (c->Q[a] + Pc * x[a] / dc)));
				li[a] = -n0[a] * l0;
				lj[a] = n0[a] * l1;
			}
			vec3_cross(li, c->Q, m0);
			vec3_cross(lj, c->Q, m1);
			for (a = 0; a < 3; a++) {
				devr = fmax(devr, fabs(g[9 + a] + m0[a] / R0));
				devr = fmax(devr, fabs(g[12 + a] - m1[a] / R1));
			}
			CHECK(dev <= 1e-12 * Pc, "%s: dPi/du_0 = -Q - P n, dPi/du_1 = Q + P n (deviation %.3g of P)", tag, dev / Pc);
			CHECK(devr <= 1e-12 * rp.qmax && vec3_dot(g + 9, b0) * vec3_dot(g + 12, b0) > 0,
			    "%s: dPi/d(R0 Omega0) = -(R_01 x Q)/R0, dPi/d(R1 Omega1) = (R_10 x Q)/R1: both grains roll the same way "
			    "(deviation %.3g of mu P)", tag, devr / rp.qmax);
			CHECK(vec3_norm(g + 15) == 0, "%s: grain 2 feels no couple", tag);
		}
	}
	/* A second increment from the sliding state.  The first one moved grain 0 by 3 Q_max/k*
	 * along the tangent: the centre distance grew by (3 Q_max/k*)^2 / 2d, the normal force fell,
	 * and the committed |Q0| = mu P_old is above the new limit mu P: fr_begin clamps it, with
	 * excess P_old / P - 1 (1e-8: the rounding of the small change of h, 2e-10 m, is 1e-10 of it). */
	{
		double dc = vec3_norm(x), R0 = p.r[0], R1 = p.r[1];
		double Pn = hertz_force(hertz_Estar(p.E[0], p.nu[0], p.E[1], p.nu[1]), hertz_Rstar(R0, R1), R0 + R1 - dc);
		int rb = commit(&f, &s, x, tag) || begin(&f, &s, x, tag);
		CHECK(rb == 0 && f.clamped == 1, "%s: commit the slid state and begin: 1 line clamped (%zu)", tag, f.clamped);
		check_rel(f.clamp_excess, rp.P / Pn - 1, 1e-8, "%s: clamp excess = P_old / P_new - 1", tag);
	}
	memcpy(xs, x, sizeof xs);
	{
		long cp = find_contact(&f, 0, 1);
		const struct fr_contact *c = &f.c[cp < 0 ? 0 : cp];
		double qp[3], us[3], q[3], dq[3], cr[3], e[3], qn, qq, lim = c->qmax, dev = 0, kr;

		memcpy(qp, c->qp, sizeof qp);
		CHECK(cp >= 0 && fabs(vec3_norm(qp) - lim) <= BOUND_TOL * lim && vec3_dot(qp, t0) < -0.999 * lim,
		    "%s: the new increment starts at the limit, Q^p along -t0", tag);
		/* (i) pushed sideways (along b0, normal to Q^p) by 0.7 Q_max/k*: the return map turns the
		 * force towards the trial force; the paper rule cannot (|Q^p - k u_s| > Q_max for every
		 * k > 0 when u_s is normal to Q^p and |Q^p| = Q_max): k = 0, Q = Q^p, to the square root
		 * of the rounding of Q_max^2 - |Q^p|^2 (1e-7) */
		for (a = 0; a < 3; a++)
			x[a] = xs[a] + 0.7 * rp.qmax / rp.k * b0[a];
		tangential(x, xs, c->n, us);
		eval(&s, x, g, tag);
		qn = vec3_norm(c->Q);
		for (a = 0; a < 3; a++)
			q[a] = qp[a] - c->k * us[a];
		qq = vec3_norm(q);
		for (a = 0; a < 3; a++)
			dev = fmax(dev, fabs(c->Q[a] - (rule == FR_RETURN_MAP ? lim * q[a] / qq : qp[a])));
		CHECK(fabs(qn - lim) <= BOUND_TOL * lim && dev <= (rule == FR_RETURN_MAP ? 1e-12 : 1e-7) * lim,
		    "%s: sideways push at the limit: |Q| = Q_max, Q = %s (deviation %.3g of Q_max)", tag,
		    rule == FR_RETURN_MAP ? "Q_max q / |q|" : "Q^p (k = 0)", dev / lim);
		/* (ii) pushed by 3 Q_max/k* along e = 0.8 b0 - 0.6 t0 (partly against the motion that
		 * built Q^p): both rules slide at |Q| = Q_max; the return map along q, the paper rule
		 * along Q^p - k u_s, k = 2 (Q^p . e) / |u_s| = 0.4 k* to first order in the 1e-3 rad turn
		 * of the normal */
		for (a = 0; a < 3; a++) {
			e[a] = 0.8 * b0[a] - 0.6 * t0[a];
			x[a] = xs[a] + 3 * rp.qmax / rp.k * e[a];
		}
		tangential(x, xs, c->n, us);
		eval(&s, x, g, tag);
		qn = vec3_norm(c->Q);
		CHECK(fabs(qn - lim) <= BOUND_TOL * lim, "%s: push at 3 Q_max/k*: |Q| = Q_max (%.3g)", tag, qn / lim - 1);
		for (a = 0; a < 3; a++) {
			q[a] = qp[a] - c->k * us[a];
			dq[a] = c->Q[a] - qp[a];
		}
		qq = vec3_norm(q);
		dev = 0;
		if (rule == FR_RETURN_MAP) {
			for (a = 0; a < 3; a++)
				dev = fmax(dev, fabs(c->Q[a] - lim * q[a] / qq));
			CHECK(dev <= 1e-12 * lim, "%s: Q = Q_max q / |q| (deviation %.3g of Q_max)", tag, dev / lim);
		} else {
			kr = -vec3_dot(dq, us) / vec3_dot(us, us);
			vec3_cross(dq, us, cr);
			CHECK(vec3_norm(cr) <= 1e-12 * vec3_norm(dq) * vec3_norm(us) && fabs(kr / c->k - 0.4) <= 1e-3,
			    "%s: Q = Q^p - k u_s with k = %.6g k* (F (6)-(7b); 0.4 expected)", tag, kr / c->k);
			for (a = 0; a < 3; a++)
				dev = fmax(dev, fabs(c->Q[a] - lim * q[a] / qq));
			CHECK(dev > 0.1 * lim, "%s: ... a direction other than the return map's (differs by %.3g Q_max)", tag, dev / lim);
		}
	}
	fr_free(&f);
	qs_free(&s);
	pack_free(&p);
}

/* ---------- test 5b: the sliding count of an increment ---------- */

/* fr_commit counts a contact as sliding when its elastic trial force |Q^p - k* u_s| reaches
 * the limit mu P_end of its normal force at the end of the increment.  Grain 0 is pushed
 * along the tangent by 1.2 Q_max/k* from Q0 = 0 (trial 1.2 Q_max, beyond the frozen limit:
 * fr_sliding counts it) and towards grain 1 by the overlap that raises P to ratio x P: with
 * ratio 1.3 the end limit 1.3 Q_max is above the trial (it sticks under the limit it has
 * then, no trial slip), with 1.1 below (a trial slip), with 0.9 (the normal force fell) too.
 * The committed force, clamped to the frozen Q_max, is at the new limit mu P_end only at 0.9
 * (the paper's count, nlimit).  The expected count comes from the closed
 * forms (trial k* u, Hertz P of the final centre distance); 1.1, 1.2 and 1.3 are far apart
 * against the second-order change of the distance by the tangential push (u^2 / 2d: about
 * 1e-4 of P). */
static void
test_slide_count(void)
{
	static const double ratio[] = {1.3, 1.1, 0.9};
	size_t m;

	for (m = 0; m < sizeof ratio / sizeof ratio[0]; m++) {
		struct pack p;
		struct qs_system s;
		struct qs_friction f;
		struct ref_contact rp;
		double x[18], g[18], t0[3], b0[3], dh, u, dc, Pend, trial;
		int a, rc;

		pair_pack(&p);
		pair_frame(t0, b0);
		ref_of(&p, 0, 1, PAIR_H, &rp);
		CHECK(qs_init(&s, &p, 0.3) == 0, "slide count: qs_init");
		fr_init(&f, FR_RETURN_MAP);
		CHECK(begin(&f, &s, x, "slide count") == 0, "slide count: fr_begin");
		u = 1.2 * rp.qmax / rp.k;
		dh = PAIR_H * (pow(ratio[m], 2.0 / 3.0) - 1);
		for (a = 0; a < 3; a++)
			x[a] += u * t0[a] - dh * n0[a];
		eval(&s, x, g, "slide count");
		CHECK(fr_sliding(&f) == 1, "slide count %.1f: at the frozen limit (fr_sliding %zu)", ratio[m], fr_sliding(&f));
		dc = vec3_norm(x);	/* grain 1 sits at the origin */
		Pend = hertz_force(hertz_Estar(p.E[0], p.nu[0], p.E[1], p.nu[1]), hertz_Rstar(p.r[0], p.r[1]), p.r[0] + p.r[1] - dc);
		trial = rp.k * u;
		/* the tangential push lengthens the centre distance by u^2 / 2d, 1e-4 of P here */
		check_rel(Pend / rp.P, ratio[m], 1e-3, "slide count %.1f: P_end / P of the pushed overlap", ratio[m]);
		rc = commit(&f, &s, x, "slide count");
		CHECK(rc == 0 && f.ntrial_slip == (size_t)(trial >= p.mu * Pend),
		    "slide count %.1f: trial %.6g mu P, end limit %.6g mu P: fr_commit counts %zu trial slips (expected %d)", ratio[m],
		    trial / (p.mu * rp.P), Pend / rp.P, f.ntrial_slip, trial >= p.mu * Pend);
		/* the committed force is the return map's, clamped to the frozen limit mu P (the
		 * trial is 1.2 of it): at the limit of the new normal force only when P fell */
		CHECK(rc == 0 && f.nlimit == (size_t)(fmin(trial, rp.qmax) >= p.mu * Pend * (1 - 1e-9)),
		    "slide count %.1f: |Q0| %.6g mu P against the new limit %.6g mu P: fr_commit counts %zu at the limit (expected %d)",
		    ratio[m], fmin(trial, rp.qmax) / (p.mu * rp.P), Pend / rp.P, f.nlimit,
		    fmin(trial, rp.qmax) >= p.mu * Pend * (1 - 1e-9));
		fr_free(&f);
		qs_free(&s);
		pack_free(&p);
	}
}

/* ---------- test 6: history ---------- */

static void
test_history(void)
{
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	struct ref_contact rp, rw;
	double x[18], t0[3], b0[3], th, Q[3], M, d = 7 * PAIR_T;
	long cp;
	int a;

	pair_pack(&p);
	pair_frame(t0, b0);
	ref_of(&p, 0, 1, PAIR_H, &rp);
	ref_of(&p, 2, PACK_WALL(WALL_ZLO), WALL_H, &rw);
	CHECK(qs_init(&s, &p, 0.3) == 0, "history: qs_init");
	fr_init(&f, FR_RETURN_MAP);

	/* (a) commit, then begin: grain 0 orbits by th (tangential 0.3 Q_max/k* along t0) and moves
	 * 0.4 Q_max/k* along b0, and turns by 0.5 M_max/k*_t about n0: stick, Q = -k* u_s. */
	CHECK(begin(&f, &s, x, "history") == 0 && f.n == 2 && f.stale == 0 && f.clamped == 0,
	    "history: begin without history lines: 2 contacts, nothing stale or clamped");
	th = asin(0.3 * rp.qmax / rp.k / d);
	orbit(x, th, t0);
	for (a = 0; a < 3; a++) {
		x[a] += 0.4 * rp.qmax / rp.k * b0[a];
		x[9 + a] = p.r[0] * 0.5 * rp.mmax / rp.kt * n0[a];
	}
	eval(&s, x, NULL, "history");
	cp = find_contact(&f, 0, 1);
	memcpy(Q, f.c[cp].Q, sizeof Q);
	M = f.c[cp].M;
	/* T du = d sin(th) t0 + 0.4 Q_max/k* b0 exactly (the orbit's normal part is cut by T), |u_s| =
	 * 0.5 Q_max/k*: 1e-12, the rounding of the coordinates against u_s */
	check_rel(vec3_norm(Q), 0.5 * rp.qmax, 1e-12, "history: stick force |Q| = k* |u_s|");
	check_rel(M, -0.5 * rp.mmax, 1e-13, "history: stick couple M = -k*_t Omega_t");
	CHECK(commit(&f, &s, x, "history") == 0, "history: commit");
	{
		const struct pack_contact *l = find_line(&p, 0, 1);
		double dd = vec3_norm(p.x), Pnow = hertz_force(hertz_Estar(p.E[0], p.nu[0], p.E[1], p.nu[1]),
		    hertz_Rstar(p.r[0], p.r[1]), p.r[0] + p.r[1] - dd);
		CHECK(p.nc == 2 && l && l->Q0[0] == Q[0] && l->Q0[1] == Q[1] && l->Q0[2] == Q[2] && l->M0 == M,
		    "history: the committed line carries the increment's Q and M exactly");
		CHECK(l && fabs(l->P0 / Pnow - 1) <= 1e-12, "history: P0 = Hertz force at the committed positions");
		CHECK(vec3_norm(x + 9) == 0, "history: fr_commit zeroes the rotations");
	}
	/* begin again: the normal has turned by th; Q^p = |Q0| T Q0 / |T Q0| */
	{
		double nn[3], tq[3], qn, dev = 0;
		CHECK(begin(&f, &s, x, "history") == 0 && f.stale == 0 && f.clamped == 0, "history: begin from the commit");
		cp = find_contact(&f, 0, 1);
		qn = vec3_norm(p.x);
		for (a = 0; a < 3; a++)
			nn[a] = p.x[a] / qn;
		for (a = 0; a < 3; a++)
			tq[a] = Q[a] - vec3_dot(Q, nn) * nn[a];
		qn = vec3_norm(tq);
		for (a = 0; a < 3; a++)
			dev = fmax(dev, fabs(f.c[cp].qp[a] - tq[a] * vec3_norm(Q) / qn));
		CHECK(cp >= 0 && dev <= 4 * EPS * vec3_norm(Q), "history: Q^p = |Q0| T Q0 / |T Q0| after the commit (%.3g of |Q0|)",
		    dev / vec3_norm(Q));
		CHECK(f.c[cp].mp == M, "history: M^p = M0");
	}
	/* the normal turned by 0.3 rad since the line was written (grain 0 moved round grain 1) */
	{
		double nn[3], tq[3], qn, dev, Q0n = vec3_norm(Q);
		orbit(p.x, th + 0.3, t0);
		CHECK(begin(&f, &s, x, "history") == 0, "history: begin with the normal turned by 0.3 rad");
		cp = find_contact(&f, 0, 1);
		for (a = 0; a < 3; a++)
			nn[a] = f.c[cp].n[a];
		for (a = 0; a < 3; a++)
			tq[a] = Q[a] - vec3_dot(Q, nn) * nn[a];
		qn = vec3_norm(tq);
		dev = fabs(vec3_norm(f.c[cp].qp) / Q0n - 1);
		CHECK(qn < 0.99 * Q0n && dev <= 4 * EPS && fabs(vec3_dot(f.c[cp].qp, nn)) <= 4 * EPS * Q0n &&
		          vec3_dot(f.c[cp].qp, tq) > (1 - 1e-14) * qn * Q0n,
		    "history: Q^p in the new tangent plane, along T Q0, magnitude |Q0| kept (|T Q0| = %.4f |Q0|, |Q^p| off %.3g)",
		    qn / Q0n, dev);
		orbit(p.x, th, t0);	/* back */
	}

	/* (b) stale lines: grains 1 and 2 do not touch, nor grain 0 and the xhi wall */
	{
		struct pack_contact l1 = {1, 2, 0.01, {1e-3, 0, 0}, 0}, l2 = {0, PACK_WALL(WALL_XHI), 0.01, {0, 1e-3, 0}, 0};
		int rb;

		pack_add_contact(&p, &l1);
		pack_add_contact(&p, &l2);
		rb = begin(&f, &s, x, "history");
		CHECK(rb == 0 && f.stale == 2 && f.n == 2,
		    "history: 2 lines for pairs not touching: f->stale = %zu, %zu contacts", f.stale, f.n);
		eval(&s, x, NULL, "history");
		rb = commit(&f, &s, x, "history");
		CHECK(rb == 0 && p.nc == 2 && !find_line(&p, 1, 2) && !find_line(&p, 0, PACK_WALL(WALL_XHI)),
		    "history: the stale lines are dropped at the commit (%zu lines)", p.nc);
	}
	/* (c) a contact that opens during the increment keeps its frozen spring until the commit,
	 * then loses its history */
	{
		CHECK(begin(&f, &s, x, "history") == 0 && f.n == 2, "history: begin");
		for (a = 0; a < 3; a++)
			x[a] += 2 * PAIR_H * f.c[find_contact(&f, 0, 1)].n[a];
		eval(&s, x, NULL, "history");
		CHECK(s.ncontacts == 1 && vec3_norm(f.c[find_contact(&f, 0, 1)].Q) > 0,
		    "history: an opened contact keeps its frozen tangential force within the increment");
		CHECK(commit(&f, &s, x, "history") == 0 && p.nc == 1 && !find_line(&p, 0, 1),
		    "history: the opened contact's line is dropped at the commit");
		CHECK(begin(&f, &s, x, "history") == 0 && f.n == 1 && f.stale == 0, "history: next increment has 1 contact");
	}
	fr_free(&f);
	qs_free(&s);
	pack_free(&p);

	/* (d) clamping at fr_begin: |Q0| = 1.5 Q_max and M0 = -1.25 M_max on the pair, |Q0| =
	 * (1 + 1e-12) Q_max on the wall (below the 1e-9 that counts) */
	{
		struct pack_contact *lp, *lw;
		const struct fr_contact *c, *cw;
		double dir[3], qn;
		int rb;

		pair_pack(&p);
		pair_frame(t0, b0);
		contacts_store(&p, 0);
		lp = find_line(&p, 0, 1);
		lw = find_line(&p, 2, PACK_WALL(WALL_ZLO));
		for (a = 0; a < 3; a++) {
			dir[a] = 0.6 * t0[a] + 0.8 * b0[a];
			lp->Q0[a] = 1.5 * rp.qmax * dir[a];
			lw->Q0[a] = (1 + 1e-12) * rw.qmax * (a == 0);
		}
		lp->M0 = -1.25 * rp.mmax;
		CHECK(qs_init(&s, &p, 0.3) == 0, "clamp: qs_init");
		fr_init(&f, FR_RETURN_MAP);
		rb = begin(&f, &s, x, "clamp");
		CHECK(rb == 0 && f.clamped == 1, "clamp: one line above its limit beyond 1e-9 is counted (f->clamped = %zu)",
		    f.clamped);
		check_rel(f.clamp_excess, 0.5, 1e-12, "clamp: largest excess |Q0| / Q_max - 1 = 0.5 (M0's is 0.25)");
		c = &f.c[find_contact(&f, 0, 1)];
		cw = &f.c[find_contact(&f, 2, PACK_WALL(WALL_ZLO))];
		qn = vec3_norm(c->qp);
		CHECK(fabs(qn / c->qmax - 1) <= BOUND_TOL && vec3_dot(c->qp, dir) >= (1 - 1e-15) * qn,
		    "clamp: Q^p clamped to Q_max in the direction of Q0 (%.3g)", qn / c->qmax - 1);
		CHECK(c->mp == -c->mmax, "clamp: M^p = -M_max exactly");
		CHECK(fabs(vec3_norm(cw->qp) / cw->qmax - 1) <= BOUND_TOL, "clamp: the wall line is clamped too");
		/* unloading from the clamped limit: grain 0 moved along +dir (the force on it was
		 * along +dir, so moving that way relaxes it) by 0.5 Q_max / k*: |Q| = 0.5 Q_max */
		for (a = 0; a < 3; a++)
			x[a] += 0.5 * c->qmax / c->k * dir[a];
		eval(&s, x, NULL, "clamp");
		check_rel(vec3_norm(c->Q), 0.5 * c->qmax, 1e-12, "clamp: unloading from the clamped limit with slope k*");
		fr_free(&f);
		qs_free(&s);
	}

	/* (e) fr_check_history: |Q0| up to mu (P0 + P_mean) (wall lines: wall_mu), |M0| up to
	 * M_max(P0) + M_max(P_mean) */
	{
		struct pack_contact *lp = find_line(&p, 0, 1), *lw = find_line(&p, 2, PACK_WALL(WALL_ZLO));
		double Pm = (lp->P0 + lw->P0) / 2, qa, ma, qb, mb, lim_p, lim_w, mlim_p;
		int rc;

		line_limits(&p, lp, lp->P0, &qa, &ma);
		line_limits(&p, lp, Pm, &qb, &mb);
		lim_p = qa + qb;
		mlim_p = ma + mb;
		line_limits(&p, lw, lw->P0, &qa, &ma);
		line_limits(&p, lw, Pm, &qb, &mb);
		lim_w = qa + qb;
		memset(lp->Q0, 0, sizeof lp->Q0);
		memset(lw->Q0, 0, sizeof lw->Q0);
		lp->M0 = 0;
		lp->Q0[0] = 0.99 * lim_p;
		lw->Q0[1] = 0.99 * lim_w;	/* with mu instead of wall_mu this is 1.32 times the limit */
		lw->M0 = 0;
		CHECK(fr_check_history(&contact_law_hertz_mindlin, &p) == 0, "check_history: lines at 0.99 of mu (P0 + P_mean) (wall_mu on the wall) pass");
		lp->Q0[0] = 1.01 * lim_p;
		rc = fr_check_history(&contact_law_hertz_mindlin, &p);
		CHECK(rc == -1, "check_history: |Q0| = 1.01 mu (P0 + P_mean) is refused (%s)", msg_geterr());
		lp->Q0[0] = 0.99 * lim_p;
		lw->Q0[1] = 1.01 * lim_w;
		CHECK(fr_check_history(&contact_law_hertz_mindlin, &p) == -1, "check_history: a wall line above wall_mu (P0 + P_mean) is refused");
		lw->Q0[1] = 0;
		lp->M0 = -0.99 * mlim_p;
		CHECK(fr_check_history(&contact_law_hertz_mindlin, &p) == 0, "check_history: |M0| = 0.99 (M_max(P0) + M_max(P_mean)) passes");
		lp->M0 = -1.01 * mlim_p;
		rc = fr_check_history(&contact_law_hertz_mindlin, &p);
		CHECK(rc == -1, "check_history: |M0| = 1.01 (M_max(P0) + M_max(P_mean)) is refused (%s)", msg_geterr());
	}
	pack_free(&p);

	/* (f) a pair listed as "1 0": Q0 is the force on grain 1 (the pack format allows either
	 * order), so the contact of grains 0 and 1, whose forces the engine keeps on grain 0, must
	 * start from -Q0; M0, a couple about the normal from j to i, is the same in both orders. */
	{
		struct pack_contact *l;
		const struct fr_contact *c;
		double Qv[3], dev = 0;

		pair_pack(&p);
		pair_frame(t0, b0);
		contacts_store(&p, 0);
		l = find_line(&p, 0, 1);
		l->i = 1;
		l->j = 0;
		for (a = 0; a < 3; a++)
			Qv[a] = l->Q0[a] = 0.5 * rp.qmax * t0[a];
		l->M0 = 0.25 * rp.mmax;
		CHECK(qs_init(&s, &p, 0.3) == 0, "order: qs_init");
		fr_init(&f, FR_RETURN_MAP);
		CHECK(begin(&f, &s, x, "order") == 0 && f.stale == 0, "order: the line \"1 0\" matches the contact of 0 and 1");
		c = &f.c[find_contact(&f, 0, 1)];
		for (a = 0; a < 3; a++)
			dev = fmax(dev, fabs(c->qp[a] + Qv[a]));
		CHECK(dev <= 1e-15 * rp.qmax,
		    "order: a line \"1 0\" gives the force -Q0 on grain 0 (Q^p = (%.6g, %.6g, %.6g), -Q0 = (%.6g, %.6g, %.6g))",
		    c->qp[0], c->qp[1], c->qp[2], -Qv[0], -Qv[1], -Qv[2]);
		CHECK(c->mp == 0.25 * rp.mmax, "order: M^p = M0 in either order");
		fr_free(&f);
		qs_free(&s);
		pack_free(&p);
	}
}

/* ---------- random packs with history ---------- */

/* Nominal solid fraction of the random packs: at 0.52 random_pack resolves the overlaps of
 * 20-50 grains to at most 2.4 % of R (at 0.62 a few remain at 10-30 %). */
#define PACK_PHI 0.52

/* Random history on every line of p: Q0 a random direction (fr_begin turns it into the
 * tangent plane) of magnitude mu P0 times U(qlo, qhi), M0 = M_max(P0) times U(-mhi, mhi). */
static void
random_history(struct pack *p, gsl_rng *rng, double qlo, double qhi, double mhi)
{
	size_t k;
	int a;

	for (k = 0; k < p->nc; k++) {
		struct pack_contact *c = &p->c[k];
		double v[3], qmax, mmax, vn, m = qlo + (qhi - qlo) * gsl_rng_uniform(rng);
		line_limits(p, c, c->P0, &qmax, &mmax);
		for (a = 0; a < 3; a++)
			v[a] = gsl_ran_gaussian(rng, 1.0);
		vn = vec3_norm(v);
		for (a = 0; a < 3; a++)
			c->Q0[a] = m * qmax * v[a] / vn;
		c->M0 = mhi * (2 * gsl_rng_uniform(rng) - 1) * mmax;
	}
}

/* Random increment: centres by scale U(-1, 1) per coordinate, R_i Omega_i likewise. */
static void
random_move(double *x, size_t n, gsl_rng *rng, double scale, double rscale)
{
	size_t k;

	for (k = 0; k < 3 * n; k++)
		x[k] += scale * (2 * gsl_rng_uniform(rng) - 1);
	for (k = 3 * n; k < 6 * n; k++)
		x[k] = rscale * (2 * gsl_rng_uniform(rng) - 1);
}

/* Mean of Q_max / k* over the contacts: the tangential displacement that reaches the limit. */
static double
slip_scale(const struct qs_friction *f)
{
	double s = 0;
	size_t k;

	for (k = 0; k < f->n; k++)
		s += f->c[k].qmax / f->c[k].k;
	return f->n ? s / f->n : 0;
}

/* The engine's u_s and Omega_t of contact c at x (its frozen n, lever arms, reference x0). */
static void
contact_kinematics(const struct qs_friction *f, const struct qs_system *s, const struct fr_contact *c, const double *x,
    double us[3], double *Ot)
{
	const double *w = x + 3 * s->n, *r = s->p->r;
	double du[3], Oi[3], Oj[3] = {0, 0, 0}, t[3], dn, li[3], lj[3];
	int a, wall = PACK_IS_WALL(c->j);
	size_t i = c->i, j = wall ? 0 : (size_t)c->j;

	for (a = 0; a < 3; a++) {
		du[a] = x[3 * i + a] - f->x0[3 * i + a];
		Oi[a] = w[3 * i + a] / r[i];
		if (!wall) {
			du[a] -= x[3 * j + a] - f->x0[3 * j + a];
			Oj[a] = w[3 * j + a] / r[j];
		}
	}
	/* the lever arms as vectors, R_ij = -li n and R_ji = lj n (friction.h) */
	for (a = 0; a < 3; a++) {
		li[a] = -c->n[a] * c->li;
		lj[a] = c->n[a] * c->lj;
	}
	dn = vec3_dot(du, c->n);
	vec3_cross(Oi, li, t);
	for (a = 0; a < 3; a++)
		us[a] = du[a] - dn * c->n[a] + t[a];
	vec3_cross(Oj, lj, t);
	for (a = 0; a < 3; a++)
		us[a] -= t[a];
	*Ot = vec3_dot(Oi, c->n) - vec3_dot(Oj, c->n);
}

/* The frozen quantities of every contact of f against physics.md §2-5 at the reference p->x:
 * normal, lever arms (|R_ij| = sqrt(R_i^2 - A^2), R_ij + R_ji spanning the centre distance),
 * k*, Q_max (mu or wall_mu), k*_t, M_max.  h is formed as the engine forms it (S - |x_i - x_j|),
 * so the cancellation in it is shared; what is left is the order of a few operations in the
 * closed forms, a few ulps: 1e-12 is far above that and far below any wrong factor or term. */
static void
check_frozen(const struct qs_friction *f, const struct pack *p, const char *tag)
{
	size_t k, bad = 0;
	double worst = 0;

	for (k = 0; k < f->n; k++) {
		const struct fr_contact *c = &f->c[k];
		struct ref_contact rc;
		double n[3], li[3], lj[3] = {0, 0, 0}, h, d, e = 0;
		size_t i = c->i;
		int a;

		if (PACK_IS_WALL(c->j)) {
			/* wall w = 2 axis + side: inward normal +-e_axis, plane at box[axis + 3 side] */
			int w = PACK_WALL_INDEX(c->j), ax = w / 2, hi = w % 2;
			n[0] = n[1] = n[2] = 0;
			n[ax] = hi ? -1 : 1;
			d = hi ? p->box[3 + ax] - p->x[3 * i + ax] : p->x[3 * i + ax] - p->box[ax];
			h = p->r[i] - d;
			for (a = 0; a < 3; a++)
				li[a] = -n[a] * d;
		} else {
			size_t j = (size_t)c->j;
			double Ri = p->r[i], Rj = p->r[j], A2;
			for (a = 0; a < 3; a++)
				n[a] = p->x[3 * i + a] - p->x[3 * j + a];
			d = vec3_norm(n);
			for (a = 0; a < 3; a++)
				n[a] /= d;
			h = Ri + Rj - d;
			A2 = (d - Ri + Rj) * (d + Ri - Rj) * (Ri + Rj - d) * (Ri + Rj + d) / (4 * d * d);
			for (a = 0; a < 3; a++) {
				li[a] = -n[a] * sqrt(Ri * Ri - A2);
				lj[a] = n[a] * sqrt(Rj * Rj - A2);
			}
			/* the lever arms reach the plane of the intersection circle from both sides */
			e = fmax(e, fabs(sqrt(Ri * Ri - A2) + sqrt(Rj * Rj - A2) - d) / d / 1e3);
		}
		ref_of(p, i, c->j, h, &rc);
		for (a = 0; a < 3; a++) {
			e = fmax(e, fabs(c->n[a] - n[a]));
			e = fmax(e, fabs(-c->n[a] * c->li - li[a]) / p->r[i]);
			e = fmax(e, fabs(c->n[a] * c->lj - lj[a]) / p->r[i]);
		}
		/* the kernel's lever arms and reciprocals over the radii */
		e = fmax(e, fabs(c->ai * p->r[i] - c->li) / p->r[i]);
		e = fmax(e, fabs(c->bi * p->r[i] - 1));
		if (!PACK_IS_WALL(c->j)) {
			e = fmax(e, fabs(c->aj * p->r[c->j] - c->lj) / p->r[c->j]);
			e = fmax(e, fabs(c->bj * p->r[c->j] - 1));
		} else {
			e = fmax(e, fabs(c->lj) + fabs(c->aj) + fabs(c->bj));
		}
		e = fmax(e, fabs(c->k / rc.k - 1));
		e = fmax(e, fabs(c->qmax / rc.qmax - 1));
		e = fmax(e, fabs(c->kt / rc.kt - 1));
		e = fmax(e, fabs(c->mmax / rc.mmax - 1));
		worst = fmax(worst, e);
		bad += !(e <= 1e-12);
	}
	CHECK(bad == 0 && f->n > 0, "%s: frozen n, R_ij, R_ji, k*, Q_max, k*_t, M_max of all %zu contacts as physics.md (worst %.3g)",
	    tag, f->n, worst);
}

/* ---------- test 3: the gradient against central differences ---------- */

static double worst_work = 0;	/* largest |Pi - work| / E_f, return map */

/* Pi is the potential of its gradient along a path, not only locally: from the start of the
 * increment (centres x0, rotations 0: every contact at Q^p) straight to x, through the slip
 * transitions of most contacts, Pi(x) - Pi(start) = integral of g . dtheta.  Composite Simpson
 * with 4096 intervals: g is continuous but its derivative jumps where a contact starts to slide
 * (and Hertz's has a square-root end where a contact forms), so the rule is second order there:
 * a kink contributes about |jump| (1/4096)^2, a few 1e-8 of the frictional energy scale
 * E_f = sum (Q_max^2 / 2k* + M_max^2 / 2k*_t); the tolerance is 1e-6 E_f.  A potential that is
 * off by a constant on the sliding branch (Q_max^2 / 2k* per sliding contact, about E_f / 2 in
 * all) or any energy that is not the antiderivative of the force fails by orders of magnitude. */
static void
work_check(struct qs_system *s, struct qs_friction *f, const double *x, const char *tag)
{
	size_t N = s->dim, k, n = s->n;
	long i, M = 4096;
	double *xa = malloc(N * sizeof *xa), *xt = malloc(N * sizeof *xt), *g = malloc(N * sizeof *g), Ef = 0, W = 0, dPi;

	memcpy(xa, f->x0, 3 * n * sizeof *xa);
	memset(xa + 3 * n, 0, 3 * n * sizeof *xa);
	for (k = 0; k < f->n; k++)
		Ef += f->c[k].qmax * f->c[k].qmax / (2 * f->c[k].k) + f->c[k].mmax * f->c[k].mmax / (2 * f->c[k].kt);
	dPi = eval(s, x, NULL, tag) - eval(s, xa, NULL, tag);
	for (i = 0; i <= M; i++) {
		double t = (double)i / M, wgt = (i == 0 || i == M) ? 1 : (i % 2 ? 4 : 2), dot = 0;
		for (k = 0; k < N; k++)
			xt[k] = xa[k] + t * (x[k] - xa[k]);
		eval(s, xt, g, tag);
		for (k = 0; k < N; k++)
			dot += g[k] * (x[k] - xa[k]);
		W += wgt * dot / (3.0 * M);
	}
	CHECK(fabs(dPi - W) <= 1e-6 * Ef, "%s: Pi(x) - Pi(start) = work of the gradient along the path (%.3g of E_f = %.3g J)",
	    tag, fabs(dPi - W) / Ef, Ef);
	if (f->rule == FR_RETURN_MAP)
		worst_work = fmax(worst_work, fabs(dPi - W) / Ef);
	free(xa);
	free(xt);
	free(g);
}

static double worst_fd_rel = 0;	/* largest |g - fd| over the mean contact force, all packs */

/* Central differences of Pi over all 6N unknowns at a point where a good share of the
 * contacts slide.  Step hs = 1e-6 of the mean radius (1e-10 m; the tangential displacements
 * are of order Q_max / k* ~ 1e-8..1e-7 m).  Error of the difference quotient:
 *  - truncation hs^2/6 |Pi'''|: the Hertz bound of test_functional (0.75 P/h^2 + 4.5 P/(h d) +
 *    3 P/d^2 per contact of the grain, translations only); the stick spring and the torsion are
 *    piecewise quadratic (no truncation); a sliding contact adds (Q_max / k*) d^3|q|/dxi^3 <=
 *    3 Q_max k*^2 / |q|^2 (|d u_s / d xi| <= 1 for a centre and for R_i Omega_i alike);
 *  - rounding: each Pi is M terms (Hertz and the two frictional terms of every contact) off a
 *    few ulps each; worst case eps (M sum|terms| + 4 sum P S + 4 sum |q| ulp(x)) per evaluation
 *    (the last two: the cancellations in h = S - d and in x - x0), divided by hs;
 * tolerance 2 (truncation + rounding).  Coordinates whose step crosses a kink of Pi'' are left
 * out and counted: Hertz within 50 hs of h = 0, a contact within 2 k* hs of |q| = Q_max, or
 * (rotations) within 2 k*_t hs / R of |m| = M_max.  The steps are the representable
 * differences (x +- hs) - x.  Friction forces 1 % too large must fail this tolerance on nearly
 * every rotation coordinate, and a gradient with the torsion's sign flipped must fail too. */
static void
fd_check(struct qs_system *s, struct qs_friction *f, double *x, const char *tag)
{
	const struct pack *p = s->p;
	size_t n = s->n, N = 6 * n, i, k, tested = 0, bad = 0, excluded = 0, scaled_fail = 0, rot_tested = 0;
	size_t nsl = 0, nslt = 0, rot_fail = 0, flip_fail = 0;
	double *g = calloc(N, sizeof *g), *gf = calloc(N, sizeof *gf), *gt = calloc(N, sizeof *gt);
	double *trunc = calloc(2 * n, sizeof *trunc);
	char *excl = calloc(2 * n, 1);
	double Pi, hs = 0, sabs = 0, rsum = 0, xmax = 0, worst = 0, worst_f, Fmean, Mterms;
	int a;

	for (i = 0; i < n; i++)
		hs += p->r[i] / n;
	hs *= 1e-6;
	for (k = 0; k < 3 * n; k++)
		xmax = fmax(xmax, fabs(x[k]));
	Pi = eval(s, x, g, tag);
	Fmean = s->sum_force / s->ncontacts;
	/* the frictional gradient alone, and the torsional part alone (to build wrong gradients) */
	{
		struct qs_term *ft = qs_term_named(s, "friction");
		ft->energy(ft, s, x, gf, NULL);
	}
	{
		/* torsion only: the couple part of the rotation gradient, -M n / R */
		for (k = 0; k < f->n; k++) {
			const struct fr_contact *c = &f->c[k];
			for (a = 0; a < 3; a++) {
				gt[3 * n + 3 * c->i + a] -= c->M * c->n[a] / p->r[c->i];
				if (c->j >= 0)
					gt[3 * n + 3 * c->j + a] += c->M * c->n[a] / p->r[c->j];
			}
		}
	}
	/* Hertz: truncation, rounding, exclusion near h = 0 */
	unit_hertz_fd_bounds(p, x, hs, trunc, excl, &rsum, &sabs);
	/* friction: sliding contacts' truncation, the kinks, rounding */
	for (k = 0; k < f->n; k++) {
		const struct fr_contact *c = &f->c[k];
		double us[3], q[3], qn, m, Ot, add = 0;
		int near_q, near_m;

		contact_kinematics(f, s, c, x, us, &Ot);
		for (a = 0; a < 3; a++)
			q[a] = c->qp[a] - c->k * us[a];
		qn = vec3_norm(q);
		m = c->mp - c->kt * Ot;
		near_q = fabs(qn - c->qmax) <= 2 * c->k * hs;
		near_m = fabs(fabs(m) - c->mmax) <= 2 * c->kt * hs / fmin(p->r[c->i], c->j >= 0 ? p->r[c->j] : INFINITY);
		if (qn > c->qmax) {
			add = 3 * c->qmax * c->k * c->k / (qn * qn);
			nsl++;
		}
		nslt += fabs(m) > c->mmax;
		trunc[c->i] += add;
		trunc[n + c->i] += add;
		if (near_q)
			excl[c->i] = excl[n + c->i] = 1;
		if (near_m)
			excl[n + c->i] = 1;
		if (c->j >= 0) {
			trunc[c->j] += add;
			trunc[n + c->j] += add;
			if (near_q)
				excl[c->j] = excl[n + c->j] = 1;
			if (near_m)
				excl[n + c->j] = 1;
		}
		sabs += (qn * qn + vec3_dot(c->qp, c->qp)) / (2 * c->k) + (m * m + c->mp * c->mp) / (2 * c->kt);
		rsum += 4 * qn * xmax * EPS;
	}
	CHECK(nsl >= f->n / 5 && nsl <= 4 * f->n / 5 && nslt >= f->n / 10,
	    "%s: %zu of %zu contacts slide (fr_sliding %zu), %zu at the torsional limit", tag, nsl, f->n, fr_sliding(f), nslt);
	Mterms = (double)(s->ncontacts + 2 * f->n);
	for (k = 0; k < N; k++) {
		double save = x[k], ep, em, hp, hm, fd, tol, err;
		size_t slot = k < 3 * n ? k / 3 : n + (k - 3 * n) / 3;
		if (excl[slot]) {
			excluded++;
			continue;
		}
		x[k] = save + hs;
		hp = x[k] - save;
		ep = eval(s, x, NULL, tag);
		x[k] = save - hs;
		hm = save - x[k];
		em = eval(s, x, NULL, tag);
		x[k] = save;
		fd = (ep - em) / (hp + hm);
		tol = 2 * (trunc[slot] * hs * hs / 6 + EPS * (Mterms * sabs + rsum) / hs);
		err = fabs(g[k] - fd);
		tested++;
		bad += !(err <= tol);
		worst = fmax(worst, err / tol);
		worst_fd_rel = fmax(worst_fd_rel, err / Fmean);
		scaled_fail += fabs(g[k] + 0.01 * gf[k] - fd) > tol;
		flip_fail += fabs(g[k] - 2 * gt[k] - fd) > tol;
		if (k >= 3 * n && fabs(gf[k]) > 0) {
			rot_tested++;
			rot_fail += fabs(g[k] + 0.01 * gf[k] - fd) > tol;
		}
	}
	eval(s, x, NULL, tag);	/* restore Q, M of the point */
	work_check(s, f, x, tag);
	eval(s, x, NULL, tag);
	worst_f = 0;
	for (k = 0; k < N; k++)
		worst_f = fmax(worst_f, fabs(g[k]));
	CHECK(tested >= 5 * N / 10, "%s: %zu of %zu unknowns tested (%zu within a step of a kink left out)", tag, tested, N,
	    excluded);
	CHECK(bad == 0, "%s: dPi/dtheta = central difference on every tested unknown (%zu outside; worst %.3g of the tolerance)",
	    tag, bad, worst);
	CHECK(rot_fail >= 9 * rot_tested / 10 && rot_tested >= n,
	    "%s: friction forces 1 %% too large fail the tolerance on %zu of %zu rotation unknowns (%zu of all)", tag, rot_fail,
	    rot_tested, scaled_fail);
	CHECK(flip_fail >= tested / 3, "%s: a torsional couple of the wrong sign fails on %zu of %zu unknowns", tag, flip_fail,
	    tested);
	printf("     %s: Pi %.6g J, step %.3g m, mean contact force %.3g N, largest |g| %.3g\n", tag, Pi, hs, Fmean, worst_f);
	free(g);
	free(gf);
	free(gt);
	free(trunc);
	free(excl);
}

/* The evaluation's kernels in lanes (four contacts at a time where the processor has AVX2,
 * and two, fr_set_lanes; the clamps by masks) against fr_energy_scalar (one contact at a time
 * through fr_contact_eval): the same energy, gradient, forces, couples and trial forces to
 * the bit, at a point where contacts stick, slide and twist at their limits. */
static void lanes_check_n(struct qs_system *s, struct qs_friction *f, const double *x, const char *tag, int lanes);

static void
lanes_check(struct qs_system *s, struct qs_friction *f, const double *x, const char *tag)
{
	lanes_check_n(s, f, x, tag, 4);
	lanes_check_n(s, f, x, tag, 2);
	fr_set_lanes(4);
}

static void
lanes_check_n(struct qs_system *s, struct qs_friction *f, const double *x, const char *tag, int lanes)
{
	struct qs_term *term = NULL;
	size_t dim = s->dim, k, slide, twist = 0, differ = 0;
	double *g2 = calloc(dim, sizeof *g2), *g1 = calloc(dim, sizeof *g1), *c1 = malloc(5 * f->n * sizeof *c1), E2, E1;
	int q;

	for (q = 0; q < s->nterms; q++)
		if (strcmp(s->term[q].name, "friction") == 0)
			term = &s->term[q];
	fr_set_lanes(lanes);
	E2 = term ? term->energy(term, s, x, g2, NULL) : NAN;
	for (k = 0; k < f->n; k++) {
		memcpy(c1 + 5 * k, f->c[k].Q, 3 * sizeof *c1);
		c1[5 * k + 3] = f->c[k].M;
		c1[5 * k + 4] = f->c[k].qtrial;
	}
	slide = fr_sliding(f);
	for (k = 0; k < f->n; k++)
		twist += f->c[k].mmax > 0 && fabs(f->c[k].M) >= f->c[k].mmax * (1 - 1e-9);
	E1 = fr_energy_scalar(f, s, x, g1);
	for (k = 0; k < f->n; k++)
		differ += memcmp(c1 + 5 * k, f->c[k].Q, 3 * sizeof *c1) != 0 || c1[5 * k + 3] != f->c[k].M ||
		    c1[5 * k + 4] != f->c[k].qtrial;
	CHECK(term && slide > 0 && twist > 0 && slide < f->n && E1 == E2 && memcmp(g1, g2, dim * sizeof *g1) == 0 &&
	    differ == 0, "%s: the kernel in %d lanes equals the scalar walk to the bit (energy, gradient, %zu contacts: "
	    "%zu sliding, %zu twisting; %zu differ)", tag, lanes, f->n, slide, twist, differ);
	free(g1), free(g2), free(c1);
}

static void
test_fd(gsl_rng *rng, size_t n, const char *tag)
{
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	double *x, sc;
	char t[96];
	size_t k;

	int rb;

	random_pack(&p, rng, n, 1e-4, PACK_PHI, 0.02);
	p.mu = 0.3;
	p.wall_mu = 0.4;
	rb = contacts_store(&p, 0) || qs_init(&s, &p, 0.3);
	CHECK(rb == 0, "fd %s: set up (%zu history lines)", tag, p.nc);
	random_history(&p, rng, 0.2, 1.2, 1.2);
	x = malloc(6 * n * sizeof *x);
	fr_init(&f, FR_RETURN_MAP);
	snprintf(t, sizeof t, "fd %s", tag);
	rb = begin(&f, &s, x, t);
	CHECK(rb == 0 && f.clamped > 0, "%s: begin from a random history (%zu lines clamped)", t, f.clamped);
	check_frozen(&f, &p, t);
	/* one increment, committed: the history of the tested increment comes from a commit */
	sc = slip_scale(&f);
	random_move(x, n, rng, 0.7 * sc, 0.7 * sc);
	eval(&s, x, NULL, t);
	rb = commit(&f, &s, x, t) || begin(&f, &s, x, t);
	CHECK(rb == 0, "%s: commit and begin again (%zu contacts, %zu stale, %zu clamped)", t, f.n, f.stale, f.clamped);
	check_frozen(&f, &p, t);
	sc = slip_scale(&f);
	random_move(x, n, rng, 0.7 * sc, 0.7 * sc);
	snprintf(t, sizeof t, "fd %s return-map", tag);
	fd_check(&s, &f, x, t);
	lanes_check(&s, &f, x, t);

	/* FR_PAPER at the same point: it runs, |Q| = the return map's |Q| (both are Q_max when
	 * sliding, the same q when sticking), M identical, stick contacts identical */
	{
		double *Qrm = malloc(3 * f.n * sizeof *Qrm), *Mrm = malloc(f.n * sizeof *Mrm), dev = 0, devs = 0, E;
		size_t differ = 0;
		int a;

		eval(&s, x, NULL, t);
		for (k = 0; k < f.n; k++) {
			memcpy(Qrm + 3 * k, f.c[k].Q, 3 * sizeof *Qrm);
			Mrm[k] = f.c[k].M;
		}
		f.rule = FR_PAPER;
		snprintf(t, sizeof t, "fd %s paper", tag);
		E = eval(&s, x, NULL, t);
		for (k = 0; k < f.n; k++) {
			const struct fr_contact *c = &f.c[k];
			double qn = vec3_norm(c->Q), qr = vec3_norm(Qrm + 3 * k);
			dev = fmax(dev, fabs(qn - qr) / c->qmax);
			if (qr < c->qmax * (1 - 1e-9))
				for (a = 0; a < 3; a++)
					devs = fmax(devs, fabs(c->Q[a] - Qrm[3 * k + a]) / c->qmax);
			else
				for (a = 0; a < 3; a++)
					differ += fabs(c->Q[a] - Qrm[3 * k + a]) > 1e-6 * c->qmax;
			devs = fmax(devs, c->M == Mrm[k] ? 0 : 1);
		}
		CHECK(isfinite(E) && dev <= 1e-12 && devs == 0,
		    "%s: finite Pi, |Q| as the return map (%.3g of Q_max), stick forces and couples identical", t, dev);
		CHECK(differ > 0, "%s: the sliding forces' directions differ from the return map's (%zu components)", t, differ);
		free(Qrm);
		free(Mrm);
		f.rule = FR_RETURN_MAP;
	}
	fr_free(&f);
	qs_free(&s);
	free(x);
	pack_free(&p);
}

/* A commit without evaluating again (fr_commit_evaluated, where qs_minimizer_current says the
 * minimiser's last evaluation was at its x) writes the same history and positions to the bit
 * as fr_commit, which evaluates there first; and qs_minimizer_current turns false once
 * something else is evaluated. */
static void
test_commit_evaluated(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	struct qs_minimizer *m = NULL;
	struct qs_min_params mp;
	struct qs_min_report rep;
	struct pack_contact *lines = NULL;
	double *x, *x2, *xs = NULL, sc;
	size_t n = 35, nc = 0;
	int rb, cur = 0, same = 0;

	random_pack(&p, rng, n, 1e-4, PACK_PHI, 0.02);
	p.mu = 0.3;
	p.wall_mu = 0.4;
	rb = contacts_store(&p, 0) || qs_init(&s, &p, 0.3);
	random_history(&p, rng, 0.2, 1.2, 1.2);
	x = malloc(6 * n * sizeof *x);
	x2 = malloc(6 * n * sizeof *x2);
	fr_init(&f, FR_RETURN_MAP);
	rb = rb || begin(&f, &s, x, "commit_evaluated");
	sc = slip_scale(&f);
	random_move(x, n, rng, 0.7 * sc, 0.7 * sc);
	qs_min_params_default(&mp);
	mp.tol = 1e-6;
	if (!rb && (m = qs_minimizer_alloc(&s, &mp)) && qs_minimize_in(m, x, &mp, &rep) == 0) {
		cur = qs_minimizer_current(m);
		memcpy(x2, x, 6 * n * sizeof *x);
		rb = fr_commit_evaluated(&f, &s, x);
		nc = p.nc;
		lines = malloc((nc ? nc : 1) * sizeof *lines);
		xs = malloc(3 * n * sizeof *xs);
		memcpy(lines, p.c, nc * sizeof *lines);
		memcpy(xs, p.x, 3 * n * sizeof *xs);
		/* the same commit, evaluating first at the minimiser's final state */
		rb = rb || fr_commit(&f, &s, x2);
		same = !rb && p.nc == nc && memcmp(lines, p.c, nc * sizeof *lines) == 0 &&
		    memcmp(xs, p.x, 3 * n * sizeof *xs) == 0;
	}
	CHECK(m && cur, "commit_evaluated: after the minimisation the functional's last evaluation is at the minimiser's x");
	CHECK(same && nc > 0, "commit_evaluated: the same %zu history lines and positions to the bit as fr_commit", nc);
	if (m) {
		qs_energy(&s, x2, NULL, NULL);
		CHECK(!qs_minimizer_current(m), "commit_evaluated: another evaluation makes the minimiser's state not current");
	}
	qs_minimizer_free(m);
	free(lines), free(xs), free(x), free(x2);
	fr_free(&f);
	qs_free(&s);
	pack_free(&p);
}

/* ---------- test 4: mu = 0 ---------- */

/* With mu = wall_mu = 0 every Q_max and M_max is 0: every frictional term is an exact zero
 * (0 times a finite number), so Pi and the translational gradient are those of the
 * frictionless functional to the last bit (checked at 1e-15 relative all the same) and the
 * rotation gradient is 0, after a random increment. */
static void
test_mu0(gsl_rng *rng, enum fr_rule rule)
{
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	size_t n = 40, k;
	double *x = malloc(6 * n * sizeof *x), *g = malloc(6 * n * sizeof *g), *g0 = malloc(3 * n * sizeof *g0);
	double E, E0, dev = 0, gmax = 0, rot = 0, qm = 0;
	char t[64];

	snprintf(t, sizeof t, "mu=0 %s", fr_rule_name(rule));
	int rb;

	random_pack(&p, rng, n, 1e-4, PACK_PHI, 0.02);
	p.mu = p.wall_mu = 0;
	rb = contacts_store(&p, 0) || qs_init(&s, &p, 0.3);
	CHECK(rb == 0, "%s: set up", t);
	fr_init(&f, rule);
	rb = begin(&f, &s, x, t);
	CHECK(rb == 0 && f.n > 2 * n, "%s: begin (%zu contacts)", t, f.n);
	random_move(x, n, rng, 2e-8, 2e-8);
	E = eval(&s, x, g, t);
	for (k = 0; k < f.n; k++)
		qm = fmax(qm, vec3_norm(f.c[k].Q) + fabs(f.c[k].M));
	fr_detach(&s);
	E0 = qs_energy(&s, x, g0, NULL);
	for (k = 0; k < 3 * n; k++) {
		dev = fmax(dev, fabs(g[k] - g0[k]));
		gmax = fmax(gmax, fabs(g0[k]));
		rot = fmax(rot, fabs(g[3 * n + k]));
	}
	CHECK(fabs(E - E0) <= 1e-15 * fabs(E0), "%s: Pi = frictionless Pi (%.17g vs %.17g)", t, E, E0);
	CHECK(dev <= 1e-15 * gmax, "%s: translational gradient = frictionless (worst %.3g of the largest)", t, dev / gmax);
	CHECK(rot == 0 && qm == 0, "%s: rotation gradient 0 (%.3g), every Q and M 0 (%.3g)", t, rot, qm);
	CHECK(fr_sliding(&f) == 0, "%s: no contact counted as sliding (Q_max = 0)", t);
	fr_free(&f);
	qs_free(&s);
	free(x);
	free(g);
	free(g0);
	pack_free(&p);
}

/* ---------- test 7: rigid motions ---------- */

/* A random pack moved away from its walls, random history (some lines clamped), then
 * (a) every centre by the same vector c, |c| ~ 10 Q_max / k* (a missing T or a wrong sign
 *     would move every force by up to 10 Q_max);
 * (b) a rigid rotation Omega about a point: centres by Omega x (x - xc), R_i Omega_i = R_i Omega,
 *     |Omega| R ~ 5 Q_max / k*: u_s = (d - |R_ij| - |R_ji|) Omega x n = 0, since the lever arms
 *     meet at the plane of the intersection circle, and Omega_t = 0; a lever arm of the wrong
 *     sign or length (R_i instead of sqrt(R_i^2 - A^2): off by h) shows.
 * Q must stay Q^p and M stay M^p to the rounding of u_s: the coordinates' ulps (x - x0) and
 * eps |Omega| R in the lever arms, times k*: tolerance k* 16 eps (|x|max + 2 |Omega| R_max),
 * about 1e-9 of Q_max; for the couple k*_t 16 eps |Omega|. */
static void
test_rigid(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	size_t n = 40, i, k, nwall = 0;
	double *x = malloc(6 * n * sizeof *x), sc, c[3], Om[3], xc[3] = {0, 0, 0}, xmax = 0, rmax = 0, worst = 0,
	    worst_m = 0, big = 0;
	int a, pass;

	random_pack(&p, rng, n, 1e-4, PACK_PHI, 0.02);
	for (a = 0; a < 3; a++) {
		p.box[a] -= 1e-3;
		p.box[3 + a] += 1e-3;
	}
	p.mu = 0.3;
	p.wall_mu = 0.4;
	CHECK(contacts_store(&p, 0) == 0 && qs_init(&s, &p, 0.3) == 0, "rigid: set up");
	random_history(&p, rng, 0.2, 1.2, 1.2);
	fr_init(&f, FR_RETURN_MAP);
	CHECK(begin(&f, &s, x, "rigid") == 0, "rigid: begin");
	for (k = 0; k < f.n; k++)
		nwall += f.c[k].j < 0;
	CHECK(nwall == 0 && f.n > n, "rigid: %zu contacts, none with a wall", f.n);
	sc = slip_scale(&f);
	for (i = 0; i < n; i++) {
		for (a = 0; a < 3; a++) {
			xmax = fmax(xmax, fabs(p.x[3 * i + a]) + 10 * sc);
			xc[a] += p.x[3 * i + a] / n;
		}
		rmax = fmax(rmax, p.r[i]);
	}
	for (pass = 0; pass < 2; pass++) {
		double om = 0;
		memcpy(x, p.x, 3 * n * sizeof *x);
		memset(x + 3 * n, 0, 3 * n * sizeof *x);
		for (a = 0; a < 3; a++) {
			c[a] = gsl_ran_gaussian(rng, 1.0);
			Om[a] = gsl_ran_gaussian(rng, 1.0);
		}
		for (a = 0; a < 3; a++) {
			c[a] *= 10 * sc / vec3_norm(c);
			Om[a] *= 5 * sc / p.r[0] / vec3_norm(Om);
		}
		if (pass == 0) {
			for (i = 0; i < n; i++)
				for (a = 0; a < 3; a++)
					x[3 * i + a] += c[a];
		} else {
			om = vec3_norm(Om);
			for (i = 0; i < n; i++) {
				double rel[3], v[3];
				for (a = 0; a < 3; a++)
					rel[a] = p.x[3 * i + a] - xc[a];
				vec3_cross(Om, rel, v);
				for (a = 0; a < 3; a++) {
					x[3 * i + a] += v[a];
					x[3 * n + 3 * i + a] = p.r[i] * Om[a];
				}
			}
		}
		eval(&s, x, NULL, "rigid");
		worst = worst_m = big = 0;
		for (k = 0; k < f.n; k++) {
			const struct fr_contact *ct = &f.c[k];
			double d[3], tol = ct->k * 16 * EPS * (xmax + 2 * om * rmax), tm = ct->kt * 16 * EPS * om;
			for (a = 0; a < 3; a++)
				d[a] = ct->Q[a] - ct->qp[a];
			worst = fmax(worst, vec3_norm(d) / tol);
			worst_m = fmax(worst_m, tm > 0 ? fabs(ct->M - ct->mp) / tm : (ct->M == ct->mp ? 0 : INFINITY));
			big = fmax(big, vec3_norm(d) / ct->qmax);
		}
		CHECK(worst <= 1 && worst_m <= 1,
		    "rigid %s: every Q = Q^p, M = M^p to round-off (worst %.3g and %.3g of the tolerance; largest change %.3g of Q_max)",
		    pass ? "rotation" : "translation", worst, worst_m, big);
	}
	/* The check can fail: the same rotation seen by a rule that leaves out the grains' own
	 * rotation (u_s = T (u_i - u_j) = d Omega x n), or takes the lever arms as R_i and R_j
	 * (u_s = (d - R_i - R_j) Omega x n = -h Omega x n), moves the forces by k* |u_s|, far
	 * beyond the tolerance on most contacts. */
	{
		size_t caught_rot = 0, caught_arm = 0;
		for (k = 0; k < f.n; k++) {
			const struct fr_contact *ct = &f.c[k];
			double om = vec3_norm(Om), tol = ct->k * 16 * EPS * (xmax + 2 * om * rmax), d, h, on[3];
			size_t i0 = ct->i, j0 = (size_t)ct->j;
			vec3_cross(Om, ct->n, on);
			d = 0;
			for (a = 0; a < 3; a++)
				d += (p.x[3 * i0 + a] - p.x[3 * j0 + a]) * (p.x[3 * i0 + a] - p.x[3 * j0 + a]);
			d = sqrt(d);
			h = p.r[i0] + p.r[j0] - d;
			caught_rot += ct->k * d * vec3_norm(on) > tol;
			caught_arm += ct->k * h * vec3_norm(on) > tol;
		}
		CHECK(caught_rot >= 9 * f.n / 10 && caught_arm >= 9 * f.n / 10,
		    "rigid: a rule without the rotation terms would fail on %zu, one with lever arms R_i on %zu of %zu contacts",
		    caught_rot, caught_arm, f.n);
	}
	fr_free(&f);
	qs_free(&s);
	free(x);
	pack_free(&p);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);

	msg_init("test_friction");
	gsl_rng_set(rng, 20100131);
	test_loop(FR_RETURN_MAP, 0);
	test_loop(FR_PAPER, 0);
	test_loop(FR_RETURN_MAP, 1);
	test_loop(FR_PAPER, 1);
	test_shear(FR_RETURN_MAP);
	test_shear(FR_PAPER);
	test_slide_count();
	test_history();
	test_fd(rng, 20, "n=20");
	test_fd(rng, 35, "n=35");
	test_fd(rng, 50, "n=50");
	test_mu0(rng, FR_RETURN_MAP);
	test_mu0(rng, FR_PAPER);
	test_rigid(rng);
	test_commit_evaluated(rng);
	printf("     largest FD gradient error over all packs: %.3g of the mean contact force; work integral off %.3g of E_f\n",
	    worst_fd_rel, worst_work);
	CHECK(bnd.viol == 0, "bounds: |Q| <= Q_max and |M| <= M_max after all %ld evaluations (%ld contact checks; worst "
	    "|Q|/Q_max - 1 = %.3g, |M|/M_max - 1 = %.3g)%s%s", bnd.evals, bnd.checks, bnd.worst_q, bnd.worst_m,
	    bnd.viol ? "; first: " : "", bnd.first);
	gsl_rng_free(rng);
	return unit_summary();
}
