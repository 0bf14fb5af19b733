/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_packio: the pack writer and reader are exact inverses, and num_format is the shortest
 * round-trip-safe form (share/doc/pack-format.md, "Numbers").
 *
 * No tolerance in this file but one (a volume summed in another order, in shapes()): every
 * other comparison is of bytes or of bit patterns, because the format promises that
 * write -> read -> write is the identity. */
#include "base/msg.h"
#include "base/numfmt.h"
#include "base/quat.h"
#include "pack/pack.h"
#include "pack/packio.h"
#include "pack/shape.h"
#include "unit.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

/* A pack with awkward numbers (no short decimal form, 1e-300, -0.0, a subnormal, 1e-22),
 * history, meta, a refbox, and grain-grain and grain-wall contacts with nonzero Q0 and M0,
 * each within the reader's ranges (forces below Hertz's at an overlap of R*: a P0 of
 * 6.02214076e23 N and a Q0 of 1e22 N, taken once, are refused now). */
static void
build(struct pack *p)
{
	size_t k;
	struct pack_contact c;

	pack_init(p);
	p->box[0] = -1.0 / 3.0;
	p->box[1] = 0;
	p->box[2] = -0.0;
	p->box[3] = 1e-3 / 3.0;
	p->box[4] = 0.1 + 0.2;
	p->box[5] = 123.456789123456789;	/* within PACK_BOX_MAX (1 km), 18 digits all the same */
	memcpy(p->refbox, p->box, sizeof p->box);
	p->refbox[3] = 2.0 / 3.0 * 1e-3;
	p->has_refbox = 1;
	p->wall_E = 7e12 / 3.0;
	p->wall_nu = 0.495;
	p->mu = 0.1;
	p->wall_mu = 1.0 / 3.0;
	pack_add_history(p, "packgen 0.1.0: packgen -n 5 --seed 7 ; --n=5 --seed=7 --psd=uniform:7e-05,0.00013");
	pack_add_history(p, "densify 0.1.0: densify '--stress=4e6' - ; --stress=4000000");
	pack_set_meta(p, "sigma_c", "4000000");
	pack_set_meta(p, "note", "a value with  spaces\tand a tab");
	for (k = 0; k < 5; k++) {
		double x[3] = {0.1 * (double)k * 1e-4, 1.0 / 3.0 * 1e-4, 1e-300};
		/* ids out of order and with gaps: the writer keeps them, not the indices */
		pack_add_grain(p, (long)(100 - 7 * k), x, 7e-5 + (double)k / 3.0 * 1e-5, 7e10 / 3.0,
		    k == 4 ? -0.99 : 0.2 + 1e-17 * (double)k, 2420.123456789123);
	}
	p->E[2] = 123456789.123456789;
	p->nu[3] = -0.0;
	memset(&c, 0, sizeof c);
	c.i = 0, c.j = 1, c.P0 = 0.1, c.Q0[0] = 1.0 / 3.0, c.Q0[1] = -1e-300, c.Q0[2] = -0.0, c.M0 = 0.00123456789123456789;
	pack_add_contact(p, &c);
	c.i = 3, c.j = 2, c.P0 = 0, c.Q0[0] = 4.9406564584124654e-324, c.Q0[1] = 0, c.Q0[2] = 1e-22, c.M0 = -1.0 / 3.0 * 1e-5;
	pack_add_contact(p, &c);
	c.i = 2, c.j = PACK_WALL(WALL_ZHI), c.P0 = 1e-300, c.Q0[0] = 0.1, c.Q0[1] = 0.2, c.Q0[2] = 0.3, c.M0 = -0.0;
	pack_add_contact(p, &c);
	c.i = 4, c.j = PACK_WALL(WALL_XLO), c.P0 = 6.02214076e-23, c.Q0[0] = -1.0 / 3.0, c.Q0[1] = 0, c.Q0[2] = 0, c.M0 = 1e-300;
	pack_add_contact(p, &c);
	c.i = 4, c.j = PACK_WALL(WALL_YHI), c.P0 = 2.0 / 3.0, c.Q0[0] = 0, c.Q0[1] = 0.30000000000000004, c.Q0[2] = 0, c.M0 = 0;
	pack_add_contact(p, &c);
}

static int
same_bits(double a, double b)
{
	return memcmp(&a, &b, sizeof a) == 0;
}

static int
same_array(const double *a, const double *b, size_t n)
{
	size_t k;

	for (k = 0; k < n; k++)
		if (!same_bits(a[k], b[k]))
			return 0;
	return 1;
}

static char *
slurp(const char *path, size_t *len, int gunzip)
{
	char *buf = NULL;
	size_t cap = 0, n = 0;

	*len = 0;
	if (gunzip) {
		gzFile z = gzopen(path, "rb");
		int got;

		if (!z)
			return NULL;
		do {
			if (n + 4096 > cap) {
				cap = 2 * (n + 4096);
				buf = realloc(buf, cap);
			}
			got = gzread(z, buf + n, 4096);
			if (got > 0)
				n += (size_t)got;
		} while (got > 0);
		gzclose(z);
	} else {
		FILE *fp = fopen(path, "rb");
		size_t got;

		if (!fp)
			return NULL;
		do {
			if (n + 4096 > cap) {
				cap = 2 * (n + 4096);
				buf = realloc(buf, cap);
			}
			got = fread(buf + n, 1, 4096, fp);
			n += got;
		} while (got > 0);
		fclose(fp);
	}
	*len = n;
	return buf;
}

static int
same_file(const char *a, const char *b, int gunzip)
{
	size_t la, lb;
	char *x = slurp(a, &la, gunzip), *y = slurp(b, &lb, gunzip);
	int same = x && y && la == lb && memcmp(x, y, la) == 0;

	free(x);
	free(y);
	return same;
}

static void
check_fields(const struct pack *a, const struct pack *b, const char *how)
{
	size_t k;
	int ok;

	CHECK(a->n == b->n && memcmp(a->id, b->id, a->n * sizeof *a->id) == 0, "%s: grain count and ids", how);
	CHECK(same_array(a->x, b->x, 3 * a->n), "%s: centres (bit patterns)", how);
	CHECK(same_array(a->r, b->r, a->n), "%s: radii", how);
	CHECK(same_array(a->E, b->E, a->n), "%s: Young's moduli", how);
	CHECK(same_array(a->nu, b->nu, a->n), "%s: Poisson ratios (with -0)", how);
	CHECK(same_array(a->rho, b->rho, a->n), "%s: densities", how);
	CHECK(same_array(a->box, b->box, 6), "%s: box", how);
	CHECK(a->has_refbox == b->has_refbox && same_array(a->refbox, b->refbox, 6), "%s: refbox", how);
	CHECK(same_bits(a->wall_E, b->wall_E) && same_bits(a->wall_nu, b->wall_nu) &&
	    same_bits(a->wall_mu, b->wall_mu), "%s: walls E nu mu", how);
	CHECK(same_bits(a->mu, b->mu), "%s: friction", how);
	CHECK(memcmp(a->periodic, b->periodic, sizeof a->periodic) == 0, "%s: boundary (periodic %d %d %d)", how,
	    b->periodic[0], b->periodic[1], b->periodic[2]);
	ok = a->nc == b->nc;
	for (k = 0; ok && k < a->nc; k++)
		ok = a->c[k].i == b->c[k].i && a->c[k].j == b->c[k].j;
	CHECK(ok, "%s: contact pairs (grain-grain and grain-wall)", how);
	ok = a->nc == b->nc;
	for (k = 0; ok && k < a->nc; k++)
		ok = same_bits(a->c[k].P0, b->c[k].P0) && same_array(a->c[k].Q0, b->c[k].Q0, 3) &&
		    same_bits(a->c[k].M0, b->c[k].M0);
	CHECK(ok, "%s: contact P0 Q0 M0 (bit patterns)", how);
	CHECK(a->has_shapes == b->has_shapes && (!a->has_shapes || (same_array(a->side, b->side, a->n) &&
	    same_array(a->q, b->q, 4 * a->n) && memcmp(a->shape, b->shape, a->n) == 0)),
	    "%s: shape columns shape side qw qx qy qz (%s)", how, a->has_shapes ? "present, bit patterns" : "absent");
	ok = a->nhist == b->nhist;
	for (k = 0; ok && k < a->nhist; k++)
		ok = strcmp(a->history[k], b->history[k]) == 0;
	CHECK(ok, "%s: history lines", how);
	ok = a->nmeta == b->nmeta;
	for (k = 0; ok && k < a->nmeta; k++)
		ok = strcmp(a->meta[k].key, b->meta[k].key) == 0 && strcmp(a->meta[k].value, b->meta[k].value) == 0;
	CHECK(ok, "%s: meta keys and values", how);
}

static void
round_trip(const char *first, const char *second, int gz)
{
	struct pack p, q, q2;
	char how[64];

	snprintf(how, sizeof how, "round trip%s", gz ? " .gz" : "");
	build(&p);
	CHECK(pack_validate(&p) == 0, "%s: the built pack is valid (%s)", how, msg_geterr());
	CHECK(pack_write_path(&p, first) == 0, "%s: write %s", how, first);
	CHECK(pack_read_path(first, &q) == 0, "%s: read %s back (%s)", how, first, msg_geterr());
	check_fields(&p, &q, how);
	CHECK(pack_write_path(&q, second) == 0, "%s: write again", how);
	CHECK(same_file(first, second, 0), "%s: write-read-write is byte-identical", how);
	CHECK(pack_read_path(second, &q2) == 0, "%s: read the second file", how);
	check_fields(&p, &q2, how);
	pack_free(&p);
	pack_free(&q);
	pack_free(&q2);
}

/* The form num_format must choose: the first of %.15g %.16g %.17g that reads back. */
static int
expected_format(char *buf, double v)
{
	int prec, n = 0;

	for (prec = 15; prec <= 17; prec++) {
		n = snprintf(buf, 40, "%.*g", prec, v);
		if (same_bits(strtod(buf, NULL), v))
			break;
	}
	return n;
}

static void
numfmt_random(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	long k, bad_value = 0, bad_bits = 0, bad_short = 0, bad_parse = 0, tried_bits = 0;
	char buf[40], want[40];

	gsl_rng_set(rng, 1);
	for (k = 0; k < 100000; k++) {
		/* values spread over magnitudes: a mantissa times a power of ten */
		double v = (gsl_rng_uniform(rng) - 0.5) * pow(10.0, (double)gsl_rng_uniform_int(rng, 600) - 300), back;
		uint64_t bits;
		double w;

		num_format(buf, v);
		back = strtod(buf, NULL);
		if (!same_bits(back, v))
			bad_value++;
		expected_format(want, v);
		if (strcmp(buf, want) != 0)
			bad_short++;
		if (num_parse(buf, &back) || !same_bits(back, v))
			bad_parse++;
		/* arbitrary bit patterns: every finite double, subnormals included */
		bits = ((uint64_t)gsl_rng_get(rng) << 32) | (uint64_t)gsl_rng_get(rng);
		memcpy(&w, &bits, sizeof w);
		if (!isfinite(w))
			continue;
		tried_bits++;
		num_format(buf, w);
		if (!same_bits(strtod(buf, NULL), w))
			bad_bits++;
		expected_format(want, w);
		if (strcmp(buf, want) != 0)
			bad_short++;
	}
	CHECK(bad_value == 0, "num_format: 1e5 random doubles over 1e-300..1e300 read back exactly (%ld failed)",
	    bad_value);
	CHECK(bad_bits == 0 && tried_bits > 99000, "num_format: %ld random finite bit patterns read back exactly (%ld failed)",
	    tried_bits, bad_bits);
	CHECK(bad_short == 0, "num_format: always the first of %%.15g %%.16g %%.17g that reads back (%ld not)",
	    bad_short);
	CHECK(bad_parse == 0, "num_parse reads num_format's output back exactly (%ld failed)", bad_parse);
	gsl_rng_free(rng);
}

static void
numfmt_hand(void)
{
	static const struct {
		double v;
		const char *s;
	} t[] = {
		{0.1, "0.1"},
		{1.0 / 3.0, "0.3333333333333333"},
		{0.1 + 0.2, "0.30000000000000004"},
		{1e-300, "1e-300"},
		{-0.0, "-0"},
		{0, "0"},
		{123456789.123456789, "123456789.12345679"},
		{2420, "2420"},
		{7e10, "70000000000"},
		{1e22, "1e+22"},
		{0.0001220703125, "0.0001220703125"},
		{4.9406564584124654e-324, "4.94065645841247e-324"},	/* subnormal: 15 digits suffice */
		{2.0 / 3.0, "0.6666666666666666"},
	};
	size_t k;
	char buf[40];

	for (k = 0; k < sizeof t / sizeof t[0]; k++) {
		int n = num_format(buf, t[k].v);
		CHECK(strcmp(buf, t[k].s) == 0 && n == (int)strlen(t[k].s), "num_format(%.17g) = '%s' (want '%s')",
		    t[k].v, buf, t[k].s);
	}
}

static void
numparse_strict(void)
{
	double v;
	long l;

	CHECK(num_parse("nan", &v) != 0 && num_parse("inf", &v) != 0 && num_parse("-inf", &v) != 0,
	    "num_parse refuses nan and inf");
	CHECK(num_parse("1e999", &v) != 0, "num_parse refuses overflow");
	CHECK(num_parse("1e-320", &v) == 0 && v > 0, "num_parse takes a subnormal");
	CHECK(num_parse("1x", &v) != 0 && num_parse("", &v) != 0 && num_parse("1 ", &v) != 0,
	    "num_parse wants the whole token");
	CHECK(num_parse_long("12", &l) == 0 && l == 12 && num_parse_long("1.5", &l) != 0 &&
	    num_parse_long("99999999999999999999999", &l) != 0, "num_parse_long: whole integer tokens in range");
}

/* build's pack made periodic along y: its contact with the yhi wall goes. */
static void
build_periodic(struct pack *p)
{
	size_t k, m = 0;

	build(p);
	for (k = 0; k < p->nc; k++)
		if (!(PACK_IS_WALL(p->c[k].j) && PACK_WALL_INDEX(p->c[k].j) / 2 == 1))
			p->c[m++] = p->c[k];
	p->nc = m;
	p->periodic[1] = 1;
}

/* The text of a file, NUL-terminated (NULL if unreadable). */
static char *
text_of(const char *path)
{
	size_t len;
	char *s = slurp(path, &len, 1), *t = s ? realloc(s, len + 1) : NULL;

	if (!t) {
		free(s);
		return NULL;
	}
	t[len] = 0;
	return t;
}

/* Version 2: a periodic axis is written as version 2 and round-trips byte for byte, plain
 * and gzip; the lowest version is chosen; a version-2 file that says only what version 1
 * implies is written back as version 1. */
static void
format_2(const char *dir)
{
	struct pack p, q, r;
	char a[160], b[160], how[64], *t;
	int gz, k;

	build(&p);
	CHECK(pack_format_version(&p) == 1, "pack_format_version: 1 for the standard columns and six walls");
	for (k = 0; k < 3; k++) {
		p.periodic[k] = 1;
		CHECK(pack_format_version(&p) == 2, "pack_format_version: 2 with axis %c periodic", 'x' + k);
		p.periodic[k] = 0;
	}
	snprintf(a, sizeof a, "%s/v1.pack", dir);
	pack_write_path(&p, a);
	t = text_of(a);
	CHECK(t && strncmp(t, "qusgm-pack 1\n", 13) == 0 && !strstr(t, "\nboundary ") && !strstr(t, "\ncolumns "),
	    "six walls: written as version 1, without boundary and columns lines");
	free(t);
	pack_free(&p);
	for (gz = 0; gz < 2; gz++) {
		snprintf(how, sizeof how, "version 2 round trip%s", gz ? " .gz" : "");
		snprintf(a, sizeof a, "%s/p2a.pack%s", dir, gz ? ".gz" : "");
		snprintf(b, sizeof b, "%s/p2b.pack%s", dir, gz ? ".gz" : "");
		build_periodic(&p);
		CHECK(pack_validate(&p) == 0, "%s: the periodic pack is valid (%s)", how, msg_geterr());
		CHECK(pack_write_path(&p, a) == 0, "%s: write", how);
		t = text_of(a);
		CHECK(t && strncmp(t, "qusgm-pack 2\n", 13) == 0 && strstr(t, "\nboundary walls periodic walls\n") &&
		    strstr(t, "\ncolumns id x y z r E nu rho\nend\n"), "%s: magic 'qusgm-pack 2', the boundary and columns lines", how);
		free(t);
		CHECK(pack_read_path(a, &q) == 0, "%s: read back (%s)", how, msg_geterr());
		check_fields(&p, &q, how);
		CHECK(pack_write_path(&q, b) == 0, "%s: write again", how);
		CHECK(same_file(a, b, 0), "%s: write-read-write is byte-identical", how);
		pack_free(&p);
		pack_free(&q);
		unlink(a);
		unlink(b);
	}
	/* a version-2 file with the standard columns and six walls */
	snprintf(a, sizeof a, "%s/v1.pack", dir);
	snprintf(b, sizeof b, "%s/std2.pack", dir);
	t = text_of(a);
	if (t) {
		char *end = strstr(t, "\nend\n"), *box = strstr(t, "\nbox "), *eol = box ? strchr(box + 1, '\n') : NULL;
		FILE *fp = fopen(b, "wb");
		fprintf(fp, "qusgm-pack 2%.*s\nboundary walls walls walls%.*s\ncolumns id x y z r E nu rho%s",
		    (int)(eol - (t + 12)), t + 12, (int)(end - eol), eol, end);
		fclose(fp);
	}
	free(t);
	CHECK(pack_read_path(b, &q) == 0, "version 2 saying only what version 1 implies: read (%s)", msg_geterr());
	build(&r);
	check_fields(&r, &q, "version 2 with the standard columns and six walls");
	snprintf(b, sizeof b, "%s/back.pack", dir);
	CHECK(pack_write_path(&q, b) == 0 && same_file(a, b, 0),
	    "version 2 with the standard columns and six walls is written back as the version-1 file");
	pack_free(&q);
	pack_free(&r);
	unlink(b);
	snprintf(b, sizeof b, "%s/std2.pack", dir);
	unlink(b);
	unlink(a);
	/* what the reader refuses, pack_validate refuses */
	build_periodic(&p);
	p.periodic[0] = 2;
	CHECK(pack_validate(&p) != 0 && strstr(msg_geterr(), "periodic[0] = 2"), "pack_validate: a boundary flag other than 0 or 1 (%s)",
	    msg_geterr());
	p.periodic[0] = 1;
	CHECK(pack_validate(&p) != 0 && strstr(msg_geterr(), "wall 'xlo', on a periodic axis"),
	    "pack_validate: a contact with a wall of a periodic axis (%s)", msg_geterr());
	pack_free(&p);
}

/* Two packs back to back in one stream, read with pack_read_next; pack_read_path refuses it. */
static void
two_in_a_stream(const char *path)
{
	struct pack p, a, b, c;
	struct pack_reader *rd;
	FILE *fp;
	int r1, r2, r3;

	build(&p);
	fp = fopen(path, "wb");
	pack_write_stream(&p, fp, 0);
	pack_write_stream(&p, fp, 0);
	fclose(fp);
	fp = fopen(path, "rb");
	rd = pack_reader_open(fp, path);
	r1 = pack_read_next(rd, &a);
	r2 = pack_read_next(rd, &b);
	r3 = pack_read_next(rd, &c);
	CHECK(r1 == 1 && r2 == 1 && r3 == 0, "two packs in one stream: 1, 1, then 0 at the end (%d %d %d)", r1, r2, r3);
	if (r1 == 1 && r2 == 1)
		check_fields(&a, &b, "second pack of a stream");
	pack_reader_close(rd);
	fclose(fp);
	CHECK(pack_read_path(path, &c) != 0 && strstr(msg_geterr(), "second pack"),
	    "pack_read_path refuses a second pack (%s)", msg_geterr());
	pack_free(&a);
	pack_free(&b);
	pack_free(&p);
}

/* Carriage returns: a CRLF pack reads and writes back without them, and written, read and
 * written again is the same bytes; a history line ending in CR CR LF is refused at its line
 * (once read as "text\r" and written back with the \r, which the next read dropped). */
static const char cr_pack[] = "qusgm-pack 1\r\n"
			      "history packgen 0.1.0: packgen -n 1 ; --n=1%s\r\n"
			      "units SI\r\n"
			      "box 0 0 0 1 1 1\r\n"
			      "walls 7e12 0.3 0.3\r\n"
			      "friction 0.3\r\n"
			      "grains 1\r\n"
			      "contacts 0\r\n"
			      "end\r\n"
			      "1 0.5 0.5 0.5 0.1 7e10 0.2 2420\r\n";

static void
carriage_returns(const char *dir)
{
	char in[160], a[160], b[160];
	struct pack p, q;
	FILE *fp;

	snprintf(in, sizeof in, "%s/cr.pack", dir);
	snprintf(a, sizeof a, "%s/cr-a.pack", dir);
	snprintf(b, sizeof b, "%s/cr-b.pack", dir);
	fp = fopen(in, "wb");
	fprintf(fp, cr_pack, "");
	fclose(fp);
	{
		int rc = pack_read_path(in, &p);
		CHECK(rc == 0, "a CRLF pack reads%s%s", rc ? ": " : "", rc ? msg_geterr() : "");
	}
	CHECK(pack_write_path(&p, a) == 0 && pack_read_path(a, &q) == 0 && pack_write_path(&q, b) == 0 && same_file(a, b, 0),
	    "a CRLF pack: written, read and written again, the same bytes");
	CHECK(p.nhist == 1 && strcmp(p.history[0], "packgen 0.1.0: packgen -n 1 ; --n=1") == 0,
	    "a CRLF pack: the history text without its \\r");
	pack_free(&p);
	pack_free(&q);
	fp = fopen(in, "wb");
	fprintf(fp, cr_pack, "\r");
	fclose(fp);
	CHECK(pack_read_path(in, &p) != 0 && strstr(msg_geterr(), "cr.pack:2: a carriage return"),
	    "a history line ending in CR CR LF is refused at line 2 (%s)", msg_geterr());
	unlink(in);
	unlink(a);
	unlink(b);
}

/* build's pack with the shape columns: a sphere (side 0, the identity), sides without a
 * short decimal form, 1e-300 and -0, and unit quaternions whose components have none. */
static void
build_shapes(struct pack *p)
{
	double q[4];

	build(p);
	pack_set_shapes(p);
	q[0] = 1, q[1] = 2, q[2] = 3, q[3] = 4;
	quat_normalize(q);
	pack_set_grain_shape(p, 1, 1e-4 / 3.0, q);
	q[0] = cos(M_PI / 8), q[1] = 0, q[2] = 0, q[3] = sin(M_PI / 8);
	pack_set_grain_shape(p, 2, 2.5e-5, q);
	q[0] = q[1] = q[2] = q[3] = 0.5;
	pack_set_grain_shape(p, 3, 1e-300, q);
	q[0] = -0.0, q[1] = 0, q[2] = 0, q[3] = -1;
	pack_set_grain_shape(p, 4, -0.0, q);
}

static int
is_sphere(const struct pack *p, size_t i)
{
	return p->side[i] == 0 && p->q[4 * i] == 1 && p->q[4 * i + 1] == 0 && p->q[4 * i + 2] == 0 &&
	    p->q[4 * i + 3] == 0;
}

/* The shape columns (side qw qx qy qz): storage, growth, the writer's version 2 and its
 * columns line, the round trip to the bit, and what pack_validate refuses. */
static void
shapes(const char *dir)
{
	struct pack p, q, s;
	char a[160], b[160], how[64], *t;
	double x[3] = {0.5e-4, 0.5e-4, 0.5e-4}, vs, qq[4];
	size_t k;
	int gz, ok;
	enum shape_radius conv;

	build(&p);
	CHECK(!p.has_shapes && !p.side && !p.q, "a pack has no shape columns until pack_set_shapes");
	vs = pack_grain_volume(&p);
	CHECK(pack_first_plate(&p) == (size_t)-1 && pack_require_spheres(&p, "densify") == 0,
	    "no shape columns: every grain a sphere, pack_require_spheres passes");
	CHECK(pack_set_shapes(&p) == 0 && p.has_shapes, "pack_set_shapes");
	for (k = 0, ok = 1; k < p.n; k++)
		ok = ok && is_sphere(&p, k);
	CHECK(ok, "pack_set_shapes: every grain side 0 and q = (1, 0, 0, 0)");
	CHECK(pack_set_shapes(&p) == 0 && is_sphere(&p, 0), "pack_set_shapes twice changes nothing");
	CHECK(same_bits(pack_grain_volume(&p), vs), "pack_grain_volume: shape columns with every side 0 give the spheres' volume, to the bit");
	CHECK(pack_format_version(&p) == 2, "pack_format_version: 2 with the shape columns");
	CHECK(pack_validate(&p) == 0, "pack_validate: shape columns, every side 0 (%s)", msg_geterr());
	/* growth past the capacity (64, then doubling) keeps the shape arrays in step */
	for (k = 0, ok = 1; k < 300; k++) {
		x[0] = 1e-7 * (double)(k + 1);
		ok = ok && pack_add_grain(&p, 1000 + (long)k, x, 1e-5, 7e10, 0.2, 2420) != (size_t)-1;
	}
	for (k = 0; k < p.n; k++)
		ok = ok && is_sphere(&p, k);
	CHECK(ok && p.n == 305 && p.cap >= 305, "pack_add_grain with shape columns: 300 more grains, each a sphere (%zu grains, cap %zu)",
	    p.n, p.cap);
	qq[0] = 0, qq[1] = 1, qq[2] = 0, qq[3] = 0;
	pack_set_grain_shape(&p, 304, 3e-5, qq);
	CHECK(p.side[304] == 3e-5 && p.q[4 * 304 + 1] == 1 && pack_first_plate(&p) == 304,
	    "pack_set_grain_shape, pack_first_plate: the last grain");
	CHECK(pack_require_spheres(&p, "frictionalize") != 0 &&
	    strcmp(msg_geterr(), "grain 1299 is a spheroplate (side > 0); frictionalize handles spheres only") == 0,
	    "pack_require_spheres: '%s'", msg_geterr());
	/* the one tolerance of this file: 305 terms summed in another order, 305 roundings of
	 * 1.1e-16 at most, 3.4e-14 */
	CHECK(fabs(pack_grain_volume(&p) - (vs + 299 * 4.0 / 3 * M_PI * 1e-15 + shape_volume(1e-5, 3e-5))) <=
	    1e-13 * pack_grain_volume(&p), "pack_grain_volume: spheres plus shape_volume(r, L) of the plate (%.17g, want %.17g)",
	    pack_grain_volume(&p), vs + 299 * 4.0 / 3 * M_PI * 1e-15 + shape_volume(1e-5, 3e-5));
	pack_free(&p);

	/* the round trip, plain and gzip */
	for (gz = 0; gz < 2; gz++) {
		snprintf(how, sizeof how, "shape columns round trip%s", gz ? " .gz" : "");
		snprintf(a, sizeof a, "%s/s-a.pack%s", dir, gz ? ".gz" : "");
		snprintf(b, sizeof b, "%s/s-b.pack%s", dir, gz ? ".gz" : "");
		build_shapes(&p);
		CHECK(pack_validate(&p) == 0, "%s: the built pack is valid (%s)", how, msg_geterr());
		CHECK(pack_write_path(&p, a) == 0, "%s: write", how);
		t = text_of(a);
		CHECK(t && strncmp(t, "qusgm-pack 2\n", 13) == 0 && strstr(t, "\nboundary walls walls walls\n") &&
		    strstr(t, "\ncolumns id x y z r E nu rho shape side qw qx qy qz\nend\n"),
		    "%s: version 2, 'columns id x y z r E nu rho shape side qw qx qy qz'", how);
		CHECK(t && strstr(t, " 2420.123456789123 sphere 0 1 0 0 0\n") && strstr(t, " spheroplate 1e-300 0.5 0.5 0.5 0.5\n") &&
		    strstr(t, " sphere -0 -0 0 0 -1\n"), "%s: the kind, side and q follow rho on each grain line", how);
		free(t);
		CHECK(pack_read_path(a, &q) == 0, "%s: read back (%s)", how, msg_geterr());
		check_fields(&p, &q, how);
		CHECK(pack_write_path(&q, b) == 0 && same_file(a, b, 0), "%s: write-read-write is byte-identical", how);
		pack_free(&p);
		pack_free(&q);
		unlink(a);
		unlink(b);
	}
	/* the same with a periodic axis: the two version-2 features together */
	snprintf(a, sizeof a, "%s/sp-a.pack", dir);
	snprintf(b, sizeof b, "%s/sp-b.pack", dir);
	build_periodic(&p);
	pack_set_shapes(&p);
	pack_set_grain_shape(&p, 0, 1.0 / 3.0, (const double[4]){0, 0, 1, 0});
	CHECK(pack_write_path(&p, a) == 0 && pack_read_path(a, &q) == 0 && pack_write_path(&q, b) == 0 &&
	    same_file(a, b, 0), "shape columns and a periodic axis: write-read-write is byte-identical");
	check_fields(&p, &q, "shape columns and a periodic axis");
	pack_free(&p);
	pack_free(&q);
	unlink(a);
	unlink(b);

	/* what pack_validate refuses, as the reader does */
	build_shapes(&s);
	s.side[2] = -1e-5;
	CHECK(pack_validate(&s) != 0 && strstr(msg_geterr(), "grain 86: side -1e-05 is negative"),
	    "pack_validate: a negative side (%s)", msg_geterr());
	s.side[2] = INFINITY;
	CHECK(pack_validate(&s) != 0 && strstr(msg_geterr(), "side inf is not finite"), "pack_validate: an infinite side (%s)",
	    msg_geterr());
	s.side[2] = NAN;
	CHECK(pack_validate(&s) != 0 && strstr(msg_geterr(), "is not finite"), "pack_validate: a NaN side (%s)", msg_geterr());
	s.side[2] = 2.5e-5;
	s.q[4] = 1 + 2e-6, s.q[5] = s.q[6] = s.q[7] = 0;
	CHECK(pack_validate(&s) != 0 && strstr(msg_geterr(), "grain 93: (qw, qx, qy, qz) = (1.000002, 0, 0, 0) is not a unit quaternion (norm 1.000002"),
	    "pack_validate: |q| - 1 = 2e-6 (%s)", msg_geterr());
	s.q[4] = 1 - 0.9e-6;
	CHECK(pack_validate(&s) == 0, "pack_validate: |q| - 1 = -0.9e-6 is within 1e-6 (%s)", msg_geterr());
	s.q[4] = 0.7071, s.q[5] = 0.7071;
	CHECK(pack_validate(&s) != 0 && strstr(msg_geterr(), "(norm 0.99999041"), "pack_validate: (0.7071, 0.7071, 0, 0), norm 1 - 9.6e-6 (%s)",
	    msg_geterr());
	s.q[4] = s.q[5] = 0.707107;
	CHECK(pack_validate(&s) == 0, "pack_validate: (0.707107, 0.707107, 0, 0), %%g's 6 digits, reads (%s)", msg_geterr());
	s.q[4] = NAN;
	CHECK(pack_validate(&s) != 0 && strstr(msg_geterr(), "not a unit quaternion"), "pack_validate: a NaN component (%s)",
	    msg_geterr());
	pack_free(&s);

	/* the plate-radius convention of the pack */
	build(&s);
	CHECK(pack_plate_radius(&s, &conv) == 0 && conv == SHAPE_R_EDGE, "pack_plate_radius: edge when the meta key is absent");
	pack_set_meta(&s, "plate-radius", "corner");
	CHECK(pack_plate_radius(&s, &conv) == 0 && conv == SHAPE_R_CORNER, "pack_plate_radius: meta plate-radius corner");
	pack_set_meta(&s, "plate-radius", "edge");
	CHECK(pack_plate_radius(&s, &conv) == 0 && conv == SHAPE_R_EDGE, "pack_plate_radius: meta plate-radius edge");
	pack_set_meta(&s, "plate-radius", "Edge");
	CHECK(pack_plate_radius(&s, &conv) != 0 && strcmp(msg_geterr(), "meta plate-radius 'Edge' is neither 'edge' nor 'corner'") == 0,
	    "pack_plate_radius: another value is refused (%s)", msg_geterr());
	pack_free(&s);
}

/* A small pack with the phase column for the reader's refusals: grain 2 hydrate; %s is the
 * columns line's names after rho, %s each grain's fields after rho. */
static const char phase_pack[] = "qusgm-pack 2\n"		/* 1 */
				 "units SI\n"			/* 2 */
				 "box 0 0 0 1 1 1\n"		/* 3 */
				 "boundary walls walls walls\n"	/* 4 */
				 "walls 7e12 0.3 0.3\n"		/* 5 */
				 "friction 0.3\n"		/* 6 */
				 "grains 2\n"			/* 7 */
				 "contacts 0\n"			/* 8 */
				 "columns id x y z r E nu rho%s\n"	/* 9 */
				 "end\n"			/* 10 */
				 "1 0.25 0.5 0.5 0.1 1e11 0.15 2650%s\n"	/* 11 */
				 "2 0.75 0.5 0.5 0.05 6.6e9 0.32 900%s\n";	/* 12 */

/* Write phase_pack with the given columns tail and grain tails, and read it: 0, or -1 with
 * the reader's message in the slot. */
static int
read_phase_pack(const char *path, const char *cols, const char *g1, const char *g2, struct pack *p)
{
	FILE *fp = fopen(path, "wb");

	if (!fp)
		return -1;
	fprintf(fp, phase_pack, cols, g1, g2);
	fclose(fp);
	return pack_read_path(path, p);
}

/* The phase column (0 mineral, 1 hydrate): storage and growth, the writer's version 2 and
 * its columns line, the round trip to the byte, with and without the shape columns, and what
 * the reader and pack_validate refuse. */
static void
phases(const char *dir)
{
	struct pack p, q;
	char a[160], b[160], in[160], how[64], *t;
	double x[3] = {0.5e-4, 0.5e-4, 0.5e-4}, vh;
	size_t k;
	int ok, sh;
	static const struct {
		const char *cols, *g1, *g2, *want;
	} bad[] = {
		{" phase", " 0", " 2", "p.pack:12: grain 2: phase '2' is neither 0 (mineral) nor 1 (hydrate)"},
		{" phase", " 0.5", " 1", "p.pack:11: grain 1: phase '0.5' is neither 0 (mineral) nor 1 (hydrate)"},
		{" phase", " 0", " -1", "p.pack:12: grain 2: phase '-1' is neither 0 (mineral) nor 1 (hydrate)"},
		{" phase", " 1.0", " 1", "p.pack:11: grain 1: phase '1.0' is neither 0 (mineral) nor 1 (hydrate)"},
		{" phase", " nan", " 1", "p.pack:11: grain 1: phase 'nan' is neither 0 (mineral) nor 1 (hydrate)"},
		{" phase", " 0", " hydrate", "p.pack:12: grain 2: phase 'hydrate' is neither 0 (mineral) nor 1 (hydrate)"},
		{" phase", " 0", "", "p.pack:12: grain line: expected 9 columns (id x y z r E nu rho phase), found 8"},
		{"", " 0", " 1", "p.pack:11: grain line: expected 8 columns (id x y z r E nu rho), found 9"},
		{" phase side qw qx qy qz", " 0 0 1 0 0 0", " 1 0 1 0 0 0",
		    "p.pack:9: columns: column 10 'side': the shape columns come before the phase columns"},
		{" phase phase", " 0 0", " 1 1", "p.pack:9: columns: column 'phase' named twice"},
		{" rho", " 0", " 1", "p.pack:9: columns: column 'rho' named twice"},
	};

	build(&p);
	CHECK(!p.has_phase && !p.phase && pack_grain_phase(&p, 0) == PHASE_MINERAL,
	    "a pack has no phase column until pack_set_phases: every grain mineral");
	CHECK(pack_hydrate_grains(&p, &vh) == 0 && vh == 0 && pack_hydrate_saturation(&p) == 0,
	    "no phase column: no hydrate grains, S = 0");
	CHECK(pack_set_phases(&p) == 0 && p.has_phase, "pack_set_phases");
	for (k = 0, ok = 1; k < p.n; k++)
		ok = ok && p.phase[k] == PHASE_MINERAL;
	CHECK(ok, "pack_set_phases: every grain mineral");
	CHECK(pack_format_version(&p) == 2, "pack_format_version: 2 with the phase column");
	for (k = 0, ok = 1; k < 300; k++) {
		x[0] = 1e-7 * (double)(k + 1);
		ok = ok && pack_add_grain(&p, 1000 + (long)k, x, 1e-5, 7e10, 0.2, 2420) != (size_t)-1;
	}
	for (k = 0; k < p.n; k++)
		ok = ok && p.phase[k] == PHASE_MINERAL;
	CHECK(ok && p.n == 305 && p.cap >= 305, "pack_add_grain with the phase column: 300 more grains, each mineral");
	pack_free(&p);

	for (sh = 0; sh < 2; sh++) {
		snprintf(how, sizeof how, "phase column round trip%s", sh ? " with the shape columns" : "");
		snprintf(a, sizeof a, "%s/ph-a.pack", dir);
		snprintf(b, sizeof b, "%s/ph-b.pack", dir);
		if (sh)
			build_shapes(&p);
		else
			build(&p);
		pack_set_phases(&p);
		p.phase[1] = p.phase[4] = PHASE_HYDRATE;
		CHECK(pack_validate(&p) == 0, "%s: the built pack is valid (%s)", how, msg_geterr());
		CHECK(pack_write_path(&p, a) == 0, "%s: write", how);
		t = text_of(a);
		CHECK(t && strncmp(t, "qusgm-pack 2\n", 13) == 0 &&
		    strstr(t, sh ? "\ncolumns id x y z r E nu rho shape side qw qx qy qz phase\nend\n" : "\ncolumns id x y z r E nu rho phase\nend\n"),
		    "%s: version 2, the columns line ends in phase", how);
		CHECK(t && strstr(t, sh ? " 2420.123456789123 sphere 0 1 0 0 0 0\n" : " 2420.123456789123 0\n") &&
		    strstr(t, sh ? " sphere -0 -0 0 0 -1 1\n" : " 2420.123456789123 1\n"), "%s: the tag last on each grain line, 0 or 1", how);
		free(t);
		CHECK(pack_read_path(a, &q) == 0, "%s: read back (%s)", how, msg_geterr());
		check_fields(&p, &q, how);
		CHECK(q.has_phase && memcmp(p.phase, q.phase, p.n) == 0, "%s: the phases read back", how);
		CHECK(pack_write_path(&q, b) == 0 && same_file(a, b, 0), "%s: write-read-write is byte-identical", how);
		pack_free(&p);
		pack_free(&q);
		unlink(a);
		unlink(b);
	}

	/* a hand-written pack: reads, S and the volumes from its own numbers */
	snprintf(in, sizeof in, "%s/p.pack", dir);
	CHECK(read_phase_pack(in, " phase", " 0", " 1", &p) == 0, "the phase pack reads (%s)", msg_geterr());
	CHECK(p.has_phase && p.phase[0] == PHASE_MINERAL && p.phase[1] == PHASE_HYDRATE && pack_grain_phase(&p, 1) == PHASE_HYDRATE,
	    "the phase pack: grain 1 mineral, grain 2 hydrate");
	CHECK(pack_hydrate_grains(&p, &vh) == 1 && fabs(vh - 4.0 / 3.0 * M_PI * 1.25e-4) <= 1e-15 * vh,
	    "pack_hydrate_grains: one, 4/3 pi 0.05^3 (%.17g)", vh);
	CHECK_CLOSE(pack_hydrate_saturation(&p), 4.0 / 3.0 * M_PI * 1.25e-4 / (1 - 4.0 / 3.0 * M_PI * 1e-3), 1e-14,
	    "pack_hydrate_saturation: V_h / (V_box - V_mineral)");
	p.phase[1] = 2;
	CHECK(pack_validate(&p) != 0 && strcmp(msg_geterr(), "grain 2: phase 2 is neither 0 (mineral) nor 1 (hydrate)") == 0,
	    "pack_validate: phase 2 (%s)", msg_geterr());
	pack_free(&p);
	CHECK(read_phase_pack(in, " side qw qx qy qz phase", " 0 1 0 0 0 1", " 0 1 0 0 0 0", &p) == 0 && p.has_shapes &&
	    p.has_phase && p.phase[0] == PHASE_HYDRATE, "the shape columns then phase read (%s)", msg_geterr());
	pack_free(&p);
	for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		int rc = read_phase_pack(in, bad[k].cols, bad[k].g1, bad[k].g2, &p);
		const char *e = rc ? msg_geterr() : "";
		size_t le = strlen(e), lw = strlen(bad[k].want);

		CHECK(rc != 0 && le >= lw && strcmp(e + le - lw, bad[k].want) == 0, "refused: columns '%s', grains '%s' '%s': '%s' (want '%s')",
		    bad[k].cols, bad[k].g1, bad[k].g2, e, bad[k].want);
		if (!rc)
			pack_free(&p);
	}
	unlink(in);
}

/* The glued column ('-' free or a wall name): the reader, the writer's version 2 and the
 * round trip to the byte (after the phase column), an old pack without it (every grain
 * free), and the refusals. */
static void
glued_column(const char *dir)
{
	struct pack p, q;
	char in[160], b[160], *t;
	size_t k;
	static const struct {
		const char *cols, *g1, *g2, *want;
	} bad[] = {
		{" glued", " -", " 1", "p.pack:12: grain 2: glued '1' is neither '-' (free) nor a wall (xlo ... zhi)"},
		{" glued", " top", " -", "p.pack:11: grain 1: glued 'top' is neither '-' (free) nor a wall (xlo ... zhi)"},
		{" glued phase", " - 0", " - 1", "p.pack:9: columns: column 10 'phase': the phase columns come before the glued columns"},
	};

	snprintf(in, sizeof in, "%s/p.pack", dir);
	snprintf(b, sizeof b, "%s/p2.pack", dir);
	CHECK(read_phase_pack(in, "", "", "", &p) == 0 && !p.has_glue && !pack_grain_glued(&p, 0) && !pack_grain_glued(&p, 1),
	    "a pack without the glued column: every grain free (%s)", msg_geterr());
	pack_free(&p);
	CHECK(read_phase_pack(in, " phase glued", " 0 ylo", " 1 -", &p) == 0, "phase then glued reads (%s)", msg_geterr());
	CHECK(p.has_glue && p.glue[0] == 1 + WALL_YLO && p.glue[1] == 0 && pack_grain_glued(&p, 0) && !pack_grain_glued(&p, 1),
	    "glued: grain 1 on ylo (1 + %d), grain 2 free", WALL_YLO);
	CHECK(pack_write_path(&p, b) == 0, "glued: write");
	t = text_of(b);
	CHECK(t && strstr(t, "\ncolumns id x y z r E nu rho phase glued\nend\n") && strstr(t, " 2650 0 ylo\n") && strstr(t, " 900 1 -\n"),
	    "glued: the column last, '-' or the wall's name");
	free(t);
	CHECK(pack_read_path(b, &q) == 0 && q.has_glue && memcmp(p.glue, q.glue, p.n) == 0, "glued: read back");
	pack_free(&q);
	CHECK(pack_copy(&q, &p) == 0 && q.has_glue && q.glue[0] == 1 + WALL_YLO, "glued: pack_copy keeps it");
	pack_free(&q);
	p.periodic[1] = 1;
	CHECK(pack_validate(&p) != 0 && strcmp(msg_geterr(), "grain 1: glued to ylo, but that axis is periodic") == 0,
	    "pack_validate: glued to a wall of a periodic axis (%s)", msg_geterr());
	pack_free(&p);
	for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		int rc = read_phase_pack(in, bad[k].cols, bad[k].g1, bad[k].g2, &p);
		const char *e = rc ? msg_geterr() : "";
		size_t le = strlen(e), lw = strlen(bad[k].want);

		CHECK(rc != 0 && le >= lw && strcmp(e + le - lw, bad[k].want) == 0, "refused: columns '%s', grains '%s' '%s': '%s' (want '%s')",
		    bad[k].cols, bad[k].g1, bad[k].g2, e, bad[k].want);
		if (!rc)
			pack_free(&p);
	}
	unlink(in);
	unlink(b);
}

int
main(void)
{
	char dir[] = "/tmp/qusgm-test-packio.XXXXXX", a[128], b[128];

	if (!mkdtemp(dir)) {
		CHECK(0, "mkdtemp");
		return unit_summary();
	}
	snprintf(a, sizeof a, "%s/a.pack", dir);
	snprintf(b, sizeof b, "%s/b.pack", dir);
	round_trip(a, b, 0);
	{
		char ag[128], bg[128];
		snprintf(ag, sizeof ag, "%s/a.pack.gz", dir);
		snprintf(bg, sizeof bg, "%s/b.pack.gz", dir);
		round_trip(ag, bg, 1);
		CHECK(same_file(ag, bg, 0), "round trip .gz: the compressed bytes are identical too");
		CHECK(!same_file(ag, a, 0), "a .gz name compresses");
		CHECK(same_file(ag, a, 1), "the .gz file holds exactly the plain file's bytes");
		unlink(ag);
		unlink(bg);
	}
	two_in_a_stream(b);
	format_2(dir);
	shapes(dir);
	phases(dir);
	glued_column(dir);
	carriage_returns(dir);
	unlink(a);
	unlink(b);
	rmdir(dir);
	numfmt_hand();
	numfmt_random();
	numparse_strict();
	return unit_summary();
}
