/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_minimize: lib/qs/minimize.c on a random dense polydisperse pack.
 *
 * The pack (200 grains, radii 0.07-0.13 mm, glass-like moduli with a 10 % spread, walls
 * 100 x stiffer) is made by random placement and pairwise separation, brought to equilibrium
 * once, and then strained by 1e-3 along z (affine) and perturbed: that is the common start.
 *  - CG and FIRE both converge from it (status 0, residual <= tol) to the same equilibrium:
 *    energies to 1e-8 relative, positions of grains that carry contacts to a small fraction
 *    of R (rattlers float and are left out);
 *  - CG never raises the energy: the runs with max_iter = 1, 2, 3 ... from the same start on
 *    fresh systems are prefixes of one another (the method is deterministic), so their final
 *    energies are the energies of successive iterations; each such run also reports status 1
 *    and stopped_by "max_iter";
 *  - the displacement cap: between successive iterations no grain moves more than cap R, and
 *    the cap is reached (so the check is not vacuous); FIRE likewise for its first step;
 *  - the table of the methods (QS_METHODS), row by row, so that a new method is tested
 *    without an edit here: its name finds it, it has a one-line description, and it reaches
 *    CG's equilibrium from the common start; an unknown name lists every method. */
#include "base/msg.h"
#include "base/par.h"
#include "qs/functional.h"
#include "qs/loading.h"
#include "qs/minimize.h"
#include "pack/pack.h"
#include "unit.h"
#include "unit_pack.h"
#include "unit_min.h"

#include <float.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Largest displacement between two configurations, in units of each grain's radius. */
static double
maxmove(const struct pack *p, const double *a, const double *b)
{
	double m = 0;
	size_t i;

	for (i = 0; i < p->n; i++) {
		double d0 = a[3 * i] - b[3 * i], d1 = a[3 * i + 1] - b[3 * i + 1], d2 = a[3 * i + 2] - b[3 * i + 2];
		m = fmax(m, sqrt(d0 * d0 + d1 * d1 + d2 * d2) / p->r[i]);
	}
	return m;
}

/* Rounding of a displacement measured as a difference of centres: a few ulps of the largest
 * coordinate, over the smallest radius (2e-9 of a 1e-4 R step for 1 mm boxes). */
static double
move_slack(const struct pack *p, const double *x)
{
	double xm = 0, rmin = INFINITY;
	size_t i;

	for (i = 0; i < 3 * p->n; i++)
		xm = fmax(xm, fabs(x[i]));
	for (i = 0; i < p->n; i++)
		rmin = fmin(rmin, p->r[i]);
	return 4 * DBL_EPSILON * xm / rmin;
}

/* par's fused passes against the plain ones they stand for, to the bit: par_quad3 (the
 * L-BFGS preconditioner's gamma) against d = M y node by node and par_dot(y, d), and
 * par_axpy_scale_dot against par_axpy, par_scale and par_dot, on vectors of several
 * blocks whose bounds fall inside a node (4096 is not a multiple of 3), on 1 and 2 threads. */
static void
test_fused_passes(gsl_rng *rng)
{
	size_t nn = 4001, n3 = 3 * nn, k, i;
	double *M = malloc(9 * nn * sizeof *M), *y = malloc(n3 * sizeof *y), *d = malloc(n3 * sizeof *d);
	double *a = malloc(n3 * sizeof *a), *b = malloc(n3 * sizeof *b), *e = malloc(n3 * sizeof *e);
	int th;

	for (k = 0; k < 9 * nn; k++)
		M[k] = gsl_ran_gaussian(rng, 1.0);
	for (i = 0; i < nn; i += 7)	/* rows where the order of a row's three products shows */
		for (k = 0; k < 3; k++)
			M[9 * i + 3 * k + 1] += 3e15, M[9 * i + 3 * k + 2] -= 3e15;
	for (k = 0; k < n3; k++)
		y[k] = gsl_ran_gaussian(rng, 1.0) * exp(8 * gsl_rng_uniform(rng)), a[k] = gsl_ran_gaussian(rng, 1.0);
	for (i = 0; i < nn; i++) {
		const double *Mi = M + 9 * i, *yi = y + 3 * i;
		for (k = 0; k < 3; k++)
			d[3 * i + k] = Mi[3 * k] * yi[0] + Mi[3 * k + 1] * yi[1] + Mi[3 * k + 2] * yi[2];
	}
	for (th = 1; th <= 2; th++) {
		double q, ref = par_dot(y, d, n3), t1, t2;
		par_set_threads(th);
		q = par_quad3(M, y, n3);
		CHECK(q == ref, "par_quad3 on %d thread(s): y.(M y) as d = M y then par_dot, to the bit (%.17g, %.17g)", th, q,
		    ref);
		memcpy(b, a, n3 * sizeof *b);
		t1 = par_axpy_scale_dot(b, -0.37, y, 1.3, d, n3);
		memcpy(e, a, n3 * sizeof *e);
		par_axpy(e, -0.37, y, n3);
		par_scale(e, 1.3, e, n3);
		t2 = par_dot(d, e, n3);
		CHECK(t1 == t2 && memcmp(b, e, n3 * sizeof *e) == 0,
		    "par_axpy_scale_dot on %d thread(s): the plain passes' vector and sum to the bit (%.17g, %.17g)", th, t1,
		    t2);
	}
	par_set_threads(0);
	free(M), free(y), free(d), free(a), free(b), free(e);
}

/* par_dot against its definition written out: blocks of max(par_block(n), PAR_MIN_VEC)
 * elements, each summed one term at a time from its first, the block sums then added in
 * order; with an even block length (4096) and an odd one (4097, n = 1024 x 4097), n not a
 * multiple of the block, on 1 and 2 threads.  The two-lane walk of four blocks at a time
 * (par.c, op_chains4) must keep each chain's order. */
static void
test_dot_blocks(gsl_rng *rng)
{
	size_t sizes[] = {3 * 2740 * 2, 4 * 4096 + 7, 1024 * 4097}, z, k, q;
	int th;

	for (z = 0; z < sizeof sizes / sizeof *sizes; z++) {
		size_t n = sizes[z], bl = par_block(n) < PAR_MIN_VEC ? PAR_MIN_VEC : par_block(n), nb = (n + bl - 1) / bl;
		double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), ref = 0;

		for (k = 0; k < n; k++)
			a[k] = gsl_ran_gaussian(rng, 1.0) * exp(20 * gsl_rng_uniform(rng)), b[k] = gsl_ran_gaussian(rng, 1.0);
		for (q = 0; q < nb; q++) {
			double t = 0;
			for (k = q * bl; k < (q + 1) * bl && k < n; k++)
				t += a[k] * b[k];
			ref += t;
		}
		for (th = 1; th <= 2; th++) {
			double d;
			par_set_threads(th);
			d = par_dot(a, b, n);
			CHECK(d == ref, "par_dot of %zu elements in blocks of %zu, %d thread(s): the blocks' sums in order, to the "
			    "bit (%.17g, %.17g)", n, bl, th, d, ref);
		}
		/* par_diff_dots: s = a - b, y = b - a / 3 (stand-ins for the new pair), s.y and y.y */
		{
			double *c = malloc(n * sizeof *c), *sv = malloc(n * sizeof *sv), *yv = malloc(n * sizeof *yv), sy, yy;
			double rsy = 0, ryy = 0;
			size_t bad = 0;

			for (k = 0; k < n; k++)
				c[k] = a[k] / 3;
			for (q = 0; q < nb; q++) {
				double t1 = 0, t2 = 0;
				for (k = q * bl; k < (q + 1) * bl && k < n; k++) {
					double sk = a[k] - b[k], yk = b[k] - c[k];
					t1 += sk * yk;
					t2 += yk * yk;
				}
				rsy += t1, ryy += t2;
			}
			for (th = 1; th <= 2; th++) {
				par_set_threads(th);
				par_diff_dots(sv, a, b, yv, b, c, n, &sy, &yy);
				for (bad = k = 0; k < n; k++)
					bad += sv[k] != a[k] - b[k] || yv[k] != b[k] - c[k];
				CHECK(sy == rsy && yy == ryy && bad == 0, "par_diff_dots of %zu elements, %d thread(s): the vectors "
				    "(%zu differ) and both sums to the bit (%.17g %.17g, %.17g %.17g)", n, th, bad, sy, rsy, yy, ryy);
			}
			free(c), free(sv), free(yv);
		}
		par_set_threads(0);
		free(a), free(b);
	}
}

/* CG iteration by iteration: max_iter = k from the same start x0 on a fresh system (xa, xb:
 * work space). */
static void
test_cg_steps(struct pack *p, const double *x0, double *xa, double *xb)
{
	struct qs_min_report rep;
	size_t n3 = 3 * p->n;
	/* the start is 1e-4 strain from equilibrium, so a cap of 2e-5 R binds */
	double cap = 2e-5, eprev, rise = 0, mv = 0, mvmax = 0;
	int allmax = 1;
	long kk, K = 40;

	eprev = energy_from(p, x0, &qs_method_cg, 0, 1e-30, cap, xa, &rep, NULL);
	allmax &= rep.status == 1 && strcmp(rep.stopped_by, "max_iter") == 0 && rep.iter == 0;
	for (kk = 1; kk <= K; kk++) {
		double e = energy_from(p, x0, &qs_method_cg, kk, 1e-30, cap, xb, &rep, NULL);
		allmax &= rep.status == 1 && strcmp(rep.stopped_by, "max_iter") == 0 && rep.iter == kk;
		/* rounding: the energy is a sum of a few thousand terms, so 1e-13 relative */
		rise = fmax(rise, (e - eprev) / fabs(eprev));
		mv = maxmove(p, xa, xb);
		mvmax = fmax(mvmax, mv);
		eprev = e;
		memcpy(xa, xb, n3 * sizeof *xa);
	}
	CHECK(rise <= 1e-13, "cg: the energy never rises over %ld iterations (largest relative rise %.3g)", K, rise);
	CHECK(allmax, "cg: max_iter too small gives status 1, stopped_by \"max_iter\" and iter = max_iter");
	/* the line search may stop at alpha_max, where one grain moves exactly cap R: allow the
	 * rounding of measuring the move (move_slack) above it */
	CHECK(mvmax <= cap + move_slack(p, x0) && mvmax >= 0.5 * cap,
	    "cg: no grain moves more than cap R = %g R in one iteration (largest %.17g R)", cap, mvmax);
}

/* Every row of the method table: found by its name, described in one line, and from the
 * common start x0 at the equilibrium CG reached (energy Ec, positions xc, contacts cc) to tol,
 * as test_hessian compares newton and lbfgs; an unknown name lists the rows' names. */
static void
test_method_table(struct pack *p, const double *x0, double Ec, const double *xc, const unsigned *cc, double tol)
{
	const struct qs_method_type *const *t;
	double *x = malloc(3 * p->n * sizeof *x);
	unsigned *cnt = malloc(p->n * sizeof *cnt), rattlers;
	size_t rows = 0;
	int listed = 1;

	for (t = qs_methods; *t; t++, rows++) {
		const struct qs_method_type *m = *t;
		struct qs_min_report rep;
		double E, dpos;
		char tag[96];

		CHECK(m->name && qs_method_find(m->name) == m, "table row %zu: '%s' finds its own row", rows,
		    m->name ? m->name : "(null)");
		CHECK(m->description && m->description[0] && !strchr(m->description, '\n'),
		    "%s: a one-line description ('%s')", m->name, m->description ? m->description : "(null)");
		CHECK(m->size > 0 || (!m->alloc && !m->free), "%s: a state, or nothing to allocate", m->name);
		CHECK(m->start && m->iterate, "%s: start and iterate", m->name);
		E = energy_from(p, x0, m, 200000, tol, 0, x, &rep, cnt);
		CHECK(rep.status == 0 && rep.res_max <= tol && strcmp(rep.stopped_by, "residual") == 0,
		    "%s converges (status %d, %ld iterations, %ld evaluations, residual %.3g <= %g)", m->name, rep.status,
		    rep.iter, rep.evals, rep.res_max, tol);
		snprintf(tag, sizeof tag, "%s reaches cg's energy", m->name);
		CHECK_CLOSE(E, Ec, 1e-8, tag);
		dpos = equilibria_apart(p, xc, x, cc, cnt, &rattlers);
		CHECK(dpos <= 1e-6, "%s reaches cg's positions: %.3g R apart (%u rattlers left out)", m->name, dpos,
		    rattlers);
	}
	CHECK(rows >= 1, "the method table has rows (%zu)", rows);
	CHECK(qs_method_find("no-such-method") == NULL, "an unknown method name: no method");
	for (t = qs_methods; *t; t++)
		listed &= strstr(msg_geterr(), (*t)->name) != NULL;
	CHECK(listed && strstr(msg_geterr(), "'no-such-method'"), "... and its message names it and lists the methods (%s)",
	    msg_geterr());
	free(x), free(cnt);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct pack p;
	struct qs_min_report rep, rc, rf;
	size_t n = 200, n3 = 3 * n;
	double *x0, *xc, *xf, *xa, *xb, tol = 1e-9, Ec, Ef, dpos = 0;
	unsigned *cc, *cf, nz = 0, rattlers = 0;

	x0 = malloc(n3 * sizeof *x0);
	xc = malloc(n3 * sizeof *xc);
	xf = malloc(n3 * sizeof *xf);
	xa = malloc(n3 * sizeof *xa);
	xb = malloc(n3 * sizeof *xb);
	cc = malloc(n * sizeof *cc);
	cf = malloc(n * sizeof *cf);

	test_fused_passes(rng);
	test_dot_blocks(rng);

	/* the common start: equilibrium of the generated pack, strained 1e-4 along z, perturbed */
	nz = (unsigned)strained_start(&p, rng, x0, NULL, &rep, cc);
	CHECK(rep.status == 0, "setup: the generated pack reaches equilibrium (%ld iterations, residual %.3g)", rep.iter,
	    rep.res_max);
	CHECK(nz >= 8 * n / 10 && rep.energy > 0, "setup: jammed: %u of %zu grains with >= 4 contacts, Pi = %.3g J", nz, n,
	    rep.energy);

	/* both methods from the same start */
	Ec = energy_from(&p, x0, &qs_method_cg, 200000, tol, 0, xc, &rc, cc);
	Ef = energy_from(&p, x0, &qs_method_fire, 200000, tol, 0, xf, &rf, cf);
	CHECK(rc.status == 0 && rc.res_max <= tol && strcmp(rc.stopped_by, "residual") == 0,
	    "cg converges (status %d, %ld iterations, %ld evaluations, residual %.3g <= %g)", rc.status, rc.iter, rc.evals,
	    rc.res_max, tol);
	CHECK(rf.status == 0 && rf.res_max <= tol && strcmp(rf.stopped_by, "residual") == 0,
	    "fire converges (status %d, %ld iterations, residual %.3g <= %g)", rf.status, rf.iter, rf.res_max, tol);
	/* at a residual of 1e-9 the energy sits within about (1e-9)^2 of the minimum, relative; two
	 * runs into the same minimum agree far below 1e-8 */
	CHECK_CLOSE(Ec, Ef, 1e-8, "cg and fire reach the same energy");
	dpos = equilibria_apart(&p, xc, xf, cc, cf, &rattlers);
	/* forces off by 1e-9 of the largest contact force move a grain by about 1e-9 h / 1.5 through
	 * its stiffest contacts and more along soft collective modes; 1e-6 R is 1e-4 of a typical
	 * overlap, far below the distance between two distinct minima */
	CHECK(dpos <= 1e-6, "cg and fire reach the same positions: %.3g R apart (%u rattlers left out)", dpos, rattlers);
	test_method_table(&p, x0, Ec, xc, cc, tol);

	test_cg_steps(&p, x0, xa, xb);
	{
		double cap = 1e-4, mv;
		energy_from(&p, x0, &qs_method_cg, 1, 1e-30, cap, xa, &rep, NULL);
		mv = maxmove(&p, x0, xa);
		CHECK(mv <= cap + move_slack(&p, x0) && mv >= 0.999 * cap, "cg, max_iter = 1, cap %g: largest move %.8g R", cap, mv);
		CHECK(rep.status == 1 && strcmp(rep.stopped_by, "max_iter") == 0, "cg, max_iter = 1: status 1, max_iter");
		energy_from(&p, x0, &qs_method_fire, 1, 1e-30, cap, xa, &rep, NULL);
		mv = maxmove(&p, x0, xa);
		CHECK(mv <= cap + move_slack(&p, x0) && mv > 0, "fire, max_iter = 1, cap %g: largest move %.8g R", cap, mv);
		CHECK(rep.status == 1 && strcmp(rep.stopped_by, "max_iter") == 0, "fire, max_iter = 1: status 1, max_iter");
	}
	{
		/* FIRE step by step, as for CG; its first steps are short (dt starts at dt_max / 10),
		 * so the cap is smaller */
		double cap = 1e-6, mvmax = 0;
		long kk;
		energy_from(&p, x0, &qs_method_fire, 0, 1e-30, cap, xa, &rep, NULL);
		for (kk = 1; kk <= 60; kk++) {
			energy_from(&p, x0, &qs_method_fire, kk, 1e-30, cap, xb, &rep, NULL);
			mvmax = fmax(mvmax, maxmove(&p, xa, xb));
			memcpy(xa, xb, n3 * sizeof *xa);
		}
		CHECK(mvmax <= cap + move_slack(&p, x0) && mvmax >= 0.5 * cap, "fire: no grain moves more than cap R = %g R in one iteration (largest %.17g R)",
		    cap, mvmax);
	}
	/* an equilibrium is recognised at once */
	energy_from(&p, xc, &qs_method_cg, 10, tol, 0, xa, &rep, NULL);
	CHECK(rep.status == 0 && rep.iter == 0 && maxmove(&p, xa, xc) == 0,
	    "cg from its own equilibrium: status 0 after 0 iterations, nothing moves");
	free(x0), free(xc), free(xf), free(xa), free(xb), free(cc), free(cf);
	pack_free(&p);
	gsl_rng_free(rng);
	return unit_summary();
}
