/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_dissociate: the rules of hydrate dissociation (qs/dissociate.h) against numbers
 * computed by hand: (a) the hydrate grains' volumes fall by dS / S, (b) every grain's by
 * p_ex / K_i, (c) the box grows by alpha_b p_ex / K in volume, 1 + eps_kk / 3 per length;
 * and the refusals. */
#include "unit.h"
#include "unit_pack.h"
#include "qs/dissociate.h"
#include "base/msg.h"

#include <string.h>

/* A 6-grain pack by hand: two hydrate grains (E 6.6e9, nu 0.32), four quartz (1e11, 0.15). */
static void
hand_pack(struct pack *p)
{
	static const double r[6] = {1e-4, 1.2e-4, 0.8e-4, 0.75e-4, 1.1e-4, 0.9e-4};
	size_t i;

	pack_init(p);
	for (i = 0; i < 6; i++) {
		double x[3] = {2e-4 + 4e-4 * (double)(i % 3), 2e-4 + 4e-4 * (double)(i / 3), 2e-4};
		pack_add_grain(p, (long)i + 1, x, r[i], i == 2 || i == 3 ? 6.6e9 : 1e11, i == 2 || i == 3 ? 0.32 : 0.15,
		    i == 2 || i == 3 ? 900 : 2650);
	}
	pack_set_phases(p);
	p->phase[2] = p->phase[3] = PHASE_HYDRATE;
	p->box[0] = p->box[1] = p->box[2] = 0;
	p->box[3] = 1.2e-3, p->box[4] = 8e-4, p->box[5] = 4e-4;
}

static double
vol(double r)
{
	return 4.0 / 3.0 * M_PI * r * r * r;
}

static void
test_saturation(void)
{
	struct pack p;
	double vh = vol(0.8e-4) + vol(0.75e-4), vm = vol(1e-4) + vol(1.2e-4) + vol(1.1e-4) + vol(0.9e-4);
	double vbox = 1.2e-3 * 8e-4 * 4e-4, vhp;

	hand_pack(&p);
	CHECK(pack_hydrate_grains(&p, &vhp) == 2, "pack_hydrate_grains counts the 2 tagged grains");
	CHECK_CLOSE(vhp, vh, 1e-14, "hydrate volume");
	/* S counts the hydrate as pore space: V_h / (V_box - V_mineral) */
	CHECK_CLOSE(pack_hydrate_saturation(&p), vh / (vbox - vm), 1e-13, "S = V_h / (V_box - V_mineral)");
	pack_free(&p);
}

static void
test_radii(void)
{
	struct pack p, q;
	double S, dS, pex = 2e6, Kq = 1e11 / (3 * (1 - 0.3)), Kh = 6.6e9 / (3 * (1 - 0.64));
	size_t i;

	hand_pack(&p);
	S = pack_hydrate_saturation(&p);
	dS = -0.3 * S;	/* 30 % of the hydrate dissociates */
	pack_copy(&q, &p);
	CHECK_CLOSE(dissociate_grain_K(1e11, 0.15), Kq, 1e-15, "K_i = E / (3 (1 - 2 nu)), quartz");
	dissociate_radii(&q, dS, S, pex);
	for (i = 0; i < 6; i++) {
		int h = i == 2 || i == 3;
		/* by hand: V'/V = (1 + dS/S) (1 - p_ex / K_i) for hydrate, (1 - p_ex / K_i) else */
		double want = h ? (1 + dS / S) * (1 - pex / Kh) : 1 - pex / Kq;
		char name[64];

		snprintf(name, sizeof name, "grain %zu (%s): V'/V", i + 1, h ? "hydrate" : "quartz");
		CHECK_CLOSE(vol(q.r[i]) / vol(p.r[i]), want, 1e-14, name);
	}
	/* (a) alone: the hydrate volume falls by the fraction dS/S, so S falls by dS exactly */
	pack_free(&q);
	pack_copy(&q, &p);
	dissociate_radii(&q, dS, S, 0);
	CHECK_CLOSE(pack_hydrate_saturation(&q), S + dS, 1e-13, "(a) alone: S' = S + dS (box and mineral unchanged)");
	for (i = 0; i < 6; i++)
		if (!(i == 2 || i == 3) && q.r[i] != p.r[i])
			break;
	CHECK(i == 6, "(a) alone leaves the mineral grains' radii bit for bit");
	pack_free(&q);
	pack_free(&p);
}

static void
test_refusals(void)
{
	struct pack p, m;
	struct dissociation d = {0, 0, 0.8, NAN, 1e-5};
	double S;
	size_t i;
	int r;

	hand_pack(&p);
	S = pack_hydrate_saturation(&p);
	d.dS = 0.01;
	r = dissociate_check(&p, &d, &S);
	CHECK(r < 0 && strstr(msg_geterr(), "--dS"), "dS > 0 refused: %s", msg_geterr());
	d.dS = -S;
	r = dissociate_check(&p, &d, &S);
	CHECK(r < 0 && strstr(msg_geterr(), "above -S"), "dS = -S refused: %s", msg_geterr());
	d.dS = -0.999 * S;
	r = dissociate_check(&p, &d, &S);
	CHECK(r == 0, "dS = -0.999 S accepted");
	d.dS = 0, d.pex = -1;
	r = dissociate_check(&p, &d, &S);
	CHECK(r < 0 && strstr(msg_geterr(), "--pex"), "p_ex < 0 refused: %s", msg_geterr());
	d.pex = 0.011 * dissociate_grain_K(6.6e9, 0.32);
	r = dissociate_check(&p, &d, &S);
	CHECK(r < 0 && strstr(msg_geterr(), "small strain"), "p_ex beyond 1 %% of the softest K_i refused: %s",
	    msg_geterr());
	d.pex = 1e6, d.alpha = 0;
	r = dissociate_check(&p, &d, &S);
	CHECK(r < 0 && strstr(msg_geterr(), "--alpha"), "alpha 0 refused: %s", msg_geterr());
	/* the same grains untagged: no hydrate, whatever their moduli and density say */
	pack_copy(&m, &p);
	for (i = 0; i < m.n; i++)
		m.phase[i] = PHASE_MINERAL;
	d.alpha = 0.8, d.dS = -0.01, d.pex = 0;
	r = dissociate_check(&m, &d, &S);
	CHECK(r < 0 && strstr(msg_geterr(), "no hydrate"), "dS < 0 without hydrate refused: %s",
	    msg_geterr());
	CHECK(S == 0, "S = 0 without hydrate grains (hydrate-like moduli and density do not count)");
	pack_free(&m);
	pack_free(&p);
}

/* (c) and (d) on a real equilibrium: a random pack with controlled overlaps, brought to
 * equilibrium by a zero increment, then dissociated with K given: the box lengths grow by
 * 1 + eps_kk / 3 with eps_kk = alpha p_ex / K, the volume by about eps_kk. */
static void
test_box(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct pack p;
	struct load_params lp;
	struct dissociation d = {0, 3e6, 0.8, 2e9, 1e-5};
	struct dissociation_report rep;
	double box0[6], eps, de[3] = {0, 0, 0};
	struct loader L;
	struct load_row row;
	int a, ok = 1;

	gsl_rng_set(rng, 12);
	random_pack(&p, rng, 60, 1e-4, 0.6, 2e-3);
	memcpy(p.refbox, p.box, sizeof p.box);
	p.has_refbox = 1;
	load_params_default(&lp);
	lp.friction = 0;
	loader_open(&L, &p, &lp);
	loader_step(&L, de, &row);
	loader_close(&L);
	memcpy(box0, p.box, sizeof box0);
	a = dissociate_run(&p, &lp, &d, &rep);
	CHECK(a == 0, "dissociate_run with K given%s%s", a ? ": " : "", a ? msg_geterr() : "");
	eps = d.alpha * d.pex / d.K;
	CHECK_CLOSE(rep.eps_kk, eps, 1e-15, "eps_kk = alpha_b p_ex / K");
	for (a = 0; a < 3; a++)
		ok &= unit_close(pack_box_length(p.box, a) / pack_box_length(box0, a), 1 + eps / 3, 1e-13, 0);
	CHECK(ok, "each box length grew by 1 + eps_kk / 3 (%.15g, %.15g, %.15g; want %.15g)",
	    pack_box_length(p.box, 0) / pack_box_length(box0, 0), pack_box_length(p.box, 1) / pack_box_length(box0, 1),
	    pack_box_length(p.box, 2) / pack_box_length(box0, 2), 1 + eps / 3);
	/* (1 + e/3)^3 - 1 = e (1 + e/3 + e^2/27): off e by the relative e/3 */
	CHECK_CLOSE(pack_box_volume(p.box) / pack_box_volume(box0) - 1, eps, eps, "the volume by eps_kk to second order");
	CHECK(rep.after.res_max <= lp.min.tol, "the dissociated state is an equilibrium (residual %.3g <= %g)", rep.after.res_max,
	    lp.min.tol);
	CHECK(rep.sigma_after < rep.sigma_before, "the effective stress fell (%.6g -> %.6g Pa)", rep.sigma_before, rep.sigma_after);
	pack_free(&p);
	gsl_rng_free(rng);
}

int
main(void)
{
	test_saturation();
	test_radii();
	test_refusals();
	test_box();
	return unit_summary();
}
