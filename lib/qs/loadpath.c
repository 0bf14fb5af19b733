/* SPDX-License-Identifier: GPL-3.0-or-later */
/* loadpath: parsing and walking loading paths (see loadpath.h). */
#include "qs/loadpath.h"
#include "qs/friction.h"
#include "analysis/measure.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *
path_kind_name(enum path_kind k)
{
	static const char *const names[] = {"uniaxial", "isotropic", "triaxial", "polyaxial"};
	return names[k];
}

static int
parse_num(const char *s, double *v)
{
	char *end;

	*v = strtod(s, &end);
	return *s && !*end && isfinite(*v) ? 0 : -1;
}

int
path_parse_axis(const char *s, int *axis)
{
	if (s[0] >= 'x' && s[0] <= 'z' && !s[1]) {
		*axis = s[0] - 'x';
		return 0;
	}
	return -1;
}

static int
parse_kind(const char *word, int k, enum path_kind *kind, int *probe)
{
	enum path_kind kk;

	*probe = strcmp(word, "probe") == 0;
	if (*probe) {
		*kind = PATH_UNIAXIAL;
		return 0;
	}
	for (kk = PATH_UNIAXIAL; kk <= PATH_POLYAXIAL; kk++)
		if (strcmp(word, path_kind_name(kk)) == 0) {
			*kind = kk;
			return 0;
		}
	msg_seterr("segment %d: unknown path '%s' (uniaxial, isotropic, triaxial, polyaxial, probe)", k, word);
	return -1;
}

/* What a segment's words say beyond struct path_seg: triaxial's lateral ratio and whether
 * polyaxial's ratio= was given at all (ratio=0:0:0 and no ratio are different errors). */
struct seg_extra {
	double lateral;
	int have_ratio;
};

/* One key=value word after the kind (the word is modified in place). */
static int
parse_setting(char *word, int k, struct path_seg *sg, struct seg_extra *x)
{
	char *eq = strchr(word, '=');
	const char *key = word, *val = eq ? eq + 1 : NULL;
	double v;

	if (eq)
		*eq = '\0';
	if (strcmp(key, "hold") == 0 && !val) {
		if (sg->kind != PATH_TRIAXIAL) {
			msg_seterr("segment %d: hold belongs to a triaxial segment", k);
			return -1;
		}
		sg->hold = 2;
		return 0;
	}
	if (!val || !*val) {
		msg_seterr("segment %d: '%s' needs a value (key=value)", k, key);
		return -1;
	}
	if (strcmp(key, "axis") == 0) {
		if (path_parse_axis(val, &sg->axis))
			goto bad;
	} else if (strcmp(key, "step") == 0) {
		if (parse_num(val, &v) || v == 0 || fabs(v) > 0.01)
			goto bad;
		sg->step = v;
	} else if (strcmp(key, "steps") == 0) {
		if (parse_num(val, &v) || v < 1 || v > 1e7 || v != floor(v))
			goto bad;
		sg->steps = (long)v;
	} else if (strcmp(key, "to-stress") == 0) {
		if (parse_num(val, &v) || !(v > 0))
			goto bad;
		sg->to_stress = v;
	} else if (strcmp(key, "to-strain") == 0) {
		if (parse_num(val, &v) || fabs(v) > 0.5)
			goto bad;
		sg->to_strain = v;
	} else if (strcmp(key, "lateral") == 0 && sg->kind == PATH_TRIAXIAL) {
		if (parse_num(val, &x->lateral) || fabs(x->lateral) > 10)
			goto bad;
	} else if (strcmp(key, "hold") == 0 && sg->kind == PATH_TRIAXIAL) {
		if (parse_num(val, &v) || !(v > 0))
			goto bad;
		sg->hold = 1;
		sg->hold_stress = v;
	} else if (strcmp(key, "ratio") == 0 && sg->kind == PATH_POLYAXIAL) {
		int used = 0;
		if (sscanf(val, "%lf:%lf:%lf%n", &sg->ratio[0], &sg->ratio[1], &sg->ratio[2], &used) != 3 ||
		    val[used] != '\0' || !isfinite(sg->ratio[0] + sg->ratio[1] + sg->ratio[2]))
			goto bad;
		x->have_ratio = 1;
	} else {
		msg_seterr("segment %d: '%s' is not a setting of a %s path", k, key, path_kind_name(sg->kind));
		return -1;
	}
	return 0;
bad:
	msg_seterr("segment %d: bad value in '%s=%s'", k, key, val);
	return -1;
}

/* Polyaxial: the largest ratio is the step's unit, and its axis the segment's axis. */
static int
scale_polyaxial(int k, struct path_seg *sg)
{
	double big = 0;
	int a;

	for (a = 0; a < 3; a++)
		if (!isfinite(sg->ratio[a]) || fabs(sg->ratio[a]) > 1e6)
			goto badratio;
	for (a = 0; a < 3; a++)
		if (fabs(sg->ratio[a]) > big) {
			big = fabs(sg->ratio[a]);
			sg->axis = a;
		}
	if (big == 0)
		goto badratio;
	for (a = 0; a < 3; a++)
		sg->ratio[a] /= big;
	return 0;
badratio:
	msg_seterr("segment %d: ratio must be three finite numbers, not all zero", k);
	return -1;
}

/* The strain increment per unit of step on each axis, from the kind and its settings. */
static int
set_ratio(int k, struct path_seg *sg, const struct seg_extra *x)
{
	int a;

	switch (sg->kind) {
	case PATH_UNIAXIAL:
		sg->ratio[sg->axis] = 1;
		break;
	case PATH_ISOTROPIC:
		sg->ratio[0] = sg->ratio[1] = sg->ratio[2] = 1;
		break;
	case PATH_TRIAXIAL:
		if (sg->hold && x->lateral != 0) {
			msg_seterr("segment %d: lateral= and hold are exclusive", k);
			return -1;
		}
		for (a = 0; a < 3; a++)
			sg->ratio[a] = a == sg->axis ? 1 : x->lateral;
		break;
	case PATH_POLYAXIAL:
		if (!x->have_ratio) {
			msg_seterr("segment %d: a polyaxial path needs ratio=A:B:C", k);
			return -1;
		}
		return scale_polyaxial(k, sg);
	}
	return 0;
}

/* A segment without a stop of its own takes the first default stop there is. */
static int
set_default_stop(int k, const struct path_defaults *def, struct path_seg *sg)
{
	if (sg->steps != 0 || !isnan(sg->to_stress) || !isnan(sg->to_strain))
		return 0;
	if (def->steps > 0)
		sg->steps = def->steps;
	else if (!isnan(def->to_stress))
		sg->to_stress = def->to_stress;
	else if (!isnan(def->to_strain))
		sg->to_strain = def->to_strain;
	else {
		msg_seterr("segment %d: no stop (steps=N, to-stress=PA or to-strain=E)", k);
		return -1;
	}
	return 0;
}

/* One segment from its words (modified in place); *probe is set for a probe, which the
 * caller expands into its three uniaxial segments. */
static int
parse_seg(char *text, int k, const struct path_defaults *def, struct path_seg *sg, int *probe)
{
	struct seg_extra x = {0, 0};
	char *w, *save = NULL;
	const char *seen[32];
	size_t nseen = 0;

	memset(sg, 0, sizeof *sg);
	sg->axis = def->axis;
	sg->step = def->step;
	sg->to_stress = sg->to_strain = NAN;
	w = strtok_r(text, " \t\n", &save);
	if (!w) {
		msg_seterr("segment %d is empty", k);
		return -1;
	}
	if (parse_kind(w, k, &sg->kind, probe))
		return -1;
	while ((w = strtok_r(NULL, " \t\n", &save))) {
		if (*probe && strncmp(w, "axis=", 5) == 0) {
			msg_seterr("segment %d: a probe loads x, y and z in turn: no axis=", k);
			return -1;
		}
		if (*probe && (strncmp(w, "to-stress=", 10) == 0 || strncmp(w, "to-strain=", 10) == 0)) {
			msg_seterr("segment %d: a probe stops by steps=N (per axis), not '%s'", k, w);
			return -1;
		}
		{	/* each key once: steps=1 steps=2 took the last without a word */
			size_t len = strcspn(w, "="), j;

			for (j = 0; j < nseen; j++)
				if (strlen(seen[j]) == len && strncmp(seen[j], w, len) == 0) {
					msg_seterr("segment %d: '%.*s' is given twice", k, (int)len, w);
					return -1;
				}
		}
		if (parse_setting(w, k, sg, &x))
			return -1;
		if (nseen < sizeof seen / sizeof seen[0])
			seen[nseen++] = w;	/* the key alone now: parse_setting cut it at '=' */
	}
	if (isnan(sg->step) || sg->step == 0) {
		msg_seterr("segment %d: no strain step (step=D or --strain-step)", k);
		return -1;
	}
	if (set_ratio(k, sg, &x))
		return -1;
	if (*probe) {
		if (sg->steps == 0)
			sg->steps = def->steps;
		if (sg->steps <= 0) {
			msg_seterr("segment %d: a probe needs steps=N (increments per axis) or --steps", k);
			return -1;
		}
		return 0;
	}
	return set_default_stop(k, def, sg);
}

int
path_parse(const char *spec, const struct path_defaults *def, struct load_path *path)
{
	char *copy = strdup(spec), *seg, *save = NULL;
	int k = 0, probe;

	if (!copy) {
		msg_seterr("out of memory");
		return -1;
	}
	path->n = 0;
	for (seg = strtok_r(copy, ";", &save); seg; seg = strtok_r(NULL, ";", &save)) {
		struct path_seg sg;
		int a, nseg;
		k++;
		if (parse_seg(seg, k, def, &sg, &probe)) {
			free(copy);
			return -1;
		}
		nseg = probe ? 3 : 1;
		if (path->n + nseg > sizeof path->seg / sizeof path->seg[0]) {
			msg_seterr("more than %zu segments", sizeof path->seg / sizeof path->seg[0]);
			free(copy);
			return -1;
		}
		for (a = 0; a < nseg; a++) {
			struct path_seg *d = &path->seg[path->n++];
			*d = sg;
			if (probe) {
				d->axis = a;
				d->ratio[0] = d->ratio[1] = d->ratio[2] = 0;
				d->ratio[a] = 1;
			}
		}
	}
	free(copy);
	if (path->n == 0) {
		msg_seterr("empty path");
		return -1;
	}
	return 0;
}

/* The strain a segment's to-strain refers to. */
static double
control_strain(const struct path_seg *sg, const double eps[3])
{
	if (sg->kind == PATH_ISOTROPIC)
		return (eps[0] + eps[1] + eps[2]) / 3;
	return eps[sg->axis];
}

int
path_read_pack(const char *input, const char *who, struct pack *p, size_t *stale)
{
	const struct contact_law *law;
	struct geo_contacts gc;
	struct pack_measures m;
	int r;

	if (pack_read_path(input, p))
		return -1;
	if (pack_require_spheres(p, who))
		return 1;
	if (!(law = contact_law_require(p, who, contact_laws_qs_friction)))
		return 1;
	if (p->n < 5) {
		msg_seterr("%zu grains: %s needs at least 5", p->n, who);
		return 1;
	}
	if (!p->has_refbox) {
		msg_seterr("no reference box: densify the pack first");
		return 1;
	}
	/* History written by a tool satisfies the sliding limit of the pack's own coefficients:
	 * a line far above it is corrupt, not something to repair silently. */
	if (fr_check_history(law, p))
		return 1;
	contacts_init(&gc);
	r = measure_pack(p, &gc, &m);
	contacts_free(&gc);
	if (r)	/* the pack's fault (a periodic box too short for its grains), or out of memory */
		return 1;
	*stale = m.stale_history;
	return 0;
}

int
path_set_friction(struct pack *p, double mu, double wall_mu)
{
	if (!isnan(mu)) {
		p->mu = mu;
		p->wall_mu = isnan(wall_mu) ? mu : wall_mu;
	} else if (!isnan(wall_mu))
		p->wall_mu = wall_mu;
	if (p->mu > 0 || p->wall_mu > 0)
		return 1;
	p->mu = p->wall_mu = 0;
	return 0;
}

/* Whether a segment has reached its stop at the state prev, after n increments. */
static int
reached_stop(const struct path_seg *sg, const struct load_row *prev, long n)
{
	double dir = sg->step > 0 ? 1 : -1;

	if (sg->steps > 0 && n >= sg->steps)
		return 1;
	if (!isnan(sg->to_stress) && (prev->sigma_c - sg->to_stress) * dir >= 0)
		return 1;
	if (!isnan(sg->to_strain) && (control_strain(sg, prev->eps) - sg->to_strain) * dir >= 0)
		return 1;
	return 0;
}

/* 0, or -1 with msg_seterr when segment k's stop is already passed at its start prev: it would
 * run no increment (a loadtest to a stress the pack was already above wrote its header and
 * exited 0 without a word). */
static int
check_start(size_t k, const struct path_seg *sg, const struct load_row *prev)
{
	double dir = sg->step > 0 ? 1 : -1;

	if (!isnan(sg->to_stress) && (prev->sigma_c - sg->to_stress) * dir >= 0) {
		msg_seterr("segment %zu (%s): to-stress %g Pa is already passed at its start (sigma_c %.6g Pa, which a step of %g %s): nothing to load; give a stop %s %.6g Pa, or a %s step",
		    k + 1, path_kind_name(sg->kind), sg->to_stress, prev->sigma_c, sg->step, dir > 0 ? "raises" : "lowers",
		    dir > 0 ? "above" : "below", prev->sigma_c, dir > 0 ? "negative (unloading)" : "positive (loading)");
		return -1;
	}
	if (!isnan(sg->to_strain) && (control_strain(sg, prev->eps) - sg->to_strain) * dir >= 0) {
		msg_seterr("segment %zu (%s): to-strain %g is already passed at its start (strain %.6g, which a step of %g %s): nothing to load; give a stop %s %.6g, or a %s step",
		    k + 1, path_kind_name(sg->kind), sg->to_strain, control_strain(sg, prev->eps), sg->step,
		    dir > 0 ? "raises" : "lowers", dir > 0 ? "above" : "below", control_strain(sg, prev->eps),
		    dir > 0 ? "negative (unloading)" : "positive (loading)");
		return -1;
	}
	return 0;
}

/* The servo of a segment that holds its mean lateral stress (hold): its model of the
 * segment's lateral stress, d sig_lat = A de_axial + B de_lat, learnt increment by increment. */
struct servo {
	int axis, u, v;		/* the segment's axis and the two lateral to it */
	double target;		/* the mean lateral stress held */
	double A, B;		/* NaN until the first increment has given them */
};

static double
lateral_mean(const struct servo *sv, const double sig[3])
{
	return 0.5 * (sig[sv->u] + sig[sv->v]);
}

static void
servo_start(struct servo *sv, const struct path_seg *sg, const struct load_row *prev)
{
	sv->axis = sg->axis;
	sv->u = (sg->axis + 1) % 3;
	sv->v = (sg->axis + 2) % 3;
	sv->A = sv->B = NAN;
	sv->target = 0;
	if (sg->hold)
		sv->target = sg->hold == 1 ? sg->hold_stress : lateral_mean(sv, prev->sig);
}

/* The lateral strain increment the model expects to bring the lateral stress back to its
 * target; before the model has been learnt the increment stays uniaxial. */
static void
servo_predict(const struct servo *sv, const struct load_row *prev, double de[3])
{
	if (isfinite(sv->A) && isfinite(sv->B))
		de[sv->u] = de[sv->v] = (sv->target - lateral_mean(sv, prev->sig) - sv->A * de[sv->axis]) / sv->B;
}

/* The servo learns the lateral response along its own path, not from an isotropic Hooke
 * model: a pack compacted in uniaxial strain with friction is anisotropic, and moving the
 * lateral walls out unloads its contacts, stiffer than loading (with lambda and G fitted per
 * increment the lateral stress drifted 3 % below its target in 8 increments of a 200-grain
 * pack).  The first, uniaxial increment gives A and an isotropic first guess of B,
 * 2 (lambda + G) = (d sig_axial + d sig_lat) / de_axial; each later one moves B to the
 * geometric mean of B and the secant its own lateral step needed (limited to a factor 4),
 * which damps the overshoot of a plain secant and keeps one slipping increment from throwing
 * the walls (the same pack: within 0.03 % of the target from the fourth increment; the plain
 * secant swung +-0.45 % about it). */
static void
servo_learn(struct servo *sv, const struct load_row *prev, const struct load_row *row)
{
	int a = sv->axis, u = sv->u, v = sv->v;
	double da = row->eps[a] - prev->eps[a];
	double dl = 0.5 * (row->eps[u] - prev->eps[u] + row->eps[v] - prev->eps[v]);
	double dsl = 0.5 * (row->sig[u] - prev->sig[u] + row->sig[v] - prev->sig[v]);
	double ds_a = row->sig[a] - prev->sig[a];

	if (!isfinite(sv->A) && da != 0 && dl == 0) {
		sv->A = dsl / da;
		sv->B = (ds_a + dsl) / da;
		if (!(sv->B > 0))
			sv->A = sv->B = NAN;
	} else if (isfinite(sv->B) && dl != 0) {
		double b = (dsl - sv->A * da) / dl;
		if (b > 0)
			sv->B = sqrt(sv->B * fmin(4 * sv->B, fmax(0.25 * sv->B, b)));
	}
}

/* What path_run carries from one segment to the next. */
struct walk {
	struct loader *L;
	const struct path_limits *lim;
	path_row_fn fn;
	void *ctx;
	struct load_row prev;	/* the last state reached */
};

/* 0, or 2 with msg_seterr when row's strain has passed the limit on some axis. */
static int
past_strain_limit(const struct walk *w, size_t k, const struct path_seg *sg, const struct load_row *row)
{
	int a;

	for (a = 0; a < 3; a++)
		if (fabs(row->eps[a]) > w->lim->max_strain) {
			msg_seterr("segment %zu (%s): strain %.4g along %c passed the limit %g before the target", k + 1,
			    path_kind_name(sg->kind), row->eps[a], 'x' + a, w->lim->max_strain);
			return 2;
		}
	return 0;
}

/* Segment k from w->prev to its stop; the codes of path_run. */
static int
run_segment(struct walk *w, size_t k, const struct path_seg *sg)
{
	struct servo sv;
	struct load_row row;
	long n;
	int a, r;

	if (check_start(k, sg, &w->prev))
		return -1;
	servo_start(&sv, sg, &w->prev);
	for (n = 0; !reached_stop(sg, &w->prev, n); n++) {
		double de[3];

		if (n >= w->lim->max_steps) {
			msg_seterr("segment %zu (%s): %ld increments without reaching its target (sigma_c %.6g Pa)", k + 1,
			    path_kind_name(sg->kind), n, w->prev.sigma_c);
			return 2;
		}
		for (a = 0; a < 3; a++)
			de[a] = sg->step * sg->ratio[a];
		if (sg->hold)
			servo_predict(&sv, &w->prev, de);
		if ((r = loader_step(w->L, de, &row)) < 0)
			return -1;
		if (sg->hold)
			servo_learn(&sv, &w->prev, &row);
		row.seg = (int)k + 1;
		if (w->fn && w->fn((int)k, &row, w->ctx))
			return 3;
		w->prev = row;
		if (r == 1) {
			char note[96];
			msg_seterr("segment %zu (%s), increment %ld: the minimiser hit its iteration limit (residual %.3g)%s",
			    k + 1, path_kind_name(sg->kind), row.inc, row.res_max, loader_limit_note(w->L, note, sizeof note));
			return 1;
		}
		if (past_strain_limit(w, k, sg, &row))
			return 2;
	}
	return 0;
}

int
path_run(struct loader *L, const struct load_path *path, const struct path_limits *lim, path_row_fn fn, void *ctx)
{
	struct walk w = {L, lim, fn, ctx, {0}};
	size_t k;
	int r;

	if (loader_measure(L, &w.prev))
		return -1;
	/* the first segment's stop before the first row: a test that cannot start writes nothing */
	if (path->n > 0 && check_start(0, &path->seg[0], &w.prev))
		return -1;
	if (fn && fn(-1, &w.prev, ctx))
		return 3;
	for (k = 0; k < path->n; k++)
		if ((r = run_segment(&w, k, &path->seg[k])))
			return r;
	return 0;
}
