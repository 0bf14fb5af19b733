/* SPDX-License-Identifier: GPL-3.0-or-later */
/* packio: the strict pack reader and the round-trip-exact writer (see packio.h). */
#include "pack/packio.h"
#include "base/fileio.h"
#include "base/lines.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "base/quat.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

/* Fields kept of a split line: more than any line of the format has. */
#define MAXTOK 20

struct pack_reader {
	struct lines *in;
	int failed;
};

struct pack_reader *
pack_reader_open(FILE *fp, const char *name)
{
	struct pack_reader *rd = calloc(1, sizeof *rd);

	if (!rd) {
		msg_seterr("out of memory");
		return NULL;
	}
	if (!(rd->in = lines_open(fp, name))) {
		free(rd);
		return NULL;
	}
	return rd;
}

void
pack_reader_close(struct pack_reader *rd)
{
	if (!rd)
		return;
	lines_close(rd->in);
	free(rd);
}

const char *
pack_reader_name(const struct pack_reader *rd)
{
	return lines_name(rd->in);
}

static int
rd_verror(struct pack_reader *rd, long line, const char *fmt, va_list ap)
{
	char what[1024];

	vsnprintf(what, sizeof what, fmt, ap);
	lines_error_at(rd->in, line, "%s", what);
	rd->failed = 1;
	return -1;
}

/* "name:line: what" in the slot, at the line just read; the reader is done. */
static int __attribute__((format(printf, 2, 3)))
rd_error(struct pack_reader *rd, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	rd_verror(rd, lines_lineno(rd->in), fmt, ap);
	va_end(ap);
	return -1;
}

/* The same at another line: the one after the last (an early end), or an earlier one. */
static int __attribute__((format(printf, 3, 4)))
rd_error_at(struct pack_reader *rd, long line, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	rd_verror(rd, line, fmt, ap);
	va_end(ap);
	return -1;
}

/* 1: a line in *s; 0: end of input; -1: error (in the slot). */
static int
next_line(struct pack_reader *rd, char **s)
{
	int r = lines_next(rd->in, s, NULL);

	if (r < 0)
		rd->failed = 1;
	/* The line reader drops one \r before the \n; any other would be kept in a history or
	 * meta text and written back before the \n, where the next read drops it: refused, so
	 * that what is read is what is written back. */
	/* A plain pack cut inside its last field would still parse (2420 cut to 24): the
	 * writer ends every line with \n, so a last line without one is a truncated file. */
	if (r == 1 && !lines_newline(rd->in))
		return rd_error(rd, "truncated: the last line has no newline");
	if (r == 1 && strchr(*s, '\r'))
		return rd_error(rd, "a carriage return (\\r) inside a line (only one, just before the newline, is allowed)");
	return r;
}

static long
line_after_last(const struct pack_reader *rd)
{
	return lines_lineno(rd->in) + 1;
}

/* Fields are separated by spaces and tabs. */
static int
split(char *s, char **tok, int max)
{
	return lines_split(s, " \t", tok, max);
}

static int
parse_numbers(struct pack_reader *rd, char **tok, int n, double *v, const char *what)
{
	int k;

	for (k = 0; k < n; k++)
		if (num_parse(tok[k], &v[k]))
			return rd_error(rd, "%s: '%s' is not a finite number", what, tok[k]);
	return 0;
}

static int
check_box(struct pack_reader *rd, const double b[6], const char *what)
{
	int a;

	for (a = 0; a < 3; a++)
		if (!(b[a + 3] > b[a]))
			return rd_error(rd, "%s: upper bound %g not above lower bound %g on axis %c",
			    what, b[a + 3], b[a], 'x' + a);
	for (a = 0; a < 6; a++)
		if (!(fabs(b[a]) <= PACK_BOX_MAX))
			return rd_error(rd, "%s: bound %g m is outside [-%g, %g] m (a pack of grains, in metres)", what, b[a],
			    PACK_BOX_MAX, PACK_BOX_MAX);
	return 0;
}

static const char *
check_grain_values(const struct pack *p, size_t i, char *why, size_t len)
{
	const double *x = p->x + 3 * i;
	int a;

	if (p->id[i] < 0)
		snprintf(why, len, "grain id %ld is negative", p->id[i]);
	else if (!(p->r[i] > 0))
		snprintf(why, len, "grain %ld: radius %g is not positive", p->id[i], p->r[i]);
	else if (!(p->E[i] > 0))
		snprintf(why, len, "grain %ld: Young's modulus %g is not positive", p->id[i], p->E[i]);
	else if (!(p->E[i] >= PACK_E_MIN && p->E[i] <= PACK_E_MAX))
		snprintf(why, len, "grain %ld: Young's modulus %g Pa is outside [%g, %g] Pa", p->id[i], p->E[i], PACK_E_MIN,
		    PACK_E_MAX);
	else if (!(p->nu[i] > -1 && p->nu[i] < 0.5))
		snprintf(why, len, "grain %ld: Poisson ratio %g is outside (-1, 0.5)", p->id[i], p->nu[i]);
	else if (!(p->rho[i] > 0))
		snprintf(why, len, "grain %ld: density %g is not positive", p->id[i], p->rho[i]);
	else if (p->has_shapes && !(isfinite(p->side[i]) && p->side[i] >= 0))
		snprintf(why, len, "grain %ld: side %g is %s", p->id[i], p->side[i],
		    isfinite(p->side[i]) ? "negative" : "not finite");
	else if (p->has_shapes && p->shape[i] >= SHAPE_NKINDS)
		snprintf(why, len, "grain %ld: shape %d is no kind of the table", p->id[i], p->shape[i]);
	else if (p->has_shapes && !shape_of(pack_grain_shape(p, i))->side_ok(p->side[i]))
		snprintf(why, len, "grain %ld: a %s cannot have side %g (a sphere has side 0, a spheroplate side > 0)",
		    p->id[i], shape_of(pack_grain_shape(p, i))->name, p->side[i]);
	else if (p->has_phase && p->phase[i] >= PACK_NPHASES)
		snprintf(why, len, "grain %ld: phase %d is neither 0 (mineral) nor 1 (hydrate)", p->id[i], p->phase[i]);
	else if (p->has_glue && p->glue[i] > NWALLS)
		snprintf(why, len, "grain %ld: glued to wall %d, not one of the six", p->id[i], p->glue[i] - 1);
	else if (p->has_glue && p->glue[i] && p->periodic[(p->glue[i] - 1) / 2])
		snprintf(why, len, "grain %ld: glued to %s, but that axis is periodic", p->id[i], pack_wall_names[p->glue[i] - 1]);
	else if (p->has_shapes && !(fabs(quat_norm(p->q + 4 * i) - 1) <= PACK_QUAT_TOL))
		/* not renormalised: what is read is what is written back (pack-format.md) */
		snprintf(why, len, "grain %ld: (qw, qx, qy, qz) = (%.9g, %.9g, %.9g, %.9g) is not a unit quaternion (norm %.9g, off 1 by more than %g)",
		    p->id[i], p->q[4 * i], p->q[4 * i + 1], p->q[4 * i + 2], p->q[4 * i + 3], quat_norm(p->q + 4 * i),
		    PACK_QUAT_TOL);
	else {
		for (a = 0; a < 3; a++)
			if (x[a] < p->box[a] || x[a] > p->box[a + 3]) {
				snprintf(why, len, "grain %ld: centre %c = %g is outside the box [%g, %g]",
				    p->id[i], 'x' + a, x[a], p->box[a], p->box[a + 3]);
				return why;
			}
		/* no grain larger than the box: its radius at most the box length along each axis,
		 * so that it presses into the two walls of an axis by at most R together (a grain
		 * pressed between them has 2 r a little above the length) */
		for (a = 0; a < 3; a++)
			if (p->r[i] > p->box[a + 3] - p->box[a]) {
				snprintf(why, len, "grain %ld: radius %g m is larger than the box along %c (%g m): the radius must be at most the box length",
				    p->id[i], p->r[i], 'x' + a, p->box[a + 3] - p->box[a]);
				return why;
			}
		/* a plate by its bounding radius (a side of 1 m in a box of a millimetre read as
		 * a porosity of -1.8e12) */
		if (pack_grain_shape(p, i) != SHAPE_SPHERE) {
			double rb = shape_of(pack_grain_shape(p, i))->bounding_radius(p->r[i], p->side[i]);

			for (a = 0; a < 3; a++)
				if (!(rb <= p->box[a + 3] - p->box[a])) {
					snprintf(why, len, "grain %ld: bounding radius %g m (side %g m) is larger than the box along %c (%g m): it must be at most the box length",
					    p->id[i], rb, p->side[i], 'x' + a, p->box[a + 3] - p->box[a]);
					return why;
				}
		}
		return NULL;
	}
	return why;
}

static const long *sort_ids_id;

static int
cmp_by_id(const void *a, const void *b)
{
	long x = sort_ids_id[*(const size_t *)a], y = sort_ids_id[*(const size_t *)b];

	return x < y ? -1 : x > y;
}

/* Index sorted by id; returns NULL when out of memory.  *dup gets the later index of the
 * first duplicate id found (or (size_t)-1). */
static size_t *
sort_by_id(const struct pack *p, size_t *dup)
{
	size_t *s = malloc((p->n ? p->n : 1) * sizeof *s), k;

	*dup = (size_t)-1;
	if (!s)
		return NULL;
	for (k = 0; k < p->n; k++)
		s[k] = k;
	sort_ids_id = p->id;
	qsort(s, p->n, sizeof *s, cmp_by_id);
	for (k = 1; k < p->n; k++)
		if (p->id[s[k]] == p->id[s[k - 1]]) {
			size_t a = s[k], b = s[k - 1];
			size_t later = a > b ? a : b;
			if (*dup == (size_t)-1 || later < *dup)
				*dup = later;
		}
	return s;
}

static size_t
find_duplicate_contact(const struct pack *p)
{
	long *t = pack_history_keys(p);
	size_t k, found = (size_t)-1;

	if (!t)
		return (size_t)-1;
	for (k = 1; k < p->nc; k++)
		if (t[3 * k] == t[3 * k - 3] && t[3 * k + 1] == t[3 * k - 2]) {
			size_t later = (size_t)(t[3 * k + 2] > t[3 * k - 1] ? t[3 * k + 2] : t[3 * k - 1]);
			if (found == (size_t)-1 || later < found)
				found = later;
		}
	free(t);
	return found;
}

static const double *sort_centre_x;

static int
cmp_by_centre(const void *a, const void *b)
{
	size_t i = *(const size_t *)a, j = *(const size_t *)b;
	const double *u = sort_centre_x + 3 * i, *v = sort_centre_x + 3 * j;
	int k;

	for (k = 0; k < 3; k++)
		if (u[k] != v[k])
			return u[k] < v[k] ? -1 : 1;
	return i < j ? -1 : i > j;
}

/* Two grains at the same centre have no direction between them: the contact code sees no
 * overlap and no contact (packinfo said overlap_max 0).  0 when every centre is distinct;
 * -1 when two are equal, with *first and *later the two earliest such grains (by the
 * later one's index); -2 when out of memory. */
static int
find_same_centre(const struct pack *p, size_t *first, size_t *later)
{
	size_t *s = malloc((p->n ? p->n : 1) * sizeof *s), k, g = 0;
	int found = 0;

	if (!s)
		return -2;
	for (k = 0; k < p->n; k++)
		s[k] = k;
	sort_centre_x = p->x;
	qsort(s, p->n, sizeof *s, cmp_by_centre);
	for (k = 1; k < p->n; k++) {
		if (p->x[3 * s[k]] == p->x[3 * s[g]] && p->x[3 * s[k] + 1] == p->x[3 * s[g] + 1] &&
		    p->x[3 * s[k] + 2] == p->x[3 * s[g] + 2]) {
			/* s[g] is the earliest of its group, s[g + 1] the next */
			if (k == g + 1 && (!found || s[k] < *later)) {
				*first = s[g];
				*later = s[k];
				found = 1;
			}
		} else {
			g = k;
		}
	}
	free(s);
	return found ? -1 : 0;
}

/* ---- the grain columns ---- */

/* The grain columns a pack may have, in the order writers put them.  The required ones
 * (group 0) are in every pack, first on each grain line and in this order, so that a script
 * reading a column by its position reads it from every pack; a version-1 pack has exactly
 * these and no columns line.  An optional group comes all or none, its columns together and
 * in this order, after the required ones: so a pack is spheres or shapes as a whole, and a
 * reader never meets a side without its orientation.  The kind column 'shape' (a name of
 * pack/shape.h's table) goes with the shape columns, just before them: every writer puts it
 * there, and a pack of shape columns without it (as written before it was) reads with each
 * grain's kind from its side (shape_kind_of_side).  A later group (a phase tag) is more
 * rows with a new group number, a name in groups[], the storage of its values in struct
 * pack, their parsing in read_grain_line and writing in format_pack, and a test in
 * pack_format_version that the pack has it. */
static const struct column {
	const char *name;
	int group;
} columns[] = {
	{"id", 0}, {"x", 0}, {"y", 0}, {"z", 0}, {"r", 0}, {"E", 0}, {"nu", 0}, {"rho", 0},
	{"shape", 1},
	{"side", 2}, {"qw", 2}, {"qx", 2}, {"qy", 2}, {"qz", 2},
	{"phase", 3},
	{"glued", 4},
};
#define NCOLUMNS ((int)(sizeof columns / sizeof columns[0]))
enum {
	COL_KIND = 8, COL_SIDE = 9, COL_PHASE = 14, COL_GLUED = 15,
	GROUP_KIND = 1, GROUP_SHAPE = 2, GROUP_PHASE = 3, GROUP_GLUED = 4, NGROUPS = 5
};
static const char *const groups[NGROUPS] = {"required", "kind", "shape", "phase", "glued"};

/* A columns line naming every known column once, and one more name, fits in tok[]: so the
 * unknown or repeated name of a longer line is among the fields kept. */
_Static_assert(MAXTOK >= NCOLUMNS + 2, "MAXTOK too small for the columns line");

static int
column_index(const char *name)
{
	int k;

	for (k = 0; k < NCOLUMNS; k++)
		if (strcmp(name, columns[k].name) == 0)
			return k;
	return -1;
}

/* The names of group g, "side qw qx qy qz", for messages and the columns line. */
static void
group_names(int g, char *buf, size_t len)
{
	int k;

	buf[0] = 0;
	for (k = 0; k < NCOLUMNS; k++)
		if (columns[k].group == g)
			snprintf(buf + strlen(buf), len - strlen(buf), "%s%s", buf[0] ? " " : "", columns[k].name);
}

static int
group_size(int g)
{
	int k, n = 0;

	for (k = 0; k < NCOLUMNS; k++)
		n += columns[k].group == g;
	return n;
}

/* ---- the header ---- */

/* The header being read: the version, what it declares, which keywords it has had, and
 * the grain columns. */
struct header {
	struct pack_reader *rd;
	struct pack *p;
	long version;
	long ngr, nco;
	unsigned seen;	/* bit k: keywords[k] has been read */
	int ncol;	/* fields of a grain line */
	int kinds;	/* whether a grain line has the kind column 'shape' */
	int col[MAXTOK];	/* the columns[] index of each field of a grain line */
	char colnames[256];	/* the names, "id x y z r E nu rho", for messages */
	/* The meta keys read so far, by hash: slot k holds 1 + the index of a meta line, 0 when
	 * empty; nslot a power of two, at least twice the keys.  A duplicate key is found in
	 * constant time, so a header of N meta lines reads in time linear in N (a look through
	 * the keys before each took 10 s for 40000 lines and over 2 minutes for 160000). */
	size_t *slot, nslot;
};

static size_t
key_hash(const char *k)
{
	size_t h = 14695981039346656037u;	/* FNV-1a */

	for (; *k; k++)
		h = (h ^ (unsigned char)*k) * 1099511628211u;
	return h;
}

/* The slot of key: the one holding it, or the empty one where it would go. */
static size_t
key_slot(const struct header *h, const char *key)
{
	size_t k = key_hash(key) & (h->nslot - 1);

	while (h->slot[k] && strcmp(h->p->meta[h->slot[k] - 1].key, key) != 0)
		k = (k + 1) & (h->nslot - 1);
	return k;
}

/* Room in the hash for one more key: 0, or -1 when out of memory. */
static int
keys_room(struct header *h)
{
	size_t *old = h->slot, nold = h->nslot, k, n = h->nslot ? 2 * h->nslot : 64;

	if (2 * (h->p->nmeta + 1) <= h->nslot)
		return 0;
	if (!(h->slot = calloc(n, sizeof *h->slot))) {
		h->slot = old;
		return -1;
	}
	h->nslot = n;
	for (k = 0; k < nold; k++)
		if (old[k])
			h->slot[key_slot(h, h->p->meta[old[k] - 1].key)] = old[k];
	free(old);
	return 0;
}

/* Until a columns line says otherwise: the required columns (a version-1 pack). */
static void
standard_columns(struct header *h)
{
	int k;

	h->ncol = 0;
	h->colnames[0] = 0;
	for (k = 0; k < NCOLUMNS; k++)
		if (columns[k].group == 0) {
			h->col[h->ncol++] = k;
			snprintf(h->colnames + strlen(h->colnames), sizeof h->colnames - strlen(h->colnames),
			    "%s%s", h->colnames[0] ? " " : "", columns[k].name);
		}
}

static int
kw_units(struct header *h, char **tok, int n)
{
	if (n != 2 || strcmp(tok[1], "SI") != 0)
		return rd_error(h->rd, "units: only 'units SI' is defined");
	return 0;
}

static int
kw_box(struct header *h, char **tok, int n)
{
	int ref = strcmp(tok[0], "refbox") == 0;
	double v[6];

	if (n != 7)
		return rd_error(h->rd, "%s: expected 6 numbers (xlo ylo zlo xhi yhi zhi), found %d", tok[0],
		    n - 1);
	if (parse_numbers(h->rd, tok + 1, 6, v, tok[0]) || check_box(h->rd, v, tok[0]))
		return -1;
	memcpy(ref ? h->p->refbox : h->p->box, v, sizeof v);
	if (ref)
		h->p->has_refbox = 1;
	return 0;
}

static int
kw_walls(struct header *h, char **tok, int n)
{
	double v[3];

	if (n != 4)
		return rd_error(h->rd, "walls: expected 3 numbers (E nu mu), found %d", n - 1);
	if (parse_numbers(h->rd, tok + 1, 3, v, "walls"))
		return -1;
	if (!(v[0] > 0))
		return rd_error(h->rd, "walls: Young's modulus %g is not positive", v[0]);
	if (!(v[0] >= PACK_E_MIN && v[0] <= PACK_WALL_E_MAX))
		return rd_error(h->rd, "walls: Young's modulus %g Pa is outside [%g, %g] Pa", v[0], PACK_E_MIN, PACK_WALL_E_MAX);
	if (!(v[1] > -1 && v[1] < 0.5))
		return rd_error(h->rd, "walls: Poisson ratio %g is outside (-1, 0.5)", v[1]);
	if (!(v[2] >= 0))
		return rd_error(h->rd, "walls: friction coefficient %g is negative", v[2]);
	if (!(v[2] <= PACK_MU_MAX))
		return rd_error(h->rd, "walls: friction coefficient %g is outside [0, %g] (the range of the tools' --mu)", v[2],
		    PACK_MU_MAX);
	h->p->wall_E = v[0];
	h->p->wall_nu = v[1];
	h->p->wall_mu = v[2];
	return 0;
}

static int
kw_friction(struct header *h, char **tok, int n)
{
	double mu;

	if (n != 2)
		return rd_error(h->rd, "friction: expected 1 number (mu), found %d", n - 1);
	if (parse_numbers(h->rd, tok + 1, 1, &mu, "friction"))
		return -1;
	if (!(mu >= 0))
		return rd_error(h->rd, "friction: coefficient %g is negative", mu);
	if (!(mu <= PACK_MU_MAX))
		return rd_error(h->rd, "friction: coefficient %g is outside [0, %g] (the range of the tools' --mu)", mu,
		    PACK_MU_MAX);
	h->p->mu = mu;
	return 0;
}

/* grains N (N >= 1) and contacts M (M >= 0) */
static int
kw_count(struct header *h, char **tok, int n)
{
	int grains = strcmp(tok[0], "grains") == 0;
	long cnt;

	if (n != 2)
		return rd_error(h->rd, "%s: expected 1 count, found %d", tok[0], n - 1);
	if (num_parse_long(tok[1], &cnt) || cnt < (grains ? 1 : 0) || cnt > 1000000000L)
		return rd_error(h->rd, "%s: '%s' is not a valid count", tok[0], tok[1]);
	*(grains ? &h->ngr : &h->nco) = cnt;
	return 0;
}

/* "columns NAME ...": known names, each once, the required ones first and in order, then
 * each optional group whole, its names together and in order. */
static int
kw_columns(struct header *h, char **tok, int n)
{
	unsigned named = 0;
	int k, c, g, last, have[NGROUPS] = {0};
	char names[128];

	if (n < 2)
		return rd_error(h->rd, "columns: expected the names of the grain columns (%s ...)", h->colnames);
	for (k = 1; k < n; k++) {
		if ((c = column_index(tok[k])) < 0)
			return rd_error(h->rd, "columns: unknown column '%s'", tok[k]);
		if (named & 1u << c)
			return rd_error(h->rd, "columns: column '%s' named twice", tok[k]);
		named |= 1u << c;
		have[columns[c].group]++;
	}
	for (c = 0; c < NCOLUMNS; c++)
		if (columns[c].group == 0 && !(named & 1u << c))
			return rd_error(h->rd, "columns: the required column '%s' is missing", columns[c].name);
	for (c = 0, k = 1; c < NCOLUMNS; c++) {
		if (columns[c].group != 0)
			continue;
		if (strcmp(tok[k], columns[c].name) != 0)
			return rd_error(h->rd, "columns: column %d must be '%s' (the required columns come first, in the order %s)",
			    k, columns[c].name, h->colnames);
		k++;
	}
	for (g = 1; g < NGROUPS; g++)
		if (have[g] && have[g] < group_size(g)) {
			for (c = 0; c < NCOLUMNS && (columns[c].group != g || named & 1u << c); c++)
				;
			group_names(g, names, sizeof names);
			return rd_error(h->rd, "columns: only some of the %s columns (%s): they come all %d or none; '%s' is missing",
			    groups[g], names, group_size(g), columns[c].name);
		}
	/* after the required columns, each group from its first column on, in order, and the
	 * groups in their order (shape before phase), as writers put them */
	for (last = 0; k < n; last = g) {
		g = columns[column_index(tok[k])].group;
		if (g < last)
			return rd_error(h->rd, "columns: column %d '%s': the %s columns come before the %s columns",
			    k, tok[k], groups[g], groups[last]);
		group_names(g, names, sizeof names);
		for (c = 0; c < NCOLUMNS; c++) {
			if (columns[c].group != g)
				continue;
			if (k >= n || strcmp(tok[k], columns[c].name) != 0)
				return rd_error(h->rd, "columns: column %d must be '%s' (the %s columns come together, in the order %s)",
				    k, columns[c].name, groups[g], names);
			k++;
		}
	}
	h->colnames[0] = 0;
	for (k = 1; k < n; k++) {
		snprintf(h->colnames + strlen(h->colnames), sizeof h->colnames - strlen(h->colnames), "%s%s",
		    k > 1 ? " " : "", tok[k]);
		h->col[k - 1] = column_index(tok[k]);
	}
	h->ncol = n - 1;
	h->kinds = have[GROUP_KIND] != 0;
	if (have[GROUP_KIND] && !have[GROUP_SHAPE])
		return rd_error(h->rd, "columns: 'shape' (the grains' kinds) needs the shape columns (side qw qx qy qz)");
	if ((have[GROUP_SHAPE] && pack_set_shapes(h->p)) || (have[GROUP_PHASE] && pack_set_phases(h->p)) ||
	    (have[GROUP_GLUED] && pack_set_glue(h->p)))
		return rd_error(h->rd, "out of memory");
	return 0;
}

/* "boundary X Y Z": along each axis, "walls" (two rigid walls, the box faces) or
 * "periodic" (the box length is the period; no walls). */
static int
kw_boundary(struct header *h, char **tok, int n)
{
	int a;

	if (n != 4)
		return rd_error(h->rd, "boundary: expected 3 words (x y z, each 'walls' or 'periodic'), found %d",
		    n - 1);
	for (a = 0; a < 3; a++) {
		if (strcmp(tok[1 + a], "walls") == 0)
			h->p->periodic[a] = 0;
		else if (strcmp(tok[1 + a], "periodic") == 0)
			h->p->periodic[a] = 1;
		else
			return rd_error(h->rd, "boundary: '%s' for axis %c is neither 'walls' nor 'periodic'",
			    tok[1 + a], 'x' + a);
	}
	return 0;
}

/* The header keywords other than history, meta and end, each allowed once: from format
 * version since on, and then required or not. */
static const struct keyword {
	const char *name;
	int since, required;
	int (*parse)(struct header *h, char **tok, int n);
} keywords[] = {
	{"units", 1, 1, kw_units},
	{"box", 1, 1, kw_box},
	{"refbox", 1, 0, kw_box},
	{"walls", 1, 1, kw_walls},
	{"friction", 1, 1, kw_friction},
	{"grains", 1, 1, kw_count},
	{"contacts", 1, 1, kw_count},
	{"columns", 2, 1, kw_columns},
	{"boundary", 2, 1, kw_boundary},
};
#define NKEYWORDS (sizeof keywords / sizeof keywords[0])

static int
header_keyword(struct header *h, char **tok, int n)
{
	size_t k;

	for (k = 0; k < NKEYWORDS; k++)
		if (strcmp(tok[0], keywords[k].name) == 0)
			break;
	if (k == NKEYWORDS)
		return rd_error(h->rd, "unknown header keyword '%s'", tok[0]);
	if (h->version < keywords[k].since)
		return rd_error(h->rd, "%s: not in version %ld of the format (a pack with a %s line starts '%s %d')",
		    tok[0], h->version, tok[0], PACK_FORMAT_NAME, keywords[k].since);
	if (h->seen & 1u << k)
		return rd_error(h->rd, "duplicate '%s' line (the header must contain exactly one)", tok[0]);
	h->seen |= 1u << k;
	return keywords[k].parse(h, tok, n);
}

/* s starts with the word w followed by a blank. */
static int
starts_word(const char *s, const char *w)
{
	size_t n = strlen(w);

	return strncmp(s, w, n) == 0 && (s[n] == ' ' || s[n] == '\t');
}

/* "meta KEY VALUE": VALUE is the rest of the line after the blanks that follow KEY. */
static int
header_meta(struct header *h, char *s)
{
	char *key = s + 5, *val;
	size_t k;

	while (*key == ' ' || *key == '\t')
		key++;
	val = key + strcspn(key, " \t");
	if (!*key || !*val)
		return rd_error(h->rd, "meta: expected a key and a value");
	*val++ = 0;
	while (*val == ' ' || *val == '\t')
		val++;
	if (!*val)
		return rd_error(h->rd, "meta: expected a key and a value");
	if (keys_room(h))
		return rd_error(h->rd, "out of memory");
	k = key_slot(h, key);
	if (h->slot[k])
		return rd_error(h->rd, "meta: duplicate key '%s'", key);
	if (pack_append_meta(h->p, key, val))
		return rd_error(h->rd, "out of memory");
	h->slot[k] = h->p->nmeta;
	return 0;
}

/* One header line; 1 when it was 'end'. */
static int
header_line(struct header *h, char *s)
{
	char *tok[MAXTOK];
	int n;

	if (s[0] == '#')
		return 0;
	if (starts_word(s, "history"))
		return pack_add_history(h->p, s + 8) ? rd_error(h->rd, "out of memory") : 0;
	if (starts_word(s, "meta"))
		return header_meta(h, s);
	n = split(s, tok, MAXTOK);
	if (n == 0)
		return rd_error(h->rd, "empty line in the header");
	if (strcmp(tok[0], "end") == 0)
		return n == 1 ? 1 : rd_error(h->rd, "end: unexpected text after 'end'");
	return header_keyword(h, tok, n);
}

static int
read_header(struct header *h)
{
	size_t k;
	char *s;
	int r;

	standard_columns(h);
	do {
		r = next_line(h->rd, &s);
		if (r < 0)
			return -1;
		if (r == 0)
			return rd_error_at(h->rd, line_after_last(h->rd),
			    "unexpected end of input in the header (no 'end' line)");
		r = header_line(h, s);
		if (r < 0)
			return -1;
	} while (r == 0);
	for (k = 0; k < NKEYWORDS; k++)
		if (keywords[k].required && h->version >= keywords[k].since && !(h->seen & 1u << k))
			return rd_error(h->rd, "missing '%s' line in the header", keywords[k].name);
	return 0;
}

/* ---- grains and contacts ---- */

/* A grain line of the header's columns: the required ones come first, in columns[] order;
 * the optional ones are found by the column each field is (h->col). */
static int
read_grain_line(const struct header *h, char *s)
{
	struct pack_reader *rd = h->rd;
	char *tok[MAXTOK], why[256];
	double v[NCOLUMNS];
	long id;
	int n = split(s, tok, MAXTOK), k;

	if (n != h->ncol)
		return rd_error(rd, "grain line: expected %d columns (%s), found %d%s", h->ncol, h->colnames, n,
		    h->version < 2 && n > h->ncol ? "; more columns need 'qusgm-pack 2' and a columns line" : "");
	if (num_parse_long(tok[0], &id))
		return rd_error(rd, "grain id '%s' is not an integer", tok[0]);
	for (k = 1; k < n; k++) {
		long ph;

		if (h->col[k] == COL_KIND) {	/* a name of the shapes' table */
			const struct shape_ops *sh = shape_find(tok[k]);
			char names[128];

			if (!sh) {
				shape_names(names, sizeof names);
				return rd_error(rd, "grain %ld: shape '%s' is not a kind (%s)", id, tok[k], names);
			}
			v[COL_KIND] = (double)sh->kind;
		} else if (h->col[k] == COL_PHASE) {	/* a tag, written as an integer: nothing else reads back alike */
			if (num_parse_long(tok[k], &ph) || ph < 0 || ph >= PACK_NPHASES)
				return rd_error(rd, "grain %ld: phase '%s' is neither 0 (mineral) nor 1 (hydrate)", id, tok[k]);
			v[COL_PHASE] = (double)ph;
		} else if (h->col[k] == COL_GLUED) {	/* '-' free, or the name of the wall it is glued to */
			int w;

			for (w = 0; w < NWALLS && strcmp(tok[k], pack_wall_names[w]) != 0; w++)
				;
			if (strcmp(tok[k], "-") != 0 && w == NWALLS)
				return rd_error(rd, "grain %ld: glued '%s' is neither '-' (free) nor a wall (xlo ... zhi)", id, tok[k]);
			v[COL_GLUED] = strcmp(tok[k], "-") == 0 ? 0 : 1 + w;
		} else if (num_parse(tok[k], &v[h->col[k]])) {
			return rd_error(rd, "grain: '%s' is not a finite number", tok[k]);
		}
	}
	if (pack_add_grain(h->p, id, v + 1, v[4], v[5], v[6], v[7]) == (size_t)-1)
		return rd_error(rd, "out of memory");
	if (h->p->has_shapes)
		pack_set_grain_shape(h->p, h->p->n - 1, v[COL_SIDE], v + COL_SIDE + 1);
	if (h->kinds)
		pack_set_grain_kind(h->p, h->p->n - 1, (enum shape_kind)v[COL_KIND]);
	if (h->p->has_phase)
		h->p->phase[h->p->n - 1] = (unsigned char)v[COL_PHASE];
	if (h->p->has_glue)
		h->p->glue[h->p->n - 1] = (unsigned char)v[COL_GLUED];
	if (check_grain_values(h->p, h->p->n - 1, why, sizeof why))
		return rd_error(rd, "%s", why);
	return 0;
}

static int
read_grains(const struct header *h, size_t **sorted)
{
	struct pack_reader *rd = h->rd;
	struct pack *p = h->p;
	long k, first = lines_lineno(rd->in) + 1;
	size_t dup, a, b;
	char *s;

	for (k = 0; k < h->ngr; k++) {
		int r = next_line(rd, &s);

		if (r < 0)
			return -1;
		if (r == 0)
			return rd_error_at(rd, line_after_last(rd),
			    "unexpected end of input: %ld grains declared, %ld found", h->ngr, k);
		/* room grows with the lines read, doubling up to the declared count: a header
		 * that declares 10^9 grains over one grain line costs no 64 GB before the end */
		if (p->n == p->cap) {
			size_t want = p->cap ? 2 * p->cap : 1024;
			if (want > (size_t)h->ngr)
				want = (size_t)h->ngr;
			if (pack_reserve(p, want))
				return rd_error(rd, "out of memory for %ld grains", h->ngr);
		}
		if (read_grain_line(h, s))
			return -1;
	}
	if (!(pack_grain_volume(p) <= pack_box_volume(p->box)))
		return rd_error_at(rd, first, "the grains' volume %g m^3 exceeds the box's %g m^3 (a grain far too large?)",
		    pack_grain_volume(p), pack_box_volume(p->box));
	*sorted = sort_by_id(p, &dup);
	if (!*sorted)
		return rd_error(rd, "out of memory");
	if (dup != (size_t)-1)
		return rd_error_at(rd, first + (long)dup, "duplicate grain id %ld", p->id[dup]);
	switch (find_same_centre(p, &a, &b)) {
	case -2:
		return rd_error(rd, "out of memory");
	case -1:
		return rd_error_at(rd, first + (long)b, "grains %ld and %ld have the same centre", p->id[a], p->id[b]);
	}
	return 0;
}

/* One end of a contact: a grain id, or (allow_wall) the name of a wall, which a periodic
 * axis does not have. */
static int
parse_end(struct pack_reader *rd, const struct pack *p, const size_t *sorted, const char *s,
    long *out, int allow_wall)
{
	long id;
	int w;

	if (allow_wall)
		for (w = 0; w < NWALLS; w++)
			if (strcmp(s, pack_wall_names[w]) == 0) {
				if (p->periodic[w / 2])
					return rd_error(rd, "contact: wall '%s' on axis %c, which is periodic (no walls)",
					    s, 'x' + w / 2);
				*out = PACK_WALL(w);
				return 0;
			}
	if (num_parse_long(s, &id))
		return rd_error(rd, "contact: '%s' is neither a grain id nor a wall (xlo xhi ylo yhi zlo zhi)", s);
	*out = (long)pack_find_id(p, id, (size_t *)sorted);
	if (*out == (long)(size_t)-1 || *out < 0)
		return rd_error(rd, "contact names grain %ld, which is not in the pack", id);
	return 0;
}

/* The Hertz force at an overlap equal to the contact's radius R*, (4/3) E* R*^2: the most a
 * contact line may hold (P0; |Q0| and |M0| / R* up to PACK_MU_MAX times it), far past the
 * small strains of Hertz's law.  Grain i against grain j >= 0, or against wall j. */
static int
contact_force_bound(struct pack_reader *rd, const struct pack *p, size_t i, long j, const double v[5])
{
	double Ej = PACK_IS_WALL(j) ? p->wall_E : p->E[j], nuj = PACK_IS_WALL(j) ? p->wall_nu : p->nu[j];
	double Rs = PACK_IS_WALL(j) ? p->r[i] : p->r[i] * p->r[j] / (p->r[i] + p->r[j]);
	double Es = 1 / ((1 - p->nu[i] * p->nu[i]) / p->E[i] + (1 - nuj * nuj) / Ej);
	double Pmax = 4.0 / 3.0 * Es * Rs * Rs, q = hypot(hypot(v[1], v[2]), v[3]);

	if (v[0] > Pmax)
		return rd_error(rd, "contact: normal force P0 = %g N is outside [0, %g] N, the Hertz force at an overlap as large as the contact's radius R* = %g m",
		    v[0], Pmax, Rs);
	if (q > PACK_MU_MAX * Pmax)
		return rd_error(rd, "contact: tangential force |Q0| = %g N is outside [0, %g] N (%g times the Hertz force at an overlap of R*)",
		    q, PACK_MU_MAX * Pmax, PACK_MU_MAX);
	if (fabs(v[4]) > PACK_MU_MAX * Pmax * Rs)
		return rd_error(rd, "contact: couple |M0| = %g N m is outside [0, %g] N m (%g times the Hertz force at an overlap of R*, times R*)",
		    fabs(v[4]), PACK_MU_MAX * Pmax * Rs, PACK_MU_MAX);
	return 0;
}

static int
read_contact_line(struct pack_reader *rd, struct pack *p, const size_t *sorted, char *s, int hertz)
{
	char *tok[MAXTOK];
	struct pack_contact c;
	long i, j;
	double v[5];
	int n = split(s, tok, MAXTOK);

	if (n != 7)
		return rd_error(rd, "contact line: expected 7 columns (i j P0 Q0x Q0y Q0z M0), found %d", n);
	if (parse_end(rd, p, sorted, tok[0], &i, 0) || parse_end(rd, p, sorted, tok[1], &j, 1))
		return -1;
	if (i == j)
		return rd_error(rd, "contact of grain %s with itself", tok[0]);
	if (parse_numbers(rd, tok + 2, 5, v, "contact"))
		return -1;
	if (v[0] < 0)
		return rd_error(rd, "contact: normal force P0 = %g is negative", v[0]);
	if (hertz && contact_force_bound(rd, p, (size_t)i, j, v))
		return -1;
	c.i = (size_t)i;
	c.j = j;
	c.P0 = v[0];
	memcpy(c.Q0, v + 1, sizeof c.Q0);
	c.M0 = v[4];
	if (pack_add_contact(p, &c))
		return rd_error(rd, "out of memory");
	return 0;
}

static int
read_contacts(const struct header *h, const size_t *sorted)
{
	struct pack_reader *rd = h->rd;
	long k, first = lines_lineno(rd->in) + 1;
	size_t dup;
	const char *law = pack_get_meta(h->p, "contact-law");
	int hertz = !law || strcmp(law, "linear") != 0;	/* the plate engine's law is not held to Hertz's bound */
	char *s;

	for (k = 0; k < h->nco; k++) {
		int r = next_line(rd, &s);

		if (r < 0)
			return -1;
		if (r == 0)
			return rd_error_at(rd, line_after_last(rd),
			    "unexpected end of input: %ld contacts declared, %ld found", h->nco, k);
		if (read_contact_line(rd, h->p, sorted, s, hertz))
			return -1;
	}
	dup = find_duplicate_contact(h->p);
	if (dup != (size_t)-1)
		return rd_error_at(rd, first + (long)dup, "contact pair listed twice");
	return 0;
}

/* ---- a whole pack ---- */

/* The oldest format version read; PACK_FORMAT_VERSION (pack.h) is the newest. */
#define OLDEST_VERSION 1

/* The magic line, already read into s: 0 with *version when it names a version this
 * reader knows. */
static int
read_magic(struct pack_reader *rd, char *s, long *version)
{
	char *tok[MAXTOK];
	int n = split(s, tok, MAXTOK);

	if (n < 1 || strcmp(tok[0], PACK_FORMAT_NAME) != 0)
		return rd_error(rd, "not a qusgm pack (first line must be '%s %d' or '%s %d')", PACK_FORMAT_NAME,
		    OLDEST_VERSION, PACK_FORMAT_NAME, PACK_FORMAT_VERSION);
	if (n != 2 || num_parse_long(tok[1], version))
		return rd_error(rd, "%s: missing or malformed version", PACK_FORMAT_NAME);
	if (*version > PACK_FORMAT_VERSION)
		return rd_error(rd, "pack format version %ld is newer than this qusgm reads (%d); upgrade qusgm",
		    *version, PACK_FORMAT_VERSION);
	if (*version < OLDEST_VERSION)
		return rd_error(rd, "unknown pack format version %ld", *version);
	return 0;
}

/* After the last contact: the end of input, or the magic line of the next pack (given back
 * to be read by the next call). */
static int
read_pack_end(struct pack_reader *rd, const struct header *h)
{
	char *s;
	int r = next_line(rd, &s);

	if (r < 0)
		return -1;
	if (r == 1) {
		if (strncmp(s, PACK_FORMAT_NAME, strlen(PACK_FORMAT_NAME)) != 0)
			return rd_error(rd, "unexpected line after the last contact (counts in the header are %ld grains, %ld contacts)",
			    h->ngr, h->nco);
		lines_unread(rd->in);
	}
	return 0;
}

int
pack_read_next(struct pack_reader *rd, struct pack *p)
{
	struct header h;
	size_t *sorted = NULL;
	char *s;
	int r, status;

	pack_init(p);
	memset(&h, 0, sizeof h);
	h.rd = rd;
	h.p = p;
	if (rd->failed)
		return -1;
	r = next_line(rd, &s);
	if (r <= 0) {
		if (r == 0 && lines_lineno(rd->in) == 0)
			return rd_error_at(rd, 1, "empty input (expected '%s %d' or '%s %d')", PACK_FORMAT_NAME,
			    OLDEST_VERSION, PACK_FORMAT_NAME, PACK_FORMAT_VERSION);
		return r;
	}
	status = read_magic(rd, s, &h.version);
	if (status == 0)
		status = read_header(&h);
	free(h.slot);
	h.slot = NULL;
	if (status == 0)
		status = read_grains(&h, &sorted);
	if (status == 0)
		status = read_contacts(&h, sorted);
	free(sorted);
	if (status == 0)
		status = read_pack_end(rd, &h);
	if (status) {
		pack_free(p);
		return -1;
	}
	return 1;
}

int
pack_read_path(const char *path, struct pack *p)
{
	struct pack_reader rd = {NULL, 0};
	struct pack extra;
	int r;

	pack_init(p);
	if (!(rd.in = lines_open_path(path)))
		return -1;
	r = pack_read_next(&rd, p);
	if (r == 1) {
		long line = lines_lineno(rd.in) + 1;
		int r2 = pack_read_next(&rd, &extra);
		if (r2 == 1) {
			pack_free(&extra);
			pack_free(p);
			msg_seterr("%s:%ld: a second pack follows; this tool reads one pack", lines_name(rd.in),
			    line);
			r = -1;
		} else if (r2 < 0) {
			pack_free(p);
			r = -1;
		}
	} else if (r == 0) {
		msg_seterr("%s:1: empty input", lines_name(rd.in));
		r = -1;
	}
	lines_close(rd.in);
	return r == 1 ? 0 : -1;
}

/* Output buffer: the pack is formatted in memory, then written in one go. */
struct sbuf {
	char *s;
	size_t len, cap;
	int oom;
};

static void
sb_need(struct sbuf *b, size_t more)
{
	if (b->len + more + 1 > b->cap) {
		size_t cap = 2 * (b->len + more + 1) + 4096;
		char *s = realloc(b->s, cap);
		if (!s) {
			b->oom = 1;
			return;
		}
		b->s = s;
		b->cap = cap;
	}
}

static void
sb_puts(struct sbuf *b, const char *s)
{
	size_t n = strlen(s);

	sb_need(b, n);
	if (b->oom)
		return;
	memcpy(b->s + b->len, s, n + 1);
	b->len += n;
}

static void
sb_num(struct sbuf *b, double v, char sep)
{
	char t[40];
	int n = num_format(t, v);

	t[n] = sep;
	t[n + 1] = 0;
	sb_puts(b, t);
}

static void
sb_nums(struct sbuf *b, const double *v, int n)
{
	int k;

	for (k = 0; k < n; k++)
		sb_num(b, v[k], k + 1 < n ? ' ' : '\n');
}

static void
sb_printf(struct sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void
sb_printf(struct sbuf *b, const char *fmt, ...)
{
	va_list ap;
	int n;

	va_start(ap, fmt);
	n = vsnprintf(NULL, 0, fmt, ap);
	va_end(ap);
	sb_need(b, (size_t)n);
	if (b->oom)
		return;
	va_start(ap, fmt);
	vsnprintf(b->s + b->len, (size_t)n + 1, fmt, ap);
	va_end(ap);
	b->len += (size_t)n;
}

int
pack_format_version(const struct pack *p)
{
	return p->periodic[0] || p->periodic[1] || p->periodic[2] || p->has_shapes || p->has_phase || p->has_glue ? 2 : 1;
}

/* The version-2 lines: the boundary along x y z, and the grain columns. */
static void
format_boundary(const struct pack *p, struct sbuf *b)
{
	int a;

	sb_puts(b, "boundary");
	for (a = 0; a < 3; a++)
		sb_puts(b, p->periodic[a] ? " periodic" : " walls");
	sb_puts(b, "\n");
}

static void
format_columns(const struct pack *p, struct sbuf *b)
{
	int k, g;

	sb_puts(b, "columns");
	for (k = 0; k < NCOLUMNS; k++) {
		g = columns[k].group;
		if (g == 0 || ((g == GROUP_KIND || g == GROUP_SHAPE) && p->has_shapes) || (g == GROUP_PHASE && p->has_phase) ||
		    (g == GROUP_GLUED && p->has_glue)) {
			sb_puts(b, " ");
			sb_puts(b, columns[k].name);
		}
	}
	sb_puts(b, "\n");
}

/* magic, history, meta, units, box, [boundary], [refbox], walls, friction, grains,
 * contacts, [columns], end: the order of share/doc/pack-format.md. */
static void
format_header(const struct pack *p, int version, struct sbuf *b)
{
	size_t k;
	double v[3];

	sb_printf(b, "%s %d\n", PACK_FORMAT_NAME, version);
	for (k = 0; k < p->nhist; k++)
		sb_printf(b, "history %s\n", p->history[k]);
	for (k = 0; k < p->nmeta; k++)
		sb_printf(b, "meta %s %s\n", p->meta[k].key, p->meta[k].value);
	sb_puts(b, "units SI\nbox ");
	sb_nums(b, p->box, 6);
	if (version >= 2)
		format_boundary(p, b);
	if (p->has_refbox) {
		sb_puts(b, "refbox ");
		sb_nums(b, p->refbox, 6);
	}
	v[0] = p->wall_E;
	v[1] = p->wall_nu;
	v[2] = p->wall_mu;
	sb_puts(b, "walls ");
	sb_nums(b, v, 3);
	sb_puts(b, "friction ");
	sb_nums(b, &p->mu, 1);
	sb_printf(b, "grains %zu\ncontacts %zu\n", p->n, p->nc);
	if (version >= 2)
		format_columns(p, b);
	sb_puts(b, "end\n");
}

static void
format_pack(const struct pack *p, struct sbuf *b)
{
	size_t k;
	double v[7];
	int a;

	format_header(p, pack_format_version(p), b);
	for (k = 0; k < p->n && !b->oom; k++) {
		sb_printf(b, "%ld ", p->id[k]);
		memcpy(v, p->x + 3 * k, 3 * sizeof *v);
		v[3] = p->r[k];
		v[4] = p->E[k];
		v[5] = p->nu[k];
		v[6] = p->rho[k];
		if (p->has_shapes) {	/* then shape side qw qx qy qz */
			for (a = 0; a < 7; a++)
				sb_num(b, v[a], ' ');
			sb_printf(b, "%s ", shape_of(pack_grain_shape(p, k))->name);
			sb_num(b, p->side[k], ' ');
			sb_nums(b, p->q + 4 * k, 4);
		} else {
			sb_nums(b, v, 7);
		}
		if (p->has_phase && !b->oom) {	/* the tag last: the line's newline becomes a blank */
			b->s[b->len - 1] = ' ';
			sb_printf(b, "%d\n", p->phase[k]);
		}
		if (p->has_glue && !b->oom) {	/* likewise, after the phase */
			b->s[b->len - 1] = ' ';
			sb_printf(b, "%s\n", p->glue[k] ? pack_wall_names[p->glue[k] - 1] : "-");
		}
	}
	for (k = 0; k < p->nc && !b->oom; k++) {
		const struct pack_contact *c = &p->c[k];
		sb_printf(b, "%ld ", p->id[c->i]);
		if (PACK_IS_WALL(c->j))
			sb_printf(b, "%s ", pack_wall_names[PACK_WALL_INDEX(c->j)]);
		else
			sb_printf(b, "%ld ", p->id[c->j]);
		v[0] = c->P0;
		memcpy(v + 1, c->Q0, sizeof c->Q0);
		v[4] = c->M0;
		sb_nums(b, v, 5);
	}
}

int
pack_write_stream(const struct pack *p, FILE *fp, int gz)
{
	struct sbuf b = {0};
	int status = 0;

	format_pack(p, &b);
	if (b.oom) {
		free(b.s);
		msg_seterr("out of memory formatting the pack");
		return -1;
	}
	if (gz) {
		int fd = dup(fileno(fp));
		gzFile z;

		fflush(fp);
		z = fd >= 0 ? gzdopen(fd, "wb6") : NULL;
		if (!z || gzwrite(z, b.s, (unsigned)b.len) != (int)b.len)
			status = -1;
		if (z) {
			if (gzclose(z) != Z_OK)
				status = -1;
		} else if (fd >= 0) {
			close(fd);
		}
	} else if (fwrite(b.s, 1, b.len, fp) != b.len) {
		status = -1;
	}
	free(b.s);
	if (status)
		msg_seterr("write error");
	return status;
}

int
pack_write_path(const struct pack *p, const char *path)
{
	struct file_out o;

	if (file_out_open(&o, path))
		return -1;
	if (pack_write_stream(p, o.fp, 0)) {	/* file_out_commit gzips a *.gz output */
		msg_seterr("%s: write error", path ? path : "<stdout>");
		file_out_abort(&o);
		return -1;
	}
	return file_out_commit(&o);
}

/* The boundary flags are 0 or 1, and no contact names a wall of a periodic axis. */
static int
validate_boundary(const struct pack *p)
{
	size_t k;
	int a;

	for (a = 0; a < 3; a++)
		if (p->periodic[a] != 0 && p->periodic[a] != 1) {
			msg_seterr("boundary: periodic[%d] = %d is neither 0 (walls) nor 1 (periodic)", a, p->periodic[a]);
			return -1;
		}
	for (k = 0; k < p->nc; k++)
		if (PACK_IS_WALL(p->c[k].j) && p->periodic[PACK_WALL_INDEX(p->c[k].j) / 2]) {
			msg_seterr("contact of grain %ld with wall '%s', on a periodic axis", p->id[p->c[k].i],
			    pack_wall_names[PACK_WALL_INDEX(p->c[k].j)]);
			return -1;
		}
	return 0;
}

int
pack_validate(const struct pack *p)
{
	char why[256];
	size_t k, dup, *s;

	for (k = 0; k < 3; k++)
		if (!(p->box[k + 3] > p->box[k])) {
			msg_seterr("box: upper bound not above lower bound on axis %c", (int)('x' + k));
			return -1;
		}
	for (k = 0; k < 6; k++)
		if (!(fabs(p->box[k]) <= PACK_BOX_MAX)) {
			msg_seterr("box: bound %g m is outside [-%g, %g] m", p->box[k], PACK_BOX_MAX, PACK_BOX_MAX);
			return -1;
		}
	if (!(p->wall_E >= PACK_E_MIN && p->wall_E <= PACK_WALL_E_MAX) || !(p->wall_nu > -1 && p->wall_nu < 0.5) ||
	    !(p->wall_mu >= 0 && p->wall_mu <= PACK_MU_MAX) || !(p->mu >= 0 && p->mu <= PACK_MU_MAX)) {
		msg_seterr("walls or friction out of range (walls E in [%g, %g] Pa, nu in (-1, 0.5), friction coefficients in [0, %g])",
		    PACK_E_MIN, PACK_WALL_E_MAX, PACK_MU_MAX);
		return -1;
	}
	if (p->n == 0) {
		msg_seterr("the pack has no grains");
		return -1;
	}
	for (k = 0; k < p->n; k++)
		if (check_grain_values(p, k, why, sizeof why)) {
			msg_seterr("%s", why);
			return -1;
		}
	if (!(pack_grain_volume(p) <= pack_box_volume(p->box))) {
		msg_seterr("the grains' volume %g m^3 exceeds the box's %g m^3", pack_grain_volume(p), pack_box_volume(p->box));
		return -1;
	}
	s = sort_by_id(p, &dup);
	free(s);
	if (dup != (size_t)-1) {
		msg_seterr("duplicate grain id %ld", p->id[dup]);
		return -1;
	}
	switch (find_same_centre(p, &k, &dup)) {
	case -2:
		msg_seterr("out of memory");
		return -1;
	case -1:
		msg_seterr("grains %ld and %ld have the same centre", p->id[k], p->id[dup]);
		return -1;
	}
	return validate_boundary(p);
}

int
pack_write_tool_out(struct pack *p, const struct cli_tool *tool, const struct cli_state *st, struct file_out *o)
{
	char *hist = cli_history_line(tool, st);

	if (!hist || pack_add_history(p, hist)) {
		free(hist);
		msg_seterr("out of memory");
		return -1;
	}
	free(hist);
	if (file_out_open(o, st->output))
		return -1;
	if (pack_write_stream(p, o->fp, 0)) {	/* file_out_commit gzips a *.gz output */
		msg_seterr("%s: write error", st->output ? st->output : "<stdout>");
		file_out_abort(o);
		return -1;
	}
	return 0;
}

int
pack_write_tool_with(struct pack *p, const struct cli_tool *tool, const struct cli_state *st, struct file_out *also)
{
	struct file_out packout, *outs[2] = {&packout, also};

	if (pack_write_tool_out(p, tool, st, &packout)) {
		if (also)
			file_out_abort(also);
		return -1;
	}
	return file_out_commit_all(outs, 2);
}

int
pack_write_tool(struct pack *p, const struct cli_tool *tool, const struct cli_state *st)
{
	struct file_out o;

	if (pack_write_tool_out(p, tool, st, &o))
		return -1;
	return file_out_commit(&o);
}
