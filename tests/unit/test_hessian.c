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
 *  - A term without second derivatives makes qs_hessian fail with its name in the message.
 *  - Newton from the strained, perturbed equilibrium converges to the residual 1e-9 and
 *    reaches the same energy (1e-8 relative) and positions (1e-6 R, rattlers left out) as
 *    L-BFGS from the same start; the margins are test_minimize's, argued there. */
#include "qs/functional.h"
#include "qs/hessian.h"
#include "qs/loading.h"
#include "qs/minimize.h"
#include "base/msg.h"
#include "pack/pack.h"
#include "unit.h"
#include "unit_pack.h"
#include "unit_min.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* |H v - fd| / |H v| over all coordinates, and the same for 1.01 H v. */
static void
fd_check(struct qs_system *s, const double *x0, gsl_rng *rng, const char *tag)
{
	size_t n = s->n, n3 = 3 * n, k, i;
	double *x = malloc(n3 * sizeof *x), *v = malloc(n3 * sizeof *v), *Hv = malloc(n3 * sizeof *Hv);
	double *gp = malloc(n3 * sizeof *gp), *gm = malloc(n3 * sizeof *gm), e = 1e-7;
	double num = 0, num_scaled = 0, den = 0;
	struct qs_hessian H;
	int trial, ok;

	ok = qs_hessian_init(&H, n) == 0;
	for (trial = 0; trial < 3 && ok; trial++) {
		for (i = 0; i < n; i++)
			for (k = 0; k < 3; k++)
				v[3 * i + k] = s->p->r[i] * (2 * gsl_rng_uniform(rng) - 1);
		qs_energy(s, x0, NULL, NULL);
		ok = qs_hessian(s, x0, &H) == 0;
		qs_hessian_mul(&H, v, Hv);
		for (k = 0; k < n3; k++)
			x[k] = x0[k] + e * v[k];
		qs_energy(s, x, gp, NULL);
		for (k = 0; k < n3; k++)
			x[k] = x0[k] - e * v[k];
		qs_energy(s, x, gm, NULL);
		for (k = 0; k < n3; k++) {
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

static double
zero_energy(struct qs_term *t, struct qs_system *s, const double *x, double *g, double *fmax)
{
	(void)t, (void)s, (void)x, (void)g, (void)fmax;
	return 0;
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
	double de[3] = {0, 0, 1e-4}, rmean = 0, El, En, dpos = 0, tol = 1e-9;
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
	for (k = 0; k < n3; k++)
		x0[k] += 1e-3 * rmean * (2 * gsl_rng_uniform(rng) - 1);
	fd_check(&s, x0, rng, "perturbed pack");

	qs_hessian_init(&H, n);
	qs_add_term(&s, &(struct qs_term){"no-second-derivatives", zero_energy, NULL, NULL, NULL});
	st = qs_hessian(&s, x0, &H);
	CHECK(st == -1 && strstr(msg_geterr(), "no-second-derivatives"), "a term without a Hessian: qs_hessian fails and names it (%s)",
	    msg_geterr());
	qs_hessian_free(&H);
	qs_free(&s);

	/* the start: test_minimize's (its pack, CG's equilibrium, strained 1e-4 along z, perturbed) */
	pack_free(&p);
	n = 200, n3 = 3 * n, rmean = 0;
	gsl_rng_set(rng, 31337);
	random_pack(&p, rng, n, 1e-4, 0.66, 0.04);
	for (i = 0; i < n; i++)
		rmean += p.r[i] / n;
	energy_from(&p, p.x, QS_CG, 200000, 1e-6, 0, x0, &rep, cl);
	for (i = 0, k = 0; i < n; i++)
		k += cl[i] >= 4;
	CHECK(rep.status == 0 && k >= 8 * n / 10, "setup: jammed (%zu of %zu grains with >= 4 contacts, Pi = %.3g J)", k, n,
	    rep.energy);
	load_strain_box(p.box, x0, n, de);
	for (k = 0; k < n3; k++)
		x0[k] += 1e-5 * rmean * (2 * gsl_rng_uniform(rng) - 1);
	El = energy_from(&p, x0, QS_LBFGS, 200000, tol, 0, xl, &rl, cl);
	En = energy_from(&p, x0, QS_NEWTON, 200000, tol, 0, xn, &rn, cn);
	CHECK(rn.status == 0 && rn.res_max <= tol && strcmp(rn.stopped_by, "residual") == 0,
	    "newton converges (status %d, %ld iterations, %ld evaluations, residual %.3g <= %g; lbfgs %ld iterations)",
	    rn.status, rn.iter, rn.evals, rn.res_max, tol, rl.iter);
	CHECK(rl.status == 0, "lbfgs converges from the same start (residual %.3g)", rl.res_max);
	CHECK_CLOSE(En, El, 1e-8, "newton and lbfgs reach the same energy");
	dpos = equilibria_apart(&p, xl, xn, cl, cn, &rattlers);
	CHECK(dpos <= 1e-6, "newton and lbfgs reach the same positions: %.3g R apart (%u rattlers left out)", dpos,
	    rattlers);
	pack_free(&p);
	free(x0), free(xl), free(xn), free(cl), free(cn);
	gsl_rng_free(rng);
	return unit_summary();
}
