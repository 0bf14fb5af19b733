/* SPDX-License-Identifier: GPL-3.0-or-later */
/* engine: the explicit DEM of every shape under every contact law (see engine.h). */
#include "dem/engine.h"
#include "contact/law.h"
#include "contact/hertz.h"
#include "contact/linear.h"
#include "dem/servo.h"
#include "contact/plate.h"
#include "pack/shape.h"
#include "base/lines.h"
#include "base/msg.h"
#include "base/par.h"
#include "base/quat.h"
#include "base/vec3.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

void
engine_params_default(struct engine_params *pp)
{
	pp->law = &contact_law_linear;	/* P's */
	pp->kn = pp->kt = 1.5e3;	/* P §II C: 1.5e-3 N/um */
	pp->hertz_overlap = 1e-2;
	pp->viscous = 0;
	pp->mu = pp->wall_mu = 0.58;	/* P: tan 30 deg, kaolinite */
	pp->restitution = 0.6;
	pp->damping = 0;
	/* a collision lasts pi sqrt(m* / k) >= 2.2 sqrt(m_min/k_n); a corner contact on a thin
	 * plate turns it with an effective mass about half its mass, and a grain carries a
	 * handful of interactions of one to eight elements: 0.1 keeps the stiffest oscillation
	 * at omega dt below 0.5 (stable below 2) and a binary collision above 20 steps.  0.05
	 * took 2.2x the steps to the same rest (1000 plates at eta 0.5: 66800 against 29900
	 * steps, packing 0.5417 against 0.5454) */
	pp->dt_factor = 0.1;
}

void
engine_free(struct engine *d)
{
	free(d->x), free(d->v), free(d->q), free(d->w), free(d->f), free(d->t), free(d->R);
	free(d->m), free(d->J), free(d->r), free(d->half), free(d->kind), free(d->rb), free(d->glue);
	free(d->pcache), free(d->q0), free(d->turn), free(d->turn_list), free(d->wl);
	free(d->prec), free(d->sums), free(d->ptouch), free(d->frow), free(d->mob);
	free(d->xrec), free(d->xslot), free(d->xin_first);
	contact_enum_free(&d->ce);
	memset(d, 0, sizeof *d);
}

/* The restitution of a linear spring-dashpot collision at damping ratio z when the force is
 * never attractive: the grains part when k h + gamma dh/dt reaches 0, before h does, so
 * e = exp(-(b/w) (pi - atan2(2 b w, w^2 - b^2))), b = z w0, w = w0 sqrt(1 - z^2)
 * (Schwager & Poschel, Granular Matter 9, 465, 2007), not the classical exp(-pi b / w), which
 * would give e = 0.623 where 0.6 is asked.  Valid for z < 1/sqrt(2). */
static double
restitution_of_zeta(double z)
{
	double w = sqrt(1 - z * z);

	return exp(-(z / w) * (M_PI - atan2(2 * z * w, w * w - z * z)));
}

/* Its inverse by bisection (e decreases with z; at z = 1/sqrt(2), e = exp(-pi/2) = 0.208). */
static double
zeta_of_restitution(double e)
{
	double lo = 0, hi = M_SQRT1_2;
	int it;

	if (e >= 1)
		return 0;
	for (it = 0; it < 100; it++) {
		double mid = 0.5 * (lo + hi);
		if (restitution_of_zeta(mid) > e)
			lo = mid;
		else
			hi = mid;
	}
	return 0.5 * (lo + hi);
}

int
engine_alloc(struct engine *d, size_t n)
{
	memset(d, 0, sizeof *d);
	d->n = n;
	d->x = calloc(3 * n, sizeof *d->x), d->v = calloc(3 * n, sizeof *d->v);
	d->q = calloc(4 * n, sizeof *d->q), d->w = calloc(3 * n, sizeof *d->w);
	d->f = calloc(3 * n, sizeof *d->f), d->t = calloc(3 * n, sizeof *d->t);
	d->R = calloc(9 * n, sizeof *d->R), d->m = calloc(n, sizeof *d->m);
	d->J = calloc(3 * n, sizeof *d->J), d->r = calloc(n, sizeof *d->r);
	d->half = calloc(n, sizeof *d->half), d->rb = calloc(n, sizeof *d->rb);
	d->kind = calloc(n, sizeof *d->kind);	/* 0: SHAPE_SPHERE, the first row */
	d->wl = calloc(3 * n, sizeof *d->wl);
	d->mob = calloc(2 * n, sizeof *d->mob);
	d->mob_dt = NAN;	/* made at the first step, whatever its length */
	d->cache_margin = ENGINE_CACHE_MARGIN;
	d->rec_builds = d->x_builds = -1;
	if (!d->x || !d->v || !d->q || !d->w || !d->f || !d->t || !d->R || !d->m || !d->J || !d->r || !d->half ||
	    !d->kind || !d->rb || !d->wl || !d->mob) {
		msg_seterr("out of memory for %zu grains", n);
		return -1;
	}
	return 0;
}

double
engine_shear_cache_margin(const struct engine *d)
{
	double h = 0;
	size_t i, np = 0;

	for (i = 0; i < d->n; i++)
		if (d->half[i] > 0)
			h += d->half[i], np++;
	if (!np)
		return ENGINE_CACHE_MARGIN;
	return fmin(ENGINE_CACHE_MARGIN, fmax(0.005, 0.0075 * h / (double)np));
}

static void refresh_rotations(struct engine *d);

/* The list's pair test at its build (struct engine's prune): two spheres are their bounding
 * spheres; otherwise the cores' gap bound against r_i + r_j + skin, the skin the list is
 * being built with. */
static int
cores_may_meet(void *ctx, size_t i, size_t j, const double dx[3])
{
	const struct engine *d = ctx;
	const struct narrow_pair *np = narrow_pair_of(d->kind[i], d->kind[j]);
	struct plate_body a, b;
	int q;

	if (np->bounds_exact)
		return 1;
	for (q = 0; q < 3; q++) {
		a.x[q] = d->x[3 * i + q];
		b.x[q] = a.x[q] - dx[q];
	}
	memcpy(a.R, d->R + 9 * i, sizeof a.R);
	memcpy(b.R, d->R + 9 * j, sizeof b.R);
	a.half = d->half[i], a.r = d->r[i];
	b.half = d->half[j], b.r = d->r[j];
	return np->gap_bound(&a, &b) < a.r + b.r + d->ce.skin;
}

/* Before a build: the frames cores_may_meet reads, at the orientations of the build, and the
 * turns since it start from zero. */
static void
list_prepare(void *ctx)
{
	struct engine *d = ctx;

	refresh_rotations(d);
	memset(d->turn_list, 0, d->n * sizeof *d->turn_list);
}

/* A new enumerator over the bounding radii, pruned at each build when there are plates. */
static int
list_start(struct engine *d, double skin)
{
	if (contact_enum_init(&d->ce, d->n, d->rb, d->lo, d->hi, d->periodic, skin, d->law->history))
		return -1;
	if (!d->spheres) {
		d->prune.keep = cores_may_meet;
		d->prune.prepare = list_prepare;
		d->prune.extra = d->turn_list;
		d->prune.ctx = d;
		contact_enum_prune(&d->ce, &d->prune);
	}
	return 0;
}

int
engine_start(struct engine *d, double skin)
{
	size_t i, n = d->n;

	d->spheres = 1;
	for (i = 0; i < n; i++)
		if (d->kind[i] != SHAPE_SPHERE)
			d->spheres = 0;
	/* a sphere's orientation is not observable and its Euler equations have no gyroscopic
	 * term: its frame is kept as the lab's, so its body-frame spin is the lab's too */
	for (i = 0; i < n; i++)
		if (!shape_table[d->kind[i]]->oriented) {
			memset(d->q + 4 * i, 0, 4 * sizeof *d->q);
			d->q[4 * i] = 1;
		}
	if (!d->spheres) {	/* what the plate pass keeps per grain */
		d->turn = calloc(n, sizeof *d->turn), d->q0 = calloc(4 * n, sizeof *d->q0);
		d->turn_list = calloc(n, sizeof *d->turn_list);
		d->frow = calloc(6 * n, sizeof *d->frow);
		if (!d->turn || !d->q0 || !d->turn_list || !d->frow) {
			msg_seterr("out of memory for %zu grains", n);
			return -1;
		}
	}
	return list_start(d, skin);
}

void
engine_params_law(struct engine_params *pp, const struct contact_law *law)
{
	pp->law = law;
	if (law->stiffness == LAW_MODULI)
		pp->kn = 1, pp->kt = law->kt_ratio;
}

double
engine_mean_Estar(const struct pack *p)
{
	return hertz_mean_Estar(p);
}

double
engine_kappa(const struct pack *p, const struct engine_params *pp, double sigma)
{
	return pp->law->kappa(pp->law, p, pp->kn, sigma);
}

double
engine_kappa_stress(const struct pack *p, const struct engine_params *pp, double kappa)
{
	return pp->law->kappa_stress(pp->law, p, pp->kn, kappa);
}

int
engine_init(struct engine *d, const struct pack *p, const struct engine_params *pp)
{
	double r0, rho0 = 0, mmin = INFINITY, rbmin = INFINITY, rmin = INFINITY, k0;
	size_t i, n = p->n;
	int a;

	memset(d, 0, sizeof *d);
	if (n == 0 || engine_alloc(d, n))
		return n == 0 ? (msg_seterr("no grains"), -1) : (engine_free(d), -1);
	d->law = pp->law;
	r0 = law_mean_radius(p);
	for (i = 0; i < n; i++)
		rho0 += p->rho[i] / n;
	d->u_len = r0;
	d->u_mass = rho0 * r0 * r0 * r0;
	/* the stiffness unit and the pairs in it (the law's: a spring law's k_n; Hertz's E* r0
	 * between two mean grains) */
	k0 = d->law->dem_units(d->law, p, r0, pp->kn, &d->lp_grain, &d->lp_wall);
	d->u_time = sqrt(d->u_mass / k0);
	d->u_force = k0 * r0;
	for (i = 0; i < n; i++) {
		double L = p->side ? p->side[i] / r0 : 0, rho = p->rho[i] / rho0, In, Ip;
		const struct shape_ops *sh = shape_of(pack_grain_shape(p, i));

		d->r[i] = p->r[i] / r0;
		d->half[i] = L / 2;
		d->kind[i] = (unsigned char)sh->kind;
		d->rb[i] = sh->bounding_radius(d->r[i], L);
		d->m[i] = rho * sh->volume(d->r[i], L);
		sh->inertia(d->r[i], L, &In, &Ip);
		d->J[3 * i] = d->J[3 * i + 1] = rho * Ip;
		d->J[3 * i + 2] = rho * In;
		for (a = 0; a < 3; a++)
			d->x[3 * i + a] = p->x[3 * i + a] / r0;
		if (p->q)
			memcpy(d->q + 4 * i, p->q + 4 * i, 4 * sizeof *d->q);
		else
			d->q[4 * i] = 1;
		quat_normalize(d->q + 4 * i);
		mmin = fmin(mmin, d->m[i]);
		rbmin = fmin(rbmin, d->rb[i]);
		rmin = fmin(rmin, d->r[i]);
	}
	for (a = 0; a < 3; a++) {
		d->lo[a] = p->box[a] / r0, d->hi[a] = p->box[3 + a] / r0;
		d->periodic[a] = p->periodic[a];
	}
	d->kt_ratio = pp->kt / pp->kn;
	d->mu = pp->mu, d->wall_mu = pp->wall_mu;
	d->zeta = zeta_of_restitution(pp->restitution);
	d->damping = pp->damping;
	d->viscous = pp->viscous;
	/* the pair physics in these units (R* per interaction) */
	d->lp_grain.mu = d->mu, d->lp_wall.mu = d->wall_mu;
	/* the stiffest likely contact: the smallest grain on a wall at hertz_overlap (a spring
	 * law's k_n = 1 at any overlap) */
	d->dt = pp->dt_factor * sqrt(mmin / d->law->stiffest(d->law, &d->lp_wall, rmin, pp->hertz_overlap * rmin));
	/* the skin: a tenth of the smallest bounding radius, so the list lasts many steps */
	if (engine_start(d, 0.1 * rbmin)) {
		engine_free(d);
		return -1;
	}
	return 0;
}

/* Velocity of grain i's material point p (lab frame): v + w x (p - x), w the lab-frame
 * angular velocity (refresh_rotations). */
static void
point_velocity(const struct engine *d, size_t i, const double *xi, const double p[3], double v[3])
{
	double arm[3] = {p[0] - xi[0], p[1] - xi[1], p[2] - xi[2]}, c[3];
	int a;

	vec3_cross(d->wl + 3 * i, arm, c);
	for (a = 0; a < 3; a++)
		v[a] = d->v[3 * i + a] + c[a];
}

/* Force F at point p of a grain centred at xi: into the force F and torque T it gets. */
static inline void
apply(const double *xi, const double p[3], const double Fk[3], double F[3], double T[3])
{
	double arm[3] = {p[0] - xi[0], p[1] - xi[1], p[2] - xi[2]}, c[3];
	int a;

	vec3_cross(arm, Fk, c);
	for (a = 0; a < 3; a++) {
		F[a] += Fk[a];
		T[a] += c[a];
	}
}


/* The scaled pair constants of grain i with grain j or a wall (j < 0), R* of the two
 * spheroradii (of the grain's, on a wall). */
static inline void
pair_constants(const struct engine *d, size_t i, long j, struct law_pair *lp)
{
	*lp = PACK_IS_WALL(j) ? d->lp_wall : d->lp_grain;
	lp->Rs = PACK_IS_WALL(j) ? d->r[i] : hertz_Rstar(d->r[i], d->r[(size_t)j]);
}

/* The forces of interaction it between grain i and grain j (j < 0: a wall), with j's centre
 * xj (its nearest image): the force F and torque Ti on i, and for a pair into rec what j gets
 * (the opposite force, rec->F = F, and the torque about its centre); the block's sums; hist
 * is the tangential spring. */
static void
interaction_force(const struct engine *d, size_t i, long j, const double *xj, const struct plate_interaction *it,
    double *hist, double F[3], double Ti[3], struct engine_rec *rec, struct engine_sums *sums)
{
	const double *n = it->n, *xi = d->x + 3 * i;
	int wall = PACK_IS_WALL(j), M = it->m, k, a;
	struct law_dem_elems in;
	struct law_pair lp;
	double fk[LAW_DEM_ELEMENTS], fel, fsum, hsum = 0, pc[3] = {0, 0, 0};
	double vi[3], vj[3] = {0, 0, 0}, vn, ft[3], Fk[3], c[3];

	F[0] = F[1] = F[2] = Ti[0] = Ti[1] = Ti[2] = 0;
	if (wall)	/* a moving wall's velocity (0 for the walls of a compaction) */
		memcpy(vj, d->wallv[PACK_WALL_INDEX(j)], sizeof vj);
	in.m = M;
	in.meff = wall ? d->m[i] : d->m[i] * d->m[j] / (d->m[i] + d->m[j]);
	in.dt = d->dt, in.zeta = d->zeta, in.kt_ratio = d->kt_ratio;
	memcpy(in.n, n, sizeof in.n);
	pair_constants(d, i, j, &lp);
	/* the elements: their overlaps and normal velocities, and the overlap-weighted point at
	 * which the interaction's one tangential force acts (P eqs. 3-4) */
	for (k = 0; k < M; k++) {
		const struct plate_element *e = &it->e[k];
		double h = e->h > 0 ? e->h : 0;

		point_velocity(d, i, xi, e->p, vi);
		if (!wall)
			point_velocity(d, (size_t)j, xj, e->p, vj);
		in.vn[k] = (vi[0] - vj[0]) * n[0] + (vi[1] - vj[1]) * n[1] + (vi[2] - vj[2]) * n[2];
		in.h[k] = e->h;
		for (a = 0; a < 3; a++)
			pc[a] += h * e->p[a];
		hsum += h;
	}
	if (hsum <= 0)
		memcpy(pc, it->e[0].p, sizeof pc);
	else
		for (a = 0; a < 3; a++)
			pc[a] /= hsum;
	point_velocity(d, i, xi, pc, vi);
	if (!wall)
		point_velocity(d, (size_t)j, xj, pc, vj);
	for (a = 0; a < 3; a++)
		in.vt[a] = vi[a] - vj[a];
	vn = vec3_dot(in.vt, n);
	for (a = 0; a < 3; a++)
		in.vt[a] -= vn * n[a];
	/* the law's forces (law.h: dem_interaction; the linear law's is P eqs. 2-4) */
	fsum = d->law == &contact_law_linear ? linear_dem_interaction(&lp, &in, hist, fk, ft, &fel)
	    : d->law->dem_interaction(d->law, &lp, &in, hist, fk, ft, &fel);
	for (k = 0; k < M; k++) {
		for (a = 0; a < 3; a++)
			Fk[a] = fk[k] * n[a];
		apply(xi, it->e[k].p, Fk, F, Ti);
	}
	apply(xi, pc, ft, F, Ti);
	if (!wall) {	/* on j: -F at the same points, the torque about xj */
		double br[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};

		vec3_cross(br, F, c);
		for (a = 0; a < 3; a++) {
			rec->F[a] = F[a];
			rec->Tj[a] = -(Ti[a] + c[a]);
		}
	}
	{
		double Fc[3], br[3] = {0, 0, 0};

		for (a = 0; a < 3; a++) {
			Fc[a] = fsum * n[a] + ft[a];
			if (!wall)
				br[a] = xi[a] - xj[a];
		}
		engine_count(d, i, j, br, Fc, fel, M, sums);
	}
}

/* The interaction of record c (a pair, or a grain and a wall) at the current state, with j's
 * centre (its nearest image) into xj for a pair: its element count, 0 when the bounding
 * spheres overlap but the grains do not touch. */
static int
interaction_of(const struct engine *d, const struct contact *c, struct plate_interaction *it, double xj[3])
{
	const struct narrow_grains g = {d->x, d->R, d->half, d->r, d->kind, d->lo, d->hi};

	return narrow_record_interaction(&g, c, 0, it, xj);
}

/* A pair's interaction through its cache (remade when it may have gone stale), with
 * j's centre (its nearest image) into xj. */
static int
pair_interaction_cached(struct engine *d, const struct contact *c, struct plate_interaction *it, double xj[3])
{
	size_t k = contact_pair_index(&d->ce, c), i = c->i, j = (size_t)c->j;
	struct engine_cache *pc = &d->pcache[k];
	const struct narrow_pair *np = narrow_pair_of(d->kind[i], d->kind[j]);
	struct plate_body a, b;
	double turns = d->turn[i] + d->turn[j];
	int build = pc->list != d->ce.rebuilds, m, q;

	if (!build) {	/* what the cores' points may have moved against each other since it was made */
		double e0 = c->dx[0] - pc->dx[0], e1 = c->dx[1] - pc->dx[1], e2 = c->dx[2] - pc->dx[2];
		double room = d->cache_margin - (turns - pc->turn);
		build = !(room > 0 && e0 * e0 + e1 * e1 + e2 * e2 < room * room);
	}
	/* cores that cannot touch yet (a pair of exact bounds keeps no cache) */
	if (!build && !(pc->word & PLATE_CACHE_FEATURES) && !np->bounds_exact)
		return 0;
	for (q = 0; q < 3; q++) {	/* xj written as it is made: a copy of b.x read back 16 bytes at
					 * a time what was just stored 8 at a time, a stall per pair */
		a.x[q] = d->x[3 * i + q];
		b.x[q] = xj[q] = a.x[q] - c->dx[q];
	}
	a.half = d->half[i], a.r = d->r[i];
	b.half = d->half[j], b.r = d->r[j];
	if (!np->bounds_exact) {	/* shapes that are their bounding spheres need no frame */
		memcpy(a.R, d->R + 9 * i, sizeof a.R);
		memcpy(b.R, d->R + 9 * j, sizeof b.R);
	}
	m = np->cached(&a, &b, d->cache_margin, &pc->word, build, it);
	if (build) {
		memcpy(pc->dx, c->dx, sizeof pc->dx);
		pc->turn = turns;
		pc->list = d->ce.rebuilds;
		d->cache_builds++;	/* a statistic: racy on threads, not a result */
	}
	return m;
}

/* Where pair c's record is: its place in the list's columns, the order the gather reads. */
static size_t
pair_record(const struct engine *d, const struct contact *c)
{
	return d->ce.col_pos[contact_pair_index(&d->ce, c)];
}

/* One walk of a block of rows: its sums, and the force and torque the row's grain has got
 * so far from its own pairs and walls. */
struct force_walk {
	struct engine *d;
	struct engine_sums s;
	double F[3], T[3];
};

/* Each interaction of the row into the row's sums, and a pair's share for j into its record
 * (pair_record), flagged in ptouch (which the gather clears as it reads). */
static int
on_contact(const struct contact *c, void *vw)
{
	struct force_walk *fw = vw;
	struct engine *d = fw->d;
	struct plate_interaction it;
	struct engine_rec jrec;
	double xj[3], F[3], T[3];
	int wall = PACK_IS_WALL(c->j), m, a;
	size_t k = 0;

	if (c->h <= 0)
		return 0;	/* bounding spheres apart (their spring zeroed by the enumerator) */
	if (d->glue && wall && d->glue[c->i] == 1 + PACK_WALL_INDEX(c->j))
		return 0;	/* glued to that wall: part of it */
	if (wall || d->cache_margin <= 0)
		m = interaction_of(d, c, &it, xj);
	else
		m = pair_interaction_cached(d, c, &it, xj);
	if (m == 0) {
		if (d->law->history)
			memset(c->hist, 0, d->law->history * sizeof *c->hist);
		return 0;
	}
	if (!wall)
		k = pair_record(d, c);
	interaction_force(d, c->i, c->j, wall ? NULL : xj, &it, c->hist, F, T, wall ? &jrec : &d->prec[k], &fw->s);
	if (!wall)
		d->ptouch[k] = 1;
	for (a = 0; a < 3; a++)
		fw->F[a] += F[a], fw->T[a] += T[a];
	return 0;
}

/* Grain i's rotation matrix and its angular velocity in the lab's frame. */
static inline void
rotation_refresh(struct engine *d, size_t i)
{
	const double *R = d->R + 9 * i, *wb = d->w + 3 * i;
	int a;

	quat_to_matrix(d->q + 4 * i, d->R + 9 * i);
	for (a = 0; a < 3; a++)
		d->wl[3 * i + a] = R[3 * a] * wb[0] + R[3 * a + 1] * wb[1] + R[3 * a + 2] * wb[2];
}

static void
refresh_rotations(struct engine *d)
{
	size_t i;

#pragma omp parallel for schedule(static) if (d->threads)
	for (i = 0; i < d->n; i++)
		rotation_refresh(d, i);
}

/* What grain i's turn since the last pass can move a point of its core: |R - R0| <= 2 |q - q0|
 * (the nearer of q0 and -q0, q0 the orientation at the last pass) times the core's radius
 * half sqrt 2. */
static double
core_turn(const struct engine *d, size_t i)
{
	const double *q = d->q + 4 * i, *q0 = d->q0 + 4 * i;
	double dp = 0, dm = 0;
	int a;

	for (a = 0; a < 4; a++) {
		dp += (q[a] - q0[a]) * (q[a] - q0[a]);
		dm += (q[a] + q0[a]) * (q[a] + q0[a]);
	}
	return 2 * sqrt(fmin(dp, dm)) * d->half[i] * M_SQRT2;
}

/* The caches of a list just built: a pair listed in the list the caches were made for (the
 * previous one, e->prev) keeps its cache, which stays as valid as it was (its test measures
 * the branch vector and the turns, not the list); the others are of no list yet.  A list
 * built twice since the last pass, or caches of none, carry nothing.  0 or -1. */
static int
cache_carry(struct engine *d)
{
	const struct contact_enum *e = &d->ce;
	const struct nlist *old = &e->prev, *nl = &e->nl;
	size_t i, k, np = nl->npairs, cap = np + np / 4 + 16;
	struct engine_cache *pc = malloc(cap * sizeof *pc);
	int carry = d->cache_list > 0 && d->cache_list == e->rebuilds - 1 && old->first && d->pcache;

	if (!pc) {
		msg_seterr("out of memory for the contact list's caches");
		return -1;
	}
	for (k = 0; k < cap; k++)
		pc[k].list = -1;
#pragma omp parallel for schedule(static) private(k) if (d->threads)
	for (i = 0; i < d->n; i++) {
		size_t o = carry ? old->first[i] : 0, oe = carry ? old->first[i + 1] : 0;

		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			while (o < oe && old->nbr[o] < nl->nbr[k])
				o++;
			if (o < oe && old->nbr[o] == nl->nbr[k] && d->pcache[o].list == d->cache_list) {
				pc[k] = d->pcache[o];
				pc[k].list = e->rebuilds;
			}
		}
	}
	free(d->pcache);
	d->pcache = pc;
	d->pcap = cap;
	d->cache_list = e->rebuilds;
	return 0;
}

/* The rotations (rotation_refresh) and the grains' turns, before the list is brought up to
 * date: each grain's turn is the sum over the passes of what its core's points moved by
 * turning from one pass to the next (core_turn), so that the turns of a pair's grains since
 * its cache was made, their sum then taken from their sum now, bound what turning moved a
 * point of either core, whatever the path; turn_list is the same sum since the list's build
 * (its staleness).  A run's first pass, or one after its state was read (q0_set 0), starts
 * the turns afresh.  One loop over the grains for both: each parallel region costs two
 * threads a wake-up.  A pack of spheres: the rotations alone. */
static void
rotations_and_turns(struct engine *d)
{
	size_t i;

	if (!d->turn) {
		refresh_rotations(d);
		return;
	}
	if (!d->q0_set) {	/* the turns from here */
		memcpy(d->q0, d->q, 4 * d->n * sizeof *d->q0);
		memset(d->turn, 0, d->n * sizeof *d->turn);
		d->q0_set = 1;
	}
#pragma omp parallel for schedule(static) if (d->threads)
	for (i = 0; i < d->n; i++) {
		double t;

		rotation_refresh(d, i);
		t = core_turn(d, i);
		d->turn[i] += t;
		d->turn_list[i] += t;
		memcpy(d->q0 + 4 * i, d->q + 4 * i, sizeof *d->q0 * 4);
	}
}

/* The list brought up to date for the current positions and orientations (pruned at its
 * builds, struct engine's prune), and with the narrow phase kept, the caches' room and list
 * (cache_carry).  A run's first pass, or one after its state was read (cache_list 0), makes
 * every cache anew.  0 or -1. */
static int
list_update(struct engine *d, int force)
{
	rotations_and_turns(d);
	if (contact_enum_update(&d->ce, d->x, force))
		return -1;
	if (d->turn && d->cache_margin > 0 && d->cache_list != d->ce.rebuilds && cache_carry(d))
		return -1;
	return 0;
}

/* The records' room for the current list (a pair's record per list entry) and the list's
 * columns (contact_enum_columns: the pairs (m, j), m < j, of each grain j by ascending m, and
 * their entries), for the gather.  0 or -1. */
static int
records_fit(struct engine *d)
{
	size_t np = d->ce.nl.npairs;

	if (d->rec_builds == d->ce.rebuilds)
		return 0;
	if (np + 1 > d->rcap) {
		size_t cap = np + np / 4 + 16;
		struct engine_rec *r = realloc(d->prec, cap * sizeof *r);
		unsigned char *t;

		if (!r)
			goto oom;
		d->prec = r;
		if (!(t = realloc(d->ptouch, cap)))
			goto oom;
		d->ptouch = t;
		d->rcap = cap;
	}
	if (contact_enum_columns(&d->ce))
		return -1;
	memset(d->ptouch, 0, np);	/* then each gather clears what it read */
	d->rec_builds = d->ce.rebuilds;
	return 0;
oom:
	msg_seterr("out of memory for the interactions' records");
	return -1;
}

int
engine_sums_fit(struct engine *d, size_t nb)
{
	if (nb > d->sums_cap) {
		struct engine_sums *ns = realloc(d->sums, nb * sizeof *ns);
		if (!ns) {
			msg_seterr("out of memory");
			return -1;
		}
		d->sums = ns;
		d->sums_cap = nb;
	}
	return 0;
}

void
engine_sums_total(struct engine *d, size_t nb)
{
	size_t b;
	int w, a;

	memset(d->wallf, 0, sizeof d->wallf);
	memset(d->wallF, 0, sizeof d->wallF);
	memset(d->sig, 0, sizeof d->sig);
	d->ninter = d->nwall = d->nelem = d->zends = 0;
	d->sum_f = 0;
	for (b = 0; b < nb; b++) {
		const struct engine_sums *s = &d->sums[b];

		for (w = 0; w < NWALLS; w++) {
			d->wallf[w] += s->wallf[w];
			for (a = 0; a < 3; a++)
				d->wallF[w][a] += s->wallF[w][a];
		}
		for (a = 0; a < 6; a++)
			d->sig[a] += s->sig[a];
		d->ninter += s->ninter, d->nwall += s->nwall, d->nelem += s->nelem, d->zends += s->zends;
		d->sum_f += s->sum_f;
	}
}

/* The rows of a spatially ordered half list are not equal: a grain's pairs across a periodic
 * face sit in the row of the lower number, so the first rows carry the wrapped pairs.  The
 * list's pairs alone: a grain's own share counted as two pairs more (its walls, its row's
 * set-up) made two threads 4-14 % slower on the pruned list at 8000 plates (least wall times
 * of three alternating runs at eta 0.14, 0.5, 0.8). */
size_t
engine_blocks_share(const struct nlist *nl, size_t bl, size_t nb, size_t T, size_t t)
{
	size_t n = nl->n, b;
	double want = (double)nl->first[n] * (double)t / (double)T;

	if (t == 0 || T <= 1)
		return t == 0 ? 0 : nb;
	if (t >= T)
		return nb;
	for (b = 1; b < nb; b++)	/* the first block whose start has at least the share before it */
		if ((double)nl->first[b * bl] >= want)
			return b;
	return nb;
}

/* Every grain's force and torque and the pass's sums, on threads with the same bytes for any
 * number (base/par.h).  Pass 1 computes the interactions of each block of rows (the pairs
 * (i, j > i) and the walls of grains i in the block, as contact_foreach orders them) into
 * their records and the block's sums; pass 2 gathers each grain's force and torque in a fixed
 * order: the pairs (m, i) by ascending m, then i's own pairs and walls.  The block sums are
 * added in block order.  So no sum depends on which thread did what. */
int
engine_forces(struct engine *d)
{
	struct contact_enum *e = &d->ce;
	size_t n = d->n, bl = par_block(n), nb = (n + bl - 1) / bl;
	int err = 0;

	if (d->spheres)
		return engine_sphere_forces(d);
	d->threads = par_threads() > 1 && nb > 1;
	if (list_update(d, 0) || records_fit(d) || engine_sums_fit(d, nb))
		return -1;
#pragma omp parallel if (d->threads)
	{
		size_t team = (size_t)par_team(), tid = (size_t)par_tid();
		size_t b0 = engine_blocks_share(&e->nl, bl, nb, team, tid), b1 = engine_blocks_share(&e->nl, bl, nb, team, tid + 1), bb;

		/* each thread a run of blocks, of about equal work (engine_blocks_share): so the records,
		 * rotations and rows it writes stay mostly in its own core's cache (blocks taken
		 * as they come cost two threads 10 % more CPU at 8000 plates; equal runs of grains,
		 * a third more time on the first thread than on the second) */
		for (bb = b0; bb < b1; bb++) {
			struct force_walk fw;
			size_t i, i0 = (size_t)bb * bl, i1 = i0 + bl < n ? i0 + bl : n;
			long calls = 0;

			memset(&fw, 0, sizeof fw);
			fw.d = d;
			for (i = i0; i < i1; i++) {
				memset(fw.F, 0, sizeof fw.F);
				memset(fw.T, 0, sizeof fw.T);
				/* the pairs whose bounding spheres are apart are not visited (the enumerator
				 * zeroes their springs), nor the walls beyond a grain's bounding sphere */
				if (contact_foreach_row(e, d->x, i, CONTACT_TOUCHING, e->any_periodic, e->hsize, on_contact, on_contact,
				    &fw, &calls) < 0) {
#pragma omp atomic write
					err = 1;
				}
				memcpy(d->frow + 6 * i, fw.F, sizeof fw.F);
				memcpy(d->frow + 6 * i + 3, fw.T, sizeof fw.T);
			}
			d->sums[bb] = fw.s;
		}
#pragma omp barrier
		/* the gather (every record is written) */
#pragma omp for schedule(static)
		for (long ii = 0; ii < (long)n; ii++) {
			size_t i = (size_t)ii, q;
			double F[3] = {0, 0, 0}, T[3] = {0, 0, 0};
			int a;	/* the thread's own */

			for (q = e->col_first[i]; q < e->col_first[i + 1]; q++)
				if (d->ptouch[q]) {
					const struct engine_rec *r = &d->prec[q];
					for (a = 0; a < 3; a++)
						F[a] -= r->F[a], T[a] += r->Tj[a];
					d->ptouch[q] = 0;	/* for the next pass */
				}
			for (a = 0; a < 3; a++)
				F[a] += d->frow[6 * i + a], T[a] += d->frow[6 * i + 3 + a];
			memcpy(d->f + 3 * i, F, sizeof F);
			memcpy(d->t + 3 * i, T, sizeof T);
		}
	}
	if (err)
		return -1;
	engine_sums_total(d, nb);
	return 0;
}

struct interaction_pass {
	struct engine *d;
	engine_interaction_fn fn;
	void *ctx;
};

static int
on_interaction(const struct contact *c, void *v)
{
	struct interaction_pass *ip = v;
	struct plate_interaction it;
	double xj[3];

	if (c->h <= 0 || (ip->d->glue && PACK_IS_WALL(c->j) && ip->d->glue[c->i] == 1 + PACK_WALL_INDEX(c->j)) ||
	    interaction_of(ip->d, c, &it, xj) == 0)
		return 0;
	return ip->fn(ip->d, c->i, c->j, PACK_IS_WALL(c->j) ? NULL : xj, &it, c->hist, ip->ctx);
}

int
engine_foreach_interaction(struct engine *d, int rebuild, engine_interaction_fn fn, void *ctx)
{
	struct interaction_pass ip = {d, fn, ctx};

	if (list_update(d, rebuild))
		return -1;
	return contact_foreach(&d->ce, d->x, CONTACT_NEAR, on_interaction, &ip) < 0 ? -1 : 0;
}

static inline double
local_damping(double f, double v, double alpha)
{
	return f - alpha * fabs(f) * (double)((v > 0) - (v < 0));	/* branch-free: the sign of v is random */
}

/* Euler's equations in the body frame by the implicit midpoint rule: w <- w + dt J^-1
 * (tau + (J w~) x w~ ... ) with w~ the mean of the old and new w, by fixed-point iteration
 * (it contracts by about dt |w|, far below 1). */
static void
euler_midpoint(double w[3], const double J[3], const double tau[3], double dt)
{
	/* written out component by component, in locals (w may alias J, so the compiler would
	 * reload and divide at every iteration): the same operations, so the same numbers, as
	 * the loop over a with b, c = a + 1, a + 2 (mod 3) */
	const double w0 = w[0], w1 = w[1], w2 = w[2];
	const double mob0 = dt / J[0], mob1 = dt / J[1], mob2 = dt / J[2];
	const double dJ0 = J[1] - J[2], dJ1 = J[2] - J[0], dJ2 = J[0] - J[1];
	double x0 = w0, x1 = w1, x2 = w2;
	int it;

	for (it = 0; it < 20; it++) {
		double m0 = 0.5 * (w0 + x0), m1 = 0.5 * (w1 + x1), m2 = 0.5 * (w2 + x2);
		double n0 = w0 + mob0 * (tau[0] + dJ0 * m1 * m2);
		double n1 = w1 + mob1 * (tau[1] + dJ1 * m2 * m0);
		double n2 = w2 + mob2 * (tau[2] + dJ2 * m0 * m1);
		double change = fmax(fmax(fmax(0, fabs(n0 - x0)), fabs(n1 - x1)), fabs(n2 - x2));

		x0 = n0, x1 = n1, x2 = n2;
		if (change <= 1e-15 * (fabs(n0) + fabs(n1) + fabs(n2)))
			break;
	}
	w[0] = x0, w[1] = x1, w[2] = x2;
}

/* Grain i's leapfrog translation: Cundall's local damping removes a fraction al of the force
 * that drives the motion; the viscous loss 1 - keep makes free flight decay, so that no
 * granular gas builds up whose kinetic pressure a wall servo would take for a force network. */
static inline void
translate(double *x, double *vel, const double *force, const double *mob, size_t i, double dt, double keep, double al)
{
	double am = mob[2 * i];
	int a;

	for (a = 0; a < 3; a++) {
		size_t k = 3 * i + a;
		double f = local_damping(force[k], vel[k], al), v = vel[k] * keep + f * am;

		vel[k] = v;
		x[k] += v * dt;
	}
}

/* A sphere's step: translate's, and its spin, component by component (one pass over its
 * numbers: packgen's hot loop).  Its frame is the lab's (engine_start) and its inertia
 * isotropic, so Euler's equations are w' = t / J. */
static inline void
step_sphere(double *x, double *v, double *w, const double *f, const double *t, const double *mob, size_t i, double dt,
    double keep, double al)
{
	double am = mob[2 * i], aI = mob[2 * i + 1];
	int a;

	for (a = 0; a < 3; a++) {
		size_t k = 3 * i + a;
		double vk = v[k] * keep + local_damping(f[k], v[k], al) * am;

		w[k] = w[k] * keep + local_damping(t[k], w[k], al) * aI;
		v[k] = vk;
		x[k] += vk * dt;
	}
}

void
engine_integrate(struct engine *d)
{
	double dt = d->dt, al = d->damping, keep = 1 - d->viscous;
	long ii;

	/* the mobilities dt / m and dt / J once per step length (packgen changes it every 100
	 * steps at most): two divisions per grain and step were a tenth of packgen's time */
	if (dt != d->mob_dt) {
#pragma omp parallel for schedule(static) if (d->threads)
		for (ii = 0; ii < (long)d->n; ii++) {
			d->mob[2 * ii] = dt / d->m[ii];
			d->mob[2 * ii + 1] = dt / d->J[3 * ii];	/* a sphere's (isotropic) */
		}
		d->mob_dt = dt;
	}
	/* grain by grain, nothing shared: the same bytes on any threads */
	if (d->spheres && !d->glue) {	/* packgen's: every grain a free sphere */
		double *x = d->x, *v = d->v, *w = d->w;
		const double *f = d->f, *t = d->t, *mob = d->mob;

#pragma omp parallel for schedule(static) if (d->threads)
		for (ii = 0; ii < (long)d->n; ii++)
			step_sphere(x, v, w, f, t, mob, (size_t)ii, dt, keep, al);
		return;
	}
#pragma omp parallel for schedule(static) if (d->threads)
	for (ii = 0; ii < (long)d->n; ii++) {
		size_t i = (size_t)ii;
		double tb[3];
		int a;

		if (d->glue && d->glue[i]) {	/* moves with its wall, does not turn */
			const double *vw = d->wallv[d->glue[i] - 1];

			for (a = 0; a < 3; a++) {
				d->v[3 * i + a] = vw[a];
				d->x[3 * i + a] += vw[a] * dt;
				d->w[3 * i + a] = 0;
			}
			continue;
		}
		if (!shape_table[d->kind[i]]->oriented) {
			step_sphere(d->x, d->v, d->w, d->f, d->t, d->mob, i, dt, keep, al);
			continue;
		}
		translate(d->x, d->v, d->f, d->mob, i, dt, keep, al);
		{
			const double *R = d->R + 9 * i;

			for (a = 0; a < 3; a++) {	/* torque into the body frame: R^T t */
				tb[a] = R[a] * d->t[3 * i] + R[3 + a] * d->t[3 * i + 1] + R[6 + a] * d->t[3 * i + 2];
				tb[a] = local_damping(tb[a], d->w[3 * i + a], al);
				d->w[3 * i + a] *= keep;
			}
		}
		euler_midpoint(d->w + 3 * i, d->J + 3 * i, tb, dt);
		quat_step_body(d->q + 4 * i, d->w + 3 * i, dt);
		quat_normalize(d->q + 4 * i);
	}
}

double
engine_kinetic(const struct engine *d, double L[3])
{
	double e = 0, Lt[3] = {0, 0, 0}, R[9];
	size_t i;
	int a, b;

	for (i = 0; i < d->n; i++) {
		const double *v = d->v + 3 * i, *w = d->w + 3 * i, *J = d->J + 3 * i, *x = d->x + 3 * i;
		double c[3];

		quat_to_matrix(d->q + 4 * i, R);
		e += 0.5 * d->m[i] * vec3_dot(v, v);
		for (a = 0; a < 3; a++)
			e += 0.5 * J[a] * w[a] * w[a];
		vec3_cross(x, v, c);
		for (a = 0; a < 3; a++) {
			Lt[a] += d->m[i] * c[a];
			for (b = 0; b < 3; b++)
				Lt[a] += R[3 * a + b] * J[b] * w[b];
		}
	}
	if (L)
		memcpy(L, Lt, sizeof Lt);
	return e;
}

double
engine_unbalanced(const struct engine *d)
{
	return dem_unbalanced(d->f, d->n, d->sum_f, d->ninter);
}

void
engine_wrap(struct engine *d)
{
	pack_wrap_centres(d->x, d->n, d->lo, d->hi, d->periodic);
}

int
engine_make_periodic(struct engine *d, const int periodic[3])
{
	double skin = d->ce.skin, rbmax = 0;
	size_t i;
	int a;

	for (i = 0; i < d->n; i++)
		rbmax = fmax(rbmax, d->rb[i]);
	for (a = 0; a < 3; a++)
		if (periodic[a] && d->hi[a] - d->lo[a] < 3 * (2 * rbmax + skin)) {
			/* the enumerator's cell grid needs three cells of an interaction distance */
			msg_seterr("the compacted box is %.3g bounding diameters long along %c, too short for a periodic "
			    "axis (it must hold 3 interaction distances): use more grains", (d->hi[a] - d->lo[a]) / (2 * rbmax),
			    "xyz"[a]);
			return -1;
		}
	for (a = 0; a < 3; a++)
		d->periodic[a] = d->periodic[a] || periodic[a];
	engine_wrap(d);
	contact_enum_free(&d->ce);
	d->rec_builds = d->x_builds = -1;	/* a new list: new entries */
	for (i = 0; i < d->pcap; i++)
		d->pcache[i].list = -1;
	return list_start(d, skin);
}

/* The frictional history of the pack's contact lines (pack-format.md), so that a static
 * pack read back is static: P0 the interaction's elastic normal force, Q0 the tangential
 * force on i its history carries (the law's history_force; what it reads back the law's
 * history_set), M0 0 (no rolling or twisting resistance). */
struct history_pass {
	struct pack *p;
	const long *keys;	/* reading: the pack's sorted history keys; writing: NULL */
	int err;
};

/* The pair constants (R* set) and the elements' overlaps of interaction it of grain i with
 * j, for the law's history conversions. */
static void
history_elems(const struct engine *d, size_t i, long j, const struct plate_interaction *it, struct law_pair *lp,
    struct law_dem_elems *in)
{
	int k;

	pair_constants(d, i, j, lp);
	memset(in, 0, sizeof *in);
	in->m = it->m;
	in->kt_ratio = d->kt_ratio, in->zeta = d->zeta, in->dt = d->dt;
	memcpy(in->n, it->n, sizeof in->n);
	for (k = 0; k < it->m; k++)
		in->h[k] = it->e[k].h;
}

static int
on_history(const struct engine *d, size_t i, long j, const double *xj, const struct plate_interaction *it, double *hist,
    void *vh)
{
	struct history_pass *hp = vh;
	struct law_pair lp;
	struct law_dem_elems in;
	double Q[3];
	int k, a;

	(void)xj;
	history_elems(d, i, j, it, &lp, &in);
	if (hp->keys) {
		long line = pack_history_lookup(hp->keys, hp->p->nc, i, j);

		if (line < 0)
			return 0;
		pack_contact_q0_on(&hp->p->c[line], i, Q);
		for (a = 0; a < 3; a++)
			Q[a] /= d->u_force;
		d->law->history_set(d->law, &lp, &in, Q, hist);
	} else {
		struct pack_contact pc = {i, j, 0, {0, 0, 0}, 0};
		double P;

		for (k = 0; k < it->m; k++)	/* the elements' elastic forces, by the law */
			if (it->e[k].h > 0) {
				d->law->normal(d->law, &lp, it->e[k].h, &P, NULL);
				pc.P0 += P * d->u_force;
			}
		d->law->history_force(d->law, &lp, &in, hist, Q);
		/* within the Coulomb limit of the written P0: a moving pack's spring may carry more,
		 * by its normal damping and by the step's change of overlap (which moves a Hertz
		 * spring's stiffness), which a state of elastic forces has not */
		law_clamp_tangential(Q, law_coulomb_limit(lp.mu, pc.P0 / d->u_force));
		for (a = 0; a < 3; a++)
			pc.Q0[a] = Q[a] * d->u_force;
		if (pack_add_contact(hp->p, &pc))
			return hp->err = -1;
	}
	return 0;
}

int
engine_read_history(struct engine *d, struct pack *p)
{
	struct history_pass hp = {p, NULL, 0};
	long *keys;
	int status;

	if (p->nc == 0)
		return 0;
	if (!(keys = pack_history_keys(p)))
		return -1;
	hp.keys = keys;
	status = engine_foreach_interaction(d, 1, on_history, &hp);
	free(keys);
	return status;
}

int
engine_write_back(struct engine *d, struct pack *p)
{
	struct history_pass hp = {p, NULL, 0};
	size_t i;
	int a;

	for (i = 0; i < d->n; i++) {
		for (a = 0; a < 3; a++)
			p->x[3 * i + a] = d->x[3 * i + a] * d->u_len;
		if (p->q && shape_table[d->kind[i]]->oriented)	/* a sphere keeps the pack's (engine_start) */
			memcpy(p->q + 4 * i, d->q + 4 * i, 4 * sizeof *p->q);
	}
	for (a = 0; a < 3; a++) {
		p->box[a] = d->lo[a] * d->u_len, p->box[3 + a] = d->hi[a] * d->u_len;
		p->periodic[a] = d->periodic[a];
	}
	/* the glued grains marked, so that a snapshot's descriptors can leave them out */
	if (d->glue) {
		if (pack_set_glue(p))
			return -1;
		memcpy(p->glue, d->glue, d->n);
	}
	p->nc = 0;
	if (engine_foreach_interaction(d, 0, on_history, &hp) < 0 || hp.err) {
		msg_seterr("out of memory for the contact lines");
		return -1;
	}
	return 0;
}

/* The numbers of a state line: exactly k of them, finite, after the keyword (NULL: none). */
static int
state_numbers(struct lines *in, const char *key, double *v, int k)
{
	char *line, *tok[32], *end;
	int nt, a, o = key ? 1 : 0;

	int r = lines_next(in, &line, NULL);

	if (r != 1)
		return r < 0 ? -1 : lines_error(in, "the engine's state ends early");
	nt = lines_split(line, " \t", tok, 32);
	if ((key && (nt < 1 || strcmp(tok[0], key) != 0)) || nt != k + o)
		return lines_error(in, "expected %s%s%d numbers", key ? key : "", key ? " and " : "", k);
	for (a = 0; a < k; a++) {
		v[a] = strtod(tok[a + o], &end);
		if (*end || end == tok[a + o] || !isfinite(v[a]))
			return lines_error(in, "'%s': not a finite number", tok[a + o]);
	}
	return 0;
}

/* Whether spring a comes before b in contact_enum_history_get's order: the pairs by (i, j),
 * then the walls by grain and wall index (j = PACK_WALL(w) falls as w rises). */
static int
spring_before(const long *a, const long *b)
{
	if (a[1] >= 0 && b[1] >= 0)
		return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]);
	if (a[1] >= 0 || b[1] >= 0)
		return a[1] >= 0;
	return a[0] < b[0] || (a[0] == b[0] && a[1] > b[1]);
}

int
engine_state_write(const struct engine *d, FILE *fp)
{
	size_t i, m = contact_enum_history_get(&d->ce, NULL, NULL), hs = d->ce.hsize;
	long *ij = malloc((m ? m : 1) * 2 * sizeof *ij);
	double *h = malloc((m ? m : 1) * hs * sizeof *h);
	int a, w;

	if (!ij || !h) {
		free(ij), free(h);
		msg_seterr("out of memory");
		return -1;
	}
	contact_enum_history_get(&d->ce, ij, h);
	fprintf(fp, "pdem-state 1 %zu\nbox", d->n);
	for (a = 0; a < 3; a++)
		fprintf(fp, " %a", d->lo[a]);
	for (a = 0; a < 3; a++)
		fprintf(fp, " %a", d->hi[a]);
	fprintf(fp, " %d %d %d\nwallv", d->periodic[0], d->periodic[1], d->periodic[2]);
	for (w = 0; w < NWALLS; w++)
		for (a = 0; a < 3; a++)
			fprintf(fp, " %a", d->wallv[w][a]);
	fputc('\n', fp);
	for (i = 0; i < d->n; i++) {
		const double *x = d->x + 3 * i, *v = d->v + 3 * i, *q = d->q + 4 * i, *om = d->w + 3 * i;

		fprintf(fp, "%a %a %a %a %a %a %a %a %a %a %a %a %a %d\n", x[0], x[1], x[2], v[0], v[1], v[2], q[0], q[1],
		    q[2], q[3], om[0], om[1], om[2], d->glue ? d->glue[i] : 0);
	}
	fprintf(fp, "springs %zu\n", m);
	for (i = 0; i < m; i++) {
		fprintf(fp, "%ld %ld", ij[2 * i], ij[2 * i + 1]);
		for (a = 0; a < (int)hs; a++)
			fprintf(fp, " %a", h[hs * i + (size_t)a]);
		fputc('\n', fp);
	}
	free(ij), free(h);
	if (ferror(fp)) {
		msg_seterr("write error");
		return -1;
	}
	return 0;
}

/* The pack reader's checks on grain i's state line v (X V Q W GLUE) in an engine whose box
 * (lo, hi) is read: NULL, or what is wrong.  The centre within the box on a walled axis (a
 * bounding radius of slack, for a grain pressed into a wall); on a periodic axis, where
 * centres are wrapped only at the end of a run, within 1e4 box lengths (a shear to strain
 * 100 of a box as tall as it is long carries a grain 100 lengths); a unit quaternion; the
 * grain moves less than its bounding radius, and turns less than a radian, in a time step. */
static const char *
state_grain_check(const struct engine *d, size_t i, const double *v)
{
	static char why[200];
	double qn = sqrt(v[6] * v[6] + v[7] * v[7] + v[8] * v[8] + v[9] * v[9]);
	int a;

	for (a = 0; a < 3; a++) {
		double L = d->hi[a] - d->lo[a], slack = d->periodic[a] ? 1e4 * L : d->rb[i];

		if (!(v[a] >= d->lo[a] - slack && v[a] <= d->hi[a] + slack)) {
			snprintf(why, sizeof why, "centre %c = %g m is outside the box [%g, %g] m%s", "xyz"[a], v[a] * d->u_len,
			    d->lo[a] * d->u_len, d->hi[a] * d->u_len, d->periodic[a] ? " by more than 1e4 box lengths" : "");
			return why;
		}
	}
	if (!(fabs(qn - 1) <= PACK_QUAT_TOL)) {
		snprintf(why, sizeof why, "(qw, qx, qy, qz) = (%.9g, %.9g, %.9g, %.9g) is not a unit quaternion (norm %.9g, off 1 by more than %g)",
		    v[6], v[7], v[8], v[9], qn, PACK_QUAT_TOL);
		return why;
	}
	if (!(sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]) * d->dt <= d->rb[i])) {
		snprintf(why, sizeof why, "velocity (%g, %g, %g) m/s: the grain would move more than its radius in a time step",
		    v[3] * d->u_len / d->u_time, v[4] * d->u_len / d->u_time, v[5] * d->u_len / d->u_time);
		return why;
	}
	if (!(sqrt(v[10] * v[10] + v[11] * v[11] + v[12] * v[12]) * d->dt <= 1)) {
		snprintf(why, sizeof why, "angular velocity (%g, %g, %g) rad/s: the grain would turn more than a radian in a time step",
		    v[10] / d->u_time, v[11] / d->u_time, v[12] / d->u_time);
		return why;
	}
	return NULL;
}

int
engine_state_read(struct engine *d, struct lines *in)
{
	double v[NWALLS * 3 + 3], *h = NULL;
	long *ij = NULL, hdr[3];
	size_t i, m = 0, hs = d->ce.hsize;
	char *line, *tok[4], *end;
	const char *why;
	double rbmax = 0;
	int a, w, status = -1;

	if (lines_next(in, &line, NULL) != 1 || lines_split(line, " \t", tok, 4) != 3 || strcmp(tok[0], "pdem-state") ||
	    strcmp(tok[1], "1") || (hdr[0] = strtol(tok[2], &end, 10), *end) || hdr[0] != (long)d->n)
		return lines_error(in, "expected 'pdem-state 1 %zu' (the engine's state of these grains)", d->n);
	if (state_numbers(in, "box", v, 9))
		return -1;
	for (i = 0; i < d->n; i++)
		rbmax = fmax(rbmax, d->rb[i]);
	for (a = 0; a < 3; a++) {
		if ((int)v[6 + a] != d->periodic[a])
			return lines_error(in, "the boundary is not the run's (axis %c)", "xyz"[a]);
		/* the pack reader's box, and no shorter than a grain (a periodic axis: than the
		 * three interaction distances of its cell grid, engine_make_periodic) */
		if (!(v[3 + a] - v[a] >= (d->periodic[a] ? 3 * (2 * rbmax + d->ce.skin) : rbmax)))
			return lines_error(in, "box: [%g, %g] m along %c is %s", v[a] * d->u_len, v[3 + a] * d->u_len, "xyz"[a],
			    v[3 + a] > v[a] ? "shorter than the grains allow" : "empty (upper bound not above lower bound)");
		d->lo[a] = v[a], d->hi[a] = v[3 + a];
	}
	if (state_numbers(in, "wallv", v, NWALLS * 3))
		return -1;
	for (w = 0; w < NWALLS; w++)
		for (a = 0; a < 3; a++) {
			/* a wall moves less than the largest grain's radius in a step */
			if (!(fabs(v[3 * w + a]) * d->dt <= rbmax))
				return lines_error(in, "wallv: wall %d moves %g m/s along %c, more than a grain's radius a time step",
				    w, v[3 * w + a] * d->u_len / d->u_time, "xyz"[a]);
			d->wallv[w][a] = v[3 * w + a];
		}
	for (i = 0; i < d->n; i++) {
		if (state_numbers(in, NULL, v, 14))
			return -1;
		if ((why = state_grain_check(d, i, v)))
			return lines_error(in, "grain %zu: %s", i + 1, why);
		memcpy(d->x + 3 * i, v, 3 * sizeof *v);
		memcpy(d->v + 3 * i, v + 3, 3 * sizeof *v);
		memcpy(d->q + 4 * i, v + 6, 4 * sizeof *v);
		memcpy(d->w + 3 * i, v + 10, 3 * sizeof *v);
		if (!(v[13] == 0 || v[13] == 3 || v[13] == 4) || (v[13] && !d->glue))
			return lines_error(in, "glue %g: not 0 or a y wall's", v[13]);
		if (d->glue)
			d->glue[i] = (unsigned char)v[13];
	}
	if (lines_next(in, &line, NULL) != 1 || lines_split(line, " \t", tok, 4) != 2 || strcmp(tok[0], "springs") ||
	    (m = strtoul(tok[1], &end, 10), *end) || m > 64 * d->n + 64)
		return lines_error(in, "expected 'springs M'");
	if (!(ij = malloc((m ? m : 1) * 2 * sizeof *ij)) || !(h = malloc((m ? m : 1) * hs * sizeof *h))) {
		msg_seterr("out of memory");
		goto out;
	}
	for (i = 0; i < m; i++) {
		if (state_numbers(in, NULL, v, 2 + (int)hs))
			goto out;
		ij[2 * i] = (long)v[0], ij[2 * i + 1] = (long)v[1];
		if (v[0] != (double)ij[2 * i] || v[1] != (double)ij[2 * i + 1] || ij[2 * i] < 0 || ij[2 * i] >= (long)d->n ||
		    ij[2 * i + 1] >= (long)d->n || ij[2 * i + 1] < PACK_WALL(NWALLS - 1) ||
		    (ij[2 * i + 1] >= 0 && ij[2 * i + 1] <= ij[2 * i]) || (i && !spring_before(ij + 2 * i - 2, ij + 2 * i))) {
			lines_error(in, "spring %zu: not a pair i < j or a grain and a wall, in order", i + 1);
			goto out;
		}
		memcpy(h + hs * i, v + 2, hs * sizeof *h);
	}
	if (contact_enum_history_set(&d->ce, d->x, m, ij, h))
		goto out;
	d->cache_list = 0, d->q0_set = 0;	/* the turns from here */
	status = 0;
out:
	free(ij), free(h);
	return status;
}
