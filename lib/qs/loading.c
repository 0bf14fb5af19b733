/* SPDX-License-Identifier: GPL-3.0-or-later */
/* loading: strain increments with the affine guess (see loading.h). */
#include "qs/loading.h"
#include "contact/contacts.h"
#include "analysis/measure.h"
#include "base/msg.h"
#include "base/table.h"
#include "base/vec3.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void
load_strain_box(double box[6], double *x, size_t n, const double de[3])
{
	double c[3], f[3];
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		c[a] = 0.5 * (box[a] + box[3 + a]);
		f[a] = 1 - de[a];
		box[a] = c[a] + (box[a] - c[a]) * f[a];
		box[3 + a] = c[a] + (box[3 + a] - c[a]) * f[a];
	}
	for (i = 0; i < n; i++)
		for (a = 0; a < 3; a++)
			x[3 * i + a] = c[a] + (x[3 * i + a] - c[a]) * f[a];
}

int
load_increment(struct qs_system *s, double *x, const double de[3], int nsub, long k_inc,
    const struct qs_min_params *mp, struct qs_min_report *rep)
{
	return load_increment_in(s, NULL, x, de, nsub, k_inc, mp, rep);
}

int
load_increment_in(struct qs_system *s, struct qs_minimizer *m, double *x, const double de[3], int nsub, long k_inc,
    const struct qs_min_params *mp, struct qs_min_report *rep)
{
	struct qs_min_params sub = *mp;
	struct qs_min_report r;
	long iter = 0, evals = 0;
	double part[3];
	int k, a, st = 0;

	if (nsub < 1)
		nsub = 1;
	/* equal parts of the total scale factor, so nsub parts compose to exactly 1 - de */
	for (a = 0; a < 3; a++)
		part[a] = 1 - pow(1 - de[a], 1.0 / nsub);
	for (k = 0; k < nsub; k++) {
		load_strain_box(s->p->box, x, s->n, part);
		sub.max_iter = k + 1 < nsub ? k_inc : mp->max_iter;
		st = m ? qs_minimize_in(m, x, &sub, &r) : qs_minimize(s, x, &sub, &r);
		iter += r.iter;
		evals += r.evals;
		if (st < 0)
			break;
		if (k + 1 < nsub && st == 1)
			st = 0;	/* a sub-increment stopped at k_inc iterations by design */
	}
	*rep = r;
	rep->iter = iter;
	rep->evals = evals;
	return st;
}

void
load_strain(const double box[6], const double refbox[6], double eps[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		double lref = refbox[3 + a] - refbox[a];
		eps[a] = (lref - (box[3 + a] - box[a])) / lref;
	}
}

void
load_params_default(struct load_params *lp)
{
	memset(lp, 0, sizeof *lp);
	lp->friction = 1;
	lp->rule = FR_RETURN_MAP;
	lp->nsub = 1;
	lp->k_inc = 10;
	lp->skin = 0.3;
	lp->inc_tol = LOAD_INC_TOL;
	qs_min_params_default(&lp->min);
	lp->min.lbfgs_m = 0;	/* loader_open: LOAD_LBFGS_M with friction, QS_LBFGS_M without */
}

int
loader_open(struct loader *L, struct pack *p, const struct load_params *lp)
{
	memset(L, 0, sizeof *L);
	L->p = p;
	L->lp = *lp;
	if (L->lp.min.lbfgs_m < 1)
		L->lp.min.lbfgs_m = lp->friction ? LOAD_LBFGS_M : QS_LBFGS_M;
	if (!p->has_refbox) {
		msg_seterr("the pack has no reference box (run densify first)");
		return -1;
	}
	if (lp->friction && lp->min.method->needs_hessian && lp->rule != FR_RETURN_MAP) {
		msg_seterr("%s needs the return map's Hessian (the paper's rule has no potential): "
		    "--rule return-map, or another --method", lp->min.method->name);
		return -1;
	}
	if (qs_init(&L->s, p, lp->skin))
		return -1;
	/* --skin is the ceiling: increments near equilibrium keep a list with a sixth of it
	 * (contacts.h; the same bytes, fewer pairs a walk) */
	contact_enum_skin_auto(&L->s.ce, L->s.skin);
	fr_init(&L->f, lp->rule);
	L->x = calloc(6 * (p->n ? p->n : 1), sizeof *L->x);
	if (!L->x) {
		msg_seterr("out of memory");
		return -1;
	}
	return 0;
}

void
loader_close(struct loader *L)
{
	qs_minimizer_free(L->min);
	qs_free(&L->s);
	fr_free(&L->f);
	free(L->x);
	memset(L, 0, sizeof *L);
}

/* Start an increment from the pack: x = centres (and zero rotations); with friction the
 * contact history is frozen into the functional. */
static int
begin(struct loader *L)
{
	size_t n3 = 3 * L->p->n;

	memcpy(L->x, L->p->x, n3 * sizeof *L->x);
	memset(L->x + n3, 0, n3 * sizeof *L->x);
	if (L->lp.friction ? fr_begin(&L->f, &L->s) : (fr_detach(&L->s), 0))
		return -1;
	if (!L->min || L->min_dim != L->s.dim) {
		qs_minimizer_free(L->min);
		if (!(L->min = qs_minimizer_alloc(&L->s, &L->lp.min)))
			return -1;
		L->min_dim = L->s.dim;
	}
	return 0;
}

/* The row's measures of the pack as committed; the residual comes from the caller.  The
 * sliding ratios here are the pack's record of them (meta sliding_ratio and trial_slip_ratio,
 * written by the increment that made the pack), else the count from the history lines (the
 * trial ratio then 0: a pack does not keep trial forces); loader_step replaces them with the
 * increment's own counts. */
static int
fill_row(struct loader *L, struct load_row *row, size_t *ncontacts)
{
	double rec;
	struct geo_contacts gc;
	struct pack_measures m;
	int a;

	contacts_init(&gc);
	if (measure_pack_in(L->p, &L->s.ce, &gc, &m)) {
		contacts_free(&gc);
		return -1;
	}
	measure_bulk(L->p, &gc, NAN, &m);
	contacts_free(&gc);
	row->bulk_porosity = m.bulk_porosity;
	row->bulk_coordination = m.bulk_coordination;
	row->inc = L->inc;
	load_strain(L->p->box, L->p->refbox, row->eps);
	for (a = 0; a < 3; a++)
		row->sig[a] = m.sig_wall[a];
	memcpy(row->sig_lw, m.sig_lw, sizeof row->sig_lw);
	row->sigma_c = m.sigma_c;
	row->porosity = m.porosity;
	row->coordination = m.coordination;
	row->sliding_ratio = L->lp.friction ? (isnan(m.sliding_ratio) ? 0 : m.sliding_ratio) : 0;
	if (L->lp.friction && pack_get_meta_double(L->p, "sliding_ratio", &rec) == 0 && rec >= 0 && rec <= 1)
		row->sliding_ratio = rec;
	row->trial_slip_ratio = 0;
	if (L->lp.friction && pack_get_meta_double(L->p, "trial_slip_ratio", &rec) == 0 && rec >= 0 && rec <= 1)
		row->trial_slip_ratio = rec;
	*ncontacts = m.contacts_gg + m.contacts_gw;
	return 0;
}

int
loader_measure(struct loader *L, struct load_row *row)
{
	double *g = malloc(6 * (L->p->n ? L->p->n : 1) * sizeof *g), *fmax = malloc((L->p->n ? L->p->n : 1) * sizeof *fmax);
	size_t nc;

	memset(row, 0, sizeof *row);
	if (!g || !fmax || begin(L) || isnan(qs_energy(&L->s, L->x, g, fmax))) {
		if (!g || !fmax)
			msg_seterr("out of memory");
		free(g), free(fmax);
		return -1;
	}
	qs_residual(&L->s, g, fmax, L->lp.min.tol_floor, &row->res_max, &row->res_mean);
	free(g), free(fmax);
	return fill_row(L, row, &nc);
}

/* Settle a committed frictional increment.  The increment froze each contact's sliding limit
 * at its start and kept the tangential spring of a contact that opened during it, so the
 * committed history can hold a |Q0| above mu P0 (the normal force fell) or lose the
 * tangential force of an opened contact: the state written is then not an equilibrium of its
 * own history, and the next increment (or a reader, packinfo) would find a residual up to
 * 1e-2 before any load.  Evaluate the committed state as the next increment starts it (the
 * clamp of fr_begin, opened contacts gone); when it is out of balance, minimise again at the
 * same walls and commit, until it is (each pass cuts the residual 3 to 10 times: 3.6e-2,
 * 6.8e-3, 1.6e-3, 4.5e-4, then below 1e-4 in a 200-grain pack).  The slip this adds belongs to the increment
 * that caused it; the iterations are counted in it.
 * Each pass minimises to half the tolerance: a pass that stopped just under it was pushed
 * just over it again by its own commit, and a 1e4-grain pack stalled at 1.006e-4 and, in
 * another increment, ended 10 passes at 5.1e-4 (cut by only 0.75 per pass there); with half
 * the tolerance and up to 30 passes its increments settle in 7-16 passes, at about the same
 * cost (3 increments: 20.0 s against 18.9 s).  A state that still has not settled keeps its
 * residual in the row.
 * A pass that starts at residual r needs only to reach SETTLE_CUT r: its own commit moves the
 * state again by about what it corrected (each pass cuts the residual 1.2 to 10 times), so
 * the digits below that are lost; only the last passes, near the tolerance, go to half of it.
 * With the increment minimised to inc_tol (LOAD_INC_TOL) this takes 97 L-BFGS iterations per
 * 1e-4 increment of a 2740-grain pack at 8.5 MPa instead of 172, and 307 instead of 648 at 1e4
 * grains, to the same stresses and sliding contacts (bench/settle.md).  The passes
 * themselves are cheap then, so there may be more of them. */
#define SETTLE_PASSES 60
#define SETTLE_CUT 0.3

/* Commit the friction term at L->x, without evaluating again where the minimiser's last
 * evaluation was there (one evaluation per pass, 6 % of an increment's). */
static int
commit(struct loader *L)
{
	return qs_minimizer_current(L->min) ? fr_commit_evaluated(&L->f, &L->s, L->x) : fr_commit(&L->f, &L->s, L->x);
}

static int
settle(struct loader *L, struct qs_min_report *rep)
{
	struct qs_min_params mp = L->lp.min;
	struct qs_min_report r0, r2;
	int pass, st = 0;

	for (pass = 0; pass <= SETTLE_PASSES; pass++) {
		/* after the first pass, L-BFGS goes on with the last pass's pairs and blocks: the
		 * commit moved the history, not the grains (bench/settle.md: a fifth fewer
		 * iterations at 1e4 grains) */
		int resume = pass > 0 && !L->lp.settle_fresh;
		double rmax;

		/* the committed state, evaluated by the minimiser's start (one evaluation for the
		 * check and the pass) */
		if (begin(L) || qs_minimizer_params(L->min, &mp) ||
		    (resume ? qs_minimizer_resume(L->min, L->x) : qs_minimizer_set(L->min, L->x))) {
			st = -1;
			break;
		}
		qs_minimizer_test(L->min, &r0);
		rmax = r0.res_max;
		rep->res_max = rmax;
		rep->res_mean = r0.res_mean;
		if (rmax <= L->lp.min.tol || pass == SETTLE_PASSES) {
			rep->evals += r0.evals;
			break;
		}
		/* loose while far from the tolerance; once a pass's cut would reach it, half of it,
		 * as before (the commit pushes a state that stopped just under it over) */
		st = qs_minimizer_continue(L->min, SETTLE_CUT * rmax >= mp.tol ? SETTLE_CUT * rmax : 0.5 * mp.tol, &r2);
		if (st < 0)
			break;
		rep->iter += r2.iter;
		rep->evals += r2.evals;
		if (commit(L)) {
			st = -1;
			break;
		}
		if (st == 1) {
			rep->res_max = r2.res_max;
			rep->res_mean = r2.res_mean;
			break;
		}
	}
	return st;
}

int
loader_step(struct loader *L, const double de[3], struct load_row *row)
{
	struct qs_min_report rep;
	int st;
	size_t nsl, ntr, nc;
	double dbox[3];
	int a;

	memset(row, 0, sizeof *row);
	nsl = ntr = 0;
	if (begin(L))
		return -1;
	/* de is the change of the strain eps = (L_ref - L) / L_ref, so the box shrinks by
	 * de L_ref, a factor 1 - de L_ref / L: equal de on the three axes is then an isotropic
	 * strain increment exactly, whatever the box's shape relative to the reference */
	for (a = 0; a < 3; a++)
		dbox[a] = de[a] * pack_box_length(L->p->refbox, a) / pack_box_length(L->p->box, a);
	{
		struct qs_min_params mp = L->lp.min;

		if (L->lp.friction)
			mp.tol = fmax(mp.tol, L->lp.inc_tol);
		st = load_increment_in(&L->s, L->min, L->x, dbox, L->lp.nsub, L->lp.k_inc, &mp, &rep);
	}
	if (st < 0)
		return -1;
	if (L->lp.friction) {
		/* each commit's contacts start the next settle pass, at the same positions */
		fr_keep_found(&L->f, 1);
		if (commit(L)) {
			fr_keep_found(&L->f, 0);
			return -1;
		}
		/* the increment's sliding contacts (fr_commit), before any settling: settling
		 * slips contacts to the limits of their new normal forces, which would count
		 * the relaxation of the commit, not the increment */
		nsl = L->f.nlimit;
		ntr = L->f.ntrial_slip;
		if (st == 0)
			st = settle(L, &rep);
		fr_keep_found(&L->f, 0);
		if (st < 0)
			return -1;
	} else {
		memcpy(L->p->x, L->x, 3 * L->p->n * sizeof *L->x);
		if (contacts_store_in(L->p, &L->s.ce, 0))
			return -1;
	}
	L->inc++;
	if (fill_row(L, row, &nc))
		return -1;
	row->sliding_ratio = nc ? (double)nsl / nc : 0;
	row->trial_slip_ratio = nc ? (double)ntr / nc : 0;
	{
		char buf[32], buf2[32];
		snprintf(buf, sizeof buf, "%.17g", row->sliding_ratio);
		snprintf(buf2, sizeof buf2, "%.17g", row->trial_slip_ratio);
		if (pack_set_meta(L->p, "sliding_ratio", buf) || pack_set_meta(L->p, "trial_slip_ratio", buf2)) {
			msg_seterr("out of memory");
			return -1;
		}
	}
	row->iterations = rep.iter;
	row->evals = rep.evals;
	row->res_max = rep.res_max;
	row->res_mean = rep.res_mean;
	row->status = st;
	return st;
}

static const struct table_col load_cols[] = {
	{"inc", NULL}, {"seg", NULL}, {"eps_xx", NULL}, {"eps_yy", NULL}, {"eps_zz", NULL},
	{"sig_xx", "Pa"}, {"sig_yy", "Pa"}, {"sig_zz", "Pa"},
	{"sig_lw_xx", "Pa"}, {"sig_lw_yy", "Pa"}, {"sig_lw_zz", "Pa"},
	{"sigma_c", "Pa"}, {"sig_lat", "Pa"}, {"porosity", NULL}, {"coordination", NULL},
	{"sliding_ratio", NULL}, {"trial_slip_ratio", NULL}, {"iterations", NULL}, {"residual", NULL}, {"res_mean", NULL},
	{"bulk_porosity", NULL}, {"bulk_coordination", NULL},
	{"K", "Pa"}, {"G", "Pa"},
};
#define LOAD_NCOLS ((int)(sizeof load_cols / sizeof load_cols[0]))

/* frictionalize's log: the curve's columns, K and G, then the wall time */
static const struct table_col log_cols[] = {{"elapsed", "s"}};

void
load_table_header(FILE *fp, int with_moduli)
{
	table_header(fp, load_cols, with_moduli ? LOAD_NCOLS : LOAD_NCOLS - 2);
}

void
load_log_header(FILE *fp)
{
	struct table_col c[LOAD_NCOLS + 1];

	memcpy(c, load_cols, sizeof load_cols);
	c[LOAD_NCOLS] = log_cols[0];
	table_header(fp, c, LOAD_NCOLS + 1);
}

/* The curve's values of row into v: the number written. */
static int
load_values(const struct load_row *row, int axis, double *v)
{
	int a, n = 0, u = (axis + 1) % 3, w = (axis + 2) % 3;

	v[n++] = (double)row->inc;
	v[n++] = (double)row->seg;
	for (a = 0; a < 3; a++)
		v[n++] = row->eps[a];
	for (a = 0; a < 3; a++)
		v[n++] = row->sig[a];
	for (a = 0; a < 3; a++)
		v[n++] = row->sig_lw[a];
	v[n++] = row->sigma_c;
	v[n++] = 0.5 * (row->sig[u] + row->sig[w]);
	v[n++] = row->porosity;
	v[n++] = row->coordination;
	v[n++] = row->sliding_ratio;
	v[n++] = row->trial_slip_ratio;
	v[n++] = (double)row->iterations;
	v[n++] = row->res_max;
	v[n++] = row->res_mean;
	v[n++] = row->bulk_porosity;
	v[n++] = row->bulk_coordination;
	return n;
}

void
load_table_row(FILE *fp, const struct load_row *row, int axis, int with_moduli, double K, double G)
{
	double v[LOAD_NCOLS];
	int n = load_values(row, axis, v);

	if (with_moduli) {
		v[n++] = K;
		v[n++] = G;
	}
	table_row(fp, v, n);
}

void
load_log_row(FILE *fp, const struct load_row *row, int axis, double K, double G, double elapsed)
{
	double v[LOAD_NCOLS + 1];
	int n = load_values(row, axis, v);

	v[n++] = K;
	v[n++] = G;
	v[n++] = elapsed;
	table_row(fp, v, n);
}

const char *
loader_limit_note(const struct loader *L, char *buf, size_t n)
{
	size_t sl = L->f.ncommit_slipped;

	if (n)
		buf[0] = 0;
	if (sl && n)
		snprintf(buf, n, "; %zu friction history lines slipped to their limit at the commit", sl);
	return buf;
}
