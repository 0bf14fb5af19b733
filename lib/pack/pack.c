/* SPDX-License-Identifier: GPL-3.0-or-later */
/* pack: the data model (see pack.h). */
#include "pack/pack.h"
#include "pack/shape.h"
#include "base/msg.h"
#include "base/vec3.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

const char *const pack_wall_names[NWALLS] = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi"};

void
pack_init(struct pack *p)
{
	memset(p, 0, sizeof *p);
	p->wall_nu = 0.495;
}

void
pack_free(struct pack *p)
{
	size_t k;

	free(p->id);
	free(p->x);
	free(p->r);
	free(p->E);
	free(p->nu);
	free(p->rho);
	free(p->side);
	free(p->q);
	free(p->shape);
	free(p->phase);
	free(p->glue);
	free(p->c);
	for (k = 0; k < p->nhist; k++)
		free(p->history[k]);
	free(p->history);
	for (k = 0; k < p->nmeta; k++) {
		free(p->meta[k].key);
		free(p->meta[k].value);
	}
	free(p->meta);
	memset(p, 0, sizeof *p);
}

static int
grow(void **ptr, size_t n, size_t size)
{
	void *q = realloc(*ptr, n * size);

	if (!q && n) {
		msg_seterr("out of memory for %zu grains", n);
		return -1;
	}
	*ptr = q;
	return 0;
}

int
pack_reserve(struct pack *p, size_t n)
{
	if (n <= p->cap)
		return 0;
	if (grow((void **)&p->id, n, sizeof *p->id) || grow((void **)&p->x, 3 * n, sizeof *p->x) ||
	    grow((void **)&p->r, n, sizeof *p->r) || grow((void **)&p->E, n, sizeof *p->E) ||
	    grow((void **)&p->nu, n, sizeof *p->nu) || grow((void **)&p->rho, n, sizeof *p->rho))
		return -1;
	if (p->has_shapes && (grow((void **)&p->side, n, sizeof *p->side) || grow((void **)&p->q, 4 * n, sizeof *p->q) ||
	    grow((void **)&p->shape, n, sizeof *p->shape)))
		return -1;
	if (p->has_phase && grow((void **)&p->phase, n, sizeof *p->phase))
		return -1;
	if (p->has_glue && grow((void **)&p->glue, n, sizeof *p->glue))
		return -1;
	p->cap = n;
	return 0;
}

static const double quat_identity[4] = {1, 0, 0, 0};

int
pack_set_shapes(struct pack *p)
{
	size_t i;

	if (p->has_shapes)
		return 0;
	/* room for cap grains, as pack_reserve keeps it for the other arrays */
	if (grow((void **)&p->side, p->cap, sizeof *p->side) || grow((void **)&p->q, 4 * p->cap, sizeof *p->q) ||
	    grow((void **)&p->shape, p->cap, sizeof *p->shape))
		return -1;
	p->has_shapes = 1;
	for (i = 0; i < p->n; i++)
		pack_set_grain_shape(p, i, 0, quat_identity);
	return 0;
}

int
pack_set_phases(struct pack *p)
{
	if (p->has_phase)
		return 0;
	if (grow((void **)&p->phase, p->cap, sizeof *p->phase))
		return -1;
	p->has_phase = 1;
	if (p->n)
		memset(p->phase, PHASE_MINERAL, p->n * sizeof *p->phase);
	return 0;
}

int
pack_set_glue(struct pack *p)
{
	if (p->has_glue)
		return 0;
	if (grow((void **)&p->glue, p->cap, sizeof *p->glue))
		return -1;
	p->has_glue = 1;
	if (p->n)
		memset(p->glue, 0, p->n * sizeof *p->glue);
	return 0;
}

size_t
pack_hydrate_grains(const struct pack *p, double *volume)
{
	size_t i, n = 0;
	double v = 0;

	for (i = 0; p->has_phase && i < p->n; i++)
		if (p->phase[i] == PHASE_HYDRATE) {
			n++;
			v += shape_of(pack_grain_shape(p, i))->volume(p->r[i], p->has_shapes ? p->side[i] : 0);
		}
	if (volume)
		*volume = v;
	return n;
}

double
pack_hydrate_saturation(const struct pack *p)
{
	double vh, vpore;

	if (!pack_hydrate_grains(p, &vh))
		return 0;
	vpore = pack_box_volume(p->box) - (pack_grain_volume(p) - vh);
	return vh / vpore;
}

void
pack_set_grain_shape(struct pack *p, size_t i, double side, const double q[4])
{
	p->side[i] = side;
	memcpy(p->q + 4 * i, q, 4 * sizeof *q);
	p->shape[i] = (unsigned char)shape_kind_of_side(side);
}

void
pack_set_grain_kind(struct pack *p, size_t i, enum shape_kind kind)
{
	p->shape[i] = (unsigned char)kind;
}

enum shape_kind
pack_grain_shape(const struct pack *p, size_t i)
{
	if (p->shape)
		return (enum shape_kind)p->shape[i];
	return p->side ? shape_kind_of_side(p->side[i]) : SHAPE_SPHERE;
}

size_t
pack_first_plate(const struct pack *p)
{
	size_t i;

	if (p->has_shapes)
		for (i = 0; i < p->n; i++)
			if (pack_grain_shape(p, i) != SHAPE_SPHERE)
				return i;
	return (size_t)-1;
}

int
pack_require_spheres(const struct pack *p, const char *who)
{
	size_t i = pack_first_plate(p);

	if (i == (size_t)-1)
		return 0;
	msg_seterr("grain %ld is a spheroplate (side > 0); %s handles spheres only", p->id[i], who);
	return -1;
}

size_t
pack_add_grain(struct pack *p, long id, const double x[3], double r, double E, double nu, double rho)
{
	size_t i = p->n;

	if (i == p->cap && pack_reserve(p, p->cap ? 2 * p->cap : 64))
		return (size_t)-1;
	p->id[i] = id;
	memcpy(p->x + 3 * i, x, 3 * sizeof *x);
	p->r[i] = r;
	p->E[i] = E;
	p->nu[i] = nu;
	p->rho[i] = rho;
	if (p->has_shapes)
		pack_set_grain_shape(p, i, 0, quat_identity);
	if (p->has_phase)
		p->phase[i] = PHASE_MINERAL;
	if (p->has_glue)
		p->glue[i] = 0;
	p->n++;
	return i;
}

int
pack_add_contact(struct pack *p, const struct pack_contact *c)
{
	if (p->nc == p->ccap) {
		size_t nc = p->ccap ? 2 * p->ccap : 64;
		if (grow((void **)&p->c, nc, sizeof *p->c))
			return -1;
		p->ccap = nc;
	}
	p->c[p->nc++] = *c;
	return 0;
}

int
pack_copy(struct pack *dst, const struct pack *src)
{
	size_t n = src->n, k;

	pack_init(dst);
	dst->has_shapes = src->has_shapes;
	dst->has_phase = src->has_phase;
	dst->has_glue = src->has_glue;
	if (pack_reserve(dst, n ? n : 1))
		goto oom;
	memcpy(dst->id, src->id, n * sizeof *dst->id);
	memcpy(dst->x, src->x, 3 * n * sizeof *dst->x);
	memcpy(dst->r, src->r, n * sizeof *dst->r);
	memcpy(dst->E, src->E, n * sizeof *dst->E);
	memcpy(dst->nu, src->nu, n * sizeof *dst->nu);
	memcpy(dst->rho, src->rho, n * sizeof *dst->rho);
	if (src->has_shapes) {
		memcpy(dst->side, src->side, n * sizeof *dst->side);
		memcpy(dst->q, src->q, 4 * n * sizeof *dst->q);
		memcpy(dst->shape, src->shape, n * sizeof *dst->shape);
	}
	if (src->has_phase)
		memcpy(dst->phase, src->phase, n * sizeof *dst->phase);
	if (src->has_glue)
		memcpy(dst->glue, src->glue, n * sizeof *dst->glue);
	dst->n = n;
	memcpy(dst->box, src->box, sizeof dst->box);
	memcpy(dst->periodic, src->periodic, sizeof dst->periodic);
	memcpy(dst->refbox, src->refbox, sizeof dst->refbox);
	dst->has_refbox = src->has_refbox;
	dst->wall_E = src->wall_E, dst->wall_nu = src->wall_nu;
	dst->mu = src->mu, dst->wall_mu = src->wall_mu;
	for (k = 0; k < src->nc; k++)
		if (pack_add_contact(dst, &src->c[k]))
			goto oom;
	for (k = 0; k < src->nhist; k++)
		if (pack_add_history(dst, src->history[k]))
			goto oom;
	for (k = 0; k < src->nmeta; k++)	/* src's keys are unique */
		if (pack_append_meta(dst, src->meta[k].key, src->meta[k].value))
			goto oom;
	return 0;
oom:
	pack_free(dst);
	msg_seterr("out of memory copying a pack of %zu grains", n);
	return -1;
}

/* Room for one more of n items of size in *arr (capacity *cap), doubling: one realloc per
 * line made reading N history lines cost N reallocs, each copying the array under a
 * sanitizer (50000 lines: 280 s and 1.5 GB). */
static int
room_for_one(void **arr, size_t n, size_t *cap, size_t size)
{
	void *q;
	size_t c;

	if (n < *cap)
		return 0;
	c = *cap ? 2 * *cap : 16;
	if (c > SIZE_MAX / size || !(q = realloc(*arr, c * size)))
		return -1;
	*arr = q;
	*cap = c;
	return 0;
}

int
pack_add_history(struct pack *p, const char *line)
{
	char *s;

	if (room_for_one((void **)&p->history, p->nhist, &p->hist_cap, sizeof *p->history) || !(s = strdup(line)))
		return -1;
	p->history[p->nhist++] = s;
	return 0;
}

int
pack_append_meta(struct pack *p, const char *key, const char *value)
{
	char *k, *v;

	if (room_for_one((void **)&p->meta, p->nmeta, &p->meta_cap, sizeof *p->meta))
		return -1;
	k = strdup(key);
	v = strdup(value);
	if (!k || !v) {
		free(k);
		free(v);
		return -1;
	}
	p->meta[p->nmeta].key = k;
	p->meta[p->nmeta].value = v;
	p->nmeta++;
	return 0;
}

int
pack_set_meta(struct pack *p, const char *key, const char *value)
{
	size_t k;

	for (k = 0; k < p->nmeta; k++)
		if (strcmp(p->meta[k].key, key) == 0) {
			char *v = strdup(value);
			if (!v)
				return -1;
			free(p->meta[k].value);
			p->meta[k].value = v;
			return 0;
		}
	return pack_append_meta(p, key, value);
}

const char *
pack_get_meta(const struct pack *p, const char *key)
{
	size_t k;

	for (k = 0; k < p->nmeta; k++)
		if (strcmp(p->meta[k].key, key) == 0)
			return p->meta[k].value;
	return NULL;
}

void
pack_unset_meta(struct pack *p, const char *key)
{
	size_t k;

	for (k = 0; k < p->nmeta; k++)
		if (strcmp(p->meta[k].key, key) == 0) {
			free(p->meta[k].key);
			free(p->meta[k].value);
			memmove(p->meta + k, p->meta + k + 1, (p->nmeta - k - 1) * sizeof *p->meta);
			p->nmeta--;
			return;
		}
}

int
pack_get_meta_double(const struct pack *p, const char *key, double *v)
{
	const char *s = pack_get_meta(p, key);
	char *end;
	double x;

	if (!s)
		return -1;
	x = strtod(s, &end);
	if (end == s || *end || !isfinite(x))
		return -1;
	*v = x;
	return 0;
}

int
pack_plate_radius(const struct pack *p, enum shape_radius *conv)
{
	const char *s = pack_get_meta(p, PACK_META_PLATE_RADIUS);
	int k;

	*conv = SHAPE_R_EDGE;
	if (!s)
		return 0;
	for (k = 0; k < 2; k++)
		if (strcmp(s, shape_radius_names[k]) == 0) {
			*conv = (enum shape_radius)k;
			return 0;
		}
	msg_seterr("meta %s '%s' is neither 'edge' nor 'corner'", PACK_META_PLATE_RADIUS, s);
	return -1;
}

double
pack_box_length(const double box[6], int axis)
{
	return box[3 + axis] - box[axis];
}

double
pack_box_volume(const double box[6])
{
	return pack_box_length(box, 0) * pack_box_length(box, 1) * pack_box_length(box, 2);
}

double
pack_wall_stress(const double lo[3], const double hi[3], int a, double force)
{
	int u = (a + 1) % 3, v = (a + 2) % 3;

	return force / (2 * ((hi[u] - lo[u]) * (hi[v] - lo[v])));
}

double
pack_grain_volume(const struct pack *p)
{
	double v = 0, vp = 0;
	size_t i;

	/* the spheres summed as r^3 times 4 pi/3 at the end, as before the plates came: every
	 * sphere pack keeps its porosity to the last bit, with or without shape columns */
	for (i = 0; i < p->n; i++)
		if (pack_grain_shape(p, i) != SHAPE_SPHERE)
			vp += shape_of(pack_grain_shape(p, i))->volume(p->r[i], p->side[i]);
		else
			v += p->r[i] * p->r[i] * p->r[i];
	return v * 4.0 / 3.0 * 3.14159265358979323846 + vp;
}

size_t
pack_find_id(const struct pack *p, long id, size_t *sorted)
{
	size_t lo = 0, hi = p->n;

	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		if (p->id[sorted[mid]] < id)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < p->n && p->id[sorted[lo]] == id ? sorted[lo] : (size_t)-1;
}

static int
cmp_key(const void *a, const void *b)
{
	const long *x = a, *y = b;

	if (x[0] != y[0])
		return x[0] < y[0] ? -1 : 1;
	if (x[1] != y[1])
		return x[1] < y[1] ? -1 : 1;
	return x[2] < y[2] ? -1 : x[2] > y[2];
}

long *
pack_history_keys(const struct pack *p)
{
	long *t = malloc((p->nc ? p->nc : 1) * 3 * sizeof *t);
	size_t k;

	if (!t) {
		msg_seterr("out of memory");
		return NULL;
	}
	for (k = 0; k < p->nc; k++) {
		long a = (long)p->c[k].i, b = p->c[k].j;
		/* walls sort after grains and never swap with a grain */
		if (b >= 0 && b < a) {
			long s = a;
			a = b;
			b = s;
		}
		t[3 * k] = a;
		t[3 * k + 1] = b;
		t[3 * k + 2] = (long)k;
	}
	if (p->nc > 1)
		qsort(t, p->nc, 3 * sizeof *t, cmp_key);
	return t;
}

long
pack_history_lookup(const long *keys, size_t n, size_t i, long j)
{
	size_t lo = 0, hi = n;
	long key[3] = {(long)i, j, -1};

	while (lo < hi) {
		size_t mid = (lo + hi) / 2;
		if (cmp_key(keys + 3 * mid, key) < 0)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < n && keys[3 * lo] == key[0] && keys[3 * lo + 1] == key[1] ? keys[3 * lo + 2] : -1;
}

void
pack_wrap_centres(double *x, size_t n, const double lo[3], const double hi[3], const int periodic[3])
{
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		double L = hi[a] - lo[a];
		if (!periodic[a])
			continue;
		for (i = 0; i < n; i++) {
			double *y = x + 3 * i + a;
			*y -= L * floor((*y - lo[a]) / L);
			if (*y >= hi[a])	/* rounding of floor at the upper face */
				*y = lo[a];
		}
	}
}

void
pack_checksum(const struct pack *p, char *buf, size_t len)
{
	uLong crc = crc32(0L, Z_NULL, 0);

	crc = crc32(crc, (const Bytef *)p->id, (uInt)(p->n * sizeof *p->id));
	crc = crc32(crc, (const Bytef *)p->x, (uInt)(3 * p->n * sizeof *p->x));
	crc = crc32(crc, (const Bytef *)p->r, (uInt)(p->n * sizeof *p->r));
	if (p->side)
		crc = crc32(crc, (const Bytef *)p->side, (uInt)(p->n * sizeof *p->side));
	if (p->q)
		crc = crc32(crc, (const Bytef *)p->q, (uInt)(4 * p->n * sizeof *p->q));
	snprintf(buf, len, "grains %zu crc32 %08lx", p->n, (unsigned long)crc);
}
