/* loadpath: parsing and walking loading paths (see loadpath.h). */
#include "qs/loadpath.h"
#include "base/msg.h"

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

static int
parse_axis(const char *s, int *axis)
{
	if (s[0] >= 'x' && s[0] <= 'z' && !s[1]) {
		*axis = s[0] - 'x';
		return 0;
	}
	return -1;
}

/* One segment from its words (modified in place). */
static int
parse_seg(char *text, int k, const struct path_defaults *def, struct path_seg *sg)
{
	char *w, *save = NULL;
	int first = 1, a, have_ratio = 0;
	double lateral = 0;

	memset(sg, 0, sizeof *sg);
	sg->axis = def->axis;
	sg->step = def->step;
	sg->steps = 0;
	sg->to_stress = sg->to_strain = NAN;
	for (w = strtok_r(text, " \t\n", &save); w; w = strtok_r(NULL, " \t\n", &save)) {
		char *eq = strchr(w, '=');
		const char *key = w, *val = eq ? eq + 1 : NULL;
		double v;

		if (first) {
			first = 0;
			if (strcmp(w, "uniaxial") == 0)
				sg->kind = PATH_UNIAXIAL;
			else if (strcmp(w, "isotropic") == 0)
				sg->kind = PATH_ISOTROPIC;
			else if (strcmp(w, "triaxial") == 0)
				sg->kind = PATH_TRIAXIAL;
			else if (strcmp(w, "polyaxial") == 0)
				sg->kind = PATH_POLYAXIAL;
			else {
				msg_seterr("segment %d: unknown path '%s' (uniaxial, isotropic, triaxial, polyaxial)", k, w);
				return -1;
			}
			continue;
		}
		if (eq)
			*eq = '\0';
		if (strcmp(key, "hold") == 0 && !val) {
			if (sg->kind != PATH_TRIAXIAL) {
				msg_seterr("segment %d: hold belongs to a triaxial segment", k);
				return -1;
			}
			sg->hold = 2;
			continue;
		}
		if (!val || !*val) {
			msg_seterr("segment %d: '%s' needs a value (key=value)", k, key);
			return -1;
		}
		if (strcmp(key, "axis") == 0) {
			if (parse_axis(val, &sg->axis))
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
			if (parse_num(val, &lateral) || fabs(lateral) > 10)
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
			have_ratio = 1;
		} else {
			msg_seterr("segment %d: '%s' is not a setting of a %s path", k, key, path_kind_name(sg->kind));
			return -1;
		}
		continue;
bad:
		msg_seterr("segment %d: bad value in '%s=%s'", k, key, val);
		return -1;
	}
	if (first) {
		msg_seterr("segment %d is empty", k);
		return -1;
	}
	if (isnan(sg->step) || sg->step == 0) {
		msg_seterr("segment %d: no strain step (step=D or --strain-step)", k);
		return -1;
	}
	switch (sg->kind) {
	case PATH_UNIAXIAL:
		sg->ratio[sg->axis] = 1;
		break;
	case PATH_ISOTROPIC:
		sg->ratio[0] = sg->ratio[1] = sg->ratio[2] = 1;
		break;
	case PATH_TRIAXIAL:
		if (sg->hold && lateral != 0) {
			msg_seterr("segment %d: lateral= and hold are exclusive", k);
			return -1;
		}
		for (a = 0; a < 3; a++)
			sg->ratio[a] = a == sg->axis ? 1 : lateral;
		break;
	case PATH_POLYAXIAL: {
		double big = 0;
		if (!have_ratio) {
			msg_seterr("segment %d: a polyaxial path needs ratio=A:B:C", k);
			return -1;
		}
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
		/* the largest ratio is the step's unit */
		for (a = 0; a < 3; a++)
			sg->ratio[a] /= big;
		break;
badratio:
		msg_seterr("segment %d: ratio must be three finite numbers, not all zero", k);
		return -1;
	}
	}
	if (sg->steps == 0 && isnan(sg->to_stress) && isnan(sg->to_strain)) {
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
	}
	return 0;
}

int
path_parse(const char *spec, const struct path_defaults *def, struct load_path *path)
{
	char *copy = strdup(spec), *seg, *save = NULL;
	int k = 0;

	if (!copy) {
		msg_seterr("out of memory");
		return -1;
	}
	path->n = 0;
	for (seg = strtok_r(copy, ";", &save); seg; seg = strtok_r(NULL, ";", &save)) {
		k++;
		if (path->n == sizeof path->seg / sizeof path->seg[0]) {
			msg_seterr("more than %zu segments", path->n);
			free(copy);
			return -1;
		}
		if (parse_seg(seg, k, def, &path->seg[path->n])) {
			free(copy);
			return -1;
		}
		path->n++;
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
path_run(struct loader *L, const struct load_path *path, const struct path_limits *lim, path_row_fn fn, void *ctx)
{
	struct load_row prev, row;
	size_t k;
	int a;

	if (loader_measure(L, &prev))
		return -1;
	if (fn && fn(-1, &prev, ctx))
		return 3;
	for (k = 0; k < path->n; k++) {
		const struct path_seg *sg = &path->seg[k];
		double dir = sg->step > 0 ? 1 : -1, target_lat = 0;
		int u = (sg->axis + 1) % 3, v = (sg->axis + 2) % 3;
		/* the servo's model of this segment's lateral stress: d sig_lat = A de_axial + B de_lat */
		double A = NAN, B = NAN;
		long n;

		if (sg->hold)
			target_lat = sg->hold == 1 ? sg->hold_stress : 0.5 * (prev.sig[u] + prev.sig[v]);
		for (n = 0;; n++) {
			double de[3];
			int r;

			if (sg->steps > 0 && n >= sg->steps)
				break;
			if (!isnan(sg->to_stress) && (prev.sigma_c - sg->to_stress) * dir >= 0)
				break;
			if (!isnan(sg->to_strain) && (control_strain(sg, prev.eps) - sg->to_strain) * dir >= 0)
				break;
			if (n >= lim->max_steps) {
				msg_seterr("segment %zu (%s): %ld increments without reaching its target (sigma_c %.6g Pa)", k + 1,
				    path_kind_name(sg->kind), n, prev.sigma_c);
				return 2;
			}
			for (a = 0; a < 3; a++)
				de[a] = sg->step * sg->ratio[a];
			if (sg->hold && isfinite(A) && isfinite(B))
				de[u] = de[v] = (target_lat - 0.5 * (prev.sig[u] + prev.sig[v]) - A * de[sg->axis]) / B;
			r = loader_step(L, de, &row);
			if (r < 0)
				return -1;
			if (sg->hold) {
				/* The servo learns the lateral response along its own path, not from an
				 * isotropic Hooke model: a pack compacted in uniaxial strain with friction is
				 * anisotropic, and moving the lateral walls out unloads its contacts, stiffer
				 * than loading (with lambda and G fitted per increment the lateral stress
				 * drifted 3 % below its target in 8 increments of a 200-grain pack).  The
				 * first, uniaxial increment gives A and an isotropic first guess of B,
				 * 2 (lambda + G) = (d sig_axial + d sig_lat) / de_axial; each later one moves
				 * B to the geometric mean of B and the secant its own lateral step needed
				 * (limited to a factor 4), which damps the overshoot of a plain secant and
				 * keeps one slipping increment from throwing the walls (the same pack: within
				 * 0.03 % of the target from the fourth increment; the plain secant swung
				 * +-0.45 % about it). */
				double da = row.eps[sg->axis] - prev.eps[sg->axis];
				double dl = 0.5 * (row.eps[u] - prev.eps[u] + row.eps[v] - prev.eps[v]);
				double dsl = 0.5 * (row.sig[u] - prev.sig[u] + row.sig[v] - prev.sig[v]);
				double ds_a = row.sig[sg->axis] - prev.sig[sg->axis];

				if (!isfinite(A) && da != 0 && dl == 0) {
					A = dsl / da;
					B = (ds_a + dsl) / da;
					if (!(B > 0))
						A = B = NAN;
				} else if (isfinite(B) && dl != 0) {
					double b = (dsl - A * da) / dl;
					if (b > 0)
						B = sqrt(B * fmin(4 * B, fmax(0.25 * B, b)));
				}
			}
			row.seg = (int)k + 1;
			if (fn && fn((int)k, &row, ctx))
				return 3;
			prev = row;
			if (r == 1) {
				msg_seterr("segment %zu (%s), increment %ld: the minimiser hit its iteration limit (residual %.3g)",
				    k + 1, path_kind_name(sg->kind), row.inc, row.res_max);
				return 1;
			}
			for (a = 0; a < 3; a++)
				if (fabs(row.eps[a]) > lim->max_strain) {
					msg_seterr("segment %zu (%s): strain %.4g along %c passed the limit %g before the target",
					    k + 1, path_kind_name(sg->kind), row.eps[a], 'x' + a, lim->max_strain);
					return 2;
				}
		}
	}
	return 0;
}
