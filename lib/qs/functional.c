/* SPDX-License-Identifier: GPL-3.0-or-later */
/* functional: Hertz energy and gradient over a pack (see functional.h). */
#include "qs/functional.h"
#include "contact/hertz.h"
#include "base/vec3.h"
#include "qs/hessian.h"
#include "base/lanes.h"
#include "base/msg.h"
#include "base/par.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double normal_energy(struct qs_term *t, struct qs_system *s, const double *x, double *g, double *fmax);
static void normal_stiffness(struct qs_term *t, struct qs_system *s, const double *x, double *k);
static int normal_hessian(struct qs_term *t, struct qs_system *s, const double *x, struct qs_hessian *H);

int
qs_init(struct qs_system *s, struct pack *p, double skin)
{
	size_t i;

	memset(s, 0, sizeof *s);
	s->p = p;
	s->n = p->n;
	qs_set_rotations(s, 0);
	/* the pack's law (its contact-law key; Hertz-Mindlin without one): the functional's fast
	 * path is Hertz's, any other law goes through the law's interface */
	if (!(s->law = contact_law_of_pack(p)))
		return -1;
	s->term[0].name = "normal";
	s->term[0].energy = normal_energy;
	s->term[0].stiffness = normal_stiffness;
	s->term[0].hessian = normal_hessian;
	s->nterms = 1;
	s->comp = malloc((p->n ? p->n : 1) * sizeof *s->comp);
	if (!s->comp) {
		msg_seterr("out of memory");
		return -1;
	}
	s->rmin = INFINITY;
	for (i = 0; i < p->n; i++) {
		s->comp[i] = hertz_compliance(p->E[i], p->nu[i]);
		s->rmin = fmin(s->rmin, p->r[i]);
		s->rmax = fmax(s->rmax, p->r[i]);
	}
	s->wall_comp = hertz_compliance(p->wall_E, p->wall_nu);
	s->skin = skin * s->rmin;
	return contact_enum_init(&s->ce, p->n, p->r, p->box, p->box + 3, p->periodic, s->skin, 0);
}

void
qs_free(struct qs_system *s)
{
	free(s->comp);
	free(s->blk);
	free(s->hertz_coef);
	contact_enum_free(&s->ce);
	memset(s, 0, sizeof *s);
}

int
qs_add_term(struct qs_system *s, const struct qs_term *t)
{
	if (s->nterms == QS_MAX_TERMS) {
		msg_seterr("too many terms in the functional");
		return -1;
	}
	s->term[s->nterms++] = *t;
	return 0;
}

void
qs_remove_terms(struct qs_system *s)
{
	s->nterms = 1;
}

struct qs_term *
qs_term_named(struct qs_system *s, const char *name)
{
	int q;

	for (q = 0; q < s->nterms; q++)
		if (!strcmp(s->term[q].name, name))
			return &s->term[q];
	return NULL;
}

void
qs_set_rotations(struct qs_system *s, int rotations)
{
	layout_set(&s->layout, s->n, rotations);
	s->dim = s->layout.dim;
}

/* What the normal term's callbacks accumulate. */
struct normal_acc {
	struct qs_system *s;
	const double *x;
	double *g, *fmax, *k;
	double E, sumf;
	size_t nc;
	double wf[NWALLS];	/* the wall forces */
	size_t jend;		/* grains from here on belong to another thread: no scatter */
};

/* The walks of a law through its interface: the sums, and the pack bound for its pair setup
 * (law_pack_bind, once a walk).  Hertz's fast paths keep their accumulator as it is. */
struct law_acc {
	struct normal_acc a;
	struct law_pack lk;
};

/* The larger of a grain's largest contact force so far and P, without a branch: whether a
 * pair's force is its grain's largest so far is a coin toss in a pack, and a mispredicted
 * branch throws away the next pairs' square roots already in flight (2x the walk's time at
 * 1e4 grains).  The same value as "if (P > m) m = P" (maxsd keeps m when P is NaN or equal). */
static inline double
force_max(double m, double P)
{
	return P > m ? P : m;
}

/* The normal force P of contact c on grain i (and j), with energy U: gradient, largest
 * force per grain, wall forces, sums; for a wall and for a grain pair. */
CONTACT_INLINE void
normal_add_wall(struct normal_acc *a, const struct contact *c, double P, double U)
{
	size_t i = c->i;
	int w = PACK_WALL_INDEX(c->j);

	a->E += U;
	a->sumf += P;
	a->nc++;
	a->s->wall_force[w] += P;
	if (a->g)
		a->g[3 * i + w / 2] += w % 2 ? P : -P;
	if (a->fmax)
		a->fmax[i] = force_max(a->fmax[i], P);
}

CONTACT_INLINE void
normal_add_pair(struct normal_acc *a, const struct contact *c, double P, double U)
{
	size_t i = c->i, j = (size_t)c->j;

	a->E += U;
	a->sumf += P;
	a->nc++;
	if (a->g) {
		double f = P / c->d;
		a->g[3 * i] -= f * c->dx[0];
		a->g[3 * i + 1] -= f * c->dx[1];
		a->g[3 * i + 2] -= f * c->dx[2];
		if (j < a->jend) {	/* a later thread's grain: it gathers this (hertz_gather) */
			a->g[3 * j] += f * c->dx[0];
			a->g[3 * j + 1] += f * c->dx[1];
			a->g[3 * j + 2] += f * c->dx[2];
		}
	}
	if (a->fmax) {
		a->fmax[i] = force_max(a->fmax[i], P);
		if (j < a->jend)
			a->fmax[j] = force_max(a->fmax[j], P);
	}
}

static inline void
normal_add(struct normal_acc *a, const struct contact *c, double P, double U)
{
	if (PACK_IS_WALL(c->j))
		normal_add_wall(a, c, P, U);
	else
		normal_add_pair(a, c, P, U);
}

/* Contact c through s's law's interface: its energy, normal force *P and, unless k is NULL,
 * stiffness *k (every law; Hertz's fast paths below give the same bytes). */
static double
law_normal_at(const struct qs_system *s, const struct law_pack *lk, const struct contact *c, double *P, double *k)
{
	struct law_pair lp;

	s->law->pair(s->law, lk, c->i, c->j, &lp);
	return s->law->normal(s->law, &lp, c->h, P, k);
}

/* Any other law, through its interface. */
static int
on_law(const struct contact *c, void *vacc)
{
	struct law_acc *la = vacc;
	double P, U = law_normal_at(la->a.s, &la->lk, c, &P, NULL);

	normal_add(&la->a, c, P, U);
	return 0;
}

/* The sums of one evaluation by Hertz, and by any other law: two functions, each with its own
 * accumulator, so that the fast path's stays in registers (an accumulator whose address
 * also went to the non-inlined walk of the other law lived in memory: 1.6x slower). */
/* The sums of one block of grains in the Hertz evaluation, added in block order. */
struct qs_block_sums {
	double E, sumf, wall_force[NWALLS];
	size_t nc;
};

/* Hertz's coefficient 4/3 E* sqrt(R*) of grains i and j (hertz.h), E* from the per-grain
 * compliances. */
CONTACT_INLINE double
hertz_pair_coef(const struct qs_system *s, size_t i, size_t j, double ri, double rj)
{
	return hertz_coef(hertz_Estar_c(s->comp[i], s->comp[j]), sqrt(hertz_Rstar(ri, rj)));
}

/* Hertz's normal force of a pair record: one function for the rows and for the threads'
 * gathers, so that both compute the same bytes. */
CONTACT_INLINE double
hertz_pair_P(const struct qs_system *s, const struct contact *c)
{
	return hertz_force_c(hertz_pair_coef(s, c->i, (size_t)c->j, c->ri, c->rj), c->h);
}

/* Hertz's coefficient 4/3 E* sqrt(R*) of every pair of the list, once a rebuild: the
 * product hertz_pair_P forms first, so P = coef h sqrt(h) has the same bytes (two divisions
 * and a square root fewer per contact and evaluation).  0 or -1. */
static int
hertz_coefficients(struct qs_system *s)
{
	const struct nlist *nl = &s->ce.nl;
	const double *r = s->ce.r;
	size_t i, k;

	if (s->hertz_coef && s->coef_builds == s->ce.rebuilds)
		return 0;
	if (nl->npairs > s->coef_cap || !s->hertz_coef) {
		size_t cap = nl->npairs + nl->npairs / 4 + 16;
		free(s->hertz_coef);
		s->hertz_coef = malloc(cap * sizeof *s->hertz_coef);
		s->coef_cap = s->hertz_coef ? cap : 0;
		if (!s->hertz_coef)
			return -1;
	}
	for (i = 0; i < s->n; i++)
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			s->hertz_coef[k] = hertz_pair_coef(s, i, nl->nbr[k], r[i], r[nl->nbr[k]]);
		}
	s->coef_builds = s->ce.rebuilds;
	return 0;
}

/* Hertz, inlined: the fast path of every evaluation (U = 2/5 P h), with the pair's
 * coefficient from the list (hertz_coefficients).  The scatter into j stops at a->jend: a
 * later thread gathers those (hertz_gather). */
CONTACT_INLINE int
on_hertz_pair(const struct contact *c, void *vacc)
{
	struct normal_acc *a = vacc;
	double P = hertz_force_c(a->s->hertz_coef[c->k], c->h);

	normal_add_pair(a, c, P, hertz_energy_P(P, c->h));
	return 0;
}

CONTACT_INLINE int
on_hertz_wall(const struct contact *c, void *vacc)
{
	struct normal_acc *a = vacc;
	const struct qs_system *s = a->s;
	double P = hertz_force_c(hertz_coef(hertz_Estar_c(s->comp[c->i], s->wall_comp), sqrt(c->ri)), c->h);
	size_t i = c->i;
	int w = PACK_WALL_INDEX(c->j);

	a->E += hertz_energy_P(P, c->h);
	a->sumf += P;
	a->nc++;
	a->wf[w] += P;
	if (a->g)
		a->g[3 * i + w / 2] += w % 2 ? P : -P;
	if (a->fmax)
		a->fmax[i] = force_max(a->fmax[i], P);
	return 0;
}

/* What the rows of grains below g0 (other threads') scatter into grains g0 <= j < g1: the
 * pairs (m < g0, j) in ascending m, from the columns, computed as the rows compute them. */
static void
hertz_gather(const struct qs_system *s, const double *x, double *g, double *fmax, size_t g0, size_t g1)
{
	const struct contact_enum *e = &s->ce;
	const double *r = e->r;
	int per = e->any_periodic;
	size_t j, k;

	for (j = g0; j < g1; j++)
		for (k = e->col_first[j]; k < e->col_first[j + 1] && e->col_nbr[k] < g0; k++) {
			size_t m = e->col_nbr[k];
			double sum = r[m] + r[j], dd, P, f;
			struct contact c;

			dd = contact_branch(e, &c, x[3 * m], x[3 * m + 1], x[3 * m + 2], x, j, per);
			if (dd >= sum * sum)
				continue;
			c.i = m, c.j = (long)j, c.ri = r[m], c.rj = r[j];
			c.d = sqrt(dd);
			c.h = sum - c.d;
			P = hertz_pair_P(s, &c);
			if (g) {
				f = P / c.d;
				g[3 * j] += f * c.dx[0];
				g[3 * j + 1] += f * c.dx[1];
				g[3 * j + 2] += f * c.dx[2];
			}
			if (fmax)
				fmax[j] = force_max(fmax[j], P);
		}
}

/* The sums of one evaluation by Hertz, on threads, with results that do not depend on their
 * number (base/par.h).  The grains are cut into blocks of par_block(n) (fixed by n), whose
 * energy and sums are kept apart and added in block order; each thread takes a run of
 * whole blocks and walks their rows as the serial walk does, scattering each pair's force
 * into both grains, except into grains of later threads.  A thread first gathers what
 * earlier threads' rows would have scattered into its grains (hertz_gather), so every
 * grain's gradient is the same sum in the same order as contact_foreach's one-pass walk:
 * the same bytes with one thread or many.  (A separate accumulator per law, so that the
 * fast path's stays in registers: one whose address also went to the non-inlined walk of
 * the other law lived in memory, 1.6x slower.) */
static double
normal_energy_hertz(struct qs_system *s, const double *x, double *g, double *fmax)
{
	const struct contact_enum *e = &s->ce;
	size_t n = s->n, bl = par_block(n), nb = n ? (n + bl - 1) / bl : 0, q;
	int threads = n >= PAR_MIN && par_threads() > 1;
	double E = 0, sumf = 0;

	if (nb > s->blk_cap) {
		free(s->blk);
		s->blk = malloc(nb * sizeof *s->blk);
		s->blk_cap = s->blk ? nb : 0;
	}
	if (!s->blk || hertz_coefficients(s) || (threads && contact_enum_columns(&s->ce))) {
		msg_seterr("out of memory");
		return NAN;
	}
#pragma omp parallel if (threads)
	{
		size_t T = (size_t)par_team(), t = (size_t)par_tid(), b;
		size_t b0 = nb * t / T, b1 = nb * (t + 1) / T;
		size_t g0 = b0 * bl < n ? b0 * bl : n, g1 = b1 * bl < n ? b1 * bl : n;

		if (g0 > 0 && (g || fmax))
			hertz_gather(s, x, g, fmax, g0, g1);
		for (b = b0; b < b1; b++) {
			struct normal_acc a = {s, x, g, fmax, NULL, 0, 0, 0, {0}, g1};
			size_t i, i1 = (b + 1) * bl < n ? (b + 1) * bl : n;
			long calls = 0;

			for (i = b * bl; i < i1; i++)
				if (e->any_periodic)
					contact_foreach_row(e, x, i, CONTACT_TOUCHING, 1, 0, on_hertz_pair, on_hertz_wall, &a, &calls);
				else
					contact_foreach_row(e, x, i, CONTACT_TOUCHING, 0, 0, on_hertz_pair, on_hertz_wall, &a, &calls);
			s->blk[b].E = a.E;
			s->blk[b].sumf = a.sumf;
			s->blk[b].nc = a.nc;
			memcpy(s->blk[b].wall_force, a.wf, sizeof a.wf);
		}
	}
	s->ncontacts = 0;
	for (q = 0; q < nb; q++) {
		int w;
		E += s->blk[q].E;
		sumf += s->blk[q].sumf;
		s->ncontacts += s->blk[q].nc;
		for (w = 0; w < NWALLS; w++)
			s->wall_force[w] += s->blk[q].wall_force[w];
	}
	s->sum_force = sumf;
	return E;
}

static double
normal_energy_law(struct qs_system *s, const double *x, double *g, double *fmax)
{
	struct law_acc la = {{s, x, g, fmax, NULL, 0, 0, 0, {0}, s->n}, {NULL, 0}};

	law_pack_bind(s->law, s->p, &la.lk);
	contact_foreach(&s->ce, x, CONTACT_TOUCHING, on_law, &la);
	s->ncontacts = la.a.nc;
	s->sum_force = la.a.sumf;
	return la.a.E;
}

static double
normal_energy(struct qs_term *t, struct qs_system *s, const double *x, double *g, double *fmax)
{
	(void)t;
	if (s->law == &contact_law_hertz_mindlin)
		return normal_energy_hertz(s, x, g, fmax);
	return normal_energy_law(s, x, g, fmax);
}

/* Gershgorin bound on the normal term's Hessian: the per-grain sum of contact stiffnesses
 * dP/dh, with a margin of 1.5 on grain pairs for the geometric term P/d. */
static int
on_stiffness(const struct contact *c, void *vacc)
{
	struct normal_acc *a = vacc;
	const struct qs_system *s = a->s;
	const double *r = s->p->r;

	if (s->law != &contact_law_hertz_mindlin) {
		double P, kk;

		law_normal_at(s, &((struct law_acc *)vacc)->lk, c, &P, &kk);
		a->k[c->i] += PACK_IS_WALL(c->j) ? kk : 1.5 * kk;
		if (!PACK_IS_WALL(c->j))
			a->k[c->j] += 1.5 * kk;
	} else if (PACK_IS_WALL(c->j)) {
		/* 2 (1/x) is 2/x to the bit: a factor of two rounds as nothing */
		a->k[c->i] += hertz_stiffness_t(hertz_Estar_c(s->comp[c->i], s->wall_comp), r[c->i], c->h);
	} else {
		double kk = hertz_stiffness_t(hertz_Estar_c(s->comp[c->i], s->comp[c->j]), hertz_Rstar(r[c->i], r[c->j]), c->h) *
		    1.5;
		a->k[c->i] += kk;
		a->k[c->j] += kk;
	}
	return 0;
}

static void
normal_stiffness(struct qs_term *t, struct qs_system *s, const double *x, double *k)
{
	struct law_acc la = {{s, x, NULL, NULL, k, 0, 0, 0, {0}, s->n}, {NULL, 0}};

	(void)t;
	law_pack_bind(s->law, s->p, &la.lk);	/* on_stiffness takes the law's walk's accumulator */
	contact_foreach(&s->ce, x, CONTACT_TOUCHING, on_stiffness, &la);
}

/* The normal term's second derivatives (hessian.h), through the law's stiffness: assembled
 * once per Newton step, so the law's interface serves every law. */
struct hessian_acc {
	struct qs_system *s;
	struct qs_hessian *H;
	struct law_pack lk;
};

/* A contact's block from its normal force P and stiffness k into H. */
CONTACT_INLINE int
hessian_add(struct hessian_acc *a, const struct contact *c, double P, double k)
{
	double n[3], B[9], g;
	int u, v;

	VEC3_UNROLL
	for (u = 0; u < 3; u++)
		n[u] = c->dx[u] / c->d;
	/* a wall is a plane: no geometric term */
	g = PACK_IS_WALL(c->j) ? 0 : P / c->d;
	/* the upper triangle mirrored, so that H is symmetric to the bit (CG assumes it) */
	VEC3_UNROLL
	for (u = 0; u < 3; u++)
		VEC3_UNROLL
		for (v = u; v < 3; v++)
			B[3 * u + v] = B[3 * v + u] = (k + g) * n[u] * n[v] - (u == v ? g : 0);
	VEC3_UNROLL
	for (u = 0; u < 9; u++)
		a->H->diag[9 * c->i + u] += B[u];
	if (PACK_IS_WALL(c->j))
		return 0;
	VEC3_UNROLL
	for (u = 0; u < 9; u++) {
		a->H->diag[9 * (size_t)c->j + u] += B[u];
		B[u] = -B[u];
	}
	return qs_hessian_add_pair(a->H, c->i, (size_t)c->j, B) ? 1 : 0;
}

static int
on_hessian(const struct contact *c, void *vacc)
{
	struct hessian_acc *a = vacc;
	double P, k;

	law_normal_at(a->s, &a->lk, c, &P, &k);
	return hessian_add(a, c, P, k);
}

/* Hertz inlined, with the bytes of the law's interface (hertz_mindlin_pair's E* and R*,
 * hertz_normal's P and k) but without the pair's tangential parameters, which the normal
 * block does not use: E* from the grains' compliances is hertz_Estar's sum and division.
 * The preconditioner of every frictional increment and settle pass assembles this: through
 * the interface it cost 15 divisions and two calls a contact, 5 % of the increment. */
static int
on_hessian_hertz(const struct contact *c, void *vacc)
{
	struct hessian_acc *a = vacc;
	const struct qs_system *s = a->s;
	double Es, Rs;

	if (PACK_IS_WALL(c->j)) {
		Es = hertz_Estar_c(s->comp[c->i], s->wall_comp);
		Rs = c->ri;
	} else {
		Es = hertz_Estar_c(s->comp[c->i], s->comp[c->j]);
		Rs = hertz_Rstar(c->ri, c->rj);
	}
	return hessian_add(a, c, hertz_force(Es, Rs, c->h), hertz_stiffness(Es, Rs, c->h));
}

static int
normal_hessian(struct qs_term *t, struct qs_system *s, const double *x, struct qs_hessian *H)
{
	struct hessian_acc a = {s, H, {NULL, 0}};

	(void)t;
	law_pack_bind(s->law, s->p, &a.lk);
	if (s->law == &contact_law_hertz_mindlin)
		return contact_foreach(&s->ce, x, CONTACT_TOUCHING, on_hessian_hertz, &a) < 0 ? -1 : 0;
	return contact_foreach(&s->ce, x, CONTACT_TOUCHING, on_hessian, &a) < 0 ? -1 : 0;
}

int
qs_hessian(struct qs_system *s, const double *x, struct qs_hessian *H)
{
	int q;

	for (q = 0; q < s->nterms; q++)
		if (!s->term[q].hessian) {
			msg_seterr("the term '%s' of the functional has no Hessian: Newton's method needs "
			    "every term's (with friction, --rule return-map), or choose another --method", s->term[q].name);
			return -1;
		}
	if (H->n != s->dim / 3) {
		msg_seterr("the Hessian has %zu nodes of three unknowns, the system %zu unknowns", H->n, s->dim);
		return -1;
	}
	qs_hessian_clear(H);
	for (q = 0; q < s->nterms; q++)
		if (s->term[q].hessian(&s->term[q], s, x, H))
			return -1;
	return 0;
}

void
qs_stiffness(struct qs_system *s, const double *x, double *k)
{
	int q;

	for (q = 0; q < s->nterms; q++)
		if (s->term[q].stiffness)
			s->term[q].stiffness(&s->term[q], s, x, k);
}

double
qs_energy(struct qs_system *s, const double *x, double *g, double *fmax)
{
	double E = 0;
	int q;

	if (contact_enum_update(&s->ce, x, 0))
		return NAN;
	s->evals++;
	if (g)
		par_zero(g, s->dim);
	if (fmax)
		par_zero(fmax, s->n);
	memset(s->wall_force, 0, sizeof s->wall_force);
	for (q = 0; q < s->nterms; q++)
		E += s->term[q].energy(&s->term[q], s, x, g, fmax);
	/* every caller fails on a nan energy and reports the error slot: fill it (it said
	 * 'unknown error') */
	if (isnan(E))
		msg_seterr("the energy is not a number (a grain position, radius or modulus "
		    "that is not finite)");
	return E;
}

void
qs_residual(const struct qs_system *s, const double *g, const double *fbig, double floor_rel, double *res_max,
    double *res_mean)
{
	double rmax = 0, sum = 0, fl, part[PAR_MAXBLOCKS];
	size_t n = s->n, bl = par_block(n), nb = n ? (n + bl - 1) / bl : 0, nf = 0, q, cnt[PAR_MAXBLOCKS];

	fl = s->ncontacts ? floor_rel * s->sum_force / s->ncontacts : 0;
	if (s->force_floor > fl)
		fl = s->force_floor;
	/* the sum by blocks of par_block(n) grains added in block order, the largest value in
	 * any order: the same bytes for any thread count (base/par.h) */
#pragma omp parallel for schedule(static) reduction(max : rmax) if (n >= PAR_MIN)
	for (q = 0; q < nb; q++) {
		size_t i = q * bl, i1 = (q + 1) * bl < n ? (q + 1) * bl : n, c = 0;
		double t = 0;
#if LANES_OK
		/* two grains at a time: their square roots and divisions in one instruction each
		 * (lanes.h), the sums then in grain order (the scalar loop's bytes) */
		for (; i + 1 < i1; i += 2) {
			v2m on = {fbig[i] > 0 ? -1LL : 0, fbig[i + 1] > 0 ? -1LL : 0};
			v2d f = layout_grain_len_pair(&s->layout, g, i);
			v2d den = {max_or_num(fbig[i], fl), max_or_num(fbig[i + 1], fl)};
			v2d rel = f / V2_SELECT(on, den, ((v2d){1, 1}));
			int b;

			for (b = 0; b < 2; b++)
				if (on[b]) {
					if (rel[b] > rmax)
						rmax = rel[b];
					t += f[b];
					c++;
				}
		}
#endif
		for (; i < i1; i++) {
			double f, rel;
			if (!(fbig[i] > 0))
				continue;
			f = layout_grain_len(&s->layout, g, i);
			rel = f / max_or_num(fbig[i], fl);
			if (rel > rmax)
				rmax = rel;
			t += f;
			c++;
		}
		part[q] = t;
		cnt[q] = c;
	}
	for (q = 0; q < nb; q++) {
		sum += part[q];
		nf += cnt[q];
	}
	*res_max = rmax;
	*res_mean = nf && s->ncontacts ? (sum / nf) / (s->sum_force / s->ncontacts) : 0;
}

void
qs_wall_stress(const struct qs_system *s, double sig[3])
{
	const double *b = s->p->box;
	int a;

	for (a = 0; a < 3; a++)
		sig[a] = pack_wall_stress(b, b + 3, a, s->wall_force[2 * a] + s->wall_force[2 * a + 1]);
}

static int
on_count(const struct contact *c, void *vcounts)
{
	unsigned *counts = vcounts;

	counts[c->i]++;
	if (!PACK_IS_WALL(c->j))
		counts[c->j]++;
	return 0;
}

void
qs_coordination(const struct qs_system *s, const double *x, unsigned *counts)
{
	memset(counts, 0, s->n * sizeof *counts);
	contact_foreach(&s->ce, x, CONTACT_TOUCHING, on_count, counts);
}

void
qs_radii_changed(struct qs_system *s)
{
	size_t i;

	s->rmin = INFINITY;
	s->rmax = 0;
	for (i = 0; i < s->n; i++) {
		s->rmin = fmin(s->rmin, s->p->r[i]);
		s->rmax = fmax(s->rmax, s->p->r[i]);
	}
	contact_enum_radii_changed(&s->ce);
}

/* c <= 3 unit normals nc (rows) and overlaps h: the u of least length with nc[k].u = h[k],
 * u = sum lambda_k nc[k] with G lambda = h (G the Gram matrix).  0, or -1 when the normals
 * are nearly dependent (det G below 1e-2: two normals within about 6 degrees of each other
 * or of opposite directions). */
static int
release_move(unsigned c, const double nc[3][3], const double h[3], double u[3])
{
	double G[3][3], lam[3] = {0, 0, 0}, det;
	unsigned a, b;

	for (a = 0; a < c; a++)
		for (b = 0; b < c; b++)
			G[a][b] = nc[a][0] * nc[b][0] + nc[a][1] * nc[b][1] + nc[a][2] * nc[b][2];
	if (c == 1) {
		lam[0] = h[0];
	} else if (c == 2) {
		det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
		if (det < 1e-2)
			return -1;
		lam[0] = (G[1][1] * h[0] - G[0][1] * h[1]) / det;
		lam[1] = (G[0][0] * h[1] - G[1][0] * h[0]) / det;
	} else {
		double C[3][3];
		for (a = 0; a < 3; a++)
			for (b = 0; b < 3; b++)
				C[a][b] = G[(b + 1) % 3][(a + 1) % 3] * G[(b + 2) % 3][(a + 2) % 3] -
				    G[(b + 1) % 3][(a + 2) % 3] * G[(b + 2) % 3][(a + 1) % 3];
		det = G[0][0] * C[0][0] + G[0][1] * C[1][0] + G[0][2] * C[2][0];
		if (det < 1e-2)
			return -1;
		for (a = 0; a < 3; a++)
			lam[a] = (C[a][0] * h[0] + C[a][1] * h[1] + C[a][2] * h[2]) / det;
	}
	for (b = 0; b < 3; b++)
		u[b] = lam[0] * nc[0][b] + (c > 1 ? lam[1] * nc[1][b] : 0) + (c > 2 ? lam[2] * nc[2][b] : 0);
	return 0;
}

/* The contacts of one grain for the release: up to three normals and overlaps, counted
 * beyond; a coincident neighbour (no normal) counts as too many. */
struct release_ctx {
	double nc[3][3], h[3];
	unsigned c;
};

static int
on_release_contact(const struct contact *c, void *vctx)
{
	struct release_ctx *r = vctx;

	/* touching by the distance itself (the near pairs come with the gaps) */
	if (!(c->h > 0))
		return 0;
	if (!(c->d > 0) && !PACK_IS_WALL(c->j)) {
		r->c = 4;	/* coincident centres: no normal; leave it to the minimiser */
		return 1;
	}
	if (r->c < 3) {
		contact_normal(c, r->nc[r->c]);
		r->h[r->c] = c->h;
	}
	r->c++;
	return r->c > 3;
}

/* Is x_i + u free of every neighbour and wall?  Any touching pair at the new position blocks
 * the move (the first pass); a wall does when the gap from the old position less the move
 * along its normal is below the radius (the second pass: the move's own arithmetic, so that
 * a grain released from a wall by exactly its overlap is judged as the move computed it). */
struct release_check {
	const double *lo, *hi, *old, *u, *r;
};

static int
on_release_check_pair(const struct contact *c, void *vctx)
{
	(void)vctx;
	return !PACK_IS_WALL(c->j);
}

static int
on_release_check_wall(const struct contact *c, void *vctx)
{
	const struct release_check *k = vctx;
	int w, a;

	if (!PACK_IS_WALL(c->j))
		return 0;
	w = PACK_WALL_INDEX(c->j), a = w / 2;
	return (w % 2 ? k->hi[a] - k->old[a] - k->u[a] : k->old[a] + k->u[a] - k->lo[a]) < k->r[c->i];
}

long
qs_release_unbraced(struct qs_system *s, double *x)
{
	size_t i, n = s->n;
	long moved = 0;

	if (s->layout.rotations || n == 0)
		return 0;
	/* a fresh list at x: every pair within the skin is listed, so a move shorter than a
	 * quarter of it cannot meet an unlisted grain */
	if (contact_enum_update(&s->ce, x, 1) || isnan(qs_energy(s, x, NULL, NULL)))
		return -1;
	for (i = 0; i < n; i++) {
		struct release_ctx rc;
		double u[3], old[3], uu;
		long hit;

		rc.c = 0;
		if (contact_foreach_grain(&s->ce, x, i, CONTACT_NEAR, on_release_contact, &rc) < -1)
			return -1;
		if (rc.c == 0 || rc.c > 3 || release_move(rc.c, (const double(*)[3])rc.nc, rc.h, u))
			continue;
		uu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
		if (!(uu <= 0.25 * s->skin))
			continue;
		/* a hair beyond touching: rounding must not leave an overlap of 1e-16 that counts
		 * as a contact */
		u[0] *= 1 + 1e-8, u[1] *= 1 + 1e-8, u[2] *= 1 + 1e-8;
		/* u.n_c = h_c opens each contact to first order and |d + u| >= |d| + h_c exactly
		 * (u is longer than its projection); what remains is not to touch anything new */
		memcpy(old, x + 3 * i, sizeof old);
		x[3 * i] = old[0] + u[0], x[3 * i + 1] = old[1] + u[1], x[3 * i + 2] = old[2] + u[2];
		hit = contact_foreach_grain(&s->ce, x, i, CONTACT_TOUCHING, on_release_check_pair, NULL);
		if (hit >= 0)
			hit = contact_foreach_grain(&s->ce, x, i, CONTACT_NEAR, on_release_check_wall,
			    &(struct release_check){s->ce.lo, s->ce.hi, old, u, s->p->r});
		if (hit == -2) {
			msg_seterr("out of memory");
			return -1;
		}
		if (hit == -1) {	/* blocked: stay */
			memcpy(x + 3 * i, old, sizeof old);
			continue;
		}
		moved++;
	}
	return moved;
}
