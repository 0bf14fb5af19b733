/* SPDX-License-Identifier: GPL-3.0-or-later */
/* friction: Mindlin-Deresiewicz tangential force and torsion over a frozen increment
 * (see friction.h). */
#include "qs/friction.h"
#include "qs/hessian.h"
#include "contact/contacts.h"
#include "contact/hertz.h"
#include "base/msg.h"
#include "base/par.h"
#include "base/vec3.h"
#include "base/lanes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* doubles per grain in f->gs: x - x0 (3), w = R Omega (3) */
#define FR_GS 6

void
fr_init(struct qs_friction *f, enum fr_rule rule)
{
	memset(f, 0, sizeof *f);
	f->rule = rule;
}

void
fr_free(struct qs_friction *f)
{
	free(f->c);
	free(f->lp);
	free(f->x0);
	free(f->gs);
	free(f->row_first), free(f->wall_first), free(f->col_first), free(f->col_k), free(f->blk);
	contacts_free(&f->found);
	memset(f, 0, sizeof *f);
}

void
fr_keep_found(struct qs_friction *f, int on)
{
	f->keep_found = on;
	if (!on) {
		contacts_free(&f->found);
		f->found_ok = 0;
	}
}

int
fr_rule_parse(const char *name, enum fr_rule *rule)
{
	if (strcmp(name, "return-map") == 0)
		*rule = FR_RETURN_MAP;
	else if (strcmp(name, "paper") == 0)
		*rule = FR_PAPER;
	else
		return -1;
	return 0;
}

const char *
fr_rule_name(enum fr_rule rule)
{
	return rule == FR_PAPER ? "paper" : "return-map";
}

/* The frozen quantities of one contact at the reference configuration (physics.md §3-5). */
static void
setup_contact(const struct qs_system *s, const struct law_pack *lk, const struct geo_contact *g, struct fr_contact *c,
    struct qs_friction *f)
{
	const struct pack *p = s->p;
	const struct contact_law *law = s->law;
	size_t i = g->i;
	double li, lj, Q0[3] = {0, 0, 0}, M0 = 0, tq[3], tn, qn;
	int wall = PACK_IS_WALL(g->j), k;
	struct law_pair lp;
	struct law_tangent t;

	/* every field is set below (no memset: 224 bytes of stores a contact and pass) */
	c->qp[0] = c->qp[1] = c->qp[2] = 0;
	c->qtrial = 0;
	c->i = i;
	c->j = g->j;
	memcpy(c->n, g->n, sizeof c->n);
	law->pair(law, lk, i, g->j, &lp);
	f->lp[c - f->c] = lp;	/* for its limit at the commit (fr_commit_evaluated) */
	contact_lever_lengths(wall, p->r[i], wall ? 0 : p->r[g->j], g->d, g->h, &li, &lj);
	c->li = li;
	c->lj = wall ? 0 : lj;
	c->ai = li / p->r[i];
	c->bi = 1 / p->r[i];
	c->aj = wall ? 0 : lj / p->r[g->j];
	c->bj = wall ? 0 : 1 / p->r[g->j];
	law->tangent(law, &lp, g->h, g->P, &t);
	c->k = t.k;
	c->qmax = t.qmax;
	c->kt = t.kt;
	c->mmax = t.mmax;
	if (g->hist >= 0) {
		pack_contact_q0_on(&p->c[g->hist], i, Q0);
		M0 = p->c[g->hist].M0;
	}
	/* Q^p = |Q0| T Q0 / |T Q0|: the history force turned into the reference tangent plane */
	tn = vec3_dot(Q0, c->n);
	for (k = 0; k < 3; k++)
		tq[k] = Q0[k] - tn * c->n[k];
	qn = vec3_norm(tq);
	if (qn > 0)
		for (k = 0; k < 3; k++)
			c->qp[k] = tq[k] * (vec3_norm(Q0) / qn);
	qn = vec3_norm(c->qp);
	if (qn > c->qmax || fabs(M0) > c->mmax) {
		double ex = fmax(c->qmax > 0 ? qn / c->qmax - 1 : (qn > 0 ? INFINITY : 0),
		    c->mmax > 0 ? fabs(M0) / c->mmax - 1 : (M0 != 0 ? INFINITY : 0));
		if (ex > 1e-9) {
			f->clamped++;
			f->clamp_excess = fmax(f->clamp_excess, ex);
		}
		if (qn > c->qmax)
			for (k = 0; k < 3; k++)
				c->qp[k] *= c->qmax / qn;
		if (fabs(M0) > c->mmax)
			M0 = M0 > 0 ? c->mmax : -c->mmax;
	}
	c->mp = M0;
	c->pp = vec3_dot(c->qp, c->qp);
	c->mpp = c->mp * c->mp;
	memcpy(c->Q, c->qp, sizeof c->Q);
	c->M = c->mp;
}


/* The mean committed normal force over p's history lines (0 without lines). */
static double
history_mean_P(const struct pack *p)
{
	double Pmean = 0;
	size_t k;

	for (k = 0; k < p->nc; k++)
		Pmean += p->c[k].P0 / p->nc;
	return Pmean;
}

/* A floor under M_max(Pmean) of every pair and wall contact of p, by the law at the pair
 * constants that make it least: Mindlin's grows with R* and falls with E*, so the largest E*
 * and the smallest R* (r_min / 2), with the smaller friction coefficient (the chain's laws,
 * contact_laws_qs_friction, are Mindlin's), less 0.1 % for the rounding of the per-contact
 * forms. */
static double
history_mmax_floor(const struct contact_law *law, const struct law_pack *lk, double Pmean)
{
	const struct pack *p = lk->p;
	double cmin = INFINITY, rmin = INFINITY, wall_comp = hertz_compliance(p->wall_E, p->wall_nu), mmax;
	struct law_pair lp;
	size_t i;

	for (i = 0; i < p->n; i++) {
		cmin = fmin(cmin, hertz_compliance(p->E[i], p->nu[i]));
		rmin = fmin(rmin, p->r[i]);
	}
	if (!(Pmean > 0) || !(cmin > 0) || !(rmin > 0))
		return 0;
	law->pair(law, lk, 0, 0, &lp);	/* the law's other constants, of any pair */
	lp.Es = hertz_Estar_c(cmin, wall_comp > 0 ? fmin(cmin, wall_comp) : cmin);
	lp.Rs = rmin / 2;
	lp.mu = fmin(p->mu, p->wall_mu);
	law_contact_limits(law, &lp, Pmean, NULL, &mmax);
	return 0.999 * mmax;
}

/* Whether history line c lies beyond what a commit of an equilibrium can leave: |Q0| above
 * the sliding limit at P0 + Pmean (mu (P0 + Pmean)), or |M0| above M_max(P0) + M_max(Pmean)
 * (the slip the normal force's fall in one increment calls for is far below the limit of an
 * average contact), the limits the law's (law_contact_limits).  1 for Q0, 2 for M0, 0 within.
 * mfloor: history_mmax_floor's, under which a couple needs no check. */
static int
line_beyond_commit(const struct contact_law *law, const struct law_pair *lp, const struct pack_contact *c,
    double Pmean, double mfloor)
{
	double m0, mmean;

	/* every commit checks every line: the torsional limits (two cube roots) only when the
	 * force is within its bound and the couple is above the floor of every contact's */
	if (vec3_norm(c->Q0) > law->coulomb(law, lp, c->P0 + Pmean) * (1 + 1e-9))
		return 1;
	if (fabs(c->M0) < mfloor)
		return 0;
	law_contact_limits(law, lp, c->P0, NULL, &m0);
	law_contact_limits(law, lp, Pmean, NULL, &mmean);
	return fabs(c->M0) > (m0 + mmean) * (1 + 1e-9) ? 2 : 0;
}

int
fr_check_history(const struct contact_law *law, const struct pack *p)
{
	struct law_pack lk;
	double Pmean, mfloor;
	size_t k;

	law_pack_bind(law, p, &lk);
	Pmean = history_mean_P(p), mfloor = history_mmax_floor(law, &lk, Pmean);
	for (k = 0; k < p->nc; k++) {
		const struct pack_contact *c = &p->c[k];
		double mu = pack_contact_mu(p, c->j), qn = vec3_norm(c->Q0), q0, m0, qmean;
		struct law_pair lp;
		char jn[32];
		int beyond;

		law->pair(law, &lk, c->i, c->j, &lp);
		if (!(beyond = line_beyond_commit(law, &lp, c, Pmean, mfloor)))
			continue;
		if (PACK_IS_WALL(c->j))
			snprintf(jn, sizeof jn, "%s", pack_wall_names[PACK_WALL_INDEX(c->j)]);
		else
			snprintf(jn, sizeof jn, "%ld", p->id[c->j]);
		law_contact_limits(law, &lp, c->P0, &q0, &m0);
		law_contact_limits(law, &lp, Pmean, &qmean, NULL);
		if (beyond == 1)
			msg_seterr("contact %ld %s: |Q0| = %.6g N is far above its sliding limit mu P0 = %.6g N (mu %g; "
			           "a committed pack exceeds it by less than mu times the mean normal force, %.6g N)",
			    p->id[c->i], jn, qn, q0, mu, qmean);
		else
			msg_seterr("contact %ld %s: |M0| = %.6g N m is far above its torsional limit %.6g N m (mu %g)",
			    p->id[c->i], jn, fabs(c->M0), m0, mu);
		return -1;
	}
	return 0;
}

static double friction_energy(struct qs_term *t, struct qs_system *s, const double *x, double *g, double *fmax);
static void friction_stiffness(struct qs_term *t, struct qs_system *s, const double *x, double *k);
static int friction_hessian(struct qs_term *t, struct qs_system *s, const double *x, struct qs_hessian *H);

/* The index of f->c over n grains (see struct qs_friction); the list is contacts_find's:
 * the pairs by i then j, then the walls by grain.  0 or -1. */
static int
fr_index(struct qs_friction *f, size_t n)
{
	size_t k, i, *fill, np = 0, nb = (n + par_block(n) - 1) / par_block(n);

	free(f->row_first), free(f->wall_first), free(f->col_first), free(f->col_k), free(f->blk);
	f->row_first = calloc(n + 1, sizeof *f->row_first);
	f->wall_first = calloc(n + 1, sizeof *f->wall_first);
	f->col_first = calloc(n + 1, sizeof *f->col_first);
	f->col_k = malloc((f->n ? f->n : 1) * sizeof *f->col_k);
	f->blk = malloc((nb ? nb : 1) * sizeof *f->blk);
	fill = calloc(n ? n : 1, sizeof *fill);
	if (!f->row_first || !f->wall_first || !f->col_first || !f->col_k || !f->blk || !fill) {
		free(fill);
		msg_seterr("out of memory");
		return -1;
	}
	for (k = 0; k < f->n; k++) {
		const struct fr_contact *c = &f->c[k];
		if (PACK_IS_WALL(c->j)) {
			f->wall_first[c->i + 1]++;
		} else {
			f->row_first[c->i + 1]++;
			f->col_first[c->j + 1]++;
			np++;
		}
	}
	f->wall_first[0] = np;
	for (i = 0; i < n; i++) {
		f->row_first[i + 1] += f->row_first[i];
		f->wall_first[i + 1] += f->wall_first[i];
		f->col_first[i + 1] += f->col_first[i];
	}
	for (k = 0; k < np; k++) {
		size_t j = (size_t)f->c[k].j;
		f->col_k[f->col_first[j] + fill[j]++] = k;
	}
	free(fill);
	return 0;
}

int
fr_begin(struct qs_friction *f, struct qs_system *s)
{
	struct pack *p = s->p;
	struct geo_contacts gc;
	struct law_pack lk;
	size_t k, matched = 0;

	/* the last commit's contacts when it kept them (fr_keep_found), else found here */
	if (f->found_ok) {
		gc = f->found;
		contacts_init(&f->found);
		f->found_ok = 0;
	} else {
		contacts_init(&gc);
		if (contacts_find_in(p, &s->ce, &gc))
			return -1;
	}
	if (gc.n > f->cap) {
		struct fr_contact *c = realloc(f->c, gc.n * sizeof *c);
		struct law_pair *lp = c ? realloc(f->lp, gc.n * sizeof *lp) : NULL;
		if (c)
			f->c = c;
		if (!c || !lp) {
			contacts_free(&gc);
			msg_seterr("out of memory for contacts");
			return -1;
		}
		f->lp = lp;
		f->cap = gc.n;
	}
	if (f->ngrains != p->n || !f->x0 || !f->gs) {
		free(f->x0);
		free(f->gs);
		f->x0 = malloc((p->n ? 3 * p->n : 1) * sizeof *f->x0);
		f->gs = malloc((p->n ? FR_GS * p->n : 1) * sizeof *f->gs);
		if (!f->x0 || !f->gs) {
			contacts_free(&gc);
			msg_seterr("out of memory");
			return -1;
		}
		f->ngrains = p->n;
	}
	memcpy(f->x0, p->x, 3 * p->n * sizeof *f->x0);
	f->n = gc.n;
	f->clamped = 0;
	f->clamp_excess = 0;
	law_pack_bind(s->law, p, &lk);	/* once for every contact's pair setup */
	for (k = 0; k < gc.n; k++) {
		setup_contact(s, &lk, &gc.c[k], &f->c[k], f);
		matched += gc.c[k].hist >= 0;
	}
	f->stale = p->nc - matched;
	contacts_free(&gc);
	if (fr_index(f, p->n))
		return -1;
	qs_remove_terms(s);
	qs_set_rotations(s, 1);
	/* the paper's rule has no potential, so no Hessian: Newton's method refuses it */
	return qs_add_term(s, &(struct qs_term){"friction", friction_energy, friction_stiffness, f,
	    f->rule == FR_RETURN_MAP ? friction_hessian : NULL});
}

/* s^2 below the limit, its tangent 2 lim s - lim^2 above: the return map's potential,
 * continuous with its derivative at s = lim. */
static double
clamp_potential(double s, double lim)
{
	return s <= lim ? s * s : 2 * lim * s - lim * lim;
}

/* Contact c at x: its force Q on i, couple M on i about n and elastic trial |Q^p - k u_s|
 * into Q, M, qtrial; returns its energy.  Reads only f->gs (x - x0 and w = R Omega per grain,
 * from fr_grains) and c's frozen data, so a thread may evaluate a contact that another owns
 * (fr_energy's gathers).  wall (c is a wall contact) and rule (f->rule) are constants at
 * each call, so that each kind compiles without the others' branches.
 * The slip u_s = T du + Omega_i x R_ij - Omega_j x R_ji is, with the lever arms along n,
 * T du - (ai w_i + aj w_j) x n: one cross product; the twist (Omega_i - Omega_j) . n is
 * bi w_i . n - bj w_j . n (walls translate along their normal and do not turn). */
CONTACT_INLINE double
fr_contact_eval(const struct qs_friction *f, const struct fr_contact *c, double Q[3], double *M, double *qtrial,
    const int wall, const enum fr_rule rule)
{
	size_t i = c->i, j = wall ? 0 : (size_t)c->j;
	int a;
	const double *gi = f->gs + FR_GS * i, *gj = f->gs + FR_GS * j, *wi = gi + 3, *wj = gj + 3;
	double du[3], v[3], us[3], t[3], dn, Ot, q[3], qn, m, E, Et, es, et;

	VEC3_UNROLL
	for (a = 0; a < 3; a++) {
		du[a] = wall ? gi[a] : gi[a] - gj[a];
		v[a] = wall ? c->ai * wi[a] : c->ai * wi[a] + c->aj * wj[a];
	}
	dn = vec3_dot(du, c->n);
	vec3_cross(v, c->n, t);
	VEC3_UNROLL
	for (a = 0; a < 3; a++)
		us[a] = du[a] - dn * c->n[a] - t[a];
	VEC3_UNROLL
	for (a = 0; a < 3; a++)
		q[a] = c->qp[a] - c->k * us[a];
	qn = vec3_norm(q);
	*qtrial = qn;
	/* torsion: Omega_t = (Omega_i - Omega_j) . n, the same clamp in one dimension */
	Ot = wall ? c->bi * vec3_dot(wi, c->n) : c->bi * vec3_dot(wi, c->n) - c->bj * vec3_dot(wj, c->n);
	m = c->mp - c->kt * Ot;
	*M = fabs(m) <= c->mmax ? m : (m > 0 ? c->mmax : -c->mmax);
	et = clamp_potential(fabs(m), c->mmax) - c->mpp;
	if (rule == FR_PAPER && qn > c->qmax) {
		/* F (6)-(7b): the stiffness reduced so that |Q^p - k u_s| = Q_max */
		double un = vec3_norm(us), cq = vec3_dot(c->qp, us) / un, pp = c->pp;
		double rad = cq * cq + c->qmax * c->qmax - pp, kr = rad > 0 ? (cq + sqrt(rad)) / un : 0;
		VEC3_UNROLL
		for (a = 0; a < 3; a++)
			Q[a] = c->qp[a] - kr * us[a];
		qn = vec3_norm(Q);
		if (qn > c->qmax)	/* only when |Q^p| > Q_max, which fr_begin rules out */
			VEC3_UNROLL
			for (a = 0; a < 3; a++)
				Q[a] *= c->qmax / qn;
		E = -vec3_dot(c->qp, us) + 0.5 * kr * vec3_dot(us, us);
		E += et / (2 * c->kt);
		return E;
	}
	if (qn <= c->qmax) {
		memcpy(Q, q, sizeof q);
		es = qn * qn - c->pp;
	} else {
		/* the return map: Q = Q_max q / |q| */
		V2_DIV2(Q[0], Q[1], c->qmax * q[0], c->qmax * q[1], qn, qn);
		Q[2] = c->qmax * q[2] / qn;
		es = clamp_potential(qn, c->qmax) - c->pp;
	}
	/* E = es / (2 k*) + et / (2 k*_t), in that order */
	V2_DIV2(E, Et, es, et, 2 * c->k, 2 * c->kt);
	return E + Et;
}

#if LANES_OK
/* The kernel on two contacts at once (SSE2), and on four (AVX2, where the processor has it:
 * lanes4_ok): one text, fr_lanes.h. */
#define FR_LN 2
#define FR_VD v2d
#define FR_VM v2m
#define FR_SEL V2_SELECT
#define FR_ABS V2_ABS
#define FR_SQRT V2_SQRT
#define FR_CROSS V2_CROSS
#define FR_FIELD(fld) ((v2d){cs[0]->fld, cs[1]->fld})
#define FR_AT(p, i) ((v2d){p[0][i], p[1][i]})
#define FR_ATTR CONTACT_INLINE
#define FR_NAME fr_pair2
#include "qs/fr_lanes.h"
#if LANES4_OK
#define FR_LN 4
#define FR_VD v4d
#define FR_VM v4m
#define FR_SEL V4_SELECT
#define FR_ABS V4_ABS
#define FR_SQRT V4_SQRT
#define FR_CROSS V4_CROSS
#define FR_FIELD(fld) ((v4d){cs[0]->fld, cs[1]->fld, cs[2]->fld, cs[3]->fld})
#define FR_AT(p, i) ((v4d){p[0][i], p[1][i], p[2][i], p[3][i]})
#define FR_ATTR AVX2_INLINE
#define FR_NAME fr_pair4
#include "qs/fr_lanes.h"
#endif
#endif

/* Grains g0..g1 of f->gs at x: the translation x - x0 and the rotation w = R Omega, side by
 * side, once a grain rather than once a contact. */
static void
fr_grains(struct qs_friction *f, const struct qs_system *s, const double *x, size_t g0, size_t g1)
{
	const double *x0 = f->x0, *w = x + 3 * s->n;
	size_t i;
	int a;

	for (i = g0; i < g1; i++) {
		double *gi = f->gs + FR_GS * i;
		for (a = 0; a < 3; a++) {
			gi[a] = x[3 * i + a] - x0[3 * i + a];
			gi[3 + a] = w[3 * i + a];
		}
	}
}

/* The gradient of contact c with force Q and couple M: dPi/du_i = -Q, dPi/dOmega_i =
 * -(R_ij x Q) - M n, which over R_i (the unknown is w = R Omega) is ai (n x Q) - bi M n; on j
 * the opposite force and its own lever arm, -(aj (n x Q) + bj M n).  Everything is read into
 * locals before the first store into g: g may alias c (both double), and the compiler would
 * read c's fields again after each store (a third of the kernel's instructions). */
CONTACT_INLINE void
fr_add_i(const struct qs_system *s, double *g, const struct fr_contact *c, const double Q[3], double M)
{
	size_t i = c->i;
	double *gi = g + 3 * i, *gwi = g + 3 * s->n + 3 * i;
	const double n0 = c->n[0], n1 = c->n[1], n2 = c->n[2], q0 = Q[0], q1 = Q[1], q2 = Q[2];
	const double ai = c->ai, mi = M * c->bi;
	const double x0 = n1 * q2 - n2 * q1, x1 = n2 * q0 - n0 * q2, x2 = n0 * q1 - n1 * q0;
	const double w0 = ai * x0 - mi * n0, w1 = ai * x1 - mi * n1, w2 = ai * x2 - mi * n2;

	gi[0] -= q0, gi[1] -= q1, gi[2] -= q2;
	gwi[0] += w0, gwi[1] += w1, gwi[2] += w2;
}

CONTACT_INLINE void
fr_add_j(const struct qs_system *s, double *g, const struct fr_contact *c, const double Q[3], double M)
{
	size_t j = (size_t)c->j;
	double *gj = g + 3 * j, *gwj = g + 3 * s->n + 3 * j;
	const double n0 = c->n[0], n1 = c->n[1], n2 = c->n[2], q0 = Q[0], q1 = Q[1], q2 = Q[2];
	const double aj = c->aj, mj = M * c->bj;
	const double x0 = n1 * q2 - n2 * q1, x1 = n2 * q0 - n0 * q2, x2 = n0 * q1 - n1 * q0;
	const double w0 = aj * x0 + mj * n0, w1 = aj * x1 + mj * n1, w2 = aj * x2 + mj * n2;

	gj[0] += q0, gj[1] += q1, gj[2] += q2;
	gwj[0] += w0, gwj[1] += w1, gwj[2] += w2;
}

/* fr_add_i and fr_add_j of a pair in one (n x Q once). */
CONTACT_INLINE void
fr_add_ij(const struct qs_system *s, double *g, const struct fr_contact *c, const double Q[3], double M)
{
	size_t i = c->i, j = (size_t)c->j;
	double *gi = g + 3 * i, *gwi = g + 3 * s->n + 3 * i, *gj = g + 3 * j, *gwj = g + 3 * s->n + 3 * j;
	const double n0 = c->n[0], n1 = c->n[1], n2 = c->n[2], q0 = Q[0], q1 = Q[1], q2 = Q[2];
	const double ai = c->ai, aj = c->aj, mi = M * c->bi, mj = M * c->bj;
	const double x0 = n1 * q2 - n2 * q1, x1 = n2 * q0 - n0 * q2, x2 = n0 * q1 - n1 * q0;
	const double wi0 = ai * x0 - mi * n0, wi1 = ai * x1 - mi * n1, wi2 = ai * x2 - mi * n2;
	const double wj0 = aj * x0 + mj * n0, wj1 = aj * x1 + mj * n1, wj2 = aj * x2 + mj * n2;

	gi[0] -= q0, gi[1] -= q1, gi[2] -= q2;
	gwi[0] += wi0, gwi[1] += wi1, gwi[2] += wi2;
	gj[0] += q0, gj[1] += q1, gj[2] += q2;
	gwj[0] += wj0, gwj[1] += wj1, gwj[2] += wj2;
}

/* What the rows of grains below g0 (other threads') scatter into grains g0 <= j < g1: the
 * pairs (m < g0, j) in ascending m, computed as the rows compute them. */
CONTACT_INLINE void
fr_gather(const struct qs_friction *f, const struct qs_system *s, double *g, size_t g0, size_t g1,
    const enum fr_rule rule)
{
	size_t j, k;

	for (j = g0; j < g1; j++)
		for (k = f->col_first[j]; k < f->col_first[j + 1] && f->c[f->col_k[k]].i < g0; k++) {
			const struct fr_contact *c = &f->c[f->col_k[k]];
			double Q[3], M, qt;
			fr_contact_eval(f, c, Q, &M, &qt, 0, rule);
			fr_add_j(s, g, c, Q, M);
		}
}

/* Block b's contacts (grains i0 <= i < i1) from its pair k on: its pairs, then its walls;
 * returns Eb plus their energies, added one by one.  lanes (a constant at each call): the
 * pairs two at a time (fr_pair2) under the return map; without, one at a time, the reference
 * the kernels in lanes must equal (fr_energy_scalar). */
CONTACT_INLINE double
fr_block_from(struct qs_friction *f, const struct qs_system *s, double *g, size_t k, size_t i0, size_t i1, size_t g1,
    const enum fr_rule rule, const int lanes, double Eb)
{
#if LANES_OK
	if (lanes && rule == FR_RETURN_MAP)
		for (; k + 1 < f->row_first[i1]; k += 2) {
			struct fr_contact *cs[2] = {&f->c[k], &f->c[k + 1]};
			double E2[2];
			fr_pair2(f, s, g, g1, cs, E2);
			Eb += E2[0];
			Eb += E2[1];
		}
#endif
	for (; k < f->row_first[i1]; k++) {
		struct fr_contact *c = &f->c[k];
		Eb += fr_contact_eval(f, c, c->Q, &c->M, &c->qtrial, 0, rule);
		if (g) {
			if ((size_t)c->j < g1) {
				fr_add_ij(s, g, c, c->Q, c->M);
			} else {
				fr_add_i(s, g, c, c->Q, c->M);
			}
		}
	}
	for (k = f->wall_first[i0]; k < f->wall_first[i1]; k++) {
		struct fr_contact *c = &f->c[k];
		Eb += fr_contact_eval(f, c, c->Q, &c->M, &c->qtrial, 1, rule);
		if (g)
			fr_add_i(s, g, c, c->Q, c->M);
	}
	return Eb;
}

/* Block b's contacts, all of them (fr_block_from its first pair). */
CONTACT_INLINE double
fr_block(struct qs_friction *f, const struct qs_system *s, double *g, size_t i0, size_t i1, size_t g1,
    const enum fr_rule rule, const int lanes)
{
	return fr_block_from(f, s, g, f->row_first[i0], i0, i1, g1, rule, lanes, 0);
}

/* The widest kernel the build and processor have (4 lanes with AVX2), or 2 (fr_set_lanes). */
static int fr_lanes = 4;

void
fr_set_lanes(int n)
{
	fr_lanes = n == 2 ? 2 : 4;
}

#if LANES4_OK
/* fr_block's pairs four at a time (fr_pair4, AVX2), then the rest as fr_block: the same
 * contacts in the same order, each lane fr_contact_eval's bytes (test_friction's lanes
 * check). */
static AVX2_FN double
fr_block4(struct qs_friction *f, const struct qs_system *s, double *g, size_t i0, size_t i1, size_t g1)
{
	double Eb = 0;
	size_t k = f->row_first[i0];

	for (; k + 3 < f->row_first[i1]; k += 4) {
		struct fr_contact *cs[4] = {&f->c[k], &f->c[k + 1], &f->c[k + 2], &f->c[k + 3]};
		double E4[4];
		fr_pair4(f, s, g, g1, cs, E4);
		Eb += E4[0];
		Eb += E4[1];
		Eb += E4[2];
		Eb += E4[3];
	}
	/* the rest (fewer than four pairs, the walls) as fr_block, the sum going on */
	return fr_block_from(f, s, g, k, i0, i1, g1, FR_RETURN_MAP, 1, Eb);
}
#endif

/* The friction term on threads, with the same bytes for any number of them (base/par.h):
 * the grains in blocks of par_block(n), each block's pairs (i in the block) then its walls,
 * the block energies added in block order; a thread takes a run of blocks and first
 * gathers into its grains the pairs (m, j) whose m belongs to an earlier thread, in
 * ascending m, and never scatters into a later thread's grains.  Every grain's gradient is
 * then the sum of the same terms in the same order as the serial walk of the list (the
 * pairs (m < j, j), j's own pairs, j's walls), whatever the thread count. */
static double
fr_energy(struct qs_friction *f, const struct qs_system *s, const double *x, double *g)
{
	size_t n = s->n, bl = par_block(n), nb = n ? (n + bl - 1) / bl : 0, q;
	double E = 0;

#pragma omp parallel if (n >= PAR_MIN && par_threads() > 1)
	{
		size_t T = (size_t)par_team(), t = (size_t)par_tid(), b;
		size_t b0 = nb * t / T, b1 = nb * (t + 1) / T;
		size_t g0 = b0 * bl < n ? b0 * bl : n, g1 = b1 * bl < n ? b1 * bl : n;

		fr_grains(f, s, x, g0, g1);
#pragma omp barrier
		if (g && g0 > 0) {
			if (f->rule == FR_RETURN_MAP)
				fr_gather(f, s, g, g0, g1, FR_RETURN_MAP);
			else
				fr_gather(f, s, g, g0, g1, FR_PAPER);
		}
		for (b = b0; b < b1; b++) {
			size_t i0 = b * bl, i1 = (b + 1) * bl < n ? (b + 1) * bl : n;
#if LANES4_OK
			if (f->rule == FR_RETURN_MAP && fr_lanes == 4 && lanes4_ok()) {
				f->blk[b] = fr_block4(f, s, g, i0, i1, g1);
				continue;
			}
#endif
			f->blk[b] = f->rule == FR_RETURN_MAP ? fr_block(f, s, g, i0, i1, g1, FR_RETURN_MAP, 1) :
			                                       fr_block(f, s, g, i0, i1, g1, FR_PAPER, 1);
		}
	}
	for (q = 0; q < nb; q++)
		E += f->blk[q];
	return E;
}

double
fr_energy_scalar(struct qs_friction *f, const struct qs_system *s, const double *x, double *g)
{
	size_t n = s->n, bl = par_block(n), nb = n ? (n + bl - 1) / bl : 0, b;
	double E = 0;

	fr_grains(f, s, x, 0, n);
	for (b = 0; b < nb; b++)
		E += fr_block(f, s, g, b * bl, (b + 1) * bl < n ? (b + 1) * bl : n, n, f->rule, 0);
	return E;
}

static double
friction_energy(struct qs_term *t, struct qs_system *s, const double *x, double *g, double *fmax)
{
	(void)fmax;
	return fr_energy(t->data, s, x, g);
}

size_t
fr_sliding(const struct qs_friction *f)
{
	size_t k, n = 0;

	for (k = 0; k < f->n; k++)
		if (f->c[k].qmax > 0 && vec3_norm(f->c[k].Q) >= f->c[k].qmax * (1 - 1e-9))
			n++;
	return n;
}

static void
friction_stiffness(struct qs_term *t, struct qs_system *s, const double *x, double *k)
{
	const struct qs_friction *f = t->data;
	size_t q;

	(void)x;
	for (q = 0; q < f->n; q++) {
		const struct fr_contact *c = &f->c[q];
		k[c->i] += c->k + c->kt / (s->p->r[c->i] * s->p->r[c->i]);
		if (c->j >= 0)
			k[c->j] += c->k + c->kt / (s->p->r[c->j] * s->p->r[c->j]);
	}
}

/* C = [l]x s: the matrix of v -> s (l x v). */
static void
cross_matrix(const double l[3], double s, double C[9])
{
	C[0] = 0, C[1] = -l[2] * s, C[2] = l[1] * s;
	C[3] = l[2] * s, C[4] = 0, C[5] = -l[0] * s;
	C[6] = -l[1] * s, C[7] = l[0] * s, C[8] = 0;
}

/* AB = A B (3x3, row-major); with ta, A^T B.  Inlined with ta a constant at each call, so
 * that each case compiles to straight-line code (the preconditioner's blocks are assembled at
 * every minimisation's start: this was 4 % of a frictional increment as a called loop). */
CONTACT_INLINE void
mat3_mul(const double *A, const double *B, double *AB, const int ta)
{
	int u, v, w;

	VEC3_UNROLL
	for (u = 0; u < 3; u++)
		VEC3_UNROLL
		for (v = 0; v < 3; v++) {
			double sum = 0;
			VEC3_UNROLL
			for (w = 0; w < 3; w++)
				sum += (ta ? A[3 * w + u] : A[3 * u + w]) * B[3 * w + v];
			AB[3 * u + v] = sum;
		}
}

/* D += sign S, and with sym S's upper triangle mirrored (S symmetric in exact arithmetic:
 * H then is symmetric to the bit, as CG assumes). */
CONTACT_INLINE void
mat3_add(double *D, const double *S, double sign, const int sym)
{
	int u, v;

	VEC3_UNROLL
	for (u = 0; u < 3; u++)
		VEC3_UNROLL
		for (v = 0; v < 3; v++)
			D[3 * u + v] += sign * (sym && v < u ? S[3 * v + u] : S[3 * u + v]);
}

/* A contact's blocks on one of its grains g, whose translation enters u_s as sign T and
 * whose rotation as C: (g, g) += K; (g, N+g) += sign K C (into cpl, summed per grain, unless
 * NULL); (N+g, N+g) += C^T K C + kt n n^T / R_g^2.  K C into KC. */
CONTACT_INLINE void
own_blocks(struct qs_hessian *H, double *cpl, size_t n, size_t g, const double K[9], const double C[9], double sign,
    double kt, const double nrm[3], double rg, double KC[9])
{
	double CKC[9];
	int u;

	mat3_add(H->diag + 9 * g, K, 1, 1);
	mat3_mul(K, C, KC, 0);
	if (cpl)
		mat3_add(cpl + 9 * g, KC, sign, 0);
	mat3_mul(C, KC, CKC, 1);
	VEC3_UNROLL
	for (u = 0; u < 9; u++)
		CKC[u] += kt * nrm[u / 3] * nrm[u % 3] / (rg * rg);
	mat3_add(H->diag + 9 * (n + g), CKC, 1, 1);
}

/* The return map's consistent tangent (hessian.h): Pi's tangential part is phi_s(q) with
 * q = Q^p - k* u_s and u_s linear in the unknowns, u_s = T dx_i + C_i w_i - T dx_j + C_j w_j
 * where w = R Omega, C_i = -[R_ij]x / R_i and C_j = [R_ji]x / R_j (the frozen lever arms).
 * Its second derivative in u_s is K = k* T while the contact sticks and
 * K = k* (Q_max / |q|) (T - qh qh^T), qh = q / |q|, while it slides (the disc's boundary:
 * no stiffness along the slip, the rest scaled down); K lies in the tangent plane, so
 * T K = K.  The unknowns' blocks are J_a^T K J_b with J = (T, C_i, -T, C_j), and torsion
 * adds k*_t n n^T / (R_a R_b) (signed) to the rotations while it sticks, nothing while it
 * slides.  The stick/slip state is x's: the Hessian of a piecewise smooth potential, exact
 * away from the switches (tests/unit/test_hessian.c checks it by differences of the
 * gradient).  The unknowns are 2N nodes of three: the centres, then the rotations at N + i;
 * the blocks coupling a grain's own centre and rotation are summed per grain first, one
 * block each.  With H->at_last_eval (the preconditioner's assembly at an iterate the
 * minimiser has just evaluated) each contact's force, couple and trial force are the last
 * evaluation's, not evaluated again: the same bytes (test_hessian).
 * (Closed forms of the diagonal blocks, C^T K C = a^2 k* T sticking and a^2 sc (T - p p^T),
 * p = qh x n, sliding, were tried: a fifth of the cost, but rounding in the
 * preconditioner moves every path, and s-fig4's frictionless G5036 probe at 2 MPa then
 * collapsed to 1 MPa in a rearrangement; bench/kernels.md.) */
static int
friction_hessian(struct qs_term *t, struct qs_system *s, const double *x, struct qs_hessian *H)
{
	struct qs_friction *f = t->data;
	size_t n = s->n, q, i;
	const double *r = s->p->r;
	double *cpl = H->diag_only ? NULL : calloc(9 * (n ? n : 1), sizeof *cpl);
	int st = 0;

	if (!cpl && !H->diag_only) {
		msg_seterr("out of memory for the Hessian");
		return -1;
	}
	if (!H->at_last_eval)
		fr_grains(f, s, x, 0, n);
	for (q = 0; q < f->n && !st; q++) {
		const struct fr_contact *c = &f->c[q];
		int wall = PACK_IS_WALL(c->j), u, v;
		size_t ci = c->i, cj = wall ? 0 : (size_t)c->j;
		double Q[3], M, qt, K[9], Ci[9], Cj[9], KC[9], B[9], kt, ri = r[ci], rj = wall ? 1 : r[cj], li[3], lj[3];

		if (H->at_last_eval) {
			/* the evaluation at x left them (the kernel's bytes are fr_contact_eval's) */
			memcpy(Q, c->Q, sizeof Q);
			M = c->M;
			qt = c->qtrial;
		} else {
			fr_contact_eval(f, c, Q, &M, &qt, wall, FR_RETURN_MAP);
		}
		if (!(c->qmax > 0)) {
			memset(K, 0, sizeof K);	/* no limit, no tangential force */
		} else if (qt <= c->qmax) {
			VEC3_UNROLL
			for (u = 0; u < 3; u++)
				VEC3_UNROLL
				for (v = 0; v < 3; v++)
					K[3 * u + v] = c->k * ((u == v) - c->n[u] * c->n[v]);
		} else {
			/* qh = Q / Q_max: the trial's direction */
			double sc = c->k * c->qmax / qt;
			VEC3_UNROLL
			for (u = 0; u < 3; u++)
				VEC3_UNROLL
				for (v = 0; v < 3; v++)
					K[3 * u + v] = sc * ((u == v) - c->n[u] * c->n[v] -
					    Q[u] / c->qmax * Q[v] / c->qmax);
		}
		kt = fabs(M) < c->mmax ? c->kt : 0;
		for (u = 0; u < 3; u++) {
			li[u] = -c->n[u] * c->li;
			lj[u] = c->n[u] * c->lj;
		}
		cross_matrix(li, -1 / ri, Ci);
		own_blocks(H, cpl, n, ci, K, Ci, 1, kt, c->n, ri, KC);
		if (wall)
			continue;
		cross_matrix(lj, 1 / rj, Cj);
		own_blocks(H, cpl, n, cj, K, Cj, -1, kt, c->n, rj, KC);
		if (H->diag_only)
			continue;
		/* the pair: (i, j) = -K, (i, N+j) = K C_j, (N+i, j) = -C_i^T K,
		 * (N+i, N+j) = C_i^T K C_j - kt n n^T / (R_i R_j) */
		for (u = 0; u < 9; u++)
			B[u] = -K[u];
		st |= qs_hessian_add_pair(H, ci, cj, B);
		st |= qs_hessian_add_pair(H, ci, n + cj, KC);
		mat3_mul(Ci, K, B, 1);
		for (u = 0; u < 9; u++)
			B[u] = -B[u];
		st |= qs_hessian_add_pair(H, n + ci, cj, B);
		mat3_mul(Ci, KC, B, 1);
		for (u = 0; u < 9; u++)
			B[u] -= kt * c->n[u / 3] * c->n[u % 3] / (ri * rj);
		st |= qs_hessian_add_pair(H, n + ci, n + cj, B);
	}
	for (i = 0; i < n && !st && cpl; i++) {
		int u, nz = 0;
		for (u = 0; u < 9; u++)
			nz |= cpl[9 * i + u] != 0;
		if (nz)
			st = qs_hessian_add_pair(H, i, n + i, cpl + 9 * i);
	}
	free(cpl);
	return st ? -1 : 0;
}

/* The sliding limit of reference contact c, of pair constants lp, at its normal force by the
 * law at the pack's current positions (0 when it has opened). */
static double
sliding_limit_now(const struct contact_law *law, const struct pack *p, const struct fr_contact *c,
    const struct law_pair *lp)
{
	struct contact now;
	double P;

	contact_between(p, p->x, c->i, c->j, &now);
	law->normal(law, lp, now.h, &P, NULL);
	return law->coulomb(law, lp, P);
}

int
fr_commit(struct qs_friction *f, struct qs_system *s, double *x)
{
	if (isnan(qs_energy(s, x, NULL, NULL)))
		return -1;
	return fr_commit_evaluated(f, s, x);
}

int
fr_commit_evaluated(struct qs_friction *f, struct qs_system *s, double *x)
{
	struct pack *p = s->p;
	const struct contact_law *law = s->law;
	struct law_pack lk;
	size_t k, n3 = 3 * s->n;

	/* the final forces become history lines; contacts_store keeps those still touching */
	p->nc = 0;
	for (k = 0; k < f->n; k++) {
		const struct fr_contact *c = &f->c[k];
		struct pack_contact pc = {c->i, c->j, 0, {c->Q[0], c->Q[1], c->Q[2]}, c->M};
		if (pack_add_contact(p, &pc))
			return -1;
	}
	memcpy(p->x, x, n3 * sizeof *x);
	f->found_ok = 0;
	if (contacts_store_found(p, &s->ce, 1, f->keep_found ? &f->found : NULL))
		return -1;
	f->found_ok = f->keep_found;
	memset(x + n3, 0, n3 * sizeof *x);
	/* A commit far from equilibrium (a minimisation stopped at its iteration limit, kept
	 * with --allow-limit) can leave a line whose normal force fell by far more than one
	 * increment's worth (a grain that overlapped its neighbours deeply at the start): its
	 * Q0 or M0, frozen at the start's limit, is then beyond what fr_check_history accepts
	 * from a commit, and the pack would not read back.  Such a line slips to its limit at
	 * P0 now, as the next increment's start (fr_begin's clamp) would do anyway.  A commit of
	 * an equilibrium never reaches that bound, so its lines are kept exactly. */
	f->ncommit_slipped = 0;
	f->nlimit = 0;	/* and the paper's count: the committed lines at their limit mu P0 */
	law_pack_bind(law, p, &lk);
	{
		double Pmean = history_mean_P(p), mfloor = history_mmax_floor(law, &lk, Pmean);

		for (k = 0; k < p->nc; k++) {	/* each line's limits by the law, its pair made once */
			struct pack_contact *c = &p->c[k];
			struct law_pair lp;
			double qn, qm, mm;
			int a;

			law->pair(law, &lk, c->i, c->j, &lp);
			if (line_beyond_commit(law, &lp, c, Pmean, mfloor)) {
				qn = vec3_norm(c->Q0);
				law_contact_limits(law, &lp, c->P0, &qm, &mm);
				if (qn > qm)
					for (a = 0; a < 3; a++)
						c->Q0[a] *= qm / qn;
				if (fabs(c->M0) > mm)
					c->M0 = c->M0 > 0 ? mm : -mm;
				f->ncommit_slipped++;
			}
			f->nlimit += (size_t)law_line_at_limit(law, &lp, c);
		}
	}
	/* the slip count: the trial force of each reference contact against the limit of its
	 * normal force now (opened contacts have none) */
	f->ntrial_slip = 0;
	for (k = 0; k < f->n; k++) {
		const struct fr_contact *c = &f->c[k];
		double qlim = sliding_limit_now(law, p, c, &f->lp[k]);
		if (qlim > 0 && c->qtrial >= qlim * (1 - 1e-9))
			f->ntrial_slip++;
	}
	return 0;
}

void
fr_detach(struct qs_system *s)
{
	qs_remove_terms(s);
	qs_set_rotations(s, 0);
}

struct qs_friction *
fr_attached(const struct qs_system *s)
{
	int q;

	for (q = 0; q < s->nterms; q++)
		if (s->term[q].energy == friction_energy)
			return s->term[q].data;
	return NULL;
}
