/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_contacts: the contact seam.  The enumerator (contact/contacts.h) against a brute-force
 * O(N^2) search written here, with walls and with periodic axes (nearest images); its history
 * slots carried over a rebuild; the contact-law interface (contact/law.h) against the
 * functional's inlined Hertz, bit for bit, and the linear law's energy against its closed
 * form and its gradient against central differences; the functional as a sum of terms; and
 * the steppable minimiser, whose loop is qs_minimize to the bit and which keeps converging
 * when the caller moves grains between iterations. */
#include "unit.h"
#include "unit_pack.h"
#include "base/msg.h"
#include "contact/contacts.h"
#include "contact/hertz.h"
#include "contact/law.h"
#include "contact/linear.h"
#include "qs/functional.h"
#include "qs/hessian.h"
#include "qs/minimize.h"

#include <float.h>
#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Brute force: every touching pair with the nearest image along the periodic axes, and every
 * wall nearer than the radius on the others; checks them against the enumerator's records. */
struct seen {
	const struct pack *p;
	long pairs, walls, bad;
	double hmax_err;
};

static int
on_seen(const struct contact *c, void *v)
{
	struct seen *s = v;
	const struct pack *p = s->p;

	if (PACK_IS_WALL(c->j)) {
		int w = PACK_WALL_INDEX(c->j), a = w / 2;
		double dist = w % 2 ? p->box[3 + a] - p->x[3 * c->i + a] : p->x[3 * c->i + a] - p->box[a];
		s->walls++;
		if (p->periodic[a] || !(dist < p->r[c->i]))
			s->bad++;
		s->hmax_err = fmax(s->hmax_err, fabs(c->h - (p->r[c->i] - dist)));
	} else {
		double dd = 0, h;
		int a;
		for (a = 0; a < 3; a++) {
			double e = p->x[3 * c->i + a] - p->x[3 * c->j + a], L = p->box[3 + a] - p->box[a];
			if (p->periodic[a])
				e -= L * round(e / L);
			dd += e * e;
		}
		h = p->r[c->i] + p->r[c->j] - sqrt(dd);
		s->pairs++;
		if (!(h > 0) || (size_t)c->j <= c->i)
			s->bad++;
		s->hmax_err = fmax(s->hmax_err, fabs(c->h - h));
	}
	return 0;
}

static void
brute_counts(const struct pack *p, long *pairs, long *walls)
{
	size_t i, j;
	int a;

	*pairs = *walls = 0;
	for (i = 0; i < p->n; i++) {
		for (j = i + 1; j < p->n; j++) {
			double dd = 0, s = p->r[i] + p->r[j];
			for (a = 0; a < 3; a++) {
				double e = p->x[3 * i + a] - p->x[3 * j + a], L = p->box[3 + a] - p->box[a];
				if (p->periodic[a])
					e -= L * round(e / L);
				dd += e * e;
			}
			*pairs += sqrt(dd) < s;
		}
		for (a = 0; a < 6; a++)
			if (!p->periodic[a / 2] && pack_wall_distance(p->box, p->x + 3 * i, a) < p->r[i])
				(*walls)++;
	}
}

static void
test_enumerator(gsl_rng *rng, const int periodic[3], const char *tag)
{
	struct pack p;
	struct contact_enum e;
	struct seen s;
	long bp, bw, calls;
	size_t i;
	int a;

	random_pack(&p, rng, 600, 1e-4, 0.6, 0.02);
	memcpy(p.periodic, periodic, sizeof p.periodic);
	/* on a periodic axis, grains anywhere along it: some wander out of the box, which the
	 * images must still find */
	for (i = 0; i < p.n; i++)
		for (a = 0; a < 3; a++)
			if (periodic[a] && i % 7 == 0)
				p.x[3 * i + a] += (i % 2 ? 1 : -1) * (p.box[3 + a] - p.box[a]);
	CHECK(contact_enum_init(&e, p.n, p.r, p.box, p.box + 3, p.periodic, 0.3e-4, 0) == 0 &&
	    contact_enum_update(&e, p.x, 1) == 0, "%s: enumerator built", tag);
	memset(&s, 0, sizeof s);
	s.p = &p;
	calls = contact_foreach(&e, p.x, CONTACT_TOUCHING, on_seen, &s);
	brute_counts(&p, &bp, &bw);
	CHECK(s.pairs == bp && s.walls == bw && calls == bp + bw, "%s: %ld pairs and %ld wall contacts, as brute force (%ld, %ld)",
	    tag, s.pairs, s.walls, bp, bw);
	CHECK(s.bad == 0, "%s: every record touches, i < j, no wall on a periodic axis (%ld bad)", tag, s.bad);
	CHECK(s.hmax_err <= 1e-18, "%s: overlaps as computed directly (largest difference %.3g m)", tag, s.hmax_err);
	if (periodic[0] || periodic[1] || periodic[2])
		CHECK(bp > 0 && s.walls < 600, "%s: the periodic case has contacts across the boundary to find", tag);
	contact_enum_free(&e);
	pack_free(&p);
}

/* History slots: values written into the slots of touching pairs survive a rebuild of the
 * list; a slot of a pair that came apart reads zero. */
static int
on_mark(const struct contact *c, void *v)
{
	(void)v;
	c->hist[0] = (double)c->i + 1;
	c->hist[1] = (double)c->j;
	return 0;
}

static int
on_check(const struct contact *c, void *v)
{
	long *bad = v;

	if (c->hist[0] != (double)c->i + 1 || c->hist[1] != (double)c->j)
		(*bad)++;
	return 0;
}

/* Whether grains m and j are apart (the walk's test: squared distance at least (r_m + r_j)^2). */
static int
listed_apart(const struct pack *p, size_t m, size_t j)
{
	double d0 = p->x[3 * m] - p->x[3 * j], d1 = p->x[3 * m + 1] - p->x[3 * j + 1];
	double d2 = p->x[3 * m + 2] - p->x[3 * j + 2], sum = p->r[m] + p->r[j];

	return d0 * d0 + d1 * d1 + d2 * d2 >= sum * sum;
}

static void
test_history(gsl_rng *rng)
{
	struct pack p;
	struct contact_enum e;
	long bad = 0, calls;
	size_t i;

	random_pack(&p, rng, 400, 1e-4, 0.6, 0.02);
	contact_enum_init(&e, p.n, p.r, p.box, p.box + 3, NULL, 0.3e-4, 3);
	contact_enum_update(&e, p.x, 1);
	calls = contact_foreach(&e, p.x, CONTACT_TOUCHING, on_mark, NULL);
	/* a small move (the same contacts), then a rebuild */
	for (i = 0; i < 3 * p.n; i++)
		p.x[i] += 1e-12 * (gsl_rng_uniform(rng) - 0.5);
	contact_enum_update(&e, p.x, 1);
	contact_foreach(&e, p.x, CONTACT_TOUCHING, on_check, &bad);
	CHECK(calls > 0 && bad == 0, "history: %ld contacts keep their slots over a rebuild (%ld lost)", calls, bad);
	/* pull grain 0 away from everything: its slots are zeroed, and read zero later */
	p.x[0] += 1e-3;
	contact_enum_update(&e, p.x, 1);
	{
		size_t k;
		long nonzero = 0;
		contact_foreach(&e, p.x, CONTACT_TOUCHING, on_check, &bad);
		/* grain 0's row: its listed pairs, all apart now */
		for (k = e.nl.first[0]; k < e.nl.first[1]; k++) {
			const double *h = e.hpair[e.hcur] + 3 * k;
			nonzero += h[0] != 0 || h[1] != 0;
		}
		CHECK(nonzero == 0, "history: the slots of a grain moved apart read zero (%ld not)", nonzero);
		/* slots of listed pairs apart holding -0.0 or a stray value: the walk leaves them
		 * all bits zero, as an unconditional clear did (it looks before it stores) */
		{
			static const double zero[3];
			size_t m, apart = 0;

			for (m = 0; m < p.n; m++)
				for (k = e.nl.first[m]; k < e.nl.first[m + 1]; k++) {
					double *h;

					if (!listed_apart(&p, m, e.nl.nbr[k]))
						continue;
					h = e.hpair[e.hcur] + 3 * k;
					h[0] = -0.0, h[1] = apart % 2 ? 1e-300 : 0, h[2] = apart % 3 ? 0 : -1;
					apart++;
				}
			contact_foreach(&e, p.x, CONTACT_TOUCHING, on_check, &bad);
			for (nonzero = 0, m = 0; m < p.n; m++)
				for (k = e.nl.first[m]; k < e.nl.first[m + 1]; k++) {
					if (listed_apart(&p, m, e.nl.nbr[k]))
						nonzero += memcmp(e.hpair[e.hcur] + 3 * k, zero, sizeof zero) != 0;
				}
			CHECK(apart > 0 && nonzero == 0,
			    "history: -0.0 and stray values in the slots of listed pairs apart are cleared to zero bits "
			    "(%ld not, of %zu)", nonzero, apart);
		}
	}
	/* a wall's slot: marked while the grain touches the wall, zero once it is apart (the walk
	 * zeroes only slots that went to a callback, contacts.h's hwall_set), and zero again when
	 * the grain comes back: a new contact starts from an empty spring */
	{
		size_t g = p.n;
		double *hw, x0;

		for (i = 0; i < p.n && g == p.n; i++)
			if (p.x[3 * i] - p.box[0] < p.r[i])
				g = i;
		CHECK(g < p.n, "history: a grain touches the x-low wall");
		if (g < p.n) {
			long wrong = 0;
			hw = e.hwall + 3 * NWALLS * g;	/* wall 0 (x low) of grain g */
			x0 = p.x[3 * g];
			contact_foreach(&e, p.x, CONTACT_TOUCHING, on_mark, NULL);
			wrong += hw[0] != (double)g + 1;
			p.x[3 * g] = p.box[0] + 2 * p.r[g];
			contact_enum_update(&e, p.x, 1);
			contact_foreach(&e, p.x, CONTACT_TOUCHING, on_mark, NULL);
			wrong += hw[0] != 0 || hw[1] != 0;
			contact_foreach(&e, p.x, CONTACT_TOUCHING, on_mark, NULL);	/* apart twice: still zero */
			wrong += hw[0] != 0 || hw[1] != 0;
			p.x[3 * g] = x0;
			contact_enum_update(&e, p.x, 1);
			wrong += hw[0] != 0 || hw[1] != 0;	/* what the callback of the new contact will read */
			contact_foreach(&e, p.x, CONTACT_TOUCHING, on_mark, NULL);
			wrong += hw[0] != (double)g + 1;
			CHECK(wrong == 0, "history: a wall's slot is marked, reads zero apart, and zero when the contact "
			    "comes back (%ld wrong)", wrong);
		}
	}
	contact_enum_free(&e);
	pack_free(&p);
}

/* The law interface: Hertz through it equals the inlined fast path bit for bit; the linear
 * law's energy is sum k h^2 / 2 and its gradient agrees with central differences. */
static void
test_laws(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	struct contact_law lin = contact_law_linear, hertz_copy = contact_law_hertz_mindlin;
	double *x, *g, *g2, E1, E2, Ek = 0, dev = 0, gmax = 0;
	size_t i, n3, k;

	random_pack(&p, rng, 300, 1e-4, 0.6, 0.02);
	n3 = 3 * p.n;
	x = malloc(n3 * sizeof *x), g = malloc(n3 * sizeof *g), g2 = malloc(n3 * sizeof *g2);
	memcpy(x, p.x, n3 * sizeof *x);
	qs_init(&s, &p, 0.3);
	E1 = qs_energy(&s, x, g, NULL);
	s.law = &hertz_copy;	/* the same law, not the fast path's pointer: through the interface */
	E2 = qs_energy(&s, x, g2, NULL);
	/* the forces to the bit (the same operations, scattered in the same order); the energy
	 * sums the same terms, by blocks of grains on the fast path and in one running sum
	 * through the interface, which can differ by the rounding of reassociating s->ncontacts
	 * positive terms, at most ncontacts ulps (a pack where they happened to agree hid this) */
	CHECK(memcmp(g, g2, n3 * sizeof *g) == 0, "laws: Hertz through the interface gives the fast path's gradient to the bit");
	CHECK(fabs(E1 - E2) <= (double)s.ncontacts * DBL_EPSILON * E1 && E1 > 0,
	    "laws: and its energy to the rounding of the sum's order (Pi %.17g, %.17g, %zu contacts)", E1, E2, s.ncontacts);
	{	/* and its Hessian blocks, which the fast path assembles without the interface */
		struct qs_hessian H1, H2;
		int same;

		qs_hessian_init(&H1, p.n);
		qs_hessian_init(&H2, p.n);
		s.law = &contact_law_hertz_mindlin;
		qs_energy(&s, x, g, NULL);
		qs_hessian(&s, x, &H1);
		s.law = &hertz_copy;
		qs_hessian(&s, x, &H2);
		same = H1.np == H2.np && H1.np > 0 && memcmp(H1.diag, H2.diag, 9 * p.n * sizeof *H1.diag) == 0 &&
		    memcmp(H1.off, H2.off, 9 * H1.np * sizeof *H1.off) == 0 && memcmp(H1.pi, H2.pi, H1.np * sizeof *H1.pi) == 0 &&
		    memcmp(H1.pj, H2.pj, H1.np * sizeof *H1.pj) == 0;
		CHECK(same, "laws: Hertz's Hessian through the interface is the fast path's to the bit (%zu pair blocks)", H1.np);
		qs_hessian_free(&H1);
		qs_hessian_free(&H2);
	}
	lin.kn = 2e4;
	s.law = &lin;
	E2 = qs_energy(&s, x, g, NULL);
	{
		struct geo_contacts gc;
		contacts_init(&gc);
		contacts_find(&p, &gc);
		for (k = 0; k < gc.n; k++)
			Ek += 0.5 * lin.kn * gc.c[k].h * gc.c[k].h;
		contacts_free(&gc);
	}
	CHECK(unit_close(E2, Ek, 1e-12, 0), "laws: the linear law's Pi is sum k h^2 / 2 (%.12g, %.12g)", E2, Ek);
	for (i = 0; i < 40; i++) {
		size_t q = gsl_rng_uniform_int(rng, n3);
		double hstep = 1e-9 * p.r[q / 3], save = x[q], ep, em;
		x[q] = save + hstep;
		ep = qs_energy(&s, x, NULL, NULL);
		x[q] = save - hstep;
		em = qs_energy(&s, x, NULL, NULL);
		x[q] = save;
		/* central differences: error O(h^2) from the smooth part; the energy's rounding is
		 * 1e-16 Pi / h */
		dev = fmax(dev, fabs((ep - em) / (2 * hstep) - g[q]));
		gmax = fmax(gmax, fabs(g[q]));
	}
	qs_energy(&s, x, g, NULL);
	CHECK(dev <= 1e-5 * gmax + 1e-16 * fabs(E2) / (1e-9 * 1e-4) * 10, "laws: the linear law's gradient agrees with central differences (%.3g against %.3g)",
	    dev, gmax);
	CHECK(qs_term_named(&s, "normal") == &s.term[0] && qs_term_named(&s, "friction") == NULL,
	    "terms: the frictionless functional is the normal term alone");
	qs_free(&s);
	free(x), free(g), free(g2);
	pack_free(&p);
}

/* One contact's step input as the one-element interaction of the laws' DEM entry. */
static void
one_element(const struct contact_law *law, const struct law_dem_in *in, struct law_dem_elems *el)
{
	double vn = in->vr[0] * in->n[0] + in->vr[1] * in->n[1] + in->vr[2] * in->n[2];
	int a;

	el->m = 1;
	el->h[0] = in->h;
	el->vn[0] = vn;
	for (a = 0; a < 3; a++) {
		el->n[a] = in->n[a];
		el->vt[a] = in->vr[a] - vn * in->n[a];
	}
	el->meff = in->meff, el->dt = in->dt, el->zeta = law->zeta, el->kt_ratio = law->kt_ratio;
}

static double
law_step(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_in *in, double *hist,
    double ft[3], double *fel)
{
	struct law_dem_elems el;
	double fk[1];

	one_element(law, in, &el);
	return law->dem_interaction(law, lp, &el, hist, fk, ft, fel);
}

/* The laws' frozen tangential state and DEM force against their closed forms, for one
 * contact: Hertz-Mindlin k* = 8 a / Ct, M_max = 3 pi / 16 a mu P, DEM normal force at rest
 * 4/3 E* sqrt(R*) h^(3/2) and damping 2 zeta sqrt(m* k_n) v_n; the linear law k h, k_t =
 * kt_ratio k_n, no torsion.  Tolerance 1e-14 relative: the same expressions, reordered. */
static void
test_law_closed_forms(void)
{
	const struct contact_law *hm = &contact_law_hertz_mindlin, *ln = &contact_law_linear;
	struct law_pair lp = {5e10, 6e-5, 3e-11, 2e-11, 0.3, 1e5};
	struct law_tangent t;
	struct law_dem_in in = {2e-7, {0, 0, 1}, {0, 0, 0}, 3e-9, 1e-8};
	double hist[3] = {0, 0, 0}, ft[3], fel, fn, a = sqrt(lp.Rs * in.h), P = 1.5;
	double kn = 2 * lp.Es * sqrt(lp.Rs * in.h);

	hm->tangent(hm, &lp, in.h, P, &t);
	CHECK(unit_close(t.k, 8 * a / lp.Ct, 1e-14, 0) && unit_close(t.qmax, 0.3 * P, 1e-14, 0) &&
	    unit_close(t.kt, 16.0 / 3 * a * a * a / lp.Ctor, 1e-14, 0) &&
	    unit_close(t.mmax, 3 * M_PI / 16 * a * 0.3 * P, 1e-14, 0), "laws: Hertz-Mindlin's tangential state in closed form");
	fn = law_step(hm, &lp, &in, hist, ft, &fel);
	CHECK(unit_close(fn, 4.0 / 3 * lp.Es * sqrt(lp.Rs) * pow(in.h, 1.5), 1e-14, 0) && fel == fn && ft[0] == 0 &&
	    ft[1] == 0 && ft[2] == 0, "laws: Hertz DEM force at rest is 4/3 E* sqrt(R*) h^1.5 (%.6g N)", fn);
	in.vr[2] = -1e-3;	/* approaching: i moves towards j along -n */
	fn = law_step(hm, &lp, &in, hist, ft, &fel);
	CHECK(unit_close(fn - fel, 2 * hm->zeta * sqrt(in.meff * kn) * 1e-3, 1e-12, 0),
	    "laws: the viscous normal damping is 2 zeta sqrt(m* k_n) v_n (%.6g N)", fn - fel);
	in.vr[2] = 0;
	in.vr[0] = 1e-2;	/* sliding along x: spring k_t v dt, clamped at mu fn */
	hist[0] = hist[1] = hist[2] = 0;
	fn = law_step(hm, &lp, &in, hist, ft, &fel);
	CHECK(unit_close(-ft[0], fmin(hm->kt_ratio * kn * 1e-2 * in.dt, 0.3 * fn), 1e-12, 0),
	    "laws: the tangential spring gives k_t v dt below the Coulomb limit (%.6g N)", -ft[0]);
	ln->tangent(ln, &lp, in.h, P, &t);
	CHECK(t.k == ln->kt_ratio * lp.kn && t.qmax == 0.3 * P && t.kt == 0 && t.mmax == 0,
	    "laws: the linear law's tangential state is kt_ratio k_n, mu P, no torsion");
	in.vr[0] = 0;
	hist[0] = hist[1] = hist[2] = 0;
	fn = law_step(ln, &lp, &in, hist, ft, &fel);
	CHECK(unit_close(fn, lp.kn * in.h, 1e-14, 0), "laws: the linear DEM force at rest is k_n h (%.6g N)", fn);
}

/* The laws' DEM entry on interactions of several elements (spheroplates): m elements of equal
 * overlap and velocity carry m times one element's elastic force, with the damping of the
 * whole interaction at ratio zeta (each element's at m* / m: the sum is sqrt(m) times one
 * element's at m*), and a tangential spring m times as stiff; and Hertz-Mindlin's one-element
 * case is hertz_dem_force to the bit (the sphere pass inlines that one), over random states. */
static void
test_law_elements(gsl_rng *rng)
{
	const struct contact_law *laws[2] = {&contact_law_hertz_mindlin, &contact_law_linear};
	struct law_pair lp = {5e10, 6e-5, 3e-11, 2e-11, 0.3, 1e5};
	int q, k, bad = 0;

	for (q = 0; q < 2; q++) {
		const struct contact_law *law = laws[q];
		struct law_dem_in in = {2e-7, {0, 0, 1}, {0, 0, -1e-3}, 3e-9, 1e-8};
		struct law_dem_elems one, four;
		double h1[3] = {0, 0, 0}, h4[3] = {0, 0, 0}, ft1[3], ft4[3], fk[LAW_DEM_ELEMENTS], fel1, fel4, f1, f4;

		if (q == 1)	/* the linear law's k_n: elastic and damping forces of Hertz's order, so
				 * that f - fel is not lost to cancellation */
			in.h = 2e-5, in.vr[2] = -100;
		one_element(law, &in, &one);
		four = one;
		four.m = 4;
		for (k = 1; k < 4; k++)
			four.h[k] = one.h[0], four.vn[k] = one.vn[0];
		f1 = law->dem_interaction(law, &lp, &one, h1, fk, ft1, &fel1);
		f4 = law->dem_interaction(law, &lp, &four, h4, fk, ft4, &fel4);
		CHECK(unit_close(fel4, 4 * fel1, 1e-14, 0) && unit_close(f4 - fel4, 2 * (f1 - fel1), 1e-12, 0),
		    "laws: %s, 4 equal elements: 4 x the elastic force, 2 = sqrt(4) x the damping (%.6g, %.6g N)",
		    law->name, fel4, f4 - fel4);
		one.vn[0] = 0, one.vt[0] = 1e-4;
		for (k = 0; k < 4; k++)
			four.vn[k] = 0;
		four.vt[0] = 1e-4;
		h1[0] = h1[1] = h1[2] = h4[0] = h4[1] = h4[2] = 0;
		law->dem_interaction(law, &lp, &one, h1, fk, ft1, &fel1);
		law->dem_interaction(law, &lp, &four, h4, fk, ft4, &fel4);
		/* Hertz-Mindlin's tangential force is its spring's; the linear law adds a dashpot at
		 * the interaction's stiffness, sqrt(4) = 2 times one element's */
		if (q == 0) {
			CHECK(unit_close(ft4[0], 4 * ft1[0], 1e-14, 0),
			    "laws: %s, 4 elements: the tangential spring 4 x as stiff (%.6g against %.6g N)", law->name, ft4[0],
			    ft1[0]);
		} else {
			double spring = -law->kt_ratio * lp.kn * 1e-4 * in.dt, dash = -law_damping(law->zeta, in.meff,
			    law->kt_ratio * lp.kn) * 1e-4;

			CHECK(unit_close(ft1[0], spring + dash, 1e-12, 0) && unit_close(ft4[0], 4 * spring + 2 * dash, 1e-12, 0),
			    "laws: %s, 4 elements: the tangential spring 4 x as stiff, its dashpot 2 x (%.6g against %.6g N)",
			    law->name, ft4[0], ft1[0]);
		}
	}
	for (k = 0; k < 1000; k++) {
		struct law_dem_in in;
		struct law_dem_elems el;
		double ha[3], hb[3], fa[3], fb[3], ea, eb, xa, xb, fk[1];
		int a;

		in.h = 1e-7 * gsl_rng_uniform_pos(rng);
		for (a = 0; a < 3; a++) {
			in.n[a] = gsl_rng_uniform(rng) - 0.5;
			in.vr[a] = 1e-3 * (gsl_rng_uniform(rng) - 0.5);
			ha[a] = hb[a] = 1e-9 * (gsl_rng_uniform(rng) - 0.5);
		}
		{
			double nn = sqrt(in.n[0] * in.n[0] + in.n[1] * in.n[1] + in.n[2] * in.n[2]);
			for (a = 0; a < 3; a++)
				in.n[a] /= nn;
		}
		in.meff = 1e-9 * (1 + gsl_rng_uniform(rng)), in.dt = 1e-8;
		xa = hertz_dem_force(0.3, 0.9, &lp, &in, ha, fa, &ea);
		one_element(&contact_law_hertz_mindlin, &in, &el);
		el.zeta = 0.3, el.kt_ratio = 0.9;
		xb = hertz_dem_interaction(&lp, &el, hb, fk, fb, &eb);
		for (a = 0; a < 3; a++)
			bad += fa[a] != fb[a] || ha[a] != hb[a];
		bad += xa != xb || ea != eb;
	}
	CHECK(bad == 0, "laws: Hertz-Mindlin's one-element interaction is hertz_dem_force to the bit (1000 states, %d differ)",
	    bad);
}

/* The table of the laws: found by name and by a pack's contact-law key, the first row the
 * default; the pair setup's mu is the friction-coefficient rule's (pack_contact_mu), the
 * grain-grain coefficient for a pair and the wall's for a wall; the wall stress is the wall
 * force over twice a face's area. */
static void
test_law_table(gsl_rng *rng)
{
	struct pack p;
	struct law_pair lp;
	const struct contact_law *const *l;
	double lo[3] = {-1, 0, 2}, hi[3] = {3, 0.5, 4.5};
	size_t nl = 0;

	for (l = contact_laws; *l; l++) {	/* every row: found by its name and key, its policy complete */
		nl++;
		CHECK(contact_law_find((*l)->name) == *l && (!(*l)->pack_key || contact_law_find((*l)->pack_key) == *l) &&
		    (*l)->pair && (*l)->normal && (*l)->overlap && (*l)->coulomb && (*l)->tangent && (*l)->dem_interaction && (*l)->dem_units && (*l)->stiffest &&
		    (*l)->kappa && (*l)->kappa_stress && (*l)->history_force && (*l)->history_set && (*l)->stress_in_range &&
		    (*l)->history <= 8, "law table: %s is found by its name and key and answers every question", (*l)->name);
	}
	CHECK(nl >= 2 && contact_laws[0] == &contact_law_hertz_mindlin,
	    "law table: Hertz-Mindlin first (the default, a pack without the key's; %zu rows)", nl);
	CHECK(contact_law_find("hertz-mindlin") == &contact_law_hertz_mindlin && contact_law_find("hertz") ==
	    &contact_law_hertz_mindlin && contact_law_find("linear") == &contact_law_linear && !contact_law_find("hooke"),
	    "law table: found by name and by pack key, NULL for another");
	random_pack(&p, rng, 20, 1e-4, 0.5, 0.02);
	p.mu = 0.3, p.wall_mu = 0.1;
	CHECK(contact_law_of_pack(&p) == &contact_law_hertz_mindlin, "law table: a pack without contact-law is Hertz-Mindlin's");
	pack_set_meta(&p, "contact-law", "linear");
	CHECK(contact_law_of_pack(&p) == &contact_law_linear, "law table: contact-law linear");
	pack_set_meta(&p, "contact-law", "hertz");
	CHECK(contact_law_of_pack(&p) == &contact_law_hertz_mindlin, "law table: contact-law hertz");
	pack_set_meta(&p, "contact-law", "hooke");
	CHECK(contact_law_of_pack(&p) == NULL && strstr(msg_geterr(), "hooke"), "law table: an unknown key is an error (%s)",
	    msg_geterr());
	{	/* a tool's choice: its option over the pack's key, and the key it writes back */
		char names[256];

		contact_law_names(names, sizeof names);
		{	/* every row's name, in the table's order */
			const struct contact_law *const *t;
			const char *at = names;

			for (t = contact_laws; *t && at; t++)
				if ((at = strstr(at, (*t)->name)))
					at += strlen((*t)->name);
			CHECK(at != NULL, "law table: the names for an error message name every law (%s)", names);
		}
		CHECK(contact_law_choose(&p, "linear") == &contact_law_linear, "law choice: an option over the pack's key");
		CHECK(contact_law_choose(&p, NULL) == NULL && strstr(msg_geterr(), "hooke"), "law choice: else the pack's key");
		CHECK(contact_law_choose(&p, "nosuch") == NULL && strstr(msg_geterr(), "'nosuch'") &&
		    strstr(msg_geterr(), names), "law choice: an unknown name lists the laws (%s)", msg_geterr());
		CHECK(contact_law_claim(&p, &contact_law_linear) == 0 && !strcmp(pack_get_meta(&p, "contact-law"), "linear"),
		    "law claim: a pack of another law gets the law's key");
		CHECK(contact_law_claim(&p, &contact_law_hertz_mindlin) == 0 &&
		    !strcmp(pack_get_meta(&p, "contact-law"), "hertz"), "law claim: Hertz-Mindlin's pack key");
		pack_unset_meta(&p, "contact-law");
		CHECK(contact_law_claim(&p, &contact_law_hertz_mindlin) == 0 && !pack_get_meta(&p, "contact-law"),
		    "law claim: a pack without the key, Hertz-Mindlin's, stays without it");
		pack_set_meta(&p, "contact-law", "hooke");
	}
	for (l = contact_laws; *l; l++) {
		double Es, Rs;
		struct law_pack lk;

		law_pack_bind(*l, &p, &lk);
		(*l)->pair(*l, &lk, 3, 7, &lp);
		hertz_pair_moduli(&p, 3, 7, &Es, &Rs);
		CHECK(lp.mu == 0.3 && lp.mu == pack_contact_mu(&p, 7) && lp.Es == Es && lp.Rs == Rs,
		    "%s pair setup: a pair's mu, E*, R*", (*l)->name);
		(*l)->pair(*l, &lk, 3, PACK_WALL(WALL_ZHI), &lp);
		hertz_pair_moduli(&p, 3, PACK_WALL(WALL_ZHI), &Es, &Rs);
		CHECK(lp.mu == 0.1 && lp.mu == pack_contact_mu(&p, PACK_WALL(WALL_ZHI)) && lp.Es == Es && lp.Rs == p.r[3],
		    "%s pair setup: a wall's mu, E*, R* = r_i", (*l)->name);
	}
	CHECK(pack_wall_stress(lo, hi, 0, 5) == 5 / (2 * (0.5 * 2.5)) && pack_wall_stress(lo, hi, 1, 5) == 5 / (2 * (2.5 * 4)) &&
	    pack_wall_stress(lo, hi, 2, 5) == 5 / (2 * (4 * 0.5)), "wall stress: the force over twice a face's area");
	pack_free(&p);
}

/* Every law's normal term against its own derivatives (table-driven): the force P the
 * central difference of the energy, the stiffness k that of P, over overlaps 1e-8 to 1e-6
 * of a pair of E* 5e10 Pa, R* 6e-5 m (k_n 1e5 N/m for a spring law).  The step is 1e-4 h:
 * the central difference's relative error is d^2/6 times the third derivative over the
 * first: for Hertz (U ~ h^2.5) (1e-4)^2 x 1.5 x 0.5 / 6 = 1.25e-9 (measured 1.3e-9), for a
 * spring 0, above the rounding of U's difference, about 1e-16 U / (1e-4 h P) = 1e-12;
 * tolerance 1e-7.  And
 * the frozen tangential state within the Coulomb limit: 0 <= q_max <= mu P. */
static void
test_law_normal_fd(void)
{
	const struct contact_law *const *l;

	for (l = contact_laws; *l; l++) {
		const struct contact_law *law = *l;
		struct law_pair lp = {5e10, 6e-5, 3e-11, 2e-11, 0.3, 1e5};
		struct law_tangent t;
		double worst = 0, h;
		int bad_t = 0;

		for (h = 1e-8; h <= 1e-6; h *= 1.7) {
			double d = 1e-4 * h, P, k, Pp, Pm, kk, Up, Um;

			law->normal(law, &lp, h, &P, &k);
			Up = law->normal(law, &lp, h + d, &Pp, &kk);
			Um = law->normal(law, &lp, h - d, &Pm, &kk);
			worst = fmax(worst, fabs((Up - Um) / (2 * d) - P) / P);
			worst = fmax(worst, fabs((Pp - Pm) / (2 * d) - k) / k);
			law->tangent(law, &lp, h, P, &t);
			bad_t += !(t.qmax >= 0 && t.qmax <= 0.3 * P * (1 + 1e-15) && t.k >= 0 && t.kt >= 0 && t.mmax >= 0);
		}
		CHECK(worst < 1e-7, "%s: P = dU/dh and k = dP/dh by central differences (worst relative %.2g)", law->name, worst);
		{	/* overlap, normal's inverse, and the limits at a force (law_contact_limits):
			 * the tangent's at that overlap; a few roundings (Hertz: a cube root), 1e-14 */
			double inv = 0, lim = 0, qm, mm, P;

			for (h = 1e-8; h <= 1e-6; h *= 1.7) {
				law->normal(law, &lp, h, &P, NULL);
				inv = fmax(inv, fabs(law->overlap(law, &lp, P) - h) / h);
				law_contact_limits(law, &lp, P, &qm, &mm);
				law->tangent(law, &lp, h, P, &t);
				lim = fmax(lim, t.qmax > 0 ? fabs(qm - t.qmax) / t.qmax : fabs(qm));
				lim = fmax(lim, t.qmax > 0 ? fabs(law->coulomb(law, &lp, P) - t.qmax) / t.qmax :
				    fabs(law->coulomb(law, &lp, P)));
				lim = fmax(lim, t.mmax > 0 ? fabs(mm - t.mmax) / t.mmax : fabs(mm));
			}
			CHECK(inv < 1e-14 && lim < 1e-14 && law->overlap(law, &lp, 0) == 0,
			    "%s: overlap(P) inverts P(h) (%.2g), the limits at a force (and coulomb) are the tangent's (%.2g)",
			    law->name, inv, lim);
		}
		CHECK(bad_t == 0, "%s: the tangential state within the Coulomb limit, stiffnesses >= 0 (%d off)", law->name, bad_t);
		{	/* no force apart */
			double P = 1, k = 1, U = law->normal(law, &lp, -1e-9, &P, &k);
			CHECK(U == 0 && P == 0 && k == 0, "%s: no energy, force or stiffness at a gap", law->name);
		}
	}
}

/* Every law's history against its DEM force (table-driven: a new row is tested as it is
 * added): a step that slides (v_t != 0) loads the spring, a second at rest (v = 0: no
 * dashpot, the spring unchanged) gives the tangential force ft, which history_force must read
 * from the history; history_set of ft then gives a history that history_force reads back as
 * ft (the pack's Q0 lines, written and read).  On random interactions of 1-4 elements in the
 * engine's units.  Under Hertz-Mindlin the history is a displacement: reading it as a force
 * (the engine's old convention) misses by the spring's stiffness, about 1e3 here. */
static void
test_law_history(gsl_rng *rng)
{
	const struct contact_law *const *l;

	for (l = contact_laws; *l; l++) {
		const struct contact_law *law = *l;
		long bad = 0, loaded = 0;
		int trial;

		for (trial = 0; trial < 500; trial++) {
			struct law_pair lp = {1, 0.5 + gsl_rng_uniform(rng), 0, 0, 0.2 + 0.5 * gsl_rng_uniform(rng), 1};
			struct law_dem_elems in;
			double hist[8] = {0}, back[8] = {0}, fk[LAW_DEM_ELEMENTS], ft[3], Q[3], Q2[3], fel, nn = 0, err = 0, fm;
			int k, a;

			memset(&in, 0, sizeof in);
			in.m = 1 + (int)gsl_rng_uniform_int(rng, 4);
			in.meff = 0.5 + gsl_rng_uniform(rng), in.dt = 1e-2, in.zeta = 0.2, in.kt_ratio = 0.8;
			for (a = 0; a < 3; a++)
				in.n[a] = gsl_ran_gaussian(rng, 1), nn += in.n[a] * in.n[a];
			for (a = 0; a < 3; a++)
				in.n[a] /= sqrt(nn);
			for (k = 0; k < in.m; k++)
				in.h[k] = 0.01 * gsl_rng_uniform(rng);
			for (a = 0; a < 3; a++)	/* in the tangent plane */
				in.vt[a] = 0.01 * gsl_ran_gaussian(rng, 1);
			fm = in.vt[0] * in.n[0] + in.vt[1] * in.n[1] + in.vt[2] * in.n[2];
			for (a = 0; a < 3; a++)
				in.vt[a] -= fm * in.n[a];
			law->dem_interaction(law, &lp, &in, hist, fk, ft, &fel);
			memset(in.vt, 0, sizeof in.vt);
			law->dem_interaction(law, &lp, &in, hist, fk, ft, &fel);
			law->history_force(law, &lp, &in, hist, Q);
			law->history_set(law, &lp, &in, ft, back);
			law->history_force(law, &lp, &in, back, Q2);
			fm = sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
			loaded += fm > 0;
			for (a = 0; a < 3; a++)
				err = fmax(err, fmax(fabs(Q[a] - ft[a]), fabs(Q2[a] - ft[a])));
			if (err > 1e-12 * fmax(fm, 1e-300) && err > 0)
				bad++;
		}
		CHECK(bad == 0, "%s: the history carries the DEM's tangential force, written and read back (%ld of 500 off, %ld loaded)",
		    law->name, bad, loaded);
		CHECK(law->history > 0 ? loaded == 500 : loaded == 0, "%s: %u history doubles, %ld of 500 springs loaded",
		    law->name, law->history, loaded);
	}
}

/* The linear law's spring-dashpot element kernels against the arithmetic that
 * dem/engine.c's interaction_force writes out (copied here as it stands), bit for bit on
 * random states, in the plate engine's units (k_n = 1): the elements' normal forces and
 * elastic sums, then the tangential spring on force increments, dashpot and cap. */
static void
test_linear_elements(gsl_rng *rng)
{
	long bad = 0, capped = 0;
	int trial;

	for (trial = 0; trial < 2000; trial++) {
		double meff = 0.5 + gsl_rng_uniform(rng), zeta = 0.1 + 0.5 * gsl_rng_uniform(rng), kt_ratio = 0.5;
		double dt = 1e-2 * (0.5 + gsl_rng_uniform(rng)), mu = 0.6 * gsl_rng_uniform(rng);
		double n[3], vt[3], h0[3], h1[3], ft0[3], ft1[3], fsum0 = 0, fsum1 = 0, fel0 = 0, fel1 = 0, nn = 0, vn;
		int M = 1 + (int)gsl_rng_uniform_int(rng, 4), k, a;
		double gn0 = 2 * zeta * sqrt(meff / M), gn1 = law_damping(zeta, meff / M, 1.0), Kt = M * kt_ratio;

		for (a = 0; a < 3; a++)
			n[a] = gsl_ran_gaussian(rng, 1), nn += n[a] * n[a];
		for (a = 0; a < 3; a++)
			n[a] /= sqrt(nn);
		for (k = 0; k < M; k++) {
			double h = 0.02 * (gsl_rng_uniform(rng) - 0.2), f0, f1, e1;

			vn = 0.05 * gsl_ran_gaussian(rng, 1);
			/* engine.c */
			f0 = (h > 0 ? h : 0) - gn0 * vn;
			if (f0 < 0)
				f0 = 0;
			fel0 += h > 0 ? h : 0, fsum0 += f0;
			/* linear.h */
			f1 = linear_element_force(1.0, gn1, h, vn, &e1);
			fel1 += e1, fsum1 += f1;
		}
		vn = 0;
		for (a = 0; a < 3; a++) {
			vt[a] = 0.005 * gsl_ran_gaussian(rng, 1);
			h0[a] = 0.002 * gsl_ran_gaussian(rng, 1);
			vn += vt[a] * n[a];
		}
		for (a = 0; a < 3; a++)
			vt[a] -= vn * n[a], h1[a] = h0[a];
		{	/* engine.c */
			double tn = mu * fsum0, kv[3] = {Kt * vt[0], Kt * vt[1], Kt * vt[2]}, gt, fm;

			law_dem_spring(h0, n, kv, dt, 1.0, tn, ft0);
			gt = 2 * zeta * sqrt(meff * Kt);
			for (a = 0; a < 3; a++)
				ft0[a] -= gt * vt[a];
			fm = sqrt(ft0[0] * ft0[0] + ft0[1] * ft0[1] + ft0[2] * ft0[2]);
			if (fm > tn && fm > 0) {
				capped++;
				for (a = 0; a < 3; a++)
					ft0[a] *= tn / fm;
			}
		}
		linear_tangential_force(h1, n, vt, dt, Kt, law_damping(zeta, meff, Kt), law_coulomb_limit(mu, fsum1), ft1);
		if (fsum0 != fsum1 || fel0 != fel1 || memcmp(ft0, ft1, sizeof ft0) || memcmp(h0, h1, sizeof h0))
			bad++;
	}
	CHECK(bad == 0 && capped > 100 && capped < 1900, "linear.h: the element and tangential kernels give engine's bytes (%ld of 2000 "
	    "differ; %ld capped)", bad, capped);
}

/* The steppable minimiser: the loop of qs_minimize, to the bit; and moving grains between
 * iterations (qs_minimizer_moved) still ends in equilibrium. */
static void
test_steppable(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	struct qs_min_params mp;
	struct qs_min_report r1, r2;
	struct qs_minimizer *m;
	double *x1, *x2;
	size_t n3;
	int st, moves = 0;

	random_pack(&p, rng, 300, 1e-4, 0.75, 0.05);
	n3 = 3 * p.n;
	x1 = malloc(n3 * sizeof *x1), x2 = malloc(n3 * sizeof *x2);
	memcpy(x1, p.x, n3 * sizeof *x1);
	memcpy(x2, p.x, n3 * sizeof *x2);
	qs_min_params_default(&mp);
	mp.max_iter = 20000;
	qs_init(&s, &p, 0.3);
	qs_minimize(&s, x1, &mp, &r1);
	m = qs_minimizer_alloc(&s, &mp);
	qs_minimizer_set(m, x2);
	memset(&r2, 0, sizeof r2);
	while ((st = qs_minimizer_test(m, &r2)) == QS_MIN_CONTINUE)
		qs_minimizer_iterate(m);
	CHECK(memcmp(x1, x2, n3 * sizeof *x1) == 0 && r1.iter == r2.iter && r1.evals == r2.evals,
	    "steppable: the manual loop is qs_minimize to the bit (%ld iterations, %ld evaluations)", r2.iter, r2.evals);
	/* again, now knocking grain 5 by 1 % of its radius every 10 iterations, 4 times (every
	 * 50 left a pack that converges in 177 iterations with 3 knocks: the test's premise) */
	memcpy(x2, p.x, n3 * sizeof *x2);
	qs_minimizer_set(m, x2);
	while ((st = qs_minimizer_test(m, &r2)) == QS_MIN_CONTINUE) {
		qs_minimizer_iterate(m);
		if (moves < 4 && r2.iter % 10 == 9) {
			x2[15] += 0.01 * p.r[5];
			qs_minimizer_moved(m);
			moves++;
		}
	}
	CHECK(st == QS_MIN_SUCCESS && moves == 4 && r2.res_max <= mp.tol && s.ncontacts > p.n,
	    "steppable: moved grains between iterations, still converged (residual %.3g, %ld iterations, %zu contacts)",
	    r2.res_max, r2.iter, s.ncontacts);
	qs_minimizer_free(m);
	qs_free(&s);
	free(x1), free(x2);
	pack_free(&p);
}

/* A nan energy (here from a nan radius): the error slot says why (the tools printed
 * 'unknown error' for the minimisers' failures on it). */
static void
test_nan_energy(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s;
	double *x, E;

	random_pack(&p, rng, 50, 1e-4, 0.6, 0.02);
	x = malloc(3 * p.n * sizeof *x);
	memcpy(x, p.x, 3 * p.n * sizeof *x);
	qs_init(&s, &p, 0.3);
	p.r[1] = NAN;
	msg_seterr("%s", "");
	E = qs_energy(&s, x, NULL, NULL);
	CHECK(isnan(E) && strstr(msg_geterr(), "the energy is not a number"),
	    "nan energy (a nan radius): Pi %g, error slot '%s'", E, msg_geterr());
	qs_free(&s);
	free(x);
	pack_free(&p);
}

/* contacts_find_in through a kept enumerator with a skin, after the grains move a little
 * (the list not rebuilt), finds what a new enumerator finds, record for record; and the
 * history lines are matched the same way whether they are in the enumerator's order (the
 * merge a commit's lines take) or shuffled (the sorted keys). */
static void
test_find_in(gsl_rng *rng)
{
	struct pack p;
	struct contact_enum e;
	struct geo_contacts a, b;
	size_t i, k, diff = 0, hist_diff = 0, matched = 0;
	long rebuilds;

	random_pack(&p, rng, 500, 1e-4, 0.6, 0.02);
	contacts_init(&a);
	contacts_init(&b);
	CHECK(contact_enum_init(&e, p.n, p.r, p.box, p.box + 3, p.periodic, 0.3 * 1e-4, 0) == 0 &&
	    contact_enum_update(&e, p.x, 1) == 0, "find_in: enumerator built");
	rebuilds = e.rebuilds;
	for (i = 0; i < 3 * p.n; i++)
		p.x[i] += 1e-7 * (gsl_rng_uniform(rng) - 0.5);
	i = contacts_store(&p, 0) == 0;
	CHECK(i && p.nc > 0, "find_in: %zu history lines stored", p.nc);
	/* a few lines dropped: contacts without history, the merge must skip over them */
	for (k = 0; k + 7 < p.nc; k += 7)
		p.c[k].P0 = -1;
	for (i = k = 0; k < p.nc; k++)
		if (p.c[k].P0 >= 0)
			p.c[i++] = p.c[k];
	p.nc = i;
	CHECK(contacts_find(&p, &a) == 0 && contacts_find_in(&p, &e, &b) == 0, "find_in: both found");
	CHECK(e.rebuilds == rebuilds, "find_in: the kept list served without a rebuild");
	CHECK(a.n == b.n && a.n > 0, "find_in: %zu contacts, as a new enumerator's %zu", b.n, a.n);
	for (k = 0; k < a.n && k < b.n; k++) {
		diff += memcmp(&a.c[k], &b.c[k], sizeof a.c[k]) != 0;
		matched += a.c[k].hist >= 0;
	}
	CHECK(diff == 0 && matched == p.nc, "find_in: the same records (%zu differ), %zu of %zu lines matched", diff,
	    matched, p.nc);
	/* the lines shuffled, and one pair named j i: matched through the sorted keys */
	gsl_ran_shuffle(rng, p.c, p.nc, sizeof *p.c);
	for (k = 0; k < p.nc; k++)
		if (!PACK_IS_WALL(p.c[k].j)) {
			size_t t = p.c[k].i;
			p.c[k].i = (size_t)p.c[k].j;
			p.c[k].j = (long)t;
			break;
		}
	CHECK(contacts_find_in(&p, &e, &b) == 0, "find_in: shuffled history found");
	for (k = 0; k < a.n && k < b.n; k++) {
		long h = b.c[k].hist;
		const struct pack_contact *c = h >= 0 ? &p.c[h] : NULL;
		hist_diff += (a.c[k].hist >= 0) != (h >= 0) ||
		    (c && !((c->i == b.c[k].i && c->j == b.c[k].j) || ((long)c->i == b.c[k].j && c->j == (long)b.c[k].i)));
	}
	CHECK(hist_diff == 0, "find_in: shuffled lines matched to the same pairs (%zu differ)", hist_diff);
	/* a store that hands over what it found (a commit before the next settle pass, with the
	 * shuffled lines as the old history): the list contacts_find_in gives at the same
	 * positions, record for record and history index for index */
	for (k = 0; k < p.nc; k++)
		p.c[k].Q0[0] = 1e-3 * (double)(k + 1);
	CHECK(contacts_store_found(&p, &e, 1, &a) == 0 && contacts_find_in(&p, &e, &b) == 0,
	    "store_found: stored, then found again");
	for (diff = k = 0; k < a.n && k < b.n; k++)
		diff += memcmp(&a.c[k], &b.c[k], sizeof a.c[k]) != 0 || a.c[k].hist != (long)k;
	CHECK(a.n == b.n && a.n == p.nc && diff == 0, "store_found: %zu contacts as found again (%zu), %zu differ", a.n,
	    b.n, diff);
	contacts_free(&a);
	contacts_free(&b);
	contact_enum_free(&e);
	pack_free(&p);
}

/* contact_enum_prune: keep leaves pairs out of every list (here the pairs of odd i + j),
 * prepare runs before each build, and extra makes the list stale: a grain whose points may
 * have moved by half the skin beyond its centre does, a hair less does not. */
struct prune_probe {
	int prepared;
	double *extra;
	size_t n;
};

static int
keep_even(void *ctx, size_t i, size_t j, const double dx[3])
{
	(void)ctx, (void)dx;
	return (i + j) % 2 == 0;
}

static void
prepare_probe(void *ctx)
{
	struct prune_probe *pp = ctx;

	pp->prepared++;
	memset(pp->extra, 0, pp->n * sizeof *pp->extra);
}

static void
test_prune(gsl_rng *rng)
{
	struct pack p;
	struct contact_enum e;
	struct prune_probe probe;
	struct contact_prune pr;
	double skin = 0.3e-4;
	size_t i, k, odd = 0;
	long built;

	random_pack(&p, rng, 400, 1e-4, 0.6, 0.02);
	probe.n = p.n, probe.prepared = 0, probe.extra = calloc(p.n, sizeof *probe.extra);
	pr.keep = keep_even, pr.prepare = prepare_probe, pr.extra = probe.extra, pr.ctx = &probe;
	CHECK(contact_enum_init(&e, p.n, p.r, p.box, p.box + 3, p.periodic, skin, 0) == 0, "prune: enumerator made");
	contact_enum_prune(&e, &pr);
	contact_enum_update(&e, p.x, 0);
	for (i = 0; i < p.n; i++)
		for (k = e.nl.first[i]; k < e.nl.first[i + 1]; k++)
			odd += (i + e.nl.nbr[k]) % 2;
	CHECK(e.nl.npairs > 100 && odd == 0 && probe.prepared == 1,
	    "prune: the list holds only the pairs kept (%zu listed, %zu odd), prepared once", e.nl.npairs, odd);
	built = e.rebuilds;
	probe.extra[7] = skin / 2 * (1 - 1e-9);
	contact_enum_update(&e, p.x, 0);
	CHECK(e.rebuilds == built, "prune: a grain's extra motion below half the skin keeps the list");
	probe.extra[7] = skin / 2 * (1 + 1e-9);
	contact_enum_update(&e, p.x, 0);
	CHECK(e.rebuilds == built + 1 && probe.prepared == 2 && probe.extra[7] == 0,
	    "prune: above half the skin the list is rebuilt (prepared again, extra zeroed)");
	contact_enum_prune(&e, NULL);
	contact_enum_update(&e, p.x, 0);
	for (i = 0, odd = 0; i < p.n; i++)
		for (k = e.nl.first[i]; k < e.nl.first[i + 1]; k++)
			odd += (i + e.nl.nbr[k]) % 2;
	CHECK(odd > 0 && e.rebuilds == built + 2, "prune: removed, the next list holds every pair (%zu odd)", odd);
	contact_enum_free(&e);
	free(probe.extra);
	pack_free(&p);
}

/* A skin that follows the motion (contact_enum_skin_auto) finds what a fixed skin finds,
 * record for record, after every move: small moves keep the small first skin (a sixth of
 * the ceiling) and one list; moves of a few skins per update grow it to the ceiling. */
static void
test_skin_auto(gsl_rng *rng)
{
	struct pack p;
	struct contact_enum fix, au;
	struct geo_contacts a, b;
	size_t i, k, diff = 0, compared = 0;
	int step;
	double skin = 0.3 * 1e-4;
	long built = 0;

	random_pack(&p, rng, 500, 1e-4, 0.6, 0.02);
	contacts_init(&a);
	contacts_init(&b);
	CHECK(contact_enum_init(&fix, p.n, p.r, p.box, p.box + 3, p.periodic, skin, 0) == 0 &&
	    contact_enum_init(&au, p.n, p.r, p.box, p.box + 3, p.periodic, skin, 0) == 0, "skin auto: enumerators made");
	contact_enum_skin_auto(&au, skin);
	for (step = 0; step < 400; step++) {
		double u = step < 200 ? 1e-9 : 3e-6;	/* a hundredth, then a few skins (1/6 of 3e-5) */
		for (i = 0; i < 3 * p.n; i++)
			p.x[i] += u * (gsl_rng_uniform(rng) - 0.5);
		if (contacts_find_in(&p, &fix, &a) || contacts_find_in(&p, &au, &b))
			break;
		diff += a.n != b.n;
		for (k = 0; k < a.n && k < b.n; k++)
			diff += memcmp(&a.c[k], &b.c[k], sizeof a.c[k]) != 0;
		compared += a.n;
		if (step == 199) {
			CHECK(au.skin == skin / 6 && au.rebuilds == 1,
			    "skin auto: 200 small moves kept the first skin (%.3g of the ceiling) and list (%ld built)",
			    au.skin / skin, au.rebuilds);
			built = au.rebuilds;
		}
	}
	CHECK(step == 400 && diff == 0, "skin auto: the same records as a fixed skin after every move (%zu compared, %zu "
	    "differ)", compared, diff);
	CHECK(au.skin == skin && au.rebuilds > built + 2, "skin auto: large moves grew it to the ceiling (%.3g of it, %ld "
	    "lists)", au.skin / skin, au.rebuilds);
	contacts_free(&a);
	contacts_free(&b);
	contact_enum_free(&fix);
	contact_enum_free(&au);
	pack_free(&p);
}

/* Hertz's per-pair coefficients (functional.c, hertz_coefficients) follow the radii: after
 * grains grow (densify's rounds: contact_enum_radii_changed), an evaluation of the kept
 * system equals a new system's to the bit. */
static void
test_hertz_coefficients(gsl_rng *rng)
{
	struct pack p;
	struct qs_system s, s2;
	double *x, *g, *g2, E1, E2;
	size_t i, n3;

	random_pack(&p, rng, 300, 1e-4, 0.6, 0.02);
	n3 = 3 * p.n;
	x = malloc(n3 * sizeof *x), g = malloc(n3 * sizeof *g), g2 = malloc(n3 * sizeof *g2);
	memcpy(x, p.x, n3 * sizeof *x);
	qs_init(&s, &p, 0.3);
	qs_energy(&s, x, g, NULL);
	for (i = 0; i < p.n; i += 2)
		p.r[i] *= 1.01;
	contact_enum_radii_changed(&s.ce);
	E1 = qs_energy(&s, x, g, NULL);
	qs_init(&s2, &p, 0.3);
	E2 = qs_energy(&s2, x, g2, NULL);
	CHECK(E1 == E2 && E1 > 0 && memcmp(g, g2, n3 * sizeof *g) == 0,
	    "hertz coefficients: after grains grow, the kept system's Pi and gradient are a new system's to the bit (%.17g, %.17g)",
	    E1, E2);
	qs_free(&s);
	qs_free(&s2);
	free(x), free(g), free(g2);
	pack_free(&p);
}

/* contact_wrap, which skips nearbyint for a component under half the period, gives the
 * formula's bits: random components over three periods, and the edges (half a period and its
 * neighbours, the signed zeros, a whole period). */
static void
test_wrap(gsl_rng *rng)
{
	double L = 7.3, edge[] = {0.5 * 7.3, nextafter(0.5 * 7.3, 0), nextafter(0.5 * 7.3, 8), 0.0, -0.0, 7.3, 1e-300};
	long k, bad = 0, n = 0;
	int sgn;

	for (k = 0; k < 200000 + 2 * (long)(sizeof edge / sizeof *edge); k++) {
		double dx, want, got;

		if (k < 200000)
			dx = (3 * gsl_rng_uniform(rng) - 1.5) * L;
		else {
			sgn = k % 2 ? -1 : 1;
			dx = sgn * edge[(k - 200000) / 2];
		}
		want = dx - L * nearbyint(dx / L);
		got = dx;
		contact_wrap(&got, L);
		bad += memcmp(&want, &got, sizeof got) != 0;
		n++;
	}
	CHECK(bad == 0, "nearest image: contact_wrap gives dx - L nearbyint(dx / L) to the bit (%ld of %ld differ)", bad, n);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	static const int walls[3] = {0, 0, 0}, xz[3] = {1, 0, 1}, all[3] = {1, 1, 1};

	gsl_rng_set(rng, 11);
	test_enumerator(rng, walls, "six walls");
	test_enumerator(rng, xz, "periodic x and z");
	test_enumerator(rng, all, "periodic x y z");
	test_wrap(rng);
	test_history(rng);
	test_laws(rng);
	test_law_closed_forms();
	test_law_elements(rng);
	test_steppable(rng);
	test_nan_energy(rng);
	test_find_in(rng);
	test_skin_auto(rng);
	test_prune(rng);
	test_hertz_coefficients(rng);
	test_law_table(rng);
	test_law_history(rng);
	test_law_normal_fd();
	test_linear_elements(rng);
	gsl_rng_free(rng);
	return unit_summary();
}
