/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_measure: lib/analysis/measure.c and lib/contact/contacts.c on configurations whose answers are known in
 * closed form, and the Hertz closed forms of lib/contact/hertz.h against their own derivatives.
 *
 * The main configuration is a simple-cubic lattice of n^3 identical spheres of radius R at
 * spacing 2R - delta, between six walls that overlap the outer grains by the same delta.  The
 * wall modulus is chosen so that a grain-wall contact carries the same Hertz force as a
 * grain-grain one (E*_gw sqrt(R) = E*_gg sqrt(R/2)), so every grain is in exact equilibrium.
 * R and delta are powers of two, so every centre, distance and overlap is exact in binary and
 * the only rounding is in the force laws themselves (a few ulps). */
#include "contact/contacts.h"
#include "contact/hertz.h"
#include "analysis/measure.h"
#include "base/msg.h"
#include "base/quat.h"
#include "pack/pack.h"
#include "pack/shape.h"
#include "unit.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NL 4			/* grains per lattice edge */
#define R_ ldexp(1.0, -13)	/* 122 um */
#define DELTA ldexp(1.0, -20)	/* overlap 0.95 um, delta / R = 2^-7 */
#define E_ 7e10
#define NU 0.2

static size_t
lat(int i, int j, int k)
{
	return (size_t)i + NL * ((size_t)j + NL * (size_t)k);
}

static void
lattice(struct pack *p)
{
	double s = 2 * R_ - DELTA, first = R_ - DELTA;
	int i, j, k, a;

	pack_init(p);
	for (k = 0; k < NL; k++)
		for (j = 0; j < NL; j++)
			for (i = 0; i < NL; i++) {
				double x[3] = {first + i * s, first + j * s, first + k * s};
				pack_add_grain(p, (long)lat(i, j, k), x, R_, E_, NU, 2420);
			}
	for (a = 0; a < 3; a++) {
		p->box[a] = 0;
		p->box[a + 3] = (NL - 1) * s + 2 * first;
	}
	/* (1-nu_w^2)/E_w = (2 sqrt 2 - 1)(1-nu^2)/E makes E*_gw = E*_gg / sqrt 2 */
	p->wall_nu = NU;
	p->wall_E = E_ / (2 * sqrt(2.0) - 1);
	p->mu = 0.3;
	p->wall_mu = 0.5;
}

static void
test_lattice(void)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures m;
	unsigned *cnt;
	size_t k, n3 = (size_t)NL * NL * NL, ngg = 3 * (size_t)NL * NL * (NL - 1), ngw = 6 * (size_t)NL * NL;
	double L, Pgg, Pgw, sig, phi, Egg, Egw;
	int all6 = 1, a;

	lattice(&p);
	contacts_init(&gc);
	CHECK(measure_pack(&p, &gc, &m) == 0, "lattice: measure_pack");
	L = pack_box_length(p.box, 0);
	Egg = hertz_Estar(E_, NU, E_, NU);
	Egw = hertz_Estar(E_, NU, p.wall_E, p.wall_nu);
	Pgg = hertz_force(Egg, hertz_Rstar(R_, R_), DELTA);
	Pgw = hertz_force(Egw, R_, DELTA);
	/* the wall modulus was chosen to make these equal; only rounding (a few ulps) separates them */
	CHECK_CLOSE(Pgw, Pgg, 1e-14, "lattice: grain-wall and grain-grain Hertz forces agree");

	CHECK(m.contacts_gg == ngg, "lattice: %zu grain-grain contacts (want %zu)", m.contacts_gg, ngg);
	CHECK(m.contacts_gw == ngw, "lattice: %zu grain-wall contacts (want %zu)", m.contacts_gw, ngw);
	cnt = malloc(p.n * sizeof *cnt);
	measure_coordination(&p, &gc, cnt);
	CHECK(cnt[lat(1, 1, 1)] == 6 && cnt[lat(2, 1, 2)] == 6, "lattice: an interior grain has 6 contacts (%u)",
	    cnt[lat(1, 1, 1)]);
	for (k = 0; k < p.n; k++)
		all6 &= cnt[k] == 6;
	CHECK(all6 && cnt[lat(0, 0, 0)] == 6, "lattice: every grain, corners included (3 grains + 3 walls), has 6");
	free(cnt);
	/* (2 ngg + ngw) / N = (2 * 144 + 96) / 64 = 6 exactly */
	CHECK(m.coordination == (double)(2 * ngg + ngw) / (double)n3 && m.coordination == 6,
	    "lattice: mean coordination %.17g = (2 Ngg + Ngw) / N = 6", m.coordination);
	CHECK(m.coordination_nr == 6, "lattice: coordination without rattlers %.17g = 6", m.coordination_nr);
	CHECK(m.rattlers == 0 && m.under4 == 0, "lattice: no rattlers (%zu), none under 4 (%zu)", m.rattlers, m.under4);
	CHECK(m.rattler_min_contacts == 4, "lattice: no contact lines, the frictionless rule of 4 contacts");
	CHECK(m.grains == n3, "lattice: %zu grains", m.grains);

	/* porosity: the same expression evaluated once here; both sides round a handful of
	 * operations on numbers of order 1, so they agree to a few 1e-16 */
	phi = 1 - (double)n3 * (4.0 / 3.0 * M_PI * R_ * R_ * R_) / (L * L * L);
	CHECK_CLOSE(m.porosity, phi, 1e-14, "lattice: porosity = 1 - N (4/3 pi R^3) / V");
	CHECK(fabs(m.volume - L * L * L) <= 1e-15 * L * L * L, "lattice: volume = L^3");
	CHECK(m.overlap_max == DELTA / R_, "lattice: largest overlap / radius = delta / R = 2^-7 (%.17g)",
	    m.overlap_max);

	/* wall stress: NL^2 contacts per wall, each Pgw, over the wall area L^2 */
	CHECK(m.has_forces, "lattice: has forces");
	sig = (double)(NL * NL) * Pgw / (L * L);
	for (a = 0; a < 3; a++) {
		char name[64];
		/* sums of NL^2 equal terms and one division: a few ulps; 1e-13 leaves room */
		snprintf(name, sizeof name, "lattice: wall stress sig_%c%c = NL^2 P_hertz / L^2", 'x' + a, 'x' + a);
		CHECK_CLOSE(m.sig_wall[a], sig, 1e-13, name);
	}
	CHECK_CLOSE(m.sigma_c, sig, 1e-13, "lattice: sigma_c = tr(sig_wall) / 3");
	/* Love-Weber: sum of branch x force over V; in equilibrium the branch vectors of one
	 * row add up to L, so it equals the wall stress; 240 terms of similar size, so the
	 * rounding stays far below the 1e-12 asked for */
	for (a = 0; a < 3; a++) {
		char name[64];
		snprintf(name, sizeof name, "lattice: Love-Weber sig_lw_%c%c = wall stress", 'x' + a, 'x' + a);
		CHECK_CLOSE(m.sig_lw[a], m.sig_wall[a], 1e-12, name);
	}
	CHECK(m.sig_lw[3] == 0 && m.sig_lw[4] == 0 && m.sig_lw[5] == 0, "lattice: Love-Weber shear stresses are 0");
	/* a sum of 240 forces divided by 240: worst case 240 ulps, so 1e-13 */
	CHECK_CLOSE(m.P_mean, Pgg, 1e-13, "lattice: mean normal force = Hertz force");
	/* the largest of forces that differ from Pgg by a few ulps */
	CHECK_CLOSE(m.P_max, Pgg, 1e-14, "lattice: largest normal force = Hertz force");
	/* exact equilibrium: opposite forces cancel exactly between grains; a grain on a wall is
	 * left with Pgw - Pgg, a few ulps of the force */
	CHECK(m.residual_max < 1e-12, "lattice: residual %.3g < 1e-12", m.residual_max);
	CHECK(m.residual_mean < 1e-12, "lattice: mean unbalanced-force ratio %.3g < 1e-12", m.residual_mean);
	/* fabric: a third of the grain-grain normals along each axis, each exactly +-1 */
	CHECK(fabs(m.fabric[0] - 1.0 / 3) < 1e-15 && fabs(m.fabric[1] - 1.0 / 3) < 1e-15 &&
	    fabs(m.fabric[2] - 1.0 / 3) < 1e-15, "lattice: fabric diagonal = 1/3 (%.17g %.17g %.17g)", m.fabric[0],
	    m.fabric[1], m.fabric[2]);
	CHECK(m.fabric[3] == 0 && m.fabric[4] == 0 && m.fabric[5] == 0, "lattice: fabric off-diagonal = 0");
	CHECK(fabs(m.fabric_anisotropy) < 1e-12, "lattice: fabric anisotropy %.3g = 0", m.fabric_anisotropy);
	CHECK(isnan(m.sliding_ratio) && m.history == 0, "lattice: no history, sliding ratio absent (NaN)");
	contacts_free(&gc);
	pack_free(&p);
}

/* History lines on the lattice: |Q0| = mu P0 slides, |Q0| = mu P0 (1 - 1e-6) does not;
 * the wall contact uses the wall friction coefficient; a line whose pair is not in contact
 * is stale and does not count. */
static void
test_sliding(void)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures m;
	struct pack_contact c;
	double P0 = 0.25, total = 3.0 * NL * NL * (NL - 1) + 6.0 * NL * NL;

	lattice(&p);
	memset(&c, 0, sizeof c);
	c.P0 = P0;
	c.i = lat(0, 0, 0), c.j = (long)lat(1, 0, 0), c.Q0[1] = p.mu * P0;	/* sliding */
	pack_add_contact(&p, &c);
	c.Q0[1] = 0;
	c.i = lat(2, 0, 0), c.j = (long)lat(1, 0, 0), c.Q0[2] = p.mu * P0 * (1 - 1e-6);	/* sticking */
	pack_add_contact(&p, &c);
	c.Q0[2] = 0;
	c.i = lat(0, 0, 0), c.j = PACK_WALL(WALL_XLO), c.Q0[2] = -p.wall_mu * P0;	/* sliding on the wall */
	pack_add_contact(&p, &c);
	c.Q0[2] = 0;
	c.i = lat(3, 3, 3), c.j = PACK_WALL(WALL_YHI), c.Q0[0] = p.mu * P0;	/* below wall_mu P0: sticking */
	pack_add_contact(&p, &c);
	c.Q0[0] = 0;
	c.i = lat(0, 0, 0), c.j = (long)lat(3, 3, 3), c.Q0[0] = P0;	/* not in contact: stale */
	pack_add_contact(&p, &c);
	contacts_init(&gc);
	CHECK(measure_pack(&p, &gc, &m) == 0, "sliding: measure_pack");
	CHECK(m.history == 5 && m.stale_history == 1, "sliding: 5 history lines, 1 stale (%zu, %zu)", m.history,
	    m.stale_history);
	/* counts over all geometric contacts: 2 sliding of 240 */
	CHECK(m.sliding_ratio == 2 / total, "sliding: ratio %.17g = 2 / %g (|Q0| = mu P0 slides, (1 - 1e-6) does not)",
	    m.sliding_ratio, total);
	contacts_free(&gc);
	pack_free(&p);
}

static void
test_small(void)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures m;
	unsigned cnt[1];
	double x[3] = {5e-4, 5e-4, 5e-4};

	/* one grain alone in a large box */
	pack_init(&p);
	p.box[3] = p.box[4] = p.box[5] = 1e-3;
	p.wall_E = 7e12;
	pack_add_grain(&p, 0, x, 1e-4, E_, NU, 2420);
	contacts_init(&gc);
	CHECK(measure_pack(&p, &gc, &m) == 0, "isolated grain: measure_pack");
	CHECK(m.rattlers == 1 && m.under4 == 1 && m.coordination == 0 && !m.has_forces,
	    "isolated grain: a rattler, under 4, coordination 0, no forces");
	CHECK(m.coordination_nr == 0, "isolated grain: coordination without rattlers 0");

	/* the same grain pushed into a corner: three wall contacts */
	p.x[0] = p.x[1] = p.x[2] = 1e-4 - 1e-6;
	CHECK(measure_pack(&p, &gc, &m) == 0, "corner grain: measure_pack");
	measure_coordination(&p, &gc, cnt);
	CHECK(cnt[0] == 3 && m.contacts_gw == 3 && m.contacts_gg == 0, "corner grain: 3 wall contacts (%u)", cnt[0]);
	CHECK(m.under4 == 1 && m.rattlers == 1, "corner grain: under 4 and a rattler");
	CHECK(m.has_forces && m.P_max > 0, "corner grain: carries forces");

	/* a narrow box in x and y: four wall contacts, not under 4, not a rattler */
	p.box[3] = p.box[4] = 2e-4 - 2e-6;
	p.x[0] = p.x[1] = 1e-4 - 1e-6;
	p.x[2] = 5e-4;
	CHECK(measure_pack(&p, &gc, &m) == 0, "four walls: measure_pack");
	CHECK(m.contacts_gw == 4 && m.under4 == 0 && m.rattlers == 0 && m.coordination == 4,
	    "four walls: 4 contacts, not under 4, not a rattler");
	contacts_free(&gc);
	pack_free(&p);
}

/* The rattler rule: 4 contacts without friction, 2 when a contact line carries a tangential
 * force or couple.  A grain in a corner (3 wall contacts) is a rattler by the first, not by
 * the second; a grain with one contact is one by both; lines with P0 alone (densify's) leave
 * the pack frictionless. */
static void
test_rattler_rule(void)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures m;
	struct pack_contact c;
	double x[3] = {1e-4 - 1e-6, 1e-4 - 1e-6, 1e-4 - 1e-6};
	int w, st;

	pack_init(&p);
	p.box[3] = p.box[4] = p.box[5] = 1e-3;
	p.wall_E = 7e12;
	p.mu = p.wall_mu = 0.3;
	pack_add_grain(&p, 0, x, 1e-4, E_, NU, 2420);
	memset(&c, 0, sizeof c);
	c.P0 = 1;
	for (w = 0; w < 3; w++) {
		c.j = PACK_WALL(2 * w);	/* the low walls */
		pack_add_contact(&p, &c);
	}
	contacts_init(&gc);
	st = measure_pack(&p, &gc, &m);
	CHECK(st == 0 && m.rattler_min_contacts == 4 && m.rattlers == 1 && m.under4 == 1,
	    "rattler rule: lines with P0 alone, mu 0.3: frictionless, the corner grain (3 contacts) a rattler (rule %u)",
	    m.rattler_min_contacts);
	CHECK(measure_rattler_rule(&p) == 4, "rattler rule: measure_rattler_rule 4 without tangential forces");
	p.c[1].Q0[0] = 0.1;	/* on the y wall, along x */
	st = measure_pack(&p, &gc, &m);
	CHECK(st == 0 && m.rattler_min_contacts == 2 && m.rattlers == 0 && m.under4 == 1 && m.coordination_nr == 3,
	    "rattler rule: a line with Q0: frictional, the corner grain holds (rule %u, %zu rattlers, Z_nr %g)",
	    m.rattler_min_contacts, m.rattlers, m.coordination_nr);
	p.c[1].Q0[0] = 0, p.c[2].M0 = 1e-9;
	CHECK(measure_rattler_rule(&p) == 2, "rattler rule: a torsional couple M0 alone is friction too");
	/* one contact only: a rattler by either rule */
	p.x[1] = p.x[2] = 5e-4;
	st = measure_pack(&p, &gc, &m);
	CHECK(st == 0 && m.rattler_min_contacts == 2 && m.rattlers == 1 && m.coordination == 1,
	    "rattler rule: frictional, a grain on one wall is a rattler");
	contacts_free(&gc);
	pack_free(&p);
}

/* measure_sphere_box_volume on cases with closed forms.  The quadrature is at rounding
 * (measure.c: 1e-13 or better), so 1e-12 relative is asked, well inside the 1e-9 that the
 * bulk porosity needs. */
static void
test_sphere_box_volume(void)
{
	const double r = 3e-4, V = 4.0 / 3.0 * M_PI * r * r * r, inf = INFINITY;
	const double d[] = {0.3 * r, -0.45 * r, 0.9 * r, 1e-3 * r};
	double lo[3], hi[3], a, h, cap, v, sum;
	size_t k;
	int ax, o, b;

	lo[0] = lo[1] = lo[2] = -r, hi[0] = hi[1] = hi[2] = r;
	CHECK(measure_sphere_box_volume(r, lo, hi) == V, "sphere in box: the box touching the sphere holds it whole");
	lo[0] = -1.5 * r, hi[2] = 2 * r;
	CHECK(measure_sphere_box_volume(r, lo, hi) == V, "sphere in box: a sphere inside the box is whole");
	for (ax = 0; ax < 3; ax++) {
		char name[96];

		for (b = 0; b < 3; b++)
			lo[b] = -inf, hi[b] = inf;
		lo[ax] = 0;
		snprintf(name, sizeof name, "sphere in box: a plane through the centre (%c >= 0) leaves a hemisphere", 'x' + ax);
		CHECK_CLOSE(measure_sphere_box_volume(r, lo, hi), V / 2, 1e-12, name);
		for (k = 0; k < sizeof d / sizeof d[0]; k++) {
			/* a plane at distance d: the cap of height h = r - d, pi h^2 (3 r - h) / 3 */
			lo[ax] = d[k];
			h = r - d[k];
			snprintf(name, sizeof name, "sphere in box: a plane %c = %g r cuts the cap pi h^2 (3r - h)/3", 'x' + ax, d[k] / r);
			CHECK_CLOSE(measure_sphere_box_volume(r, lo, hi), M_PI * h * h * (3 * r - h) / 3, 1e-12, name);
		}
	}
	/* a cap x >= 0.8 r with a face y <= 0.75 r that crosses the sphere but not the cap (there
	 * |y| <= 0.6 r): two faces, so the quadrature, against the one-face closed form */
	for (b = 0; b < 3; b++)
		lo[b] = -inf, hi[b] = inf;
	lo[0] = 0.8 * r, hi[1] = 0.75 * r, h = 0.2 * r;
	CHECK_CLOSE(measure_sphere_box_volume(r, lo, hi), M_PI * h * h * (3 * r - h) / 3, 1e-12,
	    "sphere in box: the quadrature of two faces, one missing the cap, gives the cap");
	/* the eight octants about the centre: V/8 each (the sign of the corner does not matter) */
	for (o = 0; o < 8; o++) {
		char name[96];

		for (b = 0; b < 3; b++)
			if (o >> b & 1)
				lo[b] = 0, hi[b] = inf;
			else
				lo[b] = -inf, hi[b] = 0;
		snprintf(name, sizeof name, "sphere in box: the box corner at the centre, octant %d, holds V/8", o);
		CHECK_CLOSE(measure_sphere_box_volume(r, lo, hi), V / 8, 1e-12, name);
	}
	lo[0] = lo[1] = 0, lo[2] = -inf, hi[0] = hi[1] = hi[2] = inf;
	CHECK_CLOSE(measure_sphere_box_volume(r, lo, hi), V / 4, 1e-12, "sphere in box: an edge through the centre, V/4");
	/* the cube inscribed in the sphere (corners on it): (2a)^3, a = r / sqrt 3 */
	a = r / sqrt(3.0);
	lo[0] = lo[1] = lo[2] = -a, hi[0] = hi[1] = hi[2] = a;
	CHECK_CLOSE(measure_sphere_box_volume(r, lo, hi), 8 * a * a * a, 1e-12, "sphere in box: the inscribed cube, (2 r/sqrt 3)^3");
	/* a cube of half side a in [r/sqrt 2, r): its six caps are disjoint (x, y > a is outside
	 * the sphere), V - 6 caps; at r/sqrt 2 its edges touch the sphere */
	for (k = 0; k < 2; k++) {
		char name[96];

		a = k ? r / sqrt(2.0) : 0.8 * r;
		h = r - a, cap = M_PI * h * h * (3 * r - h) / 3;
		lo[0] = lo[1] = lo[2] = -a, hi[0] = hi[1] = hi[2] = a;
		snprintf(name, sizeof name, "sphere in box: a centred cube of half side %.4g r, V less six caps", a / r);
		CHECK_CLOSE(measure_sphere_box_volume(r, lo, hi), V - 6 * cap, 1e-12, name);
	}
	/* off-centre boxes: two boxes that split one add up to it, and turning the axes (the
	 * quadrature runs along z, the closed-form area across it) changes nothing */
	lo[0] = -0.7 * r, lo[1] = -0.2 * r, lo[2] = -0.9 * r, hi[0] = 0.5 * r, hi[1] = 0.95 * r, hi[2] = 0.35 * r;
	v = measure_sphere_box_volume(r, lo, hi);
	sum = 0;
	for (ax = 0; ax < 3; ax++) {
		double lo1[3], hi1[3], lo2[3], hi2[3];

		memcpy(lo1, lo, sizeof lo1), memcpy(hi1, hi, sizeof hi1), memcpy(lo2, lo, sizeof lo2), memcpy(hi2, hi, sizeof hi2);
		hi1[ax] = lo2[ax] = 0.1 * r;
		sum = fmax(sum, fabs(measure_sphere_box_volume(r, lo1, hi1) + measure_sphere_box_volume(r, lo2, hi2) - v) / v);
	}
	CHECK(sum <= 1e-12, "sphere in box: a box split in two along x, y or z: the halves add up (%.3g)", sum);
	{
		const double lor[3] = {lo[2], lo[0], lo[1]}, hir[3] = {hi[2], hi[0], hi[1]};

		CHECK_CLOSE(measure_sphere_box_volume(r, lor, hir), v, 1e-12, "sphere in box: the same box with its axes turned");
	}
	lo[0] = r, hi[0] = 2 * r;
	CHECK(measure_sphere_box_volume(r, lo, hi) == 0, "sphere in box: a box beside the sphere holds none of it");
}

/* The lattice of test_lattice with the walls moved out of reach by R, so that the grains on
 * the faces have fewer contacts (corner 3, edge 4, face 5, inside 6; coordination 4.5). */
static void
lattice_free(struct pack *p)
{
	int a;

	lattice(p);
	for (a = 0; a < 3; a++)
		p->box[a] -= R_, p->box[3 + a] += R_;
}

/* measure_bulk on constructed packs with closed forms. */
static void
test_bulk(void)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures m, m0;
	const double s = 2 * R_ - DELTA, first = R_ - DELTA, Vs = 4.0 / 3.0 * M_PI * R_ * R_ * R_;
	double phi_cell = 1 - Vs / (s * s * s);
	int a;

	contacts_init(&gc);
	/* the lattice pressed by its walls: margin 0 counts the grains' overlaps with the walls
	 * in, as the box porosity does */
	lattice(&p);
	a = measure_pack(&p, &gc, &m) || measure_bulk(&p, &gc, 0, &m);
	CHECK(a == 0 && m.bulk_porosity == m.porosity && m.bulk_coordination == 6 && m.bulk_grains == 64,
	    "bulk: lattice on its walls, margin 0: bulk_porosity %.17g = porosity %.17g, coordination 6", m.bulk_porosity,
	    m.porosity);
	pack_free(&p);
	lattice_free(&p);
	a = measure_pack(&p, &gc, &m);
	CHECK(a == 0 && m.coordination == 4.5 && m.contacts_gw == 0,
	    "bulk: lattice off the walls: coordination (2 * 144) / 64 = 4.5 (%.17g)", m.coordination);
	CHECK(!m.has_bulk && isnan(m.bulk_porosity) && isnan(m.bulk_coordination) && isnan(m.bulk_margin),
	    "bulk: measure_pack leaves the bulk absent");
	/* margin 0: the box itself, to the last bit */
	m0 = m;
	a = measure_bulk(&p, &gc, 0, &m0);
	CHECK(a == 0 && m0.has_bulk, "bulk: margin 0 measured");
	CHECK(m0.bulk_porosity == m0.porosity && m0.bulk_coordination == m0.coordination && m0.bulk_grains == 64 &&
	    m0.bulk_margin == 0, "bulk: margin 0: bulk_porosity %.17g = porosity, bulk_coordination %.17g = coordination, 64 grains",
	    m0.bulk_porosity, m0.bulk_coordination);
	/* the inner faces halfway between the outer layer and the next: the 2 x 2 x 2 block inside
	 * (6 contacts each) loses three caps of height delta/2 each, the 24 grains facing it across
	 * the faces bring one each in, so the inner box (2s)^3 holds 8 spheres: the unit cell's
	 * porosity 1 - (4/3 pi R^3) / s^3 */
	CHECK(measure_bulk(&p, &gc, R_ + first + s / 2, &m) == 0 && m.has_bulk, "bulk: lattice, margin to halfway between layers");
	CHECK_CLOSE(m.bulk_porosity, phi_cell, 1e-12, "bulk: lattice: bulk porosity = 1 - (4/3 pi R^3) / s^3");
	CHECK(m.bulk_grains == 8 && m.bulk_coordination == 6, "bulk: lattice: 8 grains inside (%zu), coordination 6 (%.17g)",
	    m.bulk_grains, m.bulk_coordination);
	CHECK(m.bulk_porosity < m.porosity && m.bulk_coordination > m.coordination,
	    "bulk: lattice: the bulk is denser than the box (%.6f < %.6f) and better connected", m.bulk_porosity, m.porosity);
	CHECK(m.bulk_box[0] == first + s / 2 && m.bulk_box[3] == p.box[3] - (R_ + first + s / 2),
	    "bulk: the inner box is the box less the margin");
	/* the default margin: one mean diameter, 2R: the inner faces at x = R, just past the
	 * outer layer's centres (R - delta), so the 2 x 2 x 2 block is inside */
	a = measure_bulk(&p, &gc, NAN, &m);
	CHECK(a == 0 && m.bulk_margin == 2 * R_ && m.bulk_grains == 8,
	    "bulk: default margin 2 r_mean = %.6g m (%zu grains centred inside)", m.bulk_margin, m.bulk_grains);
	/* margins that meet: no inner box, nothing made up */
	CHECK(measure_bulk(&p, &gc, pack_box_length(p.box, 0) / 2, &m) == 0 && !m.has_bulk && isnan(m.bulk_porosity) &&
	    isnan(m.bulk_coordination) && m.bulk_grains == 0, "bulk: a margin of half the box: no inner box, the bulk absent");
	a = measure_bulk(&p, &gc, -1e-6, &m);
	CHECK(a != 0, "bulk: a negative margin is refused (%s)", msg_geterr());
	CHECK(measure_bulk(&p, &gc, INFINITY, &m) != 0, "bulk: an infinite margin is refused");
	pack_free(&p);

	/* periodic along z (a period of 4 s: the top layer touches the bottom one), walls in x and
	 * y out of reach: no margin along z, so the inner box is 2s x 2s x 4s and holds 16 spheres
	 * (the caps cancel as above), the 2 x 2 columns inside have 6 contacts each; the box has
	 * 5 (4 x 4 layers: (4 * 2 + 8 * 3 + 4 * 4) / 16 = 3 in the plane, 2 along z) */
	lattice_free(&p);
	p.periodic[2] = 1;
	p.box[2] = first - s / 2, p.box[5] = first + 3.5 * s;
	a = measure_pack(&p, &gc, &m);
	CHECK(a == 0 && m.coordination == 5, "bulk: periodic z: box coordination 5 (%.17g)",
	    m.coordination);
	CHECK(measure_bulk(&p, &gc, R_ + first + s / 2, &m) == 0 && m.has_bulk && m.bulk_box[2] == p.box[2] &&
	    m.bulk_box[5] == p.box[5], "bulk: periodic z: no margin along z");
	CHECK_CLOSE(m.bulk_porosity, phi_cell, 1e-12, "bulk: periodic z: bulk porosity = 1 - (4/3 pi R^3) / s^3");
	CHECK(m.bulk_grains == 16 && m.bulk_coordination == 6, "bulk: periodic z: 16 grains inside (%zu), coordination 6 (%.17g)",
	    m.bulk_grains, m.bulk_coordination);
	/* a margin that would empty a walled axis but for z's: still no inner box */
	CHECK(measure_bulk(&p, &gc, pack_box_length(p.box, 0), &m) == 0 && !m.has_bulk, "bulk: periodic z, margins meeting in x: absent");
	for (a = 0; a < 3; a++)
		p.periodic[a] = 1;
	CHECK(measure_bulk(&p, &gc, 1, &m) == 0 && m.has_bulk && m.bulk_porosity == m.porosity,
	    "bulk: periodic on every axis: no walls, the bulk is the box whatever the margin");
	contacts_free(&gc);
	pack_free(&p);
}

static void
test_hertz(void)
{
	static const double hs[] = {1e-10, 1e-8, 1e-7, 1e-6, 3e-6};
	double Es = hertz_Estar(7e10, 0.2, 1e11, 0.15), Rs = hertz_Rstar(1e-4, 7e-5);
	size_t k;

	CHECK_CLOSE(Rs, 1 / (1 / 1e-4 + 1 / 7e-5), 1e-15, "hertz: R* = (1/Ri + 1/Rj)^-1");
	CHECK_CLOSE(Es, 1 / ((1 - 0.04) / 7e10 + (1 - 0.0225) / 1e11), 1e-15, "hertz: E* = ((1-nu_i^2)/E_i + ...)^-1");
	CHECK(hertz_force(Es, Rs, 0) == 0 && hertz_force(Es, Rs, -1e-6) == 0 && hertz_energy(Es, Rs, -1e-6) == 0 &&
	    hertz_stiffness(Es, Rs, -1e-6) == 0 && hertz_overlap(Es, Rs, 0) == 0, "hertz: no overlap, no force");
	for (k = 0; k < sizeof hs / sizeof hs[0]; k++) {
		double h = hs[k], e = 1e-5 * h, fd, P = hertz_force(Es, Rs, h);
		char name[96];

		/* Central differences with step e = 1e-5 h.  Truncation: U'''e^2/6 relative to
		 * U' = P is (e/h)^2 / 8 = 1.25e-11 for U ~ h^5/2 (and (e/h)^2 / 24 for P ~ h^3/2);
		 * rounding: 2^-53 U / (e P) = 2^-53 (2/5) h / e ~ 1e-11.  1e-9 is 50 times both. */
		fd = (hertz_energy(Es, Rs, h + e) - hertz_energy(Es, Rs, h - e)) / (2 * e);
		snprintf(name, sizeof name, "hertz: P = dU/dh at h = %g", h);
		CHECK_CLOSE(P, fd, 1e-9, name);
		fd = (hertz_force(Es, Rs, h + e) - hertz_force(Es, Rs, h - e)) / (2 * e);
		snprintf(name, sizeof name, "hertz: stiffness = dP/dh at h = %g", h);
		CHECK_CLOSE(hertz_stiffness(Es, Rs, h), fd, 1e-9, name);
		/* a cube root, a square root and a few products: under ten ulps */
		snprintf(name, sizeof name, "hertz: overlap(force(h)) = h at h = %g", h);
		CHECK_CLOSE(hertz_overlap(Es, Rs, P), h, 1e-14, name);
		snprintf(name, sizeof name, "hertz: stiffness = 2 E* sqrt(R* h) at h = %g", h);
		CHECK_CLOSE(hertz_stiffness(Es, Rs, h), 2 * Es * sqrt(Rs * h), 1e-15, name);
	}
}

/* A pack of n plates of spheroradius r and side L on a line (centres distinct; measure_plates
 * looks at shapes only), orientations set by the caller. */
static void
plate_pack(struct pack *p, size_t n, double r, double L)
{
	size_t i;

	pack_init(p);
	p->box[3] = p->box[4] = p->box[5] = 1;
	pack_set_shapes(p);
	for (i = 0; i < n; i++) {
		double x[3] = {(double)(i + 1) / (double)(n + 1), 0.5, 0.5};
		pack_add_grain(p, (long)i + 1, x, r, E_, NU, 2420);
		pack_set_grain_shape(p, i, L, p->q + 4 * i);
	}
}

/* The director d is the unit vector w (|d - w| within tol). */
static int
is_axis(const double d[3], double x, double y, double z, double tol)
{
	return fabs(d[0] - x) <= tol && fabs(d[1] - y) <= tol && fabs(d[2] - z) <= tol;
}

/* The plate measures on closed-form cases.  Q is a sum of n exact dyads divided by n and
 * one eigensolve of a 3 x 3 matrix: a few ulps, so 1e-14 on S and the director. */
static void
test_plates(void)
{
	struct pack p;
	struct plate_measures m;
	double q[4], R[9];
	size_t i;

	/* every normal along z: S = 1, director z */
	plate_pack(&p, 10, 2e-5, 1e-4);
	CHECK(measure_plates(&p, SHAPE_R_EDGE, &m) == 0 && m.plates == 10 && m.grains == 10, "plates: 10 plates counted");
	CHECK(fabs(m.nematic - 1) <= 1e-14 && is_axis(m.director, 0, 0, 1, 1e-14),
	    "nematic: every normal along z: S = %.17g, director (%g, %g, %g)", m.nematic, m.director[0], m.director[1],
	    m.director[2]);
	/* monodisperse: one platyness, edge and corner readings; min and max absent */
	CHECK_CLOSE(m.eta_mean, 5e-5 / 7e-5, 1e-15, "plates: edge platyness (R - r)/R, R = r + L/2");
	CHECK_CLOSE(m.aspect_mean, 7e-5 / 2e-5, 1e-15, "plates: edge aspect ratio R/r");
	CHECK(isnan(m.eta_min) && isnan(m.eta_max) && isnan(m.aspect_min) && isnan(m.aspect_max),
	    "plates: monodisperse, no platyness min and max");
	CHECK_CLOSE(m.packing_fraction, 10 * shape_volume(2e-5, 1e-4), 1e-15, "plates: packing fraction with the plates' volume");
	/* ten equal values summed and divided: a few ulps; sum2 - sum^2/n cancels to ~1e-24 */
	CHECK(m.porosity == 1 - m.packing_fraction && unit_close(m.side_mean, 1e-4, 1e-15, 0) && m.side_std < 1e-15 &&
	    unit_close(m.r_mean, 2e-5, 1e-15, 0) && m.side_min == 1e-4 && m.side_max == 1e-4,
	    "plates: porosity, side and r statistics (side %.17g sd %.3g, r %.17g)", m.side_mean, m.side_std, m.r_mean);
	measure_plates(&p, SHAPE_R_CORNER, &m);
	CHECK_CLOSE(m.eta_mean, (1e-4 / M_SQRT2) / (2e-5 + 1e-4 / M_SQRT2), 1e-15, "plates: corner platyness, R = r + L/sqrt(2)");
	/* all turned by 120 degrees about (1, 1, 1): z goes to x; and q -> -q changes nothing */
	for (i = 0; i < p.n; i++) {
		q[0] = q[1] = q[2] = q[3] = i % 2 ? 0.5 : -0.5;
		pack_set_grain_shape(&p, i, 1e-4, q);
	}
	measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(fabs(m.nematic - 1) <= 1e-14 && is_axis(m.director, 1, 0, 0, 1e-14),
	    "nematic: normals R(q) e3 = x for q = +-(1, 1, 1, 1)/2: S = %.17g, director (%g, %g, %g)", m.nematic,
	    m.director[0], m.director[1], m.director[2]);
	/* every normal along (1, 1, 1)/sqrt(3), from q turning e3 onto it; director of positive
	 * sign whatever the sign of q's eigenvector */
	for (i = 0; i < p.n; i++) {
		double w[3] = {1 / sqrt(3.0), 1 / sqrt(3.0), 1 / sqrt(3.0)}, ax[3] = {-w[1], w[0], 0}, c = w[2];
		double half = acos(c) / 2, s = sin(half) / sqrt(ax[0] * ax[0] + ax[1] * ax[1]);
		q[0] = cos(half), q[1] = s * ax[0], q[2] = s * ax[1], q[3] = 0;
		if (i % 2)
			q[0] = -q[0], q[1] = -q[1], q[2] = -q[2];
		pack_set_grain_shape(&p, i, 1e-4, q);
	}
	quat_to_matrix(q, R);
	measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(fabs(m.nematic - 1) <= 1e-14 && is_axis(m.director, 1 / sqrt(3.0), 1 / sqrt(3.0), 1 / sqrt(3.0), 1e-14),
	    "nematic: every normal along (1, 1, 1)/sqrt(3) (R(q) e3 = (%g, %g, %g)): S = %.17g, director (%.15g, %.15g, %.15g)",
	    R[2], R[5], R[8], m.nematic, m.director[0], m.director[1], m.director[2]);
	pack_free(&p);

	/* three normals along z, one along x: <n n> = diag(1/4, 0, 3/4), Q = diag(-1/8, -1/2, 5/8) */
	plate_pack(&p, 4, 2e-5, 1e-4);
	q[0] = q[2] = 1 / M_SQRT2, q[1] = q[3] = 0;	/* 90 degrees about y: e3 -> x */
	pack_set_grain_shape(&p, 2, 1e-4, q);
	measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(fabs(m.nematic - 0.625) <= 1e-14 && is_axis(m.director, 0, 0, 1, 1e-14),
	    "nematic: 3 normals z, 1 x: S = 5/8 (%.17g), director z", m.nematic);
	/* a sphere among them: counted in the statistics, not in the nematic order */
	pack_add_grain(&p, 99, (const double[3]){0.5, 0.9, 0.5}, 5e-5, E_, NU, 2420);
	measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(m.plates == 4 && m.grains == 5 && fabs(m.nematic - 0.625) <= 1e-14, "nematic: a sphere (side 0) has no normal: 4 plates of 5 grains");
	CHECK(m.eta_min == 0 && m.aspect_min == 1 && fabs(m.eta_max - m.eta_mean * 1.25) <= 1e-15 && m.side_min == 0 && m.r_max == 5e-5,
	    "plates: a sphere is eta 0, aspect 1, side 0 in the statistics");
	pack_free(&p);

	/* normals z, -y and x (pack-format.md's example): <n n> = I/3, Q = 0 */
	plate_pack(&p, 3, 2e-5, 1e-4);
	pack_set_grain_shape(&p, 1, 1e-4, (const double[4]){1 / M_SQRT2, 1 / M_SQRT2, 0, 0});
	pack_set_grain_shape(&p, 2, 1e-4, (const double[4]){0.5, 0.5, 0.5, 0.5});
	measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(fabs(m.nematic) <= 1e-15, "nematic: normals z, -y, x: S = 0 (%.3g)", m.nematic);
	pack_free(&p);

	i = (size_t)measure_nematic(NULL, 0, &m.nematic, m.director);
	CHECK(i != 0, "measure_nematic: no vectors is an error (%s)", msg_geterr());
}

/* Isotropic orientations: N uniformly random rotations (quat_from_uniform) give normals
 * uniform on the sphere.  Each (3 n n - I)/2 is a traceless symmetric matrix with mean 0 and
 * E[X:X] = (9 - 6 + 3)/4 = 3/2, isotropic over the 5 dimensions of such matrices, so by the
 * central limit theorem Q:Q = (3/(2N)) chi2_5/5.  The largest eigenvalue of a traceless Q
 * lies between sqrt(Q:Q/6) (eigenvalues a, a, -2a) and sqrt(2 Q:Q/3) (2a, -a, -a), so
 * S sqrt(N) is of order 1 (its mean is 0.80, sd 0.29, by simulation), never 0 and never
 * growing with N.  The band 0.1 < S sqrt(N) < 5: above it needs chi2_5 > 125 (probability
 * 1e-24), below it chi2_5 < 0.2 (1e-3); the seed is fixed, so the check is deterministic,
 * and the band is wide enough to hold for another seed or RNG.  A wrong normal (a row of
 * R instead of a column, say) would still look isotropic here: the closed-form cases of
 * test_plates catch that. */
static void
test_nematic_random(void)
{
	const size_t N = 20000;
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct pack p;
	struct plate_measures m;
	double q[4];
	size_t i;

	gsl_rng_set(rng, 1);
	plate_pack(&p, N, 2e-5, 1e-4);
	for (i = 0; i < N; i++) {
		double u1 = gsl_rng_uniform(rng), u2 = gsl_rng_uniform(rng), u3 = gsl_rng_uniform(rng);
		quat_from_uniform(u1, u2, u3, q);
		pack_set_grain_shape(&p, i, 1e-4, q);
	}
	CHECK(measure_plates(&p, SHAPE_R_EDGE, &m) == 0 && m.plates == N, "nematic: 20000 random orientations measured");
	CHECK(m.nematic * sqrt((double)N) > 0.1 && m.nematic * sqrt((double)N) < 5,
	    "nematic: 20000 random orientations: S = %.4g, S sqrt(N) = %.3f in (0.1, 5): isotropic",
	    m.nematic, m.nematic * sqrt((double)N));
	pack_free(&p);
	gsl_rng_free(rng);
}

/* The interaction measures on closed-form cases: a plate face-down between two walls, two
 * plates face to face with a tangential force on their contact line, and the same pair across
 * a periodic boundary.  Each is a sum of a few products in SI, so 1e-12 relative (ulps). */
static void
test_plate_contacts(void)
{
	const double r = 3e-8, L = 6e-8, h = 1e-9, kn = 1.5e3, A = 4e-7;
	const double up[4] = {1, 0, 0, 0};
	struct pack p;
	struct plate_measures m;
	struct pack_contact c = {0, 1, 0, {2e-7, 0, 0}, 0};
	double ell = 2 * r - h, V;
	int i;

	/* face-down between the z walls, each pressing with four corners of overlap h */
	pack_init(&p);
	p.box[3] = p.box[4] = A, p.box[5] = 2 * (r - h);
	pack_set_shapes(&p);
	pack_add_grain(&p, 1, (const double[3]){A / 2, A / 2, r - h}, r, E_, NU, 2700);
	pack_set_grain_shape(&p, 0, L, up);
	pack_set_meta(&p, "contact-law", "linear");	/* a plate pack of the linear law */
	pack_set_meta(&p, "kn", "1.5e3");
	i = measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(i == 0, "plate contacts: measured");
	CHECK(m.contacts_gw == 2 && m.contacts_gg == 0 && m.elements == 8 && m.by_elements[2] == 2,
	    "plate contacts: squeezed plate has 2 wall interactions of 4 elements (%zu, %zu, %zu)", m.contacts_gw,
	    m.contacts_gg, m.elements);
	CHECK(m.coordination == 2 && m.floating == 0 && m.elements_per_interaction == 4,
	    "plate contacts: coordination 2 (%g), not floating", m.coordination);
	CHECK_CLOSE(m.sig_wall[2], 4 * kn * h / (A * A), 1e-12, "plate contacts: wall stress 4 k_n h / area");
	CHECK_CLOSE(m.sig_lw[2], 4 * kn * h / (A * A), 1e-12, "plate contacts: Love-Weber = wall stress in equilibrium");
	CHECK(m.sig_wall[0] == 0 && fabs(m.sig_lw[0]) <= 1e-12 * m.sig_lw[2] && m.residual_mean <= 1e-12,
	    "plate contacts: no lateral stress, balanced (residual %g)", m.residual_mean);
	/* without the stiffness: counts, no forces */
	pack_set_meta(&p, "contact-law", "linear");	/* a plate pack of the linear law */
	pack_set_meta(&p, "kn", "none");
	measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(m.contacts_gw == 2 && !m.has_forces && isnan(m.sig_wall[2]) && isnan(m.sig_lw[2]),
	    "plate contacts: no meta kn, counts but no stresses");
	/* a periodic axis has no wall stress */
	pack_set_meta(&p, "contact-law", "linear");	/* a plate pack of the linear law */
	pack_set_meta(&p, "kn", "1.5e3");
	p.periodic[0] = 1;
	p.box[3] = 4 * A;
	measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(isnan(m.sig_wall[0]) && m.sig_wall[2] > 0, "plate contacts: periodic x, no sig_xx (%g)", m.sig_wall[0]);
	pack_free(&p);

	/* two plates face to face along z, overlap h over the whole face, in a box too big to
	 * touch; the contact line carries a tangential force Q on grain 0 along x */
	pack_init(&p);
	p.box[3] = p.box[4] = p.box[5] = A;
	V = A * A * A;
	pack_set_shapes(&p);
	pack_add_grain(&p, 1, (const double[3]){A / 2, A / 2, A / 2 + ell / 2}, r, E_, NU, 2700);
	pack_add_grain(&p, 2, (const double[3]){A / 2, A / 2, A / 2 - ell / 2}, r, E_, NU, 2700);
	pack_set_grain_shape(&p, 0, L, up);
	pack_set_grain_shape(&p, 1, L, up);
	pack_set_meta(&p, "contact-law", "linear");	/* a plate pack of the linear law */
	pack_set_meta(&p, "kn", "1.5e3");
	pack_add_contact(&p, &c);
	i = measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(i == 0 && m.contacts_gg == 1 && m.contacts_gw == 0 && m.elements == 4,
	    "plate contacts: face-face pair, one interaction of 4 elements (%zu)", m.elements);
	CHECK(m.coordination == 1 && m.floating == 2 && m.floating_fraction == 1,
	    "plate contacts: one interaction each: both floating (Z = %g)", m.coordination);
	CHECK_CLOSE(m.sig_lw[2], ell * 4 * kn * h / V, 1e-12, "plate contacts: Love-Weber zz = branch x 4 k_n h / V");
	CHECK_CLOSE(m.sig_lw[4], 0.5 * ell * c.Q0[0] / V, 1e-12, "plate contacts: Love-Weber xz from the line's Q");
	CHECK_CLOSE(m.force_mean, 4 * kn * h, 1e-12, "plate contacts: normal force of the interaction, 4 k_n h");
	CHECK_CLOSE(m.residual_mean, 1, 1e-12, "plate contacts: two grains pushed apart: residual |F| / |F| = 1");
	pack_free(&p);

	/* the pair across the periodic z boundary: one near the floor, one near the ceiling, their
	 * nearest images ell apart (the box holds three interaction distances, as it must) */
	pack_init(&p);
	p.box[3] = p.box[4] = p.box[5] = 1.5 * A;
	p.periodic[2] = 1;
	V = 1.5 * A * 1.5 * A * 1.5 * A;
	pack_set_shapes(&p);
	pack_add_grain(&p, 1, (const double[3]){0.75 * A, 0.75 * A, ell / 4}, r, E_, NU, 2700);
	pack_add_grain(&p, 2, (const double[3]){0.75 * A, 0.75 * A, 1.5 * A - 3 * ell / 4}, r, E_, NU, 2700);
	pack_set_grain_shape(&p, 0, L, up);
	pack_set_grain_shape(&p, 1, L, up);
	pack_set_meta(&p, "contact-law", "linear");	/* a plate pack of the linear law */
	pack_set_meta(&p, "kn", "1.5e3");
	i = measure_plates(&p, SHAPE_R_EDGE, &m);
	CHECK(i == 0 && m.contacts_gg == 1 && m.contacts_gw == 0 && m.elements == 4,
	    "plate contacts: face-face pair across the periodic z boundary (%zu elements)", m.elements);
	CHECK_CLOSE(m.sig_lw[2], ell * 4 * kn * h / V, 1e-12, "plate contacts: periodic pair, Love-Weber zz from the nearest image");
	CHECK(isnan(m.sig_wall[2]) && fabs(m.sig_lw[4]) <= 1e-12 * m.sig_lw[2], "plate contacts: periodic z, no sig_zz, no shear");
	pack_free(&p);
}

/* measure_grain_forces, grain by grain.  The lattice: every grain 6 contacts, each carrying
 * the Hertz force of the lattice, balanced.  One interior grain moved by d along +x: its
 * contacts along x press with overlaps delta + d (ahead, pushing it back along -x) and
 * delta - d (behind), the four lateral ones with h_lat = 2R - sqrt(s^2 + d^2) at a slope
 * d / sqrt(s^2 + d^2) that pushes it along +x, so its net force over its largest, P ~ h^(3/2)
 * for every pair alike, is
 *   [(delta + d)^1.5 - (delta - d)^1.5 - 4 h_lat^1.5 d / sqrt(s^2 + d^2)] / (delta + d)^1.5,
 * the largest of the pack, and the same number measure_pack's residual_max reports.  Two
 * plates face to face: one link of 4 k_n h each way, the line's tangential force in |f|. */
static void
test_grain_forces(void)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures m;
	struct grain_forces g;
	size_t k, n3 = (size_t)NL * NL * NL, ngg = 3 * (size_t)NL * NL * (NL - 1), ngw = 6 * (size_t)NL * NL, kmax = 0;
	size_t moved = lat(1, 1, 1);
	double s = 2 * R_ - DELTA, d = DELTA / 4, dist, hl, want, rmax = 0;
	int ok6 = 1, okf = 1, okr = 1;

	lattice(&p);
	contacts_init(&gc);
	CHECK(measure_pack(&p, &gc, &m) == 0 && measure_grain_forces(&p, &g) == 0, "grain forces: lattice measured");
	CHECK(g.n == n3 && g.nlink == ngg + ngw && g.has_forces, "grain forces: %zu links (want %zu), forces",
	    g.nlink, ngg + ngw);
	for (k = 0; k < n3; k++) {
		ok6 &= g.z[k] == 6;
		okf &= fabs(g.fmax[k] - m.P_max) <= 1e-14 * m.P_max;
		okr &= g.residual[k] < 1e-12;
	}
	for (k = 0; k < g.nlink; k++)
		okf &= fabs(g.link[k].P - m.P_max) <= 1e-14 * m.P_max;
	CHECK(ok6, "grain forces: lattice, every grain 6 contacts");
	CHECK(okf, "grain forces: lattice, every link and every grain's largest force the Hertz force");
	CHECK(okr, "grain forces: lattice, every grain balanced (residual < 1e-12)");
	grain_forces_free(&g);

	p.x[3 * moved] += d;
	CHECK(measure_pack(&p, &gc, &m) == 0 && measure_grain_forces(&p, &g) == 0, "grain forces: moved grain measured");
	for (k = 0; k < n3; k++)
		if (g.residual[k] > rmax)
			rmax = g.residual[k], kmax = k;
	dist = sqrt(s * s + d * d);
	hl = 2 * R_ - dist;
	want = (pow(DELTA + d, 1.5) - pow(DELTA - d, 1.5) - 4 * pow(hl, 1.5) * d / dist) / pow(DELTA + d, 1.5);
	CHECK(kmax == moved, "grain forces: the moved grain is the least balanced (%zu)", kmax);
	CHECK_CLOSE(g.residual[moved], want, 1e-10, "grain forces: its net force over its largest, closed form");
	CHECK_CLOSE(rmax, m.residual_max, 1e-15, "grain forces: the largest is measure_pack's residual_max");
	grain_forces_free(&g);
	contacts_free(&gc);
	pack_free(&p);

	{
		const double r = 3e-8, L = 6e-8, h = 1e-9, kn = 1.5e3, A = 4e-7, up[4] = {1, 0, 0, 0};
		struct pack_contact c = {0, 1, 0, {2e-7, 0, 0}, 0};
		double ell = 2 * r - h, f = hypot(4 * kn * h, c.Q0[0]);

		pack_init(&p);
		p.box[3] = p.box[4] = p.box[5] = A;
		pack_set_shapes(&p);
		pack_add_grain(&p, 1, (const double[3]){A / 2, A / 2, A / 2 + ell / 2}, r, E_, NU, 2700);
		pack_add_grain(&p, 2, (const double[3]){A / 2, A / 2, A / 2 - ell / 2}, r, E_, NU, 2700);
		pack_set_grain_shape(&p, 0, L, up);
		pack_set_grain_shape(&p, 1, L, up);
		pack_set_meta(&p, "contact-law", "linear");	/* a plate pack of the linear law */
		pack_set_meta(&p, "kn", "1.5e3");
		pack_add_contact(&p, &c);
		CHECK(measure_is_plate_pack(&p) && measure_grain_forces(&p, &g) == 0 && g.has_forces,
		    "grain forces: plates measured");
		CHECK(g.nlink == 1 && g.link[0].i == 0 && g.link[0].j == 1 && g.z[0] == 1 && g.z[1] == 1,
		    "grain forces: plates, one link, one interaction each");
		CHECK_CLOSE(g.link[0].P, 4 * kn * h, 1e-12, "grain forces: plates, the link's normal force 4 k_n h");
		CHECK_CLOSE(g.fmax[0], f, 1e-12, "grain forces: plates, largest |f| with the line's Q");
		CHECK_CLOSE(g.fmax[1], f, 1e-12, "grain forces: plates, the same on the other");
		CHECK_CLOSE(g.residual[0], 1, 1e-12, "grain forces: plates, a lone pair's net force is its force");
		grain_forces_free(&g);
		pack_set_meta(&p, "contact-law", "linear");	/* a plate pack of the linear law */
		pack_set_meta(&p, "kn", "none");
		CHECK(measure_grain_forces(&p, &g) == 0 && !g.has_forces && g.nlink == 1 && isnan(g.residual[0]),
		    "grain forces: plates without kn, the link but no forces");
		grain_forces_free(&g);
		pack_free(&p);
	}
}

int
main(void)
{
	test_plates();
	test_plate_contacts();
	test_nematic_random();
	test_lattice();
	test_grain_forces();
	test_sliding();
	test_small();
	test_rattler_rule();
	test_sphere_box_volume();
	test_bulk();
	test_hertz();
	return unit_summary();
}
