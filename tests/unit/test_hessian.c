/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_hessian: lib/qs/hessian.c and Newton's method of lib/qs/minimize.c.
 *
 *  - H v against central differences of the exact gradient, (g(x + e v) - g(x - e v)) / 2e,
 *    for random directions v on a random dense polydisperse pack (300 grains, overlaps up to
 *    4 % of R, walls 100 x stiffer), in the pack's own state and after a random perturbation.
 *    The step e moves a grain by 1e-7 of its radius, far below the overlaps (1e-3..4e-2 R):
 *    the truncation error is of order (e / h)^2 relative, 1e-8 for the smallest common
 *    overlaps, and the rounding error eps |g| / e about 1e-9 of the largest force over e.
 *    A contact within e of h = 0, where U'' = 2 E* sqrt(R* h) has no derivative, adds at
 *    most its own stiffness sqrt(e / R) relative, 3e-4 of a typical one, on a few
 *    coordinates.  The tolerance is 1e-5 of |H v| in the norm over all coordinates, and the
 *    same Hessian scaled by 1.01 (an error of 1e-2) must fail it: the check can fail.
 *  - The preconditioner's diagonal blocks alone against the full Hessian's diagonal blocks,
 *    to the bit (diag_check), without and with friction, also when the contacts' forces come
 *    from the last evaluation (at_last_eval).
 *  - A term without second derivatives makes qs_hessian fail with its name in the message.
 *  - Newton from the strained, perturbed equilibrium converges to the residual 1e-9 and
 *    reaches the same energy (1e-8 relative) and positions (1e-6 R, rattlers left out) as
 *    L-BFGS from the same start; the margins are test_minimize's, argued there.
 *  - With friction (friction_fd, friction_newton): the return map's consistent tangent
 *    against differences of the gradient with contacts sticking, sliding and twisting;
 *    the paper's rule refused; Newton and preconditioned L-BFGS against plain L-BFGS on a
 *    frictional increment: the same energy, centres and rotations, wall stresses and
 *    contacts at the sliding limit. */
#include "qs/friction.h"
#include "qs/functional.h"
#include "qs/hessian.h"
#include "qs/loading.h"
#include "qs/minimize.h"
#include "base/msg.h"
#include "base/vec3.h"
#include "contact/contacts.h"
#include "pack/pack.h"
#include "unit.h"
#include "unit_pack.h"
#include "unit_min.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* |H v - fd| / |H v| over all coordinates (the centres, and with friction the rotations
 * R Omega too, each a length of the order of the grain's radius), and the same for 1.01 H v. */
static void
fd_check(struct qs_system *s, const double *x0, gsl_rng *rng, const char *tag)
{
	size_t n = s->n, dim = s->dim, k;
	double *x = malloc(dim * sizeof *x), *v = malloc(dim * sizeof *v), *Hv = malloc(dim * sizeof *Hv);
	double *gp = malloc(dim * sizeof *gp), *gm = malloc(dim * sizeof *gm), e = 1e-7;
	double num = 0, num_scaled = 0, den = 0;
	struct qs_hessian H;
	int trial, ok;

	ok = qs_hessian_init(&H, dim / 3) == 0;
	for (trial = 0; trial < 3 && ok; trial++) {
		for (k = 0; k < dim; k++)
			v[k] = s->p->r[(k / 3) % n] * (2 * gsl_rng_uniform(rng) - 1);
		qs_energy(s, x0, NULL, NULL);
		ok = qs_hessian(s, x0, &H) == 0;
		qs_hessian_mul(&H, v, Hv);
		for (k = 0; k < dim; k++)
			x[k] = x0[k] + e * v[k];
		qs_energy(s, x, gp, NULL);
		for (k = 0; k < dim; k++)
			x[k] = x0[k] - e * v[k];
		qs_energy(s, x, gm, NULL);
		for (k = 0; k < dim; k++) {
			double fd = (gp[k] - gm[k]) / (2 * e);
			num += (Hv[k] - fd) * (Hv[k] - fd);
			num_scaled += (1.01 * Hv[k] - fd) * (1.01 * Hv[k] - fd);
			den += Hv[k] * Hv[k];
		}
	}
	CHECK(ok && den > 0 && sqrt(num / den) <= 1e-5, "%s: H v matches central differences of the gradient (%.3g of |H v|, %zu pair blocks)",
	    tag, sqrt(num / den), H.np);
	CHECK(ok && sqrt(num_scaled / den) > 1e-5, "%s: 1.01 H v does not (%.3g): the check can fail", tag,
	    sqrt(num_scaled / den));
	qs_hessian_free(&H);
	free(x), free(v), free(Hv), free(gp), free(gm);
}

/* The preconditioner's diagonal blocks alone (diag_only) against the diagonal blocks of the
 * full Hessian: the same to the bit (the same code, without the pair blocks), and so when
 * the contacts' forces are taken from the last evaluation at x (at_last_eval) instead of
 * being evaluated again.  The same comparison with D scaled by 1 + 1e-9 must fail: the check
 * can fail. */
static void
diag_check(struct qs_system *s, const double *x, const char *tag)
{
	struct qs_hessian H, D;
	size_t nodes = s->dim / 3, k, q;
	double err[2] = {0, 0}, err_scaled[2] = {0, 0}, big[2] = {0, 0};
	int ok;

	ok = qs_hessian_init(&H, nodes) == 0 && qs_hessian_init(&D, nodes) == 0;
	D.diag_only = 1;
	qs_energy(s, x, NULL, NULL);
	ok = ok && qs_hessian(s, x, &H) == 0 && qs_hessian(s, x, &D) == 0;
	for (k = 0; k < nodes && ok; k++)
		for (q = 0; q < 9; q++) {
			int kind = k >= s->n;
			double h = H.diag[9 * k + q], d = D.diag[9 * k + q];
			big[kind] = fmax(big[kind], fabs(h));
			err[kind] = fmax(err[kind], fabs(h - d));
			err_scaled[kind] = fmax(err_scaled[kind], fabs(h - (1 + 1e-9) * d));
		}
	CHECK(ok && big[0] > 0 && err[0] == 0 && (nodes == s->n || (big[1] > 0 && err[1] == 0)),
	    "%s: the diagonal blocks alone equal the full Hessian's to the bit (centres %.3g, rotations %.3g of the largest entry)",
	    tag, err[0] / big[0], big[1] > 0 ? err[1] / big[1] : 0.0);
	CHECK(ok && err_scaled[0] > 1e-12 * big[0], "%s: scaled by 1 + 1e-9 they do not (%.3g): the check can fail", tag,
	    err_scaled[0] / big[0]);
	/* at_last_eval: the contacts' state taken from the evaluation at x, the same blocks */
	qs_hessian_clear(&H);
	H.diag_only = 1;
	H.at_last_eval = 1;
	qs_energy(s, x, NULL, NULL);
	ok = ok && qs_hessian(s, x, &H) == 0;
	CHECK(ok && memcmp(H.diag, D.diag, 9 * nodes * sizeof *H.diag) == 0,
	    "%s: with the last evaluation's contact forces (at_last_eval) the same blocks to the bit", tag);
	qs_hessian_free(&H);
	qs_hessian_free(&D);
}

static double
zero_energy(struct qs_term *t, struct qs_system *s, const double *x, double *g, double *fmax)
{
	(void)t, (void)s, (void)x, (void)g, (void)fmax;
	return 0;
}

/* Random history on every line of p: Q0 a random direction (fr_begin turns it into the
 * tangent plane) of magnitude mu P0 U(0, 0.9). */
static void
random_history(struct pack *p, gsl_rng *rng)
{
	size_t k;
	int a;

	for (k = 0; k < p->nc; k++) {
		double v[3], vn, m = 0.9 * p->mu * p->c[k].P0 * gsl_rng_uniform(rng);
		for (a = 0; a < 3; a++)
			v[a] = 2 * gsl_rng_uniform(rng) - 1;
		vn = vec3_norm(v);
		for (a = 0; a < 3; a++)
			p->c[k].Q0[a] = m * v[a] / vn;
	}
}

/* Contacts of f sliding (|Q| at its limit) and twisting at theirs (|M| at M_max). */
static void
slip_counts(const struct qs_friction *f, size_t *slide, size_t *twist)
{
	size_t k;

	*slide = fr_sliding(f);
	*twist = 0;
	for (k = 0; k < f->n; k++)
		*twist += f->c[k].mmax > 0 && fabs(f->c[k].M) >= f->c[k].mmax * (1 - 1e-9);
}

/* The frictional Hessian (the return map's consistent tangent, friction.c): on a random pack
 * with random history (|Q^p| up to 0.9 of the limit) moved by random centres of half the
 * slip distance Q_max / k* per coordinate, and random rotations: a third of the grains by
 * the twist distance R M_max / k*_t, the rest by a tenth of the slip distance, so that a
 * good part of the contacts slide (half) or twist (one in twenty at least) at their limits
 * and the rest stick: both branches of both are in the check.  The
 * step e (1e-7 R) crosses a contact's stick/slip switch only where |q| lies within
 * k* e R of Q_max, a fraction of order 1e-5 of the contacts; none does at this seed. */
static void
friction_fd(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	struct qs_hessian H;
	size_t n = 300, k, slide, twist;
	double *x = malloc(6 * n * sizeof *x), us = 0, ut = 0;
	int st;

	random_pack(&p, rng, n, 1e-4, 0.66, 0.04);
	p.mu = p.wall_mu = 0.3;
	contacts_store(&p, 0);
	random_history(&p, rng);
	qs_init(&s, &p, 0.3);
	fr_init(&f, FR_RETURN_MAP);
	st = fr_begin(&f, &s);
	CHECK(st == 0 && s.dim == 6 * n, "friction: fr_begin on %zu contacts, 6N unknowns", f.n);
	/* the slip distances: Q_max / k* along the plane, R M_max / k*_t in twist */
	for (k = 0; k < f.n; k++) {
		us += f.c[k].qmax / f.c[k].k / f.n;
		ut += p.r[f.c[k].i] * f.c[k].mmax / f.c[k].kt / f.n;
	}
	memcpy(x, p.x, 3 * n * sizeof *x);
	for (k = 0; k < 6 * n; k++)
		x[k] = (k < 3 * n ? x[k] : 0) + (k < 3 * n ? 0.5 * us : (k / 3) % 3 ? 0.1 * us : ut) * (2 * gsl_rng_uniform(rng) - 1);
	qs_energy(&s, x, NULL, NULL);
	slip_counts(&f, &slide, &twist);
	CHECK(slide > f.n / 10 && slide < 9 * f.n / 10 && twist > f.n / 20 && twist < 9 * f.n / 10,
	    "friction: both branches covered (%zu of %zu contacts sliding, %zu twisting at the limit)", slide, f.n, twist);
	fd_check(&s, x, rng, "friction");
	diag_check(&s, x, "friction");
	fr_free(&f);
	fr_init(&f, FR_PAPER);
	fr_begin(&f, &s);
	qs_hessian_init(&H, 2 * n);
	st = qs_hessian(&s, x, &H);
	CHECK(st == -1 && strstr(msg_geterr(), "friction"),
	    "the paper's rule (no potential) has no Hessian: qs_hessian refuses it (%s)", msg_geterr());
	qs_hessian_free(&H);
	fr_free(&f);
	qs_free(&s);
	pack_free(&p);
	free(x);
}

/* Minimise a frictional increment from x0 (6N, copied into x) by method m (L-BFGS's H0
 * preconditioned as precond_shift says, 0: plain) to tol; the wall
 * stresses, each grain's contacts and each reference contact's |Q| / Q_max at the end. */
static void
friction_min(struct qs_system *s, struct qs_friction *f, const double *x0, const struct qs_method_type *m,
    double precond, double tol, double *x, struct qs_min_report *rep, double sig[3], unsigned *cnt, double *ratio)
{
	struct qs_min_params mp;
	size_t k;

	memcpy(x, x0, s->dim * sizeof *x);
	qs_min_params_default(&mp);
	mp.method = m;
	mp.precond_shift = precond;
	mp.tol = tol;
	qs_minimize(s, x, &mp, rep);
	qs_energy(s, x, NULL, NULL);
	qs_wall_stress(s, sig);
	qs_coordination(s, x, cnt);
	for (k = 0; k < f->n; k++)
		ratio[k] = f->c[k].qmax > 0 ? vec3_norm(f->c[k].Q) / f->c[k].qmax : 0;
}

/* Newton with friction against L-BFGS on the same increment: the jammed pack xeq with the
 * history of a fresh frictional state (P0 from Hertz, Q0 = M0 = 0, mu 0.3) strained 1e-4
 * along z, so that part of the contacts slide.  Both to the residual 1e-9: the same energy
 * (1e-8 relative) and positions, centres and rotations R Omega (1e-6 R, rattlers left out),
 * the same wall stresses (1e-6 relative: the stress of an equilibrium within 1e-9 of the
 * largest force per grain), and the same contacts at the sliding limit (those whose |Q| is
 * within 1e-6 of the limit in one state may be on either side in the other). */
static void
friction_newton(struct pack *p, const double *xeq)
{
	struct qs_system s;
	struct qs_friction f;
	struct qs_min_report rl, rn;
	size_t n = p->n, k, slide = 0, differ = 0;
	double *x0 = calloc(6 * n, sizeof *x0), *xl = malloc(6 * n * sizeof *xl), *xn = malloc(6 * n * sizeof *xn);
	double de[3] = {0, 0, 1e-4}, sl[3], sn[3], dpos = 0, dsig = 0, *ql, *qn;
	unsigned *cl = malloc(n * sizeof *cl), *cn = malloc(n * sizeof *cn);
	int a, pass;

	memcpy(p->x, xeq, 3 * n * sizeof *xeq);
	p->mu = p->wall_mu = 0.3;
	contacts_store(p, 0);
	qs_init(&s, p, 0.3);
	fr_init(&f, FR_RETURN_MAP);
	fr_begin(&f, &s);
	ql = malloc(f.n * sizeof *ql), qn = malloc(f.n * sizeof *qn);
	memcpy(x0, p->x, 3 * n * sizeof *x0);
	load_strain_box(p->box, x0, n, de);
	for (pass = 0; pass < 2; pass++) {
		/* newton against plain lbfgs, then lbfgs preconditioned (its default) against it */
		const char *who = pass ? "preconditioned lbfgs" : "newton";
		struct qs_min_params dflt;
		qs_min_params_default(&dflt);
		friction_min(&s, &f, x0, &qs_method_lbfgs, 0, 1e-9, xl, &rl, sl, cl, ql);
		if (pass)
			friction_min(&s, &f, x0, &qs_method_lbfgs, dflt.precond_shift, 1e-9, xn, &rn, sn, cn, qn);
		else
			friction_min(&s, &f, x0, &qs_method_newton, 0, 1e-9, xn, &rn, sn, cn, qn);
		CHECK(rn.status == 0 && rn.res_max <= 1e-9 && rl.status == 0,
		    "friction: %s converges (%ld iterations, residual %.3g; plain lbfgs %ld iterations, residual %.3g)", who,
		    rn.iter, rn.res_max, rl.iter, rl.res_max);
		if (pass)
			CHECK_CLOSE(rn.energy, rl.energy, 1e-8, "friction: preconditioned and plain lbfgs reach the same energy");
		else
			CHECK_CLOSE(rn.energy, rl.energy, 1e-8, "friction: newton and plain lbfgs reach the same energy");
		dpos = 0, dsig = 0, slide = 0, differ = 0;
		for (k = 0; k < n; k++) {
			if (cl[k] == 0 || cn[k] == 0)
				continue;
			for (a = 0; a < 3; a++) {
				dpos = fmax(dpos, fabs(xl[3 * k + a] - xn[3 * k + a]) / p->r[k]);
				dpos = fmax(dpos, fabs(xl[3 * n + 3 * k + a] - xn[3 * n + 3 * k + a]) / p->r[k]);
			}
		}
		CHECK(dpos <= 1e-6, "friction, %s: the same centres and rotations (%.3g R apart)", who, dpos);
		for (a = 0; a < 3; a++)
			dsig = fmax(dsig, fabs(sn[a] - sl[a]) / fabs(sl[2]));
		CHECK(dsig <= 1e-6, "friction, %s: the same wall stresses (sigma_zz %.6g Pa, %.3g apart)", who, sl[2], dsig);
		for (k = 0; k < f.n; k++) {
			int at_l = ql[k] >= 1 - 1e-9, at_n = qn[k] >= 1 - 1e-9;
			slide += at_l;
			differ += at_l != at_n && fmin(ql[k], qn[k]) < 1 - 1e-6;
		}
		CHECK(slide > 0 && differ == 0, "friction, %s: the same contacts at the sliding limit (%zu of %zu; %zu differ)",
		    who, slide, f.n, differ);
	}
	fr_free(&f);
	qs_free(&s);
	free(x0), free(xl), free(xn), free(cl), free(cn), free(ql), free(qn);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct pack p;
	struct qs_system s;
	struct qs_hessian H;
	struct qs_min_report rep, rl, rn;
	size_t n = 300, n3 = 3 * n, i, k;
	double *x0 = malloc(n3 * sizeof *x0), *xl = malloc(n3 * sizeof *xl), *xn = malloc(n3 * sizeof *xn);
	double rmean = 0, El, En, dpos = 0, tol = 1e-9, *xeq;
	unsigned *cl = malloc(n * sizeof *cl), *cn = malloc(n * sizeof *cn), rattlers = 0;
	int st;

	msg_init("test_hessian");
	gsl_rng_set(rng, 4242);
	random_pack(&p, rng, n, 1e-4, 0.66, 0.04);
	for (i = 0; i < n; i++)
		rmean += p.r[i] / n;
	qs_init(&s, &p, 0.3);
	memcpy(x0, p.x, n3 * sizeof *x0);
	/* the wall blocks are tested too: the pack has grains in contact with its walls */
	for (i = 0, k = 0; i < n; i++) {
		int a;
		for (a = 0; a < 3; a++)
			k += (x0[3 * i + a] - p.box[a] < p.r[i]) + (p.box[3 + a] - x0[3 * i + a] < p.r[i]);
	}
	CHECK(k >= 10, "the random pack has wall contacts (%zu)", k);
	fd_check(&s, x0, rng, "random pack");
	diag_check(&s, x0, "random pack");
	for (k = 0; k < n3; k++)
		x0[k] += 1e-3 * rmean * (2 * gsl_rng_uniform(rng) - 1);
	fd_check(&s, x0, rng, "perturbed pack");
	friction_fd(rng);

	qs_hessian_init(&H, n);
	qs_add_term(&s, &(struct qs_term){"no-second-derivatives", zero_energy, NULL, NULL, NULL});
	st = qs_hessian(&s, x0, &H);
	CHECK(st == -1 && strstr(msg_geterr(), "no-second-derivatives"), "a term without a Hessian: qs_hessian fails and names it (%s)",
	    msg_geterr());
	qs_hessian_free(&H);
	qs_free(&s);

	/* the start: test_minimize's (unit_min.h) */
	pack_free(&p);
	n = 200, n3 = 3 * n;
	xeq = malloc(n3 * sizeof *xeq);
	k = strained_start(&p, rng, x0, xeq, &rep, cl);
	CHECK(rep.status == 0 && k >= 8 * n / 10, "setup: jammed (%zu of %zu grains with >= 4 contacts, Pi = %.3g J)", k, n,
	    rep.energy);
	El = energy_from(&p, x0, &qs_method_lbfgs, 200000, tol, 0, xl, &rl, cl);
	En = energy_from(&p, x0, &qs_method_newton, 200000, tol, 0, xn, &rn, cn);
	CHECK(rn.status == 0 && rn.res_max <= tol && strcmp(rn.stopped_by, "residual") == 0,
	    "newton converges (status %d, %ld iterations, %ld evaluations, residual %.3g <= %g; lbfgs %ld iterations)",
	    rn.status, rn.iter, rn.evals, rn.res_max, tol, rl.iter);
	CHECK(rl.status == 0, "lbfgs converges from the same start (residual %.3g)", rl.res_max);
	CHECK_CLOSE(En, El, 1e-8, "newton and lbfgs reach the same energy");
	dpos = equilibria_apart(&p, xl, xn, cl, cn, &rattlers);
	CHECK(dpos <= 1e-6, "newton and lbfgs reach the same positions: %.3g R apart (%u rattlers left out)", dpos,
	    rattlers);
	friction_newton(&p, xeq);
	pack_free(&p);
	free(x0), free(xl), free(xn), free(cl), free(cn), free(xeq);
	gsl_rng_free(rng);
	return unit_summary();
}
