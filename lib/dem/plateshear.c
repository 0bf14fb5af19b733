/* SPDX-License-Identifier: GPL-3.0-or-later */
/* plateshear: simple shear between glued walls (see plateshear.h). */
#include "dem/plateshear.h"
#include "dem/platepack.h"
#include "base/lines.h"
#include "base/msg.h"
#include "pack/shape.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { WALL_BOTTOM = 2, WALL_TOP = 3 };	/* the y walls, PACK_WALL_INDEX order */

void
shear_params_default(struct shear_params *sp)
{
	engine_params_default(&sp->dyn);
	sp->dyn.damping = 0;
	sp->sigma_w = 0;
	sp->inertial = 1e-3;
	sp->velocity = 0;
	sp->strain = 2.5;
	sp->every = 0.01;
	sp->profile_from = 1.5;
	sp->profile_bins = 20;
	sp->max_steps = 100000000;
	sp->relax_tol = 1e-3;
	sp->relax_damping = 0.3;
	sp->relax_steps_max = 2000000;
	sp->start_strain = 0.05;
}

int
plateshear_snapshot(struct engine *d, struct pack *p)
{
	if (engine_write_back(d, p))
		return -1;
	/* wrapped in the pack, not in the engine: the run goes on bit for bit as without it */
	pack_wrap_centres(p->x, p->n, p->box, p->box + 3, p->periodic);
	return 0;
}

void
shear_result_free(struct shear_result *res)
{
	free(res->profile);
	free(res->profile_n);
	res->profile = res->profile_n = NULL;
}

/* The grains touching a y wall at the start are glued to it. */
static int
on_glue(const struct engine *d, size_t i, long j, const double *xj, const struct plate_interaction *it, double *hist,
    void *ctx)
{
	int w = PACK_IS_WALL(j) ? PACK_WALL_INDEX(j) : -1;

	(void)xj, (void)it, (void)hist, (void)ctx;
	if (w == WALL_BOTTOM || w == WALL_TOP)
		d->glue[i] = (unsigned char)(1 + w);
	return 0;
}

/* Sums over the steps of a row. */
struct row_sums {
	long steps;
	double tau, sn, sig[6], phi, z, elements;
};

static void
row_add(struct row_sums *s, const struct engine *d, double tau, double sn, double V, double vol, size_t nglued)
{
	int a;

	s->steps++;
	s->tau += tau, s->sn += sn;
	for (a = 0; a < 6; a++)
		s->sig[a] += d->sig[a] / V;
	s->phi += vol / V;
	s->z += (double)d->zends / (double)(d->n - nglued);
	s->elements += d->ninter ? (double)d->nelem / d->ninter : 0;
}

static void
row_make(const struct row_sums *s, const struct engine *d, double sigma_s, struct shear_row *row)
{
	double k = 1.0 / s->steps, su = d->u_force / (d->u_len * d->u_len), hd, a;
	int b;

	row->tau_ratio = s->tau * k / sigma_s;
	row->sigma_ratio = s->sn * k / sigma_s;
	for (b = 0; b < 6; b++)
		row->sig[b] = s->sig[b] * k * su;
	row->p = 0.5 * (row->sig[0] + row->sig[1]);
	hd = 0.5 * (row->sig[0] - row->sig[1]);
	a = row->sig[3];
	row->q = sqrt(hd * hd + a * a);
	row->qp = row->p > 0 ? row->q / row->p : NAN;
	row->phi = s->phi * k;
	row->z = s->z * k;
	row->elements = s->elements * k;
	row->height = (d->hi[1] - d->lo[1]) * d->u_len;
}

static void
profile_add(const struct engine *d, double vw, int nb, double *sum, double *cnt)
{
	double H = d->hi[1] - d->lo[1];
	size_t i;

	for (i = 0; i < d->n; i++) {
		long b = (long)floor((d->x[3 * i + 1] - d->lo[1]) / H * nb);

		b = b < 0 ? 0 : b >= nb ? nb - 1 : b;
		sum[b] += d->v[3 * i] / vw;
		cnt[b] += 1;
	}
}

/* The relaxation before the strain (see shear_params): at sigma_s (scaled), the periodic
 * axes fixed, with local damping, until static. */
static int
relax(struct engine *d, const struct shear_params *sp, double sigma_s, struct shear_result *res)
{
	struct platepack_params pp;
	struct platepack_status st;
	double damping = d->damping;
	int r;

	platepack_params_default(&pp);
	pp.rest_tol = sp->relax_tol;
	pp.max_steps = sp->relax_steps_max;
	d->damping = sp->relax_damping;
	r = platepack_settle(d, &pp, sigma_s, 2, NULL, NULL, &st);
	d->damping = damping;
	if (r) {
		msg_seterr("the relaxation before the shear: %s", msg_geterr());
		return -1;
	}
	res->relax_steps = st.step;
	res->relax_phi = st.phi;
	res->relax_z = st.z;
	return 0;
}

static void glue_count(const struct engine *d, struct shear_result *res, double *mtop);

static int
glue_walls(struct engine *d, struct shear_result *res, double *mtop)
{
	if (engine_foreach_interaction(d, 1, on_glue, NULL))
		return -1;
	glue_count(d, res, mtop);
	if (res->glued_bottom == 0 || res->glued_top == 0) {
		msg_seterr("no grain touches the %s wall: shear a pack compacted between walls (packgen)",
		    res->glued_bottom == 0 ? "bottom (ylo)" : "top (yhi)");
		return -1;
	}
	return 0;
}

/* Where a run stands after a row: the engine, and what the loop carries from step to step
 * (the sums of the row are empty after a row). */
struct shear_state {
	struct engine *d;
	long step;
	double xw, next_row, vw, H0;
	int nb;
	double *psum, *pn;	/* the profile's sums and samples per bin */
};

int
plateshear_state_write(const struct shear_state *s, FILE *fp)
{
	int b;

	fprintf(fp, "shear-state 1 %d\nloop %ld %a %a %a %a\n", s->nb, s->step, s->xw, s->next_row, s->vw, s->H0);
	for (b = 0; b < s->nb; b++)
		fprintf(fp, "%a %a\n", s->psum[b], s->pn[b]);
	return engine_state_write(s->d, fp);
}

static int
state_read(struct shear_state *s, struct lines *in)
{
	char *line, *tok[8], *end;
	double v[5];
	int b, k, nt;

	if (lines_next(in, &line, NULL) != 1 || lines_split(line, " \t", tok, 8) != 3 || strcmp(tok[0], "shear-state") ||
	    strcmp(tok[1], "1") || strtol(tok[2], &end, 10) != s->nb || *end)
		return lines_error(in, "expected 'shear-state 1 %d' (a shear's state with this many profile bins)", s->nb);
	if (lines_next(in, &line, NULL) != 1 || (nt = lines_split(line, " \t", tok, 8)) != 6 || strcmp(tok[0], "loop"))
		return lines_error(in, "expected 'loop STEP XW NEXT_ROW V_W H0'");
	s->step = strtol(tok[1], &end, 10);
	if (*end || s->step < 0)
		return lines_error(in, "'%s': not a step", tok[1]);
	for (k = 0; k < 4; k++) {
		v[k] = strtod(tok[2 + k], &end);
		if (*end || !isfinite(v[k]))
			return lines_error(in, "'%s': not a finite number", tok[2 + k]);
	}
	s->xw = v[0], s->next_row = v[1], s->vw = v[2], s->H0 = v[3];
	if (!(s->xw >= 0 && s->next_row > 0 && s->vw > 0 && s->H0 > 0))
		return lines_error(in, "loop: the wall's travel, the next row's strain, v_w and H0 must be positive (%g %g %g %g)",
		    s->xw, s->next_row, s->vw, s->H0);
	for (b = 0; b < s->nb; b++) {
		if (lines_next(in, &line, NULL) != 1 || lines_split(line, " \t", tok, 8) != 2)
			return lines_error(in, "expected a profile bin's sum and samples");
		for (k = 0; k < 2; k++) {
			v[k] = strtod(tok[k], &end);
			if (*end || !isfinite(v[k]))
				return lines_error(in, "'%s': not a finite number", tok[k]);
		}
		s->psum[b] = v[0], s->pn[b] = v[1];
	}
	return engine_state_read(s->d, in);
}

/* The glued grains' counts and the top body's mass. */
static void
glue_count(const struct engine *d, struct shear_result *res, double *mtop)
{
	size_t i;

	res->glued_bottom = res->glued_top = 0;
	*mtop = 0;
	for (i = 0; i < d->n; i++) {
		if (d->glue[i] == 1 + WALL_BOTTOM)
			res->glued_bottom++;
		if (d->glue[i] == 1 + WALL_TOP)
			res->glued_top++, *mtop += d->m[i];
	}
}

int
plateshear_run(struct pack *p, const struct shear_params *sp, shear_row_fn fn, void *ctx, struct shear_result *res)
{
	return plateshear_run_resumable(p, sp, fn, ctx, NULL, NULL, res);
}

/* A run of no sense, refused before its first step (it ran for minutes with no row, or
 * sent the grains flying): the time step not a positive number; the wall, at v_w, moving
 * a grain's radius in a step; or so slow that the strain would take more than ten times
 * --max-steps (days or years), the box as tall as now and the wall xw along.  0, or -1
 * with the message. */
static int
steps_check(const struct engine *d, const struct shear_params *sp, double vw, double xw)
{
	double need = (sp->strain * (d->hi[1] - d->lo[1]) - xw) / (vw * d->dt), rbmax = 0;
	size_t i;

	for (i = 0; i < d->n; i++)
		rbmax = fmax(rbmax, d->rb[i]);
	if (!(d->dt > 0 && isfinite(d->dt))) {
		msg_seterr("the time step %g s is not a positive number: the stiffness (kn, kt, the grains' E) or the "
		    "density is out of any sensible range", d->dt * d->u_time);
		return -1;
	}
	if (!(vw > 0 && vw * d->dt <= rbmax)) {
		msg_seterr("the top wall at v_w %g m/s would move more than a grain's radius in a time step of %g s: "
		    "--velocity is out of any sensible range", vw * d->u_len / d->u_time, d->dt * d->u_time);
		return -1;
	}
	if (!(need <= 10.0 * (double)sp->max_steps)) {
		msg_seterr("the shear would need %.3g steps of %.3g s at v_w %.3g m/s to reach gamma %g, more than ten times "
		    "--max-steps (%ld): the stiffness (kn, the grains' E), the stress (--stress, meta sigma0), --inertial or "
		    "--velocity is out of any sensible range", need, d->dt * d->u_time, vw * d->u_len / d->u_time, sp->strain,
		    sp->max_steps);
		return -1;
	}
	return 0;
}

/* The run's start, after engine_init: the state of a run of this input after a row (from),
 * or the pack's frictional history, the relaxation at sigma_w and the glued walls; then
 * the scales the run reports.  *mtop the top body's mass, sigma_s the scaled stress, *A the
 * top's area, *vol the grains' volume.  0, -1, or -2 for a bad checkpoint (its file:line
 * message). */
static int
shear_begin(struct engine *d, struct pack *p, const struct shear_params *sp, struct lines *from, double sigma_s,
    struct shear_state *ss, struct shear_result *res, double *mtop, double *A, double *vol)
{
	size_t i;

	if (from) {	/* the state of a run of this input, after a row */
		if (state_read(ss, from))
			return -2;
		/* the wall's velocity is the run's own, as shear_begin sets it below (bit for bit:
		 * the same expression on the same numbers) */
		if (ss->vw != (sp->velocity > 0 ? sp->velocity * d->u_time / d->u_len : sp->inertial * sqrt(sigma_s) * ss->H0)) {
			msg_seterr("%s: v_w %g m/s is not the run's (--velocity, --inertial): the checkpoint was changed",
			    lines_name(from), ss->vw * d->u_len / d->u_time);
			return -2;
		}
		if (steps_check(d, sp, ss->vw, ss->xw))
			return -1;
		glue_count(d, res, mtop);
	} else {
		/* v_w as below, for the box as it is before the relaxation */
		if (steps_check(d, sp, sp->velocity > 0 ? sp->velocity * d->u_time / d->u_len :
		    sp->inertial * sqrt(sigma_s) * (d->hi[1] - d->lo[1]), 0))
			return -1;
		/* the pack's frictional history, for the pairs that were in it (those across a new
		 * periodic boundary start from zero) */
		if (engine_read_history(d, p))
			return -1;
		if (sp->relax_tol > 0 && relax(d, sp, sigma_s, res))
			return -1;
		if (glue_walls(d, res, mtop))
			return -1;
		ss->H0 = d->hi[1] - d->lo[1];
		/* I = gamma_dot r sqrt(rho / sigma_w) with r = 1 and rho = 1 in these units */
		ss->vw = sp->velocity > 0 ? sp->velocity * d->u_time / d->u_len : sp->inertial * sqrt(sigma_s) * ss->H0;
		ss->next_row = sp->every;
		d->wallv[WALL_TOP][0] = ss->vw;
	}
	*vol = 0;
	for (i = 0; i < d->n; i++)
		*vol += shape_table[d->kind[i]]->volume(d->r[i], 2 * d->half[i]);
	*A = (d->hi[0] - d->lo[0]) * (d->hi[2] - d->lo[2]);
	res->inertial = ss->vw / ss->H0 / sqrt(sigma_s);
	res->v_w = ss->vw * d->u_len / d->u_time;
	res->gamma_dot = res->v_w / (ss->H0 * d->u_len);
	res->kappa = engine_kappa(p, &sp->dyn, sp->sigma_w);
	return 0;
}

/* The force on the top body: its glued grains', and its plane's push on the free grains
 * reversed. */
static void
top_body_force(const struct engine *d, double F[3])
{
	size_t i;
	int a;

	for (a = 0; a < 3; a++)
		F[a] = -d->wallF[WALL_TOP][a];
	for (i = 0; i < d->n; i++)
		if (d->glue[i] == 1 + WALL_TOP)
			for (a = 0; a < 3; a++)
				F[a] += d->f[3 * i + a];
}

/* The top body's normal velocity after a step under force fy - sigma_s A, its motion damped
 * at the start (shear_params). */
static void
top_body_push(struct engine *d, const struct shear_params *sp, const struct shear_state *ss, double fy, double mtop)
{
	double vy = d->wallv[WALL_TOP][1];

	if (ss->xw < sp->start_strain * (d->hi[1] - d->lo[1]))
		fy -= sp->relax_damping * fabs(fy) * (vy > 0 ? 1 : vy < 0 ? -1 : 0);
	d->wallv[WALL_TOP][1] += fy / mtop * d->dt;
}

/* The row of the steps summed in rs, at strain gamma; rs emptied and the next row's strain
 * set. */
static void
row_emit(struct row_sums *rs, const struct engine *d, const struct shear_params *sp, struct shear_state *ss, double sigma_s,
    double gamma, struct shear_row *row)
{
	row_make(rs, d, sigma_s, row);
	row->step = ss->step;
	row->time = ss->step * d->dt * d->u_time;
	row->gamma = gamma;
	row->profile_sum = ss->psum;
	row->profile_n = ss->pn;
	memset(rs, 0, sizeof *rs);
	while (ss->next_row <= gamma)
		ss->next_row += sp->every;
}

int
plateshear_run_resumable(struct pack *p, const struct shear_params *sp, shear_row_fn fn, void *ctx,
    shear_checkpoint_fn ck, struct lines *from, struct shear_result *res)
{
	const int per[3] = {1, 0, 1};
	struct engine_params dyn;
	struct engine d;
	struct row_sums rs;
	struct shear_row row;
	struct shear_state ss = {&d, 0, 0, 0, 0, 0, sp->profile_bins, NULL, NULL};
	double mtop, sigma_s, A, vol;
	int status = -1, a, nb = sp->profile_bins;

	memset(res, 0, sizeof *res);
	if (p->periodic[1]) {
		msg_seterr("the gradient axis y is periodic: the shear needs its walls");
		return -1;
	}
	/* the time step made for the overlaps sigma_w makes (engine.h; the law's stiffest: a
	 * spring law's does not depend on them) */
	dyn = sp->dyn;
	dyn.hertz_overlap = fmax(dyn.hertz_overlap, ENGINE_OVERLAP_KAPPA / engine_kappa(p, &dyn, sp->sigma_w));
	if (engine_init(&d, p, &dyn))
		return -1;
	d.cache_margin = engine_shear_cache_margin(&d);	/* a slow shear's (packgen's compaction keeps the default) */
	d.stress = 1;	/* the rows' Love-Weber stress */
	if ((!d.periodic[0] || !d.periodic[2]) && engine_make_periodic(&d, per))
		goto out;
	res->profile = calloc((size_t)nb, sizeof *res->profile);
	res->profile_n = ss.pn = calloc((size_t)nb, sizeof *res->profile_n);
	ss.psum = calloc((size_t)nb, sizeof *ss.psum);
	if (!res->profile || !res->profile_n || !ss.psum || !(d.glue = calloc(d.n, 1))) {
		msg_seterr("out of memory");
		goto out;
	}
	sigma_s = sp->sigma_w / (d.u_force / (d.u_len * d.u_len));
	if ((status = shear_begin(&d, p, sp, from, sigma_s, &ss, res, &mtop, &A, &vol)) != 0)
		goto out;
	status = -1;
	memset(&rs, 0, sizeof rs);
	for (;;) {
		double F[3], gamma;

		ss.step++;
		if (ss.step > sp->max_steps) {
			msg_seterr("the shear did not reach gamma %g in %ld steps", sp->strain, sp->max_steps);
			goto out;
		}
		if (engine_forces(&d))
			goto out;
		top_body_force(&d, F);
		row_add(&rs, &d, -F[0] / A, F[1] / A, (d.hi[0] - d.lo[0]) * (d.hi[1] - d.lo[1]) * (d.hi[2] - d.lo[2]), vol,
		    res->glued_bottom + res->glued_top);
		top_body_push(&d, sp, &ss, F[1] - sigma_s * A, mtop);
		engine_integrate(&d);
		d.hi[1] += d.wallv[WALL_TOP][1] * d.dt;
		ss.xw += ss.vw * d.dt;
		gamma = ss.xw / (d.hi[1] - d.lo[1]);
		if (gamma >= sp->profile_from && ss.step % 10 == 0)
			profile_add(&d, ss.vw, nb, ss.psum, ss.pn);
		if (gamma >= ss.next_row || gamma >= sp->strain) {
			int r;

			row_emit(&rs, &d, sp, &ss, sigma_s, gamma, &row);
			if (fn && fn(&row, &d, ctx)) {
				if (!*msg_geterr())
					msg_seterr("stopped");
				goto out;
			}
			if (gamma < sp->strain && ck && (r = ck(&ss, ctx)) != 0) {
				status = r > 0 ? 2 : -1;
				goto out;
			}
		}
		if (gamma >= sp->strain)
			break;
	}
	for (a = 0; a < nb; a++)
		res->profile[a] = res->profile_n[a] > 0 ? ss.psum[a] / res->profile_n[a] : NAN;
	engine_wrap(&d);
	if (engine_write_back(&d, p))
		goto out;
	status = 0;
out:
	free(ss.psum);
	if (status)
		shear_result_free(res);
	engine_free(&d);
	return status;
}

/* a number into a meta line, as the pack's writer prints it */
static int
set_meta_g(struct pack *p, const char *key, double v)
{
	char buf[40];

	snprintf(buf, sizeof buf, "%.17g", v);
	return pack_set_meta(p, key, buf);
}

int
plateshear_choose_law(struct pack *p, const struct shear_law_choice *c, struct shear_params *sp,
    const struct contact_law **lawp)
{
	const struct contact_law *law = contact_law_choose(p, c->law);
	struct engine_params *dyn = &sp->dyn;
	double v, kn = c->kn, kt = c->kt;

	if (!(*lawp = law))
		return -1;
	if (law->stiffness == LAW_SPRING) {
		if (isnan(kn) && pack_get_meta_double(p, "kn", &kn)) {
			msg_seterr("no meta kn (the normal stiffness packgen --shape spheroplate records): give --kn");
			return -1;
		}
		if (!(kn > 0 && isfinite(kn))) {	/* --kn is checked where it is parsed: the pack's */
			msg_seterr("meta kn %g N/m: must be positive; give --kn", kn);
			return -1;
		}
		if (isnan(kt))
			kt = pack_get_meta_double(p, "kt", &v) == 0 ? v : kn;
		if (!(kt >= 0 && isfinite(kt))) {
			msg_seterr("meta kt %g N/m: must be non-negative; give --kt", kt);
			return -1;
		}
		dyn->kn = kn, dyn->kt = kt;
		/* the pack records what the run used: packinfo measures with it (law_pack_kn) */
		if ((!isnan(c->kn) && set_meta_g(p, "kn", kn)) || (!isnan(c->kt) && set_meta_g(p, "kt", kt)))
			return -1;
	} else if (!isnan(kn) || !isnan(kt)) {
		msg_seterr("--kn and --kt are a spring law's; under %s the stiffness is the grains' E and nu", law->name);
		return -2;
	}
	engine_params_law(dyn, law);
	dyn->restitution = !isnan(c->restitution) ? c->restitution :
	    pack_get_meta_double(p, "restitution", &v) == 0 ? v : 0.6;
	dyn->mu = p->mu = isnan(c->mu) ? p->mu : c->mu;
	dyn->wall_mu = p->wall_mu = isnan(c->wall_mu) ? p->wall_mu : c->wall_mu;
	if (!isnan(c->kappa))
		sp->sigma_w = engine_kappa_stress(p, dyn, c->kappa);
	if (sp->sigma_w == 0 && pack_get_meta_double(p, "sigma0", &sp->sigma_w)) {
		msg_seterr("no meta sigma0 (the compaction stress packgen records for plates): give --stress or --kappa");
		return -1;
	}
	if (!(sp->sigma_w > 0 && isfinite(sp->sigma_w))) {
		msg_seterr("the normal stress %g Pa: must be positive (--stress, --kappa, or meta sigma0)", sp->sigma_w);
		return -1;
	}
	if (!(dyn->restitution >= 0.21 && dyn->restitution <= 1)) {
		msg_seterr("meta restitution %g: must be in [0.21, 1]; give --restitution", dyn->restitution);
		return -1;
	}
	if (law->stiffness == LAW_MODULI && !(engine_mean_Estar(p) > 0 && isfinite(engine_mean_Estar(p)))) {
		msg_seterr("the grains' mean E* %g Pa: %s needs the grains' E and nu", engine_mean_Estar(p), law->name);
		return -1;
	}
	if (law->stress_in_range(law, p, sp->sigma_w)) {
		char why[512];

		snprintf(why, sizeof why, "sigma_w %s", msg_geterr());
		msg_seterr("%s", why);
		return -2;
	}
	return contact_law_claim(p, law);
}
