/* SPDX-License-Identifier: GPL-3.0-or-later */
/* densify: grow under-coordinated grains, shrink, minimise; then compact (see densify.h). */
#include "qs/densify.h"
#include "contact/contacts.h"
#include "qs/functional.h"
#include "qs/loading.h"
#include "base/cli.h"
#include "base/msg.h"
#include "base/table.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double
densify_onset_default(double stress)
{
	return fmin(1e5, 0.1 * stress);
}

void
densify_params_default(struct densify_params *dp)
{
	dp->stress = 4e6;
	dp->onset = 0;	/* densify_onset_default(stress) */
	dp->stress_tol = 0.01;
	dp->strain_step = 2e-3;
	dp->max_growth = 0.05;
	dp->grow_tol = 1e-2;
	/* 5000, not 20000: the rounds that reach the limit are the ones
	 * just above jamming, whose residual stays near 1 however long they run (0.35 after
	 * 20000 iterations in the jamming round of a 1e4 pack); a round only picks the grains
	 * that grow next, and the last one goes on to the full tolerance anyway.  The 1e4
	 * seed-1 pack: 55266 iterations and 120 s against 93966 and 207 s; 2740 grains, seeds
	 * 1-3: 18.3, 16.7, 17.6 s against 24.0, 26.4, 21.3 s, porosity within 0.0022 and
	 * coordination within 0.04 (the scatter between seeds), bench/results.md.
	 * 2500, not 5000, since phase (a) ends at the onset and every
	 * compaction step grows the grains under min_coord: a capped stage only picks the
	 * grains to grow, and picking them twice as often seats them sooner.  Iterations to
	 * 4 MPa against 5000: 2740 grains, seeds 1-6, 16717 14047 21408 18976 17625 22648
	 * against 25706 25614 25742 20992 21982 23227; 1e4, seeds 1-2, 33753 26420 against
	 * 35829 38832; 1e5 (seed 1) 47833 against 58674; porosity and coordination within
	 * the scatter between seeds.  3500 was not monotone between them (1e5: 61679);
	 * bench/densify-1e5.md, run 7. */
	dp->grow_max_iter = 2500;
	dp->release_after = 5000;
	dp->loose_steps = 1;
	dp->min_coord = 4;
	dp->max_rounds = 1000;
	dp->nsub = 1;
	dp->k_inc = 10;
	dp->skin = 0.3;
	qs_min_params_default(&dp->min);
}

struct gaps {
	double g[4];	/* the four smallest surface gaps, ascending (negative: overlap) */
	unsigned k;
};

static void
gap_insert(struct gaps *gp, unsigned want, double v)
{
	unsigned q;

	if (gp->k < want)
		gp->k++;
	else if (v >= gp->g[want - 1])
		return;
	for (q = gp->k - 1; q > 0 && gp->g[q - 1] > v; q--)
		gp->g[q] = gp->g[q - 1];
	gp->g[q] = v;
}

/* Grow each grain with fewer than min_coord contacts until it touches its min_coord-th
 * nearest neighbour or wall (from the Verlet list: neighbours within the skin), by at most
 * max_growth of its radius.  Returns the number of grains grown. */
struct grow_ctx {
	const struct pack *p;
	const unsigned *cnt;
	unsigned min_coord, want;
	struct gaps *gp;
};

/* The surface gap of a near pair (or to a wall) for the grains short of contacts. */
static int
on_gap(const struct contact *c, void *vctx)
{
	struct grow_ctx *g = vctx;
	const double *r = g->p->r;
	size_t i = c->i;

	if (PACK_IS_WALL(c->j)) {
		if (g->cnt[i] < g->min_coord)
			gap_insert(&g->gp[i], g->want, c->d - r[i]);
	} else {
		double gap = c->d - r[i] - r[c->j];
		if (g->cnt[i] < g->min_coord)
			gap_insert(&g->gp[i], g->want, gap);
		if (g->cnt[c->j] < g->min_coord)
			gap_insert(&g->gp[c->j], g->want, gap);
	}
	return 0;
}

/* Grow each grain with fewer than min_coord contacts until it touches its min_coord-th
 * nearest neighbour or wall (from the Verlet list: neighbours within the skin), by at most
 * max_growth of its radius.  Returns the number of grains grown, -1 on error. */
static long
grow_grains(struct qs_system *s, const double *x, const unsigned *cnt, const struct densify_params *dp,
    double scale, struct gaps *gp)
{
	struct pack *p = s->p;
	struct grow_ctx g = {p, cnt, dp->min_coord, dp->min_coord < 4 ? dp->min_coord : 4, gp};
	size_t i;
	long grown = 0;

	if (g.want == 0)
		return 0;
	for (i = 0; i < s->n; i++)
		gp[i].k = 0;
	/* a list built at x: every pair within the skin, whenever the list was built last, so
	 * that the growth depends on the state alone (a resumed run's list is younger) */
	if (contact_enum_update(&s->ce, x, 1))
		return -1;
	contact_foreach(&s->ce, x, CONTACT_NEAR, on_gap, &g);
	for (i = 0; i < s->n; i++) {
		double dr, cap = scale * dp->max_growth * p->r[i];
		if (cnt[i] >= dp->min_coord)
			continue;
		/* touch the want-th gap with a small overlap (1e-6 R) so that it counts; grow at
		 * least 1e-3 R (scaled), or a grain caged by neighbours that push back after each
		 * minimisation creeps for many rounds */
		dr = gp[i].k == g.want ? gp[i].g[g.want - 1] + 1e-6 * p->r[i] : cap;
		dr = fmax(dr, scale * 1e-3 * p->r[i]);
		p->r[i] += fmin(dr, cap);
		grown++;
	}
	if (grown)
		qs_radii_changed(s);
	return grown;
}

/* sigma_c = tr(sigma)/3 from the wall forces */
static double
wall_sigma_c(const struct qs_system *s)
{
	double sig[3];

	qs_wall_stress(s, sig);
	return (sig[0] + sig[1] + sig[2]) / 3;
}

/* The grains with fewer than k contacts: the log's under4 (k = 4), and the grains the
 * compaction grows and waits for (k = min_coord, 0 to 4). */
static size_t
count_under(const unsigned *cnt, size_t n, unsigned k)
{
	size_t i, u = 0;

	for (i = 0; i < n; i++)
		u += cnt[i] < k;
	return u;
}

static void
stage_measures(struct qs_system *s, const double *x, unsigned *cnt, struct densify_stage *st)
{
	double sum = 0;
	size_t i;

	st->sigma_c = wall_sigma_c(s);
	st->porosity = 1 - pack_grain_volume(s->p) / pack_box_volume(s->p->box);
	qs_coordination(s, x, cnt);
	for (i = 0; i < s->n; i++)
		sum += cnt[i];
	st->under4 = count_under(cnt, s->n, 4);
	st->coordination = sum / s->n;
}

/* The restart form: each chunk of release_after iterations is a minimisation of its own,
 * started afresh after the release. */
static int
releasing_restart(struct qs_system *s, double *x, const double *de, const struct densify_params *dp,
    const struct qs_min_params *mp, struct qs_min_report *rep)
{
	struct qs_min_params cm = *mp;
	long it = 0, evals = 0, left = mp->max_iter;
	int st;

	for (;;) {
		if (dp->release_after > 0 && left > dp->release_after)
			cm.max_iter = dp->release_after;
		else
			cm.max_iter = left;
		st = de ? load_increment(s, x, de, dp->nsub, dp->k_inc, &cm, rep) : qs_minimize(s, x, &cm, rep);
		de = NULL;
		it += rep->iter;
		evals += rep->evals;
		left -= rep->iter;
		if (st != 1 || left <= 0)
			break;
		if (qs_release_unbraced(s, x) < 0) {
			st = -1;
			break;
		}
	}
	rep->iter = it;
	rep->evals = evals;
	return st;
}

/* The keeping form: after the strain step's first chunk, one minimiser runs to the end and
 * the grains are released between its iterations, every release_after of them; a release
 * that moved grains re-evaluates at the new positions and keeps the method's memory
 * (qs_minimizer_moved). */
static int
releasing_keep(struct qs_system *s, double *x, const double *de, const struct densify_params *dp,
    const struct qs_min_params *mp, struct qs_min_report *rep)
{
	struct qs_min_params cm = *mp;
	struct qs_minimizer *m;
	long it = 0, evals = 0;
	int st;

	if (de) {
		cm.max_iter = mp->max_iter > dp->release_after ? dp->release_after : mp->max_iter;
		st = load_increment(s, x, de, dp->nsub, dp->k_inc, &cm, rep);
		it = rep->iter, evals = rep->evals;
		if (st != 1 || it >= mp->max_iter)
			return st;
		if (qs_release_unbraced(s, x) < 0)
			return -1;
	}
	m = qs_minimizer_alloc(s, mp);
	if (!m || qs_minimizer_set(m, x)) {
		qs_minimizer_free(m);
		return -1;
	}
	qs_minimizer_set_max_iter(m, mp->max_iter - it);
	memset(rep, 0, sizeof *rep);
	while ((st = qs_minimizer_test(m, rep)) == QS_MIN_CONTINUE) {
		long moved;
		if (qs_minimizer_iterate(m))
			break;
		if ((rep->iter + 1) % dp->release_after)
			continue;
		moved = qs_release_unbraced(s, x);
		if (moved < 0 || (moved > 0 && qs_minimizer_moved(m)))
			break;
	}
	if (st == QS_MIN_CONTINUE)
		st = rep->status = -1;
	else
		st = rep->status;
	qs_minimizer_free(m);
	rep->iter += it;
	rep->evals += evals;
	return st;
}

/* A strain step de (NULL: none) and its equilibrium, up to mp->max_iter iterations in all,
 * with the unbraced grains released every release_after iterations (see densify.h), the
 * minimiser restarted after each release or keeping its memory (release_keep).  Returns as
 * load_increment. */
static int
minimize_releasing(struct qs_system *s, double *x, const double *de, const struct densify_params *dp,
    const struct qs_min_params *mp, struct qs_min_report *rep)
{
	if (dp->release_keep && dp->release_after > 0)
		return releasing_keep(s, x, de, dp, mp, rep);
	return releasing_restart(s, x, de, dp, mp, rep);
}

/* One densify run: the functional, the last minimisation's report, the last stage's
 * measures and the state that carries from round to round. */
struct densify_state {
	struct pack *p;
	const struct densify_params *dp;
	densify_log_fn fn;
	void *ctx;
	struct qs_system s;
	struct qs_min_report rep;
	struct densify_stage st;
	struct gaps *gp;
	unsigned *cnt;
	double *x, *xsave, *rsave, boxsave[6];
	double r0sum, floor_loose, scale;
	int limit_hit, have_ref, full;
};

/* A row of the log: the stage's measures after the last minimisation. */
static void
record(struct densify_state *d, const char *name, long rnd)
{
	struct densify_stage *st = &d->st;
	double rs = 0;
	size_t i;

	stage_measures(&d->s, d->x, d->cnt, st);
	st->under_min = count_under(d->cnt, d->p->n, d->dp->min_coord);
	for (i = 0; i < d->p->n; i++)
		rs += d->p->r[i];
	st->stage = name;
	st->round = rnd;
	st->growth = rs / d->r0sum - 1;
	st->iterations = d->rep.iter;
	st->res_max = d->rep.res_max;
	st->res_mean = d->rep.res_mean;
	st->min_status = d->rep.status;
	/* below the onset the pack is not jammed: nothing to balance; rounds at grow_tol stop
	 * at grow_max_iter by design */
	d->limit_hit |= d->rep.status == 1 && st->sigma_c >= d->dp->onset && d->full;
	if (d->fn)
		d->fn(st, d->ctx);
}

/* r0sum: the input radii's sum, 0 to take it from p (a resumed run passes the original's) */
static int
state_alloc(struct densify_state *d, double r0sum)
{
	size_t n = d->p->n, i;

	if (qs_init(&d->s, d->p, d->dp->skin))
		return -1;
	d->x = malloc(3 * n * sizeof *d->x);
	d->cnt = malloc(n * sizeof *d->cnt);
	d->gp = malloc(n * sizeof *d->gp);
	d->xsave = malloc(3 * n * sizeof *d->xsave);
	d->rsave = malloc(n * sizeof *d->rsave);
	if (!d->x || !d->cnt || !d->gp || !d->xsave || !d->rsave) {
		msg_seterr("out of memory");
		return -1;
	}
	memcpy(d->x, d->p->x, 3 * n * sizeof *d->x);
	for (i = 0; i < n; i++)
		d->r0sum += d->p->r[i];
	if (r0sum > 0)
		d->r0sum = r0sum;
	/* Before the pack carries the onset stress there is no load to balance: judge forces
	 * against what a contact carries at the onset, about onset x (2 r_mean)^2 (forces below
	 * tol times that are balanced).  A floor 1e-3 times lower made unjammed rounds near
	 * jamming converge to residual stresses of 1e-3 Pa, critically slowly (58k L-BFGS
	 * iterations in one round of a 1e4-grain pack); the equilibria at and above the onset are
	 * judged against their own forces as before. */
	d->floor_loose = d->dp->onset * 4 * (d->r0sum / n) * (d->r0sum / n);
	d->s.force_floor = d->floor_loose;
	return 0;
}

/* The minimiser of a stage that only brings the pack nearer where it is going (a growth
 * round, a compaction step that moves the box): grow_tol, at most grow_max_iter iterations. */
static struct qs_min_params
loose_min(const struct densify_params *dp)
{
	struct qs_min_params mp = dp->min;

	mp.tol = fmax(mp.tol, dp->grow_tol);
	if (mp.max_iter > dp->grow_max_iter)
		mp.max_iter = dp->grow_max_iter;
	return mp;
}

/* Undo a round that jumped from below the onset to far above it (the pack jammed within one
 * squeeze) and redo it with half the squeeze and half the growth, so that the reference box
 * lies near the onset. */
static int
retry_round(struct densify_state *d, const struct qs_min_params *mp, long round)
{
	size_t n = d->p->n;

	memcpy(d->x, d->xsave, 3 * n * sizeof *d->x);
	memcpy(d->p->r, d->rsave, n * sizeof *d->rsave);
	memcpy(d->p->box, d->boxsave, sizeof d->boxsave);
	qs_radii_changed(&d->s);
	d->scale *= 0.5;
	d->s.force_floor = d->floor_loose;
	if (qs_minimize(&d->s, d->x, mp, &d->rep) < 0)
		return -1;
	d->full = 0;
	record(d, "retry", round);
	return 0;
}

/* One round of phase (a): grow the grains short of contacts, squeeze the box while the pack
 * is below the onset, minimise.  0, 1 when phase (a) is over, -1 on error. */
static int
phase_a_round(struct densify_state *d, long round)
{
	const struct densify_params *dp = d->dp;
	struct pack *p = d->p;
	double d3[3];

	cli_progress_stage("grow %ld", round);
	struct qs_min_params mp;

	/* Phase (a) ends where the pack has jammed, and its box becomes the reference box (a
	 * pack densified again keeps its own).  The rounds at and above the onset, which
	 * seated the last grains under min_coord at that low stress, cost most of densify's
	 * iterations (at 1e5 grains 23 rounds and 69k of 154k iterations, rounds 8-30; at 1e6
	 * the grains under 4 fell by only a fifth per 5000-iteration round) and the compaction
	 * unseated a thousand grains again (bench/densify-1e6.md).  The compaction grows the
	 * grains left under min_coord instead, at stresses where the pack is stiffer. */
	if (d->st.sigma_c >= dp->onset)
		return 1;
	if (round > dp->max_rounds) {
		msg_seterr("phase (a) did not finish in %ld rounds: %zu grains under %u contacts, sigma_c %g Pa",
		    dp->max_rounds, d->st.under4, dp->min_coord, d->st.sigma_c);
		return -1;
	}
	/* keep the state, for retry_round */
	memcpy(d->xsave, d->x, 3 * p->n * sizeof *d->x);
	memcpy(d->rsave, p->r, p->n * sizeof *d->rsave);
	memcpy(d->boxsave, p->box, sizeof d->boxsave);
	if (grow_grains(&d->s, d->x, d->cnt, dp, d->scale, d->gp) < 0)
		return -1;
	d3[0] = d3[1] = d3[2] = d->scale * dp->strain_step;
	/* Every round is minimised to grow_tol: it only decides which grains grow next.  Just
	 * above jamming a full minimisation slows critically (70k L-BFGS iterations in the
	 * jamming round of a 1e4-grain pack).  Below the onset the forces are judged against
	 * the floor of an unjammed pack (state_alloc). */
	mp = loose_min(dp);
	d->s.force_floor = d->floor_loose;
	if (minimize_releasing(&d->s, d->x, d3, dp, &mp, &d->rep) < 0)
		return -1;
	d->full = mp.tol <= dp->min.tol;
	if (wall_sigma_c(&d->s) > 10 * dp->onset && d->scale > 1.0 / 1024)
		return retry_round(d, &mp, round);
	record(d, "grow", round);
	return 0;
}

/* One step of the compaction to the target: a secant on y = sigma_c^(2/3) against the
 * strain from the reference box. */
static int
compaction_step(struct densify_state *d, long round, double *e_prev, double *y_prev)
{
	const struct densify_params *dp = d->dp;
	struct pack *p = d->p;
	double y = pow(d->st.sigma_c, 2.0 / 3.0), yt = pow(dp->stress, 2.0 / 3.0), de, d3[3], eps[3], eps_now;
	struct qs_min_params mp;

	cli_progress_stage("compact %ld", round);
	if (round > dp->max_rounds) {
		msg_seterr("compaction did not reach %g Pa in %ld steps (sigma_c %g Pa)", dp->stress, dp->max_rounds,
		    d->st.sigma_c);
		return -1;
	}
	load_strain(p->box, p->refbox, eps);
	eps_now = (eps[0] + eps[1] + eps[2]) / 3;
	if (!isnan(*e_prev) && eps_now != *e_prev && (y - *y_prev) / (eps_now - *e_prev) > 0)
		de = (yt - y) / ((y - *y_prev) / (eps_now - *e_prev));
	else if (eps_now > 1e-9 && y > pow(dp->onset, 2.0 / 3.0))
		/* first step: the line through the onset at the reference box */
		de = (yt - y) / ((y - pow(dp->onset, 2.0 / 3.0)) / eps_now);
	else
		de = (d->st.sigma_c < dp->stress ? 0.1 : -0.1) * dp->strain_step;
	de = fmax(-dp->strain_step, fmin(dp->strain_step, de));
	if (eps_now > 0 && de < -0.5 * eps_now)
		de = -0.5 * eps_now;	/* never unload the pack back towards jamming */
	*e_prev = eps_now;
	*y_prev = y;
	d3[0] = d3[1] = d3[2] = de;
	/* compaction can leave a grain with fewer than min_coord contacts: grow it too */
	if (d->st.under_min > 0 && grow_grains(&d->s, d->x, d->cnt, dp, 1.0, d->gp) < 0)
		return -1;
	if (fabs(d->st.sigma_c / dp->stress - 1) <= dp->stress_tol)
		d3[0] = d3[1] = d3[2] = 0;
	/* A step that moves the box or grows grains only brings the pack nearer the target,
	 * like a growth round: grow_tol in at most grow_max_iter iterations; the step that stays
	 * at the target with every grain seated is the full equilibrium, and only a full one
	 * can end the compaction.  (Growing grains in a full step: the 1e5 benchmark pack's
	 * first one at the target, 849 grains grown, had not converged after 30000 iterations.) */
	mp = dp->loose_steps && (d3[0] != 0 || d->st.under_min > 0) ? loose_min(dp) : dp->min;
	if (minimize_releasing(&d->s, d->x, d3, dp, &mp, &d->rep) < 0)
		return -1;
	d->full = mp.tol <= dp->min.tol;
	record(d, "compact", round);
	return 0;
}

/* The dense pack: positions, contacts, and no sliding (a frictional pack densified again). */
static int
finish(struct densify_state *d)
{
	struct pack *p = d->p;

	memcpy(p->x, d->x, 3 * p->n * sizeof *d->x);
	if (contacts_store(p, 0))
		return -1;
	if ((pack_get_meta(p, "sliding_ratio") && pack_set_meta(p, "sliding_ratio", "0")) ||
	    (pack_get_meta(p, "trial_slip_ratio") && pack_set_meta(p, "trial_slip_ratio", "0"))) {
		msg_seterr("out of memory");
		return -1;
	}
	return 0;
}

/* Hand the state after a stage to the checkpoint callback: 0 go on, 1 stop, -1 error. */
static int
checkpoint(struct densify_state *d, densify_checkpoint_fn ck, void *ctx, int phase, long round, double e_prev,
    double y_prev)
{
	struct densify_resume at;
	int r;

	if (!ck)
		return 0;
	memcpy(d->p->x, d->x, 3 * d->p->n * sizeof *d->x);
	at.phase = phase;
	at.round = round;
	at.scale = d->scale;
	at.r0sum = d->r0sum;
	at.skin = d->s.skin;
	at.e_prev = e_prev;
	at.y_prev = y_prev;
	at.full = d->full;
	at.have_ref = d->have_ref;
	at.limit_hit = d->limit_hit;
	at.st = d->st;
	r = ck(d->p, &at, ctx);
	return r < 0 ? -1 : r != 0;
}

/* The compaction's end: the target stress, no grain under min_coord, a full equilibrium.
 * (Waiting for no grain under 4 whatever min_coord is would never end --min-coord 0, growth
 * off, while a grain has fewer than 4 contacts.) */
static int
compaction_done(const struct densify_state *d)
{
	return !(fabs(d->st.sigma_c / d->dp->stress - 1) > d->dp->stress_tol || d->st.under_min > 0 || !d->full);
}

int
densify_run(struct pack *p, const struct densify_params *dp, densify_log_fn fn, void *ctx, struct densify_stage *last)
{
	return densify_run_resumable(p, dp, fn, ctx, NULL, NULL, last);
}

int
densify_run_resumable(struct pack *p, const struct densify_params *dp, densify_log_fn fn, void *ctx,
    densify_checkpoint_fn ck, const struct densify_resume *from, struct densify_stage *last)
{
	struct densify_params dpl = *dp;
	struct densify_state d;
	double e_prev = NAN, y_prev = NAN;
	long round = 0;
	int status = -1, r, phase = 0;
	size_t under;

	if (!(dpl.onset > 0))
		dpl.onset = densify_onset_default(dpl.stress);
	memset(&d, 0, sizeof d);
	d.p = p;
	d.dp = &dpl;
	d.fn = fn;
	d.ctx = ctx;
	d.scale = 1;
	d.have_ref = p->has_refbox;
	d.full = 1;
	if (state_alloc(&d, from ? from->r0sum : 0))
		goto out;
	if (from) {
		phase = from->phase;
		round = from->round;
		d.scale = from->scale;
		d.full = from->full;
		d.have_ref = from->have_ref;
		d.limit_hit = from->limit_hit;
		d.st = from->st;
		e_prev = from->e_prev;
		y_prev = from->y_prev;
		/* the skin of the run that wrote the checkpoint (qs_init took it from the grown
		 * radii): the release's longest move and the neighbours a growth sees */
		d.s.skin = d.s.ce.skin = from->skin;
		/* the contact counts the next growth decides on, as the stage left them */
		if (contact_enum_update(&d.s.ce, d.x, 0))
			goto out;
		qs_coordination(&d.s, d.x, d.cnt);
		d.st.under_min = count_under(d.cnt, p->n, dpl.min_coord);
		if ((under = count_under(d.cnt, p->n, 4)) != from->st.under4) {
			msg_seterr("the checkpoint's positions give %zu grains under 4 contacts, its stage %zu", under,
			    from->st.under4);
			goto out;
		}
	} else {
		cli_progress_stage("relax");
		if (qs_minimize(&d.s, d.x, &dpl.min, &d.rep) < 0)
			goto out;
		record(&d, "relax", 0);
		if ((r = checkpoint(&d, ck, ctx, 0, 0, e_prev, y_prev)) != 0)
			goto stop;
	}
	if (phase < 2) {
		for (round++; (r = phase_a_round(&d, round)) == 0; round++)
			if ((r = checkpoint(&d, ck, ctx, 1, round, e_prev, y_prev)) != 0)
				goto stop;
		if (r < 0)
			goto out;
		if (!d.have_ref) {
			memcpy(p->refbox, p->box, sizeof p->refbox);
			d.have_ref = 1;
		}
		p->has_refbox = 1;
		round = 0;
	}
	d.s.force_floor = 0;
	/* no checkpoint after the last step: nothing would be left to go on with */
	for (round++; !compaction_done(&d); round++) {
		if (compaction_step(&d, round, &e_prev, &y_prev))
			goto out;
		if (!compaction_done(&d) && (r = checkpoint(&d, ck, ctx, 2, round, e_prev, y_prev)) != 0)
			goto stop;
	}
	if (finish(&d))
		goto out;
	status = d.limit_hit ? 1 : 0;
	if (d.limit_hit)
		msg_seterr("a minimisation stopped at its iteration limit (largest residual %.3g)", d.st.res_max);
	goto out;
stop:
	status = r == 1 ? 2 : -1;
out:
	if (last)
		*last = d.st;
	qs_free(&d.s);
	free(d.x), free(d.cnt), free(d.gp), free(d.xsave), free(d.rsave);
	return status;
}

/* The checkpoint's meta keys.  Numbers as %.17g, which reads back to the same double. */
#define CK_STATE "densify-checkpoint"
#define CK_STAGE "densify-stage"
#define CK_REFBOX "densify-refbox"
#define CK_ROW "densify-log-"
#define CK_RUN "densify-run"
/* 3 since phase (a) ends at the onset: a checkpoint of version 2 would go on under
 * another rule, and the run would be neither version's */
#define CK_VERSION 3

static const char *const stage_names[] = {"relax", "grow", "retry", "compact"};

int
densify_resume_put(struct pack *p, const struct densify_resume *at, const char *run, const char *rows)
{
	char buf[640], key[40];
	const struct densify_stage *st = &at->st;
	const char *row, *nl;
	long k = 0, nrows = 0;
	int bad = 0;

	densify_resume_clear(p);
	for (row = rows; row && *row; row = *nl ? nl + 1 : nl) {
		nl = row + strcspn(row, "\n");
		nrows++;
	}
	snprintf(buf, sizeof buf, "%d %d %ld %.17g %.17g %.17g %.17g %.17g %d %d %d %ld", CK_VERSION, at->phase,
	    at->round, at->scale, at->r0sum, at->skin, at->e_prev, at->y_prev, at->full, at->have_ref, at->limit_hit,
	    nrows);
	bad |= pack_set_meta(p, CK_STATE, buf);
	snprintf(buf, sizeof buf, "%s %.17g %.17g %.17g %zu %.17g %ld %.17g %.17g %d", st->stage, st->sigma_c,
	    st->porosity, st->coordination, st->under4, st->growth, st->iterations, st->res_max, st->res_mean,
	    st->min_status);
	bad |= pack_set_meta(p, CK_STAGE, buf);
	bad |= pack_set_meta(p, CK_RUN, run);
	if (at->have_ref && !p->has_refbox) {
		snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g %.17g %.17g", p->refbox[0], p->refbox[1],
		    p->refbox[2], p->refbox[3], p->refbox[4], p->refbox[5]);
		bad |= pack_set_meta(p, CK_REFBOX, buf);
	}
	for (row = rows; row && *row && !bad; row = *nl ? nl + 1 : nl) {
		char *line;
		nl = row + strcspn(row, "\n");
		if (!(line = strndup(row, (size_t)(nl - row))))
			bad = 1;
		snprintf(key, sizeof key, CK_ROW "%ld", ++k);
		bad |= !line || pack_set_meta(p, key, line);
		free(line);
	}
	if (bad) {
		msg_seterr("out of memory");
		return -1;
	}
	return 0;
}

void
densify_resume_clear(struct pack *p)
{
	size_t k = 0;

	pack_unset_meta(p, CK_STATE);
	pack_unset_meta(p, CK_STAGE);
	pack_unset_meta(p, CK_REFBOX);
	pack_unset_meta(p, CK_RUN);
	while (k < p->nmeta)
		if (strncmp(p->meta[k].key, CK_ROW, strlen(CK_ROW)) == 0)
			pack_unset_meta(p, p->meta[k].key);
		else
			k++;
}

/* The state and stage lines, and the reference box when there is one: every number in its
 * range (a damaged checkpoint is refused, not run); *nrows the log rows it holds. */
static int
resume_parse(struct pack *p, struct densify_resume *at, long *nrows)
{
	const char *s = pack_get_meta(p, CK_STATE), *t = pack_get_meta(p, CK_STAGE), *rb = pack_get_meta(p, CK_REFBOX);
	struct densify_stage *st = &at->st;
	char name[16];
	int version = 0, end = -1, flags_ok;
	long under4, v[5];
	unsigned k, k0 = 99;

	if (sscanf(s, "%d", &version) != 1 || version != CK_VERSION) {
		msg_seterr("meta %s: not a densify checkpoint of version %d", CK_STATE, CK_VERSION);
		return -1;
	}
	/* every field as a long first: %d of a number beyond int is undefined */
	flags_ok = sscanf(s, "%ld %ld %ld %lg %lg %lg %lg %lg %ld %ld %ld %ld %n", &v[0], &v[1], &at->round, &at->scale,
	               &at->r0sum, &at->skin, &at->e_prev, &at->y_prev, &v[2], &v[3], &v[4], nrows, &end) == 12 &&
	           end >= 0 && !s[end] && v[1] >= 0 && v[1] <= 2 && v[2] >= 0 && v[2] <= 1 && v[3] >= 0 && v[3] <= 1 &&
	           v[4] >= 0 && v[4] <= 1;
	at->phase = (int)v[1], at->full = (int)v[2], at->have_ref = (int)v[3], at->limit_hit = (int)v[4];
	/* one log row per stage: the relaxation and one per growth round (a retry is its round's
	 * row), then one per compaction step */
	if (!flags_ok || at->round < 0 || at->round > 1000000000L || (at->phase == 0) != (at->round == 0) ||
	    !(at->scale > 0 && at->scale <= 1) || !isfinite(at->r0sum) || !(at->r0sum > 0) || !isfinite(at->skin) ||
	    !(at->skin > 0) || isnan(at->e_prev) != isnan(at->y_prev) || isinf(at->e_prev) || isinf(at->y_prev) ||
	    (at->phase == 2 && !at->have_ref) || (at->phase < 2 && *nrows != at->round + 1) ||
	    (at->phase == 2 && *nrows < at->round + 1) || *nrows > 2000000001L) {
		msg_seterr("meta %s: malformed or out of range", CK_STATE);
		return -1;
	}
	end = -1;
	if (!t || sscanf(t, "%15s %lg %lg %lg %ld %lg %ld %lg %lg %d %n", name, &st->sigma_c, &st->porosity,
	        &st->coordination, &under4, &st->growth, &st->iterations, &st->res_max, &st->res_mean,
	        &st->min_status, &end) != 10 || end < 0 || t[end] || !isfinite(st->sigma_c) || !isfinite(st->porosity) ||
	    !isfinite(st->coordination) || under4 < 0 || !isfinite(st->growth) || st->iterations < 0 ||
	    !isfinite(st->res_max) || !isfinite(st->res_mean)) {
		msg_seterr("meta %s: missing, malformed or out of range", CK_STAGE);
		return -1;
	}
	st->under4 = (size_t)under4;
	st->under_min = 0;	/* densify_run_resumable counts them from the positions */
	for (k = 0; k < sizeof stage_names / sizeof *stage_names; k++)
		if (strcmp(name, stage_names[k]) == 0)
			st->stage = stage_names[k], k0 = k;
	if (!st->stage || (at->phase == 0) != (k0 == 0) || (at->phase == 1) != (k0 == 1 || k0 == 2) ||
	    (at->phase == 2) != (k0 == 3)) {
		msg_seterr("meta %s: stage '%s' after phase %d", CK_STAGE, name, at->phase);
		return -1;
	}
	st->round = at->round;
	if (rb) {
		double *b = p->refbox;
		end = -1;
		if (sscanf(rb, "%lg %lg %lg %lg %lg %lg %n", b, b + 1, b + 2, b + 3, b + 4, b + 5, &end) != 6 ||
		    end < 0 || rb[end] || !isfinite(b[0] + b[1] + b[2] + b[3] + b[4] + b[5])) {
			msg_seterr("meta %s: expected six numbers", CK_REFBOX);
			return -1;
		}
	} else if (at->have_ref && !p->has_refbox) {
		msg_seterr("meta %s: missing", CK_REFBOX);
		return -1;
	}
	if (!pack_get_meta(p, CK_RUN)) {
		msg_seterr("meta %s: missing", CK_RUN);
		return -1;
	}
	return 0;
}

/* The log rows 1..nrows, one per line; NULL (message set) when one is missing or there are
 * more. */
static char *
resume_rows(const struct pack *p, long nrows)
{
	char key[40], *buf = malloc(1);
	size_t len = 0;
	long q;

	if (!buf) {
		msg_seterr("out of memory");
		return NULL;
	}
	*buf = 0;
	for (q = 1; q <= nrows + 1; q++) {
		const char *row;
		char *nb;
		size_t l;
		snprintf(key, sizeof key, CK_ROW "%ld", q);
		row = pack_get_meta(p, key);
		if (!row != (q > nrows)) {
			free(buf);
			msg_seterr("meta %s%ld: %s (%s says %ld rows)", CK_ROW, q, row ? "one row too many" : "missing",
			    CK_STATE, nrows);
			return NULL;
		}
		if (!row)
			break;
		l = strlen(row);
		if (!(nb = realloc(buf, len + l + 2))) {
			free(buf);
			msg_seterr("out of memory");
			return NULL;
		}
		buf = nb;
		memcpy(buf + len, row, l);
		len += l;
		buf[len++] = '\n';
		buf[len] = 0;
	}
	return buf;
}

int
densify_resume_check_input(const struct pack *input, const struct densify_params *dp, const struct densify_resume *at)
{
	double r0sum = 0, rmin = INFINITY;
	size_t i;

	/* as state_alloc and qs_init take them */
	for (i = 0; i < input->n; i++) {
		r0sum += input->r[i];
		rmin = fmin(rmin, input->r[i]);
	}
	if (at->r0sum != r0sum || at->skin != dp->skin * rmin) {
		msg_seterr("the checkpoint's radii sum or skin is not the input's");
		return -1;
	}
	return 0;
}

int
densify_resume_get(struct pack *p, struct densify_resume *at, char **run, char **rows)
{
	long nrows;

	*rows = *run = NULL;
	if (!pack_get_meta(p, CK_STATE))
		return 1;
	memset(at, 0, sizeof *at);
	if (resume_parse(p, at, &nrows) || !(*rows = resume_rows(p, nrows)))
		return -1;
	if (!(*run = strdup(pack_get_meta(p, CK_RUN)))) {
		free(*rows);
		*rows = NULL;
		msg_seterr("out of memory");
		return -1;
	}
	densify_resume_clear(p);
	return 0;
}

void
densify_log_header(FILE *fp)
{
	fputs("# stage\tround\tsigma_c[Pa]\tporosity\tcoordination\tunder4\tgrowth\titerations\tresidual\tresidual_mean"
	    "\telapsed[s]\n", fp);
}

void
densify_log_row(FILE *fp, const struct densify_stage *st, double elapsed)
{
	double v[9] = {st->sigma_c, st->porosity, st->coordination, (double)st->under4, st->growth,
	    (double)st->iterations, st->res_max, st->res_mean, elapsed};

	fprintf(fp, "%s\t%ld\t", st->stage, st->round);
	table_row(fp, v, 9);
}
