/* SPDX-License-Identifier: GPL-3.0-or-later */
/* measure: porosity, coordination, stresses, residual, fabric (see measure.h). */
#include "analysis/measure.h"
#include "base/msg.h"
#include "base/quat.h"
#include "base/vec3.h"
#include "analysis/fabric.h"
#include "contact/hertz.h"
#include "contact/law.h"
#include "contact/narrow.h"
#include "pack/shape.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void
measure_coordination(const struct pack *p, const struct geo_contacts *gc, unsigned *counts)
{
	size_t k;

	memset(counts, 0, p->n * sizeof *counts);
	for (k = 0; k < gc->n; k++) {
		counts[gc->c[k].i]++;
		if (!PACK_IS_WALL(gc->c[k].j))
			counts[gc->c[k].j]++;
	}
}

unsigned
measure_rattler_rule(const struct pack *p)
{
	size_t k;

	for (k = 0; k < p->nc; k++) {
		const struct pack_contact *c = &p->c[k];

		if (c->Q0[0] != 0 || c->Q0[1] != 0 || c->Q0[2] != 0 || c->M0 != 0)
			return 2;
	}
	return 4;
}

size_t
measure_rattlers(const struct pack *p, const struct geo_contacts *gc, unsigned min_contacts, unsigned char *flag)
{
	unsigned *cnt = malloc((p->n ? p->n : 1) * sizeof *cnt);
	size_t k, nr = 0;
	int changed = 1;

	if (!cnt)
		return 0;
	memset(flag, 0, p->n);
	measure_coordination(p, gc, cnt);
	/* iterate to a fixed point; each sweep removes at least one grain or stops */
	while (changed) {
		changed = 0;
		for (k = 0; k < p->n; k++)
			if (!flag[k] && cnt[k] < min_contacts) {
				flag[k] = 1;
				nr++;
				changed = 1;
			}
		if (!changed)
			break;
		measure_coordination(p, gc, cnt);
		for (k = 0; k < gc->n; k++) {
			size_t i = gc->c[k].i;
			long j = gc->c[k].j;
			if (PACK_IS_WALL(j))
				continue;
			/* a contact with a removed grain no longer counts */
			if (flag[i] && !flag[j])
				cnt[j]--;
			else if (flag[j] && !flag[i])
				cnt[i]--;
		}
	}
	free(cnt);
	return nr;
}

/* The volume of a sphere inside a box (measure_sphere_box_volume): the integral over the
 * polar angle theta, z = r sin theta, of the area of the disc of radius rho = r cos theta cut
 * by the box's rectangle in x and y, that area in closed form.  In theta, rho is analytic up to
 * the poles (in z it has a square root there).  The area is smooth but for the angles where
 * the disc starts to cross an edge line (rho = |e|: a circular segment grows as
 * (rho - |e|)^(3/2)) or a corner (rho^2 = ex^2 + ey^2), so the range is split there, and each
 * piece is mapped by theta = a + L (3u^2 - 2u^3), whose vanishing slope at both ends turns
 * those powers into analytic functions of u: 32-point Gauss-Legendre then integrates each
 * piece to rounding (1e-13 relative or better over random boxes against 256 points; 20
 * points gave 4e-10).  A sphere that one face alone cuts is a cap, in closed form. */
#define SPHERE_BOX_POINTS 32

/* The integral of sqrt(rho^2 - t^2) over 0 <= t <= X <= rho. */
static double
disc_column(double X, double rho)
{
	return 0.5 * (X * sqrt((rho - X) * (rho + X)) + rho * rho * asin(X / rho));
}

/* The area of the disc of radius rho about the origin within [0, x] x [0, y], x, y >= 0. */
static double
disc_quadrant_area(double x, double y, double rho)
{
	double xc;

	x = fmin(x, rho), y = fmin(y, rho);
	if (x * x + y * y <= rho * rho)
		return x * y;
	/* the columns below height y up to xc, the circle above it */
	xc = sqrt((rho - y) * (rho + y));
	/* disc_column at X = rho and at X = 0 written out (asin(1) is pi/2 to the bit, asin(0)
	 * is 0): the same bytes without the calls, which an edge's quadrature makes for each
	 * corner beyond the disc */
	return y * xc + (x == rho ? 0.5 * (rho * rho * M_PI_2) : disc_column(x, rho)) -
	    (xc == 0 ? 0 : disc_column(xc, rho));
}

/* disc_quadrant_area of the rectangle between the origin and (x, y), signed: + in the first and
 * third quadrants, - in the others, so that four corners add up to any rectangle. */
static double
disc_corner_area(double x, double y, double rho)
{
	double a = disc_quadrant_area(fabs(x), fabs(y), rho);

	return signbit(x) != signbit(y) ? -a : a;
}

/* The area of the disc of radius rho about the origin within [lo[0], hi[0]] x [lo[1], hi[1]]. */
static double
disc_rect_area(const double lo[2], const double hi[2], double rho)
{
	if (!(rho > 0))
		return 0;
	return disc_corner_area(hi[0], hi[1], rho) - disc_corner_area(lo[0], hi[1], rho) -
	    disc_corner_area(hi[0], lo[1], rho) + disc_corner_area(lo[0], lo[1], rho);
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

static double
sphere_box_volume(const gsl_integration_glfixed_table *t, double r, const double lo[3], const double hi[3])
{
	const double e[4] = {lo[0], hi[0], lo[1], hi[1]};
	double ta, tb, th[2 + 2 * 8], v = 0;
	int a, k, i, n = 0;

	for (a = 0; a < 3; a++)
		if (!(lo[a] < r && hi[a] > -r && lo[a] < hi[a]))
			return 0;
	if (lo[0] <= -r && lo[1] <= -r && lo[2] <= -r && hi[0] >= r && hi[1] >= r && hi[2] >= r)
		return 4.0 / 3.0 * M_PI * r * r * r;
	/* one face alone crosses the sphere (most grains on the bulk's boundary): the cap of
	 * height h inside it, pi h^2 (3 r - h) / 3, in closed form (the quadrature's asin and cos
	 * were 5 % of a frictional increment, whose row measures the bulk) */
	{
		double h = 0;
		int cuts = 0;

		for (a = 0; a < 3; a++) {
			if (lo[a] > -r)
				cuts++, h = r - lo[a];
			if (hi[a] < r)
				cuts++, h = r + hi[a];
		}
		if (cuts == 1)
			return M_PI * h * h * (3 * r - h) / 3;
	}
	ta = asin(fmax(lo[2], -r) / r);
	tb = asin(fmin(hi[2], r) / r);
	th[n++] = ta, th[n++] = tb;
	/* where the disc reaches an edge line or a corner, both hemispheres (an edge through the
	 * axis, e = 0, cuts every disc in the same proportion: no break) */
	for (k = 0; k < 4; k++)
		if (e[k] != 0 && fabs(e[k]) < r) {
			th[n] = acos(fabs(e[k]) / r), th[n + 1] = -th[n];
			n += 2;
		}
	for (k = 0; k < 2; k++)
		for (i = 2; i < 4; i++) {
			double d2 = e[k] * e[k] + e[i] * e[i];

			if (d2 < r * r && e[k] != 0 && e[i] != 0) {
				/* d2 < r^2 does not keep the rounded sqrt(d2) / r from 1 + 1 ulp */
				th[n] = acos(fmin(sqrt(d2) / r, 1)), th[n + 1] = -th[n];
				n += 2;
			}
		}
	qsort(th, (size_t)n, sizeof *th, cmp_double);
	for (k = 0; k + 1 < n; k++) {
		double p0 = fmax(th[k], ta), L = fmin(th[k + 1], tb) - p0;

		if (!(L > 0))
			continue;
		for (i = 0; i < SPHERE_BOX_POINTS; i++) {
			double u, w, s;

			gsl_integration_glfixed_point(0, 1, (size_t)i, &u, &w, t);
			s = p0 + L * u * u * (3 - 2 * u);
			/* dz = r cos(s) ds, ds = 6 L u (1 - u) du */
			v += w * 6 * L * u * (1 - u) * r * cos(s) * disc_rect_area(lo, hi, r * cos(s));
		}
	}
	return v;
}

double
measure_sphere_box_volume(double r, const double lo[3], const double hi[3])
{
	gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(SPHERE_BOX_POINTS);
	double v;

	if (!t) {
		msg_seterr("out of memory");
		return NAN;
	}
	v = sphere_box_volume(t, r, lo, hi);
	gsl_integration_glfixed_table_free(t);
	return v;
}

/* The bulk's state before measure_bulk, or when it finds no inner box: absent. */
static void
bulk_absent(struct pack_measures *m)
{
	int a;

	m->has_bulk = 0;
	m->bulk_porosity = m->bulk_coordination = NAN;
	m->bulk_grains = 0;
	for (a = 0; a < 6; a++)
		m->bulk_box[a] = NAN;
}

int
measure_bulk(const struct pack *p, const struct geo_contacts *gc, double margin, struct pack_measures *m)
{
	gsl_integration_glfixed_table *t;
	unsigned *cnt;
	double cut[6], whole = 0, part = 0, V = 1, zsum = 0;
	size_t i;
	int a;

	bulk_absent(m);
	if (isnan(margin))
		margin = 2 * m->r_mean;
	m->bulk_margin = margin;
	if (!(margin >= 0) || !isfinite(margin)) {
		msg_seterr("bulk margin %g: must be a finite length >= 0", margin);
		return -1;
	}
	/* A side is cut where it has a wall and the margin is > 0: with 0, nothing is cut, and the
	 * grains' overlaps with the walls count in, as the box porosity counts them. */
	for (a = 0; a < 3; a++) {
		int cuts = !p->periodic[a] && margin > 0;

		m->bulk_box[a] = p->box[a] + (cuts ? margin : 0);
		m->bulk_box[3 + a] = p->box[3 + a] - (cuts ? margin : 0);
		cut[2 * a] = cuts ? m->bulk_box[a] : -INFINITY;
		cut[2 * a + 1] = cuts ? m->bulk_box[3 + a] : INFINITY;
	}
	for (a = 0; a < 3; a++) {
		if (!(m->bulk_box[3 + a] > m->bulk_box[a])) {
			bulk_absent(m);
			return 0;	/* the margins meet: no inner box */
		}
		V *= m->bulk_box[3 + a] - m->bulk_box[a];
	}
	t = gsl_integration_glfixed_table_alloc(SPHERE_BOX_POINTS);
	cnt = malloc((p->n ? p->n : 1) * sizeof *cnt);
	if (!t || !cnt) {
		gsl_integration_glfixed_table_free(t);
		free(cnt);
		msg_seterr("out of memory");
		return -1;
	}
	measure_coordination(p, gc, cnt);
	for (i = 0; i < p->n; i++) {
		const double *x = p->x + 3 * i;
		double r = p->r[i], lo[3], hi[3];
		int inside = 1, whole_in = 1;

		for (a = 0; a < 3; a++) {
			lo[a] = cut[2 * a] - x[a];
			hi[a] = cut[2 * a + 1] - x[a];
			inside &= lo[a] <= 0 && hi[a] >= 0;
			whole_in &= lo[a] <= -r && hi[a] >= r;
		}
		/* the whole spheres summed as pack_grain_volume sums them: margin 0 gives its value
		 * to the last bit */
		if (whole_in)
			whole += r * r * r;
		else
			part += sphere_box_volume(t, r, lo, hi);
		if (inside) {
			m->bulk_grains++;
			zsum += cnt[i];
		}
	}
	gsl_integration_glfixed_table_free(t);
	free(cnt);
	m->has_bulk = 1;
	m->bulk_porosity = 1 - (whole * 4.0 / 3.0 * 3.14159265358979323846 + part) / V;
	if (m->bulk_grains)
		m->bulk_coordination = zsum / (double)m->bulk_grains;
	return 0;
}

/* The per-grain balance and the sums that measure_pack accumulates over the contacts. */
struct balance {
	double *F, *M, *fbig;	/* net force, net moment, largest contact force per grain */
	double *res;		/* the grains' residuals, for their median */
	const unsigned char *rat;
	double Psum, fsum;
	size_t cnr;		/* contact ends on non-rattlers */
	const struct contact_law *law;	/* the pack's: the history lines' limits */
	struct law_pack lk;
};

/* b's law: pack p's (contact_law_of_pack), bound.  0, or -1 for a key no law has. */
static int
balance_bind_law(struct balance *b, const struct pack *p)
{
	if (!(b->law = contact_law_of_pack(p)))
		return -1;
	law_pack_bind(b->law, p, &b->lk);
	return 0;
}

static void
add_fabric(struct pack_measures *m, const double n[3])
{
	m->fabric[0] += n[0] * n[0];
	m->fabric[1] += n[1] * n[1];
	m->fabric[2] += n[2] * n[2];
	m->fabric[3] += n[0] * n[1];
	m->fabric[4] += n[0] * n[2];
	m->fabric[5] += n[1] * n[2];
}

/* Love-Weber: branch (x) force of one contact, compression positive. */
static void
add_love_weber(struct pack_measures *m, const double n[3], double l, const double ff[3])
{
	m->sig_lw[0] += l * n[0] * ff[0];
	m->sig_lw[1] += l * n[1] * ff[1];
	m->sig_lw[2] += l * n[2] * ff[2];
	m->sig_lw[3] += l * 0.5 * (n[0] * ff[1] + n[1] * ff[0]);
	m->sig_lw[4] += l * 0.5 * (n[0] * ff[2] + n[2] * ff[0]);
	m->sig_lw[5] += l * 0.5 * (n[1] * ff[2] + n[2] * ff[1]);
}

/* Grain g's balance gains force f and, at lever arm arm, the tangential force Q and the
 * torsional couple tor (along the normal). */
static void
add_to_grain(struct balance *b, size_t g, const double f[3], const double arm[3], const double Q[3], const double tor[3],
    double fm)
{
	double t[3];
	int a;

	for (a = 0; a < 3; a++)
		b->F[3 * g + a] += f[a];
	vec3_cross(arm, Q, t);
	for (a = 0; a < 3; a++)
		b->M[3 * g + a] += t[a] + tor[a];
	b->fbig[g] = fmax(b->fbig[g], fm);
}

static void
measure_contact(const struct pack *p, const struct geo_contact *c, struct pack_measures *m, struct balance *b)
{
	int wall = PACK_IS_WALL(c->j), a;
	double Rmin = wall ? p->r[c->i] : fmin(p->r[c->i], p->r[c->j]);
	double f[3], Q[3] = {0, 0, 0}, Mt = 0, li, lj, fm, arm[3], tor[3];
	size_t i = c->i;

	if (wall) {
		m->contacts_gw++;
		if (!b->rat[i])
			b->cnr++;
	} else {
		m->contacts_gg++;
		add_fabric(m, c->n);
		if (!b->rat[i] && !b->rat[c->j])
			b->cnr += 2;
	}
	m->overlap_max = fmax(m->overlap_max, c->h / Rmin);
	if (c->hist >= 0) {
		/* the line's forces within Coulomb's limits at the normal force now (physics.md §5),
		 * as every loading's start applies them (friction.c, setup_contact): a commit leaves
		 * a line above them where its normal force fell, and the pack transmits only the
		 * limit there.  Without the clamp a settled pack read 1.1e-4 here while loadtest
		 * found 9.5e-5 on it (a 200-grain frictionalized pack). */
		struct law_pair lp;
		struct law_tangent t;
		double qlim, mlim, qn;

		b->law->pair(b->law, &b->lk, i, c->j, &lp);
		b->law->tangent(b->law, &lp, c->h, c->P, &t);
		qlim = t.qmax, mlim = t.mmax;

		pack_contact_q0_on(&p->c[c->hist], i, Q);
		Mt = p->c[c->hist].M0;
		qn = vec3_norm(Q);
		if (qn > qlim)
			for (a = 0; a < 3; a++)
				Q[a] *= qlim / qn;
		if (fabs(Mt) > mlim)
			Mt = Mt > 0 ? mlim : -mlim;
	}
	for (a = 0; a < 3; a++)
		f[a] = c->P * c->n[a] + Q[a];
	fm = vec3_norm(f);
	b->Psum += c->P;
	b->fsum += fm;
	m->P_max = fmax(m->P_max, c->P);
	contact_lever_lengths(wall, p->r[i], wall ? 0 : p->r[c->j], c->d, c->h, &li, &lj);
	add_love_weber(m, c->n, li + lj, f);
	if (wall)
		m->sig_wall[PACK_WALL_INDEX(c->j) / 2] += c->P;
	/* balance of grain i: force f, moment of Q about the centre plus torsion */
	for (a = 0; a < 3; a++) {
		arm[a] = -c->n[a] * li;
		tor[a] = Mt * c->n[a];
	}
	add_to_grain(b, i, f, arm, Q, tor, fm);
	if (!wall) {
		double mf[3], mQ[3] = {-Q[0], -Q[1], -Q[2]};
		for (a = 0; a < 3; a++) {
			mf[a] = -f[a];
			arm[a] = c->n[a] * lj;
			tor[a] = -Mt * c->n[a];
		}
		add_to_grain(b, (size_t)c->j, mf, arm, mQ, tor, fm);
	}
}

/* Mean, sample standard deviation, min and max of n values, s[0..3]. */
static void
series_stats(const double *v, size_t n, double s[4])
{
	double sum = 0, sum2 = 0;
	size_t k;

	s[2] = INFINITY;
	s[3] = 0;
	for (k = 0; k < n; k++) {
		sum += v[k];
		sum2 += v[k] * v[k];
		s[2] = fmin(s[2], v[k]);
		s[3] = fmax(s[3], v[k]);
	}
	s[0] = sum / n;
	s[1] = n > 1 ? sqrt(fmax(sum2 - sum * sum / n, 0) / (n - 1)) : 0;
}

static void
measure_radii(const struct pack *p, struct pack_measures *m)
{
	double s[4];

	series_stats(p->r, p->n, s);
	m->r_mean = s[0], m->r_std = s[1], m->r_min = s[2], m->r_max = s[3];
}

static void
measure_fabric(struct pack_measures *m)
{
	double d[6], dd;
	int a;

	if (!m->contacts_gg)
		return;
	for (a = 0; a < 6; a++)
		m->fabric[a] /= m->contacts_gg;
	memcpy(d, m->fabric, sizeof d);
	for (a = 0; a < 3; a++)
		d[a] -= 1.0 / 3.0;
	dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5]);
	m->fabric_anisotropy = 7.5 * sqrt(1.5 * dd);
}

/* Grain k's unbalance: the larger of its net force and its net moment over its radius (N). */
static double
grain_unbalance(const struct pack *p, const struct balance *b, size_t k)
{
	return fmax(vec3_norm(b->F + 3 * k), vec3_norm(b->M + 3 * k) / p->r[k]);
}

/* Stresses, mean force and the residual, once every contact is summed. */
static void
measure_forces(const struct pack *p, size_t nct, const struct balance *b, struct pack_measures *m)
{
	double Fsum = 0;
	size_t k, nres = 0;
	int a;

	for (a = 0; a < 3; a++)
		m->sig_wall[a] = pack_wall_stress(p->box, p->box + 3, a, m->sig_wall[a]);
	m->sigma_c = (m->sig_wall[0] + m->sig_wall[1] + m->sig_wall[2]) / 3;
	for (a = 0; a < 6; a++)
		m->sig_lw[a] /= m->volume;
	m->P_mean = b->Psum / nct;
	for (k = 0; k < p->n; k++) {
		double fr, un;
		if (!(b->fbig[k] > 0))
			continue;
		fr = vec3_norm(b->F + 3 * k);
		un = grain_unbalance(p, b, k);
		m->residual_strict = fmax(m->residual_strict, un / b->fbig[k]);
		b->res[nres] = un / fmax(b->fbig[k], MEASURE_RESIDUAL_FLOOR * m->P_mean);
		m->residual_max = fmax(m->residual_max, b->res[nres]);
		Fsum += fr;
		nres++;
	}
	m->residual_mean = nres ? (Fsum / nres) / (b->fsum / nct) : 0;
	qsort(b->res, nres, sizeof *b->res, cmp_double);
	m->residual_median = nres ? (nres % 2 ? b->res[nres / 2] : (b->res[nres / 2 - 1] + b->res[nres / 2]) / 2) : 0;
}

/* The sliding ratio of the history: lines at their limit mu P0, over the contacts. */
static void
measure_sliding(const struct pack *p, const struct geo_contacts *gc, const struct balance *b, struct pack_measures *m)
{
	size_t k, nsl = 0, nfr = 0;

	m->history = p->nc;
	for (k = 0; k < gc->n; k++)
		if (gc->c[k].hist >= 0) {
			nfr++;
			if (law_contact_at_limit(b->law, &b->lk, &p->c[gc->c[k].hist]))
				nsl++;
		}
	m->stale_history = p->nc - nfr;
	if (p->nc > 0)
		m->sliding_ratio = gc->n ? (double)nsl / gc->n : 0;
}

void
measure_hydrate(const struct pack *p, struct hydrate_measures *h)
{
	double vh, vg;
	size_t n;

	h->has_phase = p->has_phase;
	if (!p->has_phase) {
		h->grains = h->volume_fraction = h->saturation = h->porosity_hydrate_as_pore = NAN;
		return;
	}
	n = pack_hydrate_grains(p, &vh);
	vg = pack_grain_volume(p);
	h->grains = (double)n;
	h->volume_fraction = vh / vg;
	h->saturation = pack_hydrate_saturation(p);
	h->porosity_hydrate_as_pore = 1 - (vg - vh) / pack_box_volume(p->box);
}

int
measure_pack(const struct pack *p, struct geo_contacts *gc, struct pack_measures *m)
{
	return measure_pack_in(p, NULL, gc, m);
}

int
measure_pack_in(const struct pack *p, struct contact_enum *e, struct geo_contacts *gc, struct pack_measures *m)
{
	unsigned *cnt;
	unsigned char *rat;
	struct balance b;
	size_t k, nnr = 0;

	memset(m, 0, sizeof *m);
	memset(&b, 0, sizeof b);
	m->sliding_ratio = NAN;
	m->bulk_margin = NAN;
	bulk_absent(m);
	if (balance_bind_law(&b, p))
		return -1;
	if (e ? contacts_find_in(p, e, gc) : contacts_find(p, gc))
		return -1;
	cnt = malloc(p->n * sizeof *cnt);
	rat = malloc(p->n);
	b.F = calloc(3 * p->n, sizeof *b.F);
	b.M = calloc(3 * p->n, sizeof *b.M);
	b.fbig = calloc(p->n, sizeof *b.fbig);
	b.res = malloc(p->n * sizeof *b.res);
	if (!cnt || !rat || !b.F || !b.M || !b.fbig || !b.res) {
		free(cnt), free(rat), free(b.F), free(b.M), free(b.fbig), free(b.res);
		msg_seterr("out of memory");
		return -1;
	}
	m->grains = p->n;
	m->volume = pack_box_volume(p->box);
	m->porosity = 1 - pack_grain_volume(p) / m->volume;
	measure_radii(p, m);
	measure_coordination(p, gc, cnt);
	m->rattler_min_contacts = measure_rattler_rule(p);
	m->rattlers = measure_rattlers(p, gc, m->rattler_min_contacts, rat);
	for (k = 0; k < p->n; k++) {
		m->under4 += cnt[k] < 4;
		m->coordination += cnt[k];
	}
	m->coordination /= p->n;
	b.rat = rat;
	for (k = 0; k < gc->n; k++)
		measure_contact(p, &gc->c[k], m, &b);
	for (k = 0; k < p->n; k++)
		if (!rat[k])
			nnr++;
	m->coordination_nr = nnr ? (double)b.cnr / nnr : 0;
	measure_fabric(m);
	m->has_forces = gc->n > 0 && m->P_max > 0;
	if (m->has_forces)
		measure_forces(p, gc->n, &b, m);
	measure_sliding(p, gc, &b, m);
	free(cnt), free(rat), free(b.F), free(b.M), free(b.fbig), free(b.res);
	return 0;
}

int
measure_nematic(const double *u, size_t n, double *S, double director[3])
{
	double Q[9] = {0}, big = 0;
	gsl_matrix_view A = gsl_matrix_view_array(Q, 3, 3);
	gsl_vector *eval = gsl_vector_alloc(3);
	gsl_matrix *evec = gsl_matrix_alloc(3, 3);
	gsl_eigen_symmv_workspace *w = gsl_eigen_symmv_alloc(3);
	size_t k;
	int a, b, status = -1;

	if (!eval || !evec || !w) {
		msg_seterr("out of memory");
		goto out;
	}
	if (n == 0) {
		msg_seterr("no vectors: no nematic order");
		goto out;
	}
	for (k = 0; k < n; k++)
		for (a = 0; a < 3; a++)
			for (b = 0; b < 3; b++)
				Q[3 * a + b] += 1.5 * u[3 * k + a] * u[3 * k + b];
	for (a = 0; a < 9; a++)
		Q[a] /= n;
	for (a = 0; a < 3; a++)
		Q[4 * a] -= 0.5;
	/* symmv destroys the lower triangle and diagonal of Q: it is not used after */
	if (gsl_eigen_symmv(&A.matrix, eval, evec, w) || gsl_eigen_symmv_sort(eval, evec, GSL_EIGEN_SORT_VAL_DESC)) {
		msg_seterr("nematic order: the eigensolver failed");
		goto out;
	}
	*S = gsl_vector_get(eval, 0);
	for (a = 0; a < 3; a++) {
		director[a] = gsl_matrix_get(evec, a, 0);
		if (fabs(director[a]) > fabs(big))
			big = director[a];
	}
	/* u and -u are the same axis: one sign, so that the report is a function of the pack */
	if (big < 0)
		for (a = 0; a < 3; a++)
			director[a] = -director[a];
	status = 0;
out:
	gsl_eigen_symmv_free(w);
	gsl_matrix_free(evec);
	gsl_vector_free(eval);
	return status;
}


/* Append the contact (i, j) to g's links, its force 0 until the caller sets it. */
static int
grain_forces_link(struct grain_forces *g, size_t i, long j)
{
	if (g->nlink == g->caplink) {
		size_t cap = g->caplink ? 2 * g->caplink : 1024;
		void *q = realloc(g->link, cap * sizeof *g->link);

		if (!q) {
			msg_seterr("out of memory");
			return -1;
		}
		g->link = q, g->caplink = cap;
	}
	g->link[g->nlink++] = (struct measure_link){i, j, 0};
	return 0;
}

/* What measure_plate_contacts sums over the interactions, in SI. */
struct plate_pass {
	const struct pack *p;
	struct narrow_grains g;
	const long *keys;	/* the pack's history keys, or NULL */
	const struct contact_law *law;	/* the pack's, or NULL: no forces (a spring law without meta kn) */
	struct law_pack lk;		/* law's pair setup's, bound once */
	unsigned *z;		/* interactions per grain */
	size_t zends_free;	/* interactions' ends on free grains */
	double *F;		/* net force per grain (3n) */
	double fsum, Psum;	/* sums of |F| and of the normal force P over the interactions */
	struct fabric_interaction *fab;	/* the grain pairs, for fabric_describe */
	size_t nfab, capfab;
	double sig_pairs[6];	/* P eq. 7: the pairs' branch (x) force, summed */
	struct plate_measures *m;
	struct grain_forces *gf;	/* measure_grain_forces's per-grain record, or NULL */
	struct plate_contact *list;	/* measure_plate_contact_list's, or NULL: not kept */
	size_t nlist, caplist;
	int keep_list;
};

/* Interaction it of grain i with j (xj: j's centre, its nearest image) into the list, with
 * its force (NaN without a stiffness): the far end is j's centre, or for a wall the
 * overlap-weighted foot of the elements on its plane. */
static int
list_add(struct plate_pass *pp, size_t i, long j, const struct plate_interaction *it, const double xj[3], double P,
    const double Q[3])
{
	struct plate_contact *e;
	double hsum = 0, foot[3] = {0, 0, 0};
	int k, a;

	if (pp->nlist == pp->caplist) {
		size_t cap = pp->caplist ? 2 * pp->caplist : 1024;
		void *q = realloc(pp->list, cap * sizeof *pp->list);

		if (!q) {
			msg_seterr("out of memory");
			return -1;
		}
		pp->list = q, pp->caplist = cap;
	}
	e = &pp->list[pp->nlist++];
	e->i = i, e->j = j, e->elements = it->m, e->overlap = 0;
	for (k = 0; k < it->m; k++) {
		double h = fmax(it->e[k].h, 0);

		e->overlap = fmax(e->overlap, h);
		hsum += h;
		for (a = 0; a < 3; a++)
			foot[a] += h * it->e[k].pj[a];
	}
	for (a = 0; a < 3; a++) {
		e->a[a] = pp->p->x[3 * i + a];
		e->b[a] = !PACK_IS_WALL(j) ? xj[a] : hsum > 0 ? foot[a] / hsum : it->e[0].pj[a];
		e->n[a] = it->n[a];
		e->Q[a] = Q ? Q[a] : NAN;
	}
	e->P = P;
	return 0;
}

static void add_dyad(double s[6], const double arm[3], const double f[3]);

/* A pair for the descriptors: at the Coulomb limit when its tangential force is within 1 %
 * of mu times its normal force (the spring is capped at mu times the normal force with the
 * dashpot's part, which a static pack has not, so exactly mu P is not to be expected). */
static int
fabric_add(struct plate_pass *pp, const double n[3], const double l[3], const double F[3], double P)
{
	struct fabric_interaction *e;
	double Ft[3], fn = F[0] * n[0] + F[1] * n[1] + F[2] * n[2];
	int a;

	if (pp->nfab == pp->capfab) {
		size_t cap = pp->capfab ? 2 * pp->capfab : 1024;
		void *q = realloc(pp->fab, cap * sizeof *pp->fab);

		if (!q) {
			msg_seterr("out of memory");
			return -1;
		}
		pp->fab = q, pp->capfab = cap;
	}
	e = &pp->fab[pp->nfab++];
	for (a = 0; a < 3; a++) {
		e->n[a] = n[a], e->l[a] = l[a], e->F[a] = F[a];
		Ft[a] = F[a] - fn * n[a];
	}
	e->sliding = P > 0 && vec3_norm(Ft) >= 0.99 * pp->p->mu * P;	/* a pair: mu grain-grain */
	add_dyad(pp->sig_pairs, l, F);
	return 0;
}

/* Love-Weber: arm (x) f, symmetrised, into s (xx yy zz xy xz yz). */
static void
add_dyad(double s[6], const double arm[3], const double f[3])
{
	s[0] += arm[0] * f[0];
	s[1] += arm[1] * f[1];
	s[2] += arm[2] * f[2];
	s[3] += 0.5 * (arm[0] * f[1] + arm[1] * f[0]);
	s[4] += 0.5 * (arm[0] * f[2] + arm[2] * f[0]);
	s[5] += 0.5 * (arm[1] * f[2] + arm[2] * f[1]);
}

static int
on_plate_record(const struct contact *c, void *v)
{
	struct plate_pass *pp = v;
	struct plate_measures *m = pp->m;
	struct plate_interaction it;
	struct law_pair lp;
	const double *n = it.n, *xi = pp->p->x + 3 * c->i;
	double F[3] = {0, 0, 0}, Q[3] = {0, 0, 0}, P = 0, hsum = 0, foot[3] = {0, 0, 0}, arm[3], xj[3], fk[3];
	size_t i = c->i;
	long j = c->j;
	int wall = PACK_IS_WALL(j), k, a, gi = pack_grain_glued(pp->p, i), gj = !wall && pack_grain_glued(pp->p, (size_t)j);
	int described = !wall && !gi && !gj;	/* a pair of free grains: in the descriptors */

	if (narrow_record_interaction(&pp->g, c, 0, &it, xj) == 0)
		return 0;
	if (pp->gf && grain_forces_link(pp->gf, i, j))
		return -1;
	pp->z[i]++;
	pp->zends_free += (size_t)(!gi) + (size_t)(!wall && !gj);
	if (wall)
		m->contacts_gw++;
	else
		pp->z[j]++, m->contacts_gg++;
	m->elements += (size_t)it.m;
	m->by_elements[it.m < 3 ? it.m - 1 : 2]++;
	if (!pp->law) {
		/* no forces: the geometry of the pair for the descriptors */
		const double zero[3] = {0, 0, 0};

		for (a = 0; a < 3 && !wall; a++)
			arm[a] = xi[a] - xj[a];
		if (pp->keep_list && list_add(pp, i, j, &it, xj, NAN, NULL))
			return -1;
		return described ? fabric_add(pp, n, arm, zero, 0) : 0;
	}
	pp->law->pair(pp->law, &pp->lk, i, j, &lp);
	for (k = 0; k < it.m; k++) {
		double h = fmax(it.e[k].h, 0), Pk = 0;

		if (h > 0)	/* the element's elastic force, by the pack's law */
			pp->law->normal(pp->law, &lp, h, &Pk, NULL);
		P += Pk;
		if (wall) {
			/* the element's own lever: its foot on the wall plane */
			for (a = 0; a < 3; a++) {
				arm[a] = xi[a] - it.e[k].pj[a];
				foot[a] += h * it.e[k].pj[a];
				fk[a] = Pk * n[a];
			}
			add_dyad(m->sig_lw, arm, fk);
			hsum += h;
		}
	}
	if (pp->keys) {
		long line = pack_history_lookup(pp->keys, pp->p->nc, i, j);

		if (line >= 0)
			pack_contact_q0_on(&pp->p->c[line], i, Q);
	}
	for (a = 0; a < 3; a++)
		F[a] = P * n[a] + Q[a];
	if (pp->keep_list && list_add(pp, i, j, &it, xj, P, Q))
		return -1;
	if (wall) {
		/* the tangential force at the overlap-weighted foot */
		m->sig_wall[PACK_WALL_INDEX(j) / 2] += P;
		for (a = 0; a < 3; a++)
			arm[a] = xi[a] - (hsum > 0 ? foot[a] / hsum : it.e[0].pj[a]);
		add_dyad(m->sig_lw, arm, Q);
	} else {
		/* the pair's whole force at the branch vector: where it acts does not matter */
		for (a = 0; a < 3; a++)
			arm[a] = xi[a] - xj[a];
		add_dyad(m->sig_lw, arm, F);
		if (described && fabric_add(pp, n, arm, F, P))
			return -1;
	}
	for (a = 0; a < 3; a++) {
		pp->F[3 * i + a] += F[a];
		if (!wall)
			pp->F[3 * j + a] -= F[a];
	}
	pp->fsum += vec3_norm(F);
	pp->Psum += P;
	if (pp->gf) {
		pp->gf->link[pp->gf->nlink - 1].P = P;
		pp->gf->fmax[i] = fmax(pp->gf->fmax[i], vec3_norm(F));
		if (!wall)
			pp->gf->fmax[j] = fmax(pp->gf->fmax[j], vec3_norm(F));
	}
	m->force_max = fmax(m->force_max, P);
	return 0;
}

/* The descriptors of analysis/fabric.h over the pairs and the plates' face normals; with no
 * stiffness the forces are unknown and only the geometric ones are kept. */
static int
plate_fabric(const struct pack *p, struct plate_pass *pp, double V, struct plate_measures *m)
{
	double *nm = malloc(3 * (p->n ? p->n : 1) * sizeof *nm), R[9], sig[6];
	size_t i, np = 0;
	int a;

	if (!nm) {
		msg_seterr("out of memory");
		return -1;
	}
	for (i = 0; i < p->n; i++)
		if (shape_of(pack_grain_shape(p, i))->oriented && !pack_grain_glued(p, i)) {
			quat_to_matrix(p->q + 4 * i, R);
			nm[3 * np] = R[2], nm[3 * np + 1] = R[5], nm[3 * np + 2] = R[8];
			np++;
		}
	for (a = 0; a < 6; a++)
		sig[a] = pp->sig_pairs[a] / V;
	fabric_describe(pp->fab, pp->nfab, nm, np, m->has_forces ? sig : NULL, &m->fabric);
	if (!m->has_forces) {	/* and without forces no tangent t: no l_t either */
		struct fabric_desc *f = &m->fabric;
		f->a_fn = f->theta_fn = f->a_ft = f->theta_ft = f->K_s = NAN;
		f->a_lt = f->theta_lt = f->a_lt_direct = f->theta_lt_direct = f->a_ft_direct = f->theta_ft_direct = NAN;
	}
	free(nm);
	return 0;
}

/* The interaction measures of measure_plates (measure.h): the enumerator over the bounding
 * spheres, each record's element contacts by narrow_record_interaction, as dem/engine finds
 * them; with list, the interactions one by one too (measure_plate_contact_list). */
static int
measure_plate_contacts(const struct pack *p, struct plate_measures *m, struct grain_forces *gf, struct plate_contact **list,
    size_t *nlist)
{
	struct contact_enum ce;
	struct plate_pass pass;
	double *R = malloc(9 * p->n * sizeof *R), *half = malloc(p->n * sizeof *half), *rb = malloc(p->n * sizeof *rb);
	unsigned char *kind = malloc(p->n * sizeof *kind);
	double V = pack_box_volume(p->box), s = 0;
	size_t i, ni;
	int a, status = -1, have_ce = 0;

	memset(&pass, 0, sizeof pass);
	pass.p = p, pass.m = m, pass.gf = gf, pass.keep_list = list != NULL;
	/* forces by the pack's law; a spring law's need the stiffness the pack records */
	if (!(pass.law = contact_law_of_pack(p)))
		goto out;
	if (!law_pack_knows_stiffness(pass.law, p))
		pass.law = NULL;
	else
		law_pack_bind(pass.law, p, &pass.lk);
	pass.z = calloc(p->n, sizeof *pass.z);
	pass.F = calloc(3 * p->n, sizeof *pass.F);
	if (!R || !half || !rb || !kind || !pass.z || !pass.F) {
		msg_seterr("out of memory");
		goto out;
	}
	for (i = 0; i < p->n; i++) {
		double L = p->has_shapes ? p->side[i] : 0;
		const double one[4] = {1, 0, 0, 0};
		const struct shape_ops *sh = shape_of(pack_grain_shape(p, i));

		quat_to_matrix(p->q ? p->q + 4 * i : one, R + 9 * i);
		half[i] = L / 2;
		kind[i] = (unsigned char)sh->kind;
		rb[i] = sh->bounding_radius(p->r[i], L);
	}
	pass.g = (struct narrow_grains){p->x, R, half, p->r, kind, p->box, p->box + 3};
	if (p->nc && !(pass.keys = pack_history_keys(p)))
		goto out;
	if (contact_enum_init(&ce, p->n, rb, p->box, p->box + 3, p->periodic, 0, 0))
		goto out;
	have_ce = 1;
	if (contact_enum_update(&ce, p->x, 1) || contact_foreach(&ce, p->x, CONTACT_TOUCHING, on_plate_record, &pass) < 0)
		goto out;
	ni = m->contacts_gg + m->contacts_gw;
	for (i = 0; i < p->n; i++) {
		int glued = pack_grain_glued(p, i);

		m->glued += (size_t)glued;
		if (pass.z[i] <= 1)
			m->floating++, m->floating_free += (size_t)!glued;
	}
	m->coordination = (double)(2 * m->contacts_gg + m->contacts_gw) / (double)p->n;
	m->floating_fraction = (double)m->floating / (double)p->n;
	m->coordination_free = m->glued < p->n ? (double)pass.zends_free / (double)(p->n - m->glued) : NAN;
	m->floating_fraction_free = m->glued < p->n ? (double)m->floating_free / (double)(p->n - m->glued) : NAN;
	m->elements_per_interaction = ni ? (double)m->elements / (double)ni : NAN;
	m->has_forces = pass.law && ni > 0;
	if (!m->has_forces) {
		for (a = 0; a < 6; a++)
			m->sig_lw[a] = NAN;
		for (a = 0; a < 3; a++)
			m->sig_wall[a] = NAN;
		m->force_mean = m->force_max = m->residual_mean = NAN;
	} else {
		for (a = 0; a < 3; a++)
			m->sig_wall[a] = p->periodic[a] ? NAN : pack_wall_stress(p->box, p->box + 3, a, m->sig_wall[a]);
		for (a = 0; a < 6; a++)
			m->sig_lw[a] /= V;
		size_t nres = 0;

		m->force_mean = pass.Psum / (double)ni;
		/* as the sphere report: over the grains with an interaction, over the mean |F| */
		for (i = 0; i < p->n; i++)
			if (pass.z[i] > 0)
				s += vec3_norm(pass.F + 3 * i), nres++;
		m->residual_mean = (s / (double)nres) / (pass.fsum / (double)ni);
	}
	if (gf) {
		gf->has_forces = m->has_forces;
		for (i = 0; i < p->n; i++) {
			gf->z[i] = pass.z[i];
			gf->residual[i] = m->has_forces && gf->fmax[i] > 0 ? vec3_norm(pass.F + 3 * i) /
			    fmax(gf->fmax[i], MEASURE_RESIDUAL_FLOOR * m->force_mean) : NAN;
		}
	}
	if (plate_fabric(p, &pass, V, m))
		goto out;
	if (list)	/* handed over */
		*list = pass.list, *nlist = pass.nlist, pass.list = NULL;
	status = 0;
out:
	if (have_ce)
		contact_enum_free(&ce);
	free((void *)pass.keys);
	free(pass.z);
	free(pass.F);
	free(pass.list);
	free(pass.fab);
	free(R);
	free(half);
	free(kind);
	free(rb);
	return status;
}

int
measure_plates(const struct pack *p, enum shape_radius conv, struct plate_measures *m)
{
	double *v = calloc(3 * (p->n ? p->n : 1), sizeof *v), s[4], R[9];
	size_t i;
	int status = 0;

	memset(m, 0, sizeof *m);
	if (!v) {
		msg_seterr("out of memory");
		return -1;
	}
	m->grains = p->n;
	m->packing_fraction = pack_grain_volume(p) / pack_box_volume(p->box);
	m->porosity = 1 - m->packing_fraction;
	series_stats(p->r, p->n, s);
	m->r_mean = s[0], m->r_std = s[1], m->r_min = s[2], m->r_max = s[3];
	for (i = 0; i < p->n; i++)
		v[i] = p->has_shapes ? p->side[i] : 0;
	series_stats(v, p->n, s);
	m->side_mean = s[0], m->side_std = s[1], m->side_min = s[2], m->side_max = s[3];
	for (i = 0; i < p->n; i++)
		v[i] = shape_platyness(p->r[i], p->has_shapes ? p->side[i] : 0, conv);
	series_stats(v, p->n, s);
	/* min and max only where they say something: a monodisperse pack has one eta */
	m->eta_mean = s[0], m->eta_min = s[2] < s[3] ? s[2] : NAN, m->eta_max = s[2] < s[3] ? s[3] : NAN;
	for (i = 0; i < p->n; i++)
		v[i] = 1 / (1 - v[i]);
	series_stats(v, p->n, s);
	m->aspect_mean = s[0], m->aspect_min = s[2] < s[3] ? s[2] : NAN, m->aspect_max = s[2] < s[3] ? s[3] : NAN;
	/* the face normals n = R(q) e3, the third column of R(q), of the plates */
	for (i = 0; i < p->n; i++)
		if (shape_of(pack_grain_shape(p, i))->oriented) {
			quat_to_matrix(p->q + 4 * i, R);
			v[3 * m->plates] = R[2], v[3 * m->plates + 1] = R[5], v[3 * m->plates + 2] = R[8];
			m->plates++;
		}
	m->nematic = m->director[0] = m->director[1] = m->director[2] = NAN;
	if (m->plates)
		status = measure_nematic(v, m->plates, &m->nematic, m->director);
	free(v);
	return status ? status : measure_plate_contacts(p, m, NULL, NULL, NULL);
}

int
measure_is_plate_pack(const struct pack *p)
{
	const struct contact_law *law = contact_law_of_pack(p);

	if (!law)
		return -1;
	/* the sphere report's limits are the frictional chain's (contact_laws_qs_friction) */
	return pack_first_plate(p) != (size_t)-1 || !contact_law_in(law, contact_laws_qs_friction);
}

void
grain_forces_free(struct grain_forces *g)
{
	free(g->z);
	free(g->fmax);
	free(g->residual);
	free(g->link);
	memset(g, 0, sizeof *g);
}

/* The spheres' per-grain record: measure_pack's walk over the contacts (measure_contact),
 * its balance kept per grain. */
static int
sphere_grain_forces(const struct pack *p, struct grain_forces *g)
{
	struct geo_contacts gc;
	struct pack_measures m;
	struct balance b;
	unsigned char *rat = calloc(p->n ? p->n : 1, 1);
	size_t k;
	int status = -1;

	contacts_init(&gc);
	memset(&m, 0, sizeof m);
	memset(&b, 0, sizeof b);
	b.F = calloc(3 * (p->n ? p->n : 1), sizeof *b.F);
	b.M = calloc(3 * (p->n ? p->n : 1), sizeof *b.M);
	b.fbig = g->fmax;
	b.rat = rat;	/* no rattlers: only measure_pack's counts read them */
	if (!rat || !b.F || !b.M) {
		msg_seterr("out of memory");
		goto out;
	}
	if (balance_bind_law(&b, p) || contacts_find(p, &gc))
		goto out;
	measure_coordination(p, &gc, g->z);
	for (k = 0; k < gc.n; k++) {
		measure_contact(p, &gc.c[k], &m, &b);
		if (grain_forces_link(g, gc.c[k].i, gc.c[k].j))
			goto out;
		g->link[g->nlink - 1].P = gc.c[k].P;
	}
	g->has_forces = gc.n > 0 && m.P_max > 0;
	for (k = 0; k < p->n; k++)
		g->residual[k] = g->has_forces && b.fbig[k] > 0 ? grain_unbalance(p, &b, k) /
		    fmax(b.fbig[k], MEASURE_RESIDUAL_FLOOR * b.Psum / (double)gc.n) : NAN;
	status = 0;
out:
	contacts_free(&gc);
	free(rat);
	free(b.F);
	free(b.M);
	return status;
}

int
measure_grain_forces(const struct pack *p, struct grain_forces *g)
{
	size_t n = p->n ? p->n : 1;
	int r;

	memset(g, 0, sizeof *g);
	g->n = p->n;
	g->z = calloc(n, sizeof *g->z);
	g->fmax = calloc(n, sizeof *g->fmax);
	g->residual = calloc(n, sizeof *g->residual);
	if (!g->z || !g->fmax || !g->residual) {
		grain_forces_free(g);
		msg_seterr("out of memory");
		return -1;
	}
	if ((r = measure_is_plate_pack(p)) < 0) {
		grain_forces_free(g);
		return -1;
	}
	if (r) {
		struct plate_measures m;

		memset(&m, 0, sizeof m);
		r = measure_plate_contacts(p, &m, g, NULL, NULL);
	} else {
		r = sphere_grain_forces(p, g);
	}
	if (r)
		grain_forces_free(g);
	return r;
}

int
measure_plate_contact_list(const struct pack *p, struct plate_contact **list, size_t *n)
{
	struct plate_measures m;

	memset(&m, 0, sizeof m);
	*list = NULL, *n = 0;
	return measure_plate_contacts(p, &m, NULL, list, n);
}
