/* packio: the strict pack reader and the round-trip-exact writer (see packio.h). */
#include "pack/packio.h"
#include "base/fileio.h"
#include "base/msg.h"
#include "base/numfmt.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#define MAXTOK 16

struct pack_reader {
	gzFile gz;
	char *name;
	long line;		/* number of the line in buf */
	char *chunk;		/* raw bytes from gzread */
	size_t chunk_len, chunk_pos;
	int eof, failed;
	char *buf;		/* current line */
	size_t cap;
	int have_pushback;	/* buf holds a line to be returned again */
	int newline;		/* the line in buf ended with a newline */
};

struct pack_reader *
pack_reader_open(FILE *fp, const char *name)
{
	struct pack_reader *rd = calloc(1, sizeof *rd);
	int fd;

	if (!rd) {
		msg_seterr("out of memory");
		return NULL;
	}
	rd->name = strdup(name);
	rd->chunk = malloc(1 << 16);
	fd = dup(fileno(fp));
	if (!rd->name || !rd->chunk || fd < 0 || !(rd->gz = gzdopen(fd, "rb"))) {
		msg_seterr("%s: cannot open for reading", name);
		if (fd >= 0 && !rd->gz)
			close(fd);
		pack_reader_close(rd);
		return NULL;
	}
	gzbuffer(rd->gz, 1 << 17);
	return rd;
}

void
pack_reader_close(struct pack_reader *rd)
{
	if (!rd)
		return;
	if (rd->gz)
		gzclose(rd->gz);
	free(rd->name);
	free(rd->chunk);
	free(rd->buf);
	free(rd);
}

const char *
pack_reader_name(const struct pack_reader *rd)
{
	return rd->name;
}

static int
rd_error(struct pack_reader *rd, const char *fmt, ...)
{
	char what[512];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(what, sizeof what, fmt, ap);
	va_end(ap);
	msg_seterr("%s:%ld: %s", rd->name, rd->line > 0 ? rd->line : 1, what);
	rd->failed = 1;
	return -1;
}

/* zlib's message without its "<fd:N>: " prefix, which would make the text depend on
 * descriptor numbers. */
static const char *
gz_message(gzFile gz, int *err)
{
	const char *m = gzerror(gz, err), *c;

	if (strncmp(m, "<fd:", 4) == 0 && (c = strstr(m, ">: ")))
		return c + 3;
	return m;
}

static int
fill_chunk(struct pack_reader *rd)
{
	int n, err;
	const char *msg;

	if (rd->eof)
		return 0;
	n = gzread(rd->gz, rd->chunk, 1 << 16);
	if (n < 0) {
		msg = gz_message(rd->gz, &err);
		rd->line++;
		return rd_error(rd, "corrupt or truncated input (%s)", err == Z_BUF_ERROR ?
		    "unexpected end of compressed data" : msg);
	}
	if (n == 0) {
		/* zlib reports a truncated gzip stream as end of file plus an error state. */
		msg = gz_message(rd->gz, &err);
		if (err != Z_OK && err != Z_STREAM_END) {
			rd->line++;
			return rd_error(rd, "corrupt or truncated input (%s)", msg);
		}
		rd->eof = 1;
		return 0;
	}
	rd->chunk_len = (size_t)n;
	rd->chunk_pos = 0;
	return 1;
}

/* 1: a line in rd->buf (newline stripped); 0: end of input; -1: error. */
static int
next_line(struct pack_reader *rd)
{
	size_t len = 0;
	int got = 0;

	if (rd->have_pushback) {
		rd->have_pushback = 0;
		rd->line++;
		return 1;
	}
	for (;;) {
		char *nl;
		size_t take;

		if (rd->chunk_pos == rd->chunk_len) {
			int f = fill_chunk(rd);
			if (f < 0)
				return -1;
			if (f == 0)
				break;
		}
		nl = memchr(rd->chunk + rd->chunk_pos, '\n', rd->chunk_len - rd->chunk_pos);
		take = nl ? (size_t)(nl - (rd->chunk + rd->chunk_pos)) : rd->chunk_len - rd->chunk_pos;
		if (len + take + 1 > rd->cap) {
			size_t cap = 2 * (len + take + 1);
			char *b = realloc(rd->buf, cap);
			if (!b)
				return rd_error(rd, "out of memory");
			rd->buf = b;
			rd->cap = cap;
		}
		memcpy(rd->buf + len, rd->chunk + rd->chunk_pos, take);
		len += take;
		rd->chunk_pos += take + (nl ? 1 : 0);
		got = 1;
		rd->newline = nl != NULL;
		if (nl)
			break;
	}
	if (!got)
		return 0;
	rd->buf[len] = 0;
	if (len > 0 && rd->buf[len - 1] == '\r')
		rd->buf[len - 1] = 0;
	rd->line++;
	if (strlen(rd->buf) + 1 < len)
		return rd_error(rd, "binary data (NUL byte) in a text pack");
	return 1;
}

int
pack_reader_line(struct pack_reader *rd, const char **line, long *lineno, int *newline)
{
	int r = next_line(rd);

	if (r == 1) {
		*line = rd->buf;
		*lineno = rd->line;
		*newline = rd->newline;
	}
	return r;
}

static int
split(char *s, char **tok, int max)
{
	int n = 0;

	for (;;) {
		while (*s == ' ' || *s == '\t')
			s++;
		if (!*s)
			return n;
		if (n == max)
			return max + 1;
		tok[n++] = s;
		while (*s && *s != ' ' && *s != '\t')
			s++;
		if (*s)
			*s++ = 0;
	}
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
	else if (!(p->nu[i] > -1 && p->nu[i] < 0.5))
		snprintf(why, len, "grain %ld: Poisson ratio %g is outside (-1, 0.5)", p->id[i], p->nu[i]);
	else if (!(p->rho[i] > 0))
		snprintf(why, len, "grain %ld: density %g is not positive", p->id[i], p->rho[i]);
	else {
		for (a = 0; a < 3; a++)
			if (x[a] < p->box[a] || x[a] > p->box[a + 3]) {
				snprintf(why, len, "grain %ld: centre %c = %g is outside the box [%g, %g]",
				    p->id[i], 'x' + a, x[a], p->box[a], p->box[a + 3]);
				return why;
			}
		return NULL;
	}
	return why;
}

static const size_t *sort_ids_base;
static const long *sort_ids_id;

static int
cmp_by_id(const void *a, const void *b)
{
	long x = sort_ids_id[*(const size_t *)a], y = sort_ids_id[*(const size_t *)b];

	(void)sort_ids_base;
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

static int
cmp_pair(const void *a, const void *b)
{
	const long *x = a, *y = b;

	if (x[0] != y[0])
		return x[0] < y[0] ? -1 : 1;
	if (x[1] != y[1])
		return x[1] < y[1] ? -1 : 1;
	return x[2] < y[2] ? -1 : x[2] > y[2];
}

/* Finds a contact pair listed twice; returns the later contact index or (size_t)-1. */
static size_t
find_duplicate_contact(const struct pack *p)
{
	long *t = malloc((p->nc ? p->nc : 1) * 3 * sizeof *t);
	size_t k, found = (size_t)-1;

	if (!t)
		return (size_t)-1;
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
	qsort(t, p->nc, 3 * sizeof *t, cmp_pair);
	for (k = 1; k < p->nc; k++)
		if (t[3 * k] == t[3 * k - 3] && t[3 * k + 1] == t[3 * k - 2]) {
			size_t later = (size_t)(t[3 * k + 2] > t[3 * k - 1] ? t[3 * k + 2] : t[3 * k - 1]);
			if (found == (size_t)-1 || later < found)
				found = later;
		}
	free(t);
	return found;
}

enum { H_UNITS, H_BOX, H_REFBOX, H_WALLS, H_FRICTION, H_GRAINS, H_CONTACTS, NH };
static const char *const hkeys[NH] = {"units", "box", "refbox", "walls", "friction", "grains", "contacts"};
static const int hrequired[NH] = {1, 1, 0, 1, 1, 1, 1};

static int
read_header(struct pack_reader *rd, struct pack *p, long *ngr, long *nco)
{
	int seen[NH] = {0};
	char *tok[MAXTOK + 1];
	int r, n, k;
	double v[6];

	for (;;) {
		r = next_line(rd);
		if (r < 0)
			return -1;
		if (r == 0)
			return rd->line++, rd_error(rd, "unexpected end of input in the header (no 'end' line)");
		if (rd->buf[0] == '#')
			continue;
		if (strncmp(rd->buf, "history", 7) == 0 && (rd->buf[7] == ' ' || rd->buf[7] == '\t')) {
			if (pack_add_history(p, rd->buf + 8))
				return rd_error(rd, "out of memory");
			continue;
		}
		if (strncmp(rd->buf, "meta", 4) == 0 && (rd->buf[4] == ' ' || rd->buf[4] == '\t')) {
			char *key = rd->buf + 5, *val;
			while (*key == ' ' || *key == '\t')
				key++;
			val = key + strcspn(key, " \t");
			if (!*key || !*val)
				return rd_error(rd, "meta: expected a key and a value");
			*val++ = 0;
			while (*val == ' ' || *val == '\t')
				val++;
			if (!*val)
				return rd_error(rd, "meta: expected a key and a value");
			if (pack_get_meta(p, key))
				return rd_error(rd, "meta: duplicate key '%s'", key);
			if (pack_set_meta(p, key, val))
				return rd_error(rd, "out of memory");
			continue;
		}
		n = split(rd->buf, tok, MAXTOK);
		if (n == 0)
			return rd_error(rd, "empty line in the header");
		if (strcmp(tok[0], "end") == 0) {
			if (n != 1)
				return rd_error(rd, "end: unexpected text after 'end'");
			break;
		}
		for (k = 0; k < NH; k++)
			if (strcmp(tok[0], hkeys[k]) == 0)
				break;
		if (k == NH)
			return rd_error(rd, "unknown header keyword '%s'", tok[0]);
		if (seen[k])
			return rd_error(rd, "duplicate '%s' line (the header must contain exactly one)", tok[0]);
		seen[k] = 1;
		switch (k) {
		case H_UNITS:
			if (n != 2 || strcmp(tok[1], "SI") != 0)
				return rd_error(rd, "units: only 'units SI' is defined");
			break;
		case H_BOX:
		case H_REFBOX:
			if (n != 7)
				return rd_error(rd, "%s: expected 6 numbers (xlo ylo zlo xhi yhi zhi), found %d",
				    tok[0], n - 1);
			if (parse_numbers(rd, tok + 1, 6, v, tok[0]) || check_box(rd, v, tok[0]))
				return -1;
			memcpy(k == H_BOX ? p->box : p->refbox, v, sizeof v);
			if (k == H_REFBOX)
				p->has_refbox = 1;
			break;
		case H_WALLS:
			if (n != 4)
				return rd_error(rd, "walls: expected 3 numbers (E nu mu), found %d", n - 1);
			if (parse_numbers(rd, tok + 1, 3, v, "walls"))
				return -1;
			if (!(v[0] > 0))
				return rd_error(rd, "walls: Young's modulus %g is not positive", v[0]);
			if (!(v[1] > -1 && v[1] < 0.5))
				return rd_error(rd, "walls: Poisson ratio %g is outside (-1, 0.5)", v[1]);
			if (!(v[2] >= 0))
				return rd_error(rd, "walls: friction coefficient %g is negative", v[2]);
			p->wall_E = v[0];
			p->wall_nu = v[1];
			p->wall_mu = v[2];
			break;
		case H_FRICTION:
			if (n != 2)
				return rd_error(rd, "friction: expected 1 number (mu), found %d", n - 1);
			if (parse_numbers(rd, tok + 1, 1, v, "friction"))
				return -1;
			if (!(v[0] >= 0))
				return rd_error(rd, "friction: coefficient %g is negative", v[0]);
			p->mu = v[0];
			break;
		case H_GRAINS:
		case H_CONTACTS: {
			long cnt;
			if (n != 2)
				return rd_error(rd, "%s: expected 1 count, found %d", tok[0], n - 1);
			if (num_parse_long(tok[1], &cnt) || cnt < (k == H_GRAINS ? 1 : 0) || cnt > 1000000000L)
				return rd_error(rd, "%s: '%s' is not a valid count", tok[0], tok[1]);
			*(k == H_GRAINS ? ngr : nco) = cnt;
			break;
		}
		}
	}
	for (k = 0; k < NH; k++)
		if (hrequired[k] && !seen[k])
			return rd_error(rd, "missing '%s' line in the header", hkeys[k]);
	return 0;
}

static int
read_grains(struct pack_reader *rd, struct pack *p, long ngr, size_t **sorted)
{
	char *tok[MAXTOK + 1];
	char why[256];
	long k, first = rd->line + 1;
	size_t dup;

	if (pack_reserve(p, (size_t)ngr))
		return rd_error(rd, "out of memory for %ld grains", ngr);
	for (k = 0; k < ngr; k++) {
		double v[7];
		long id;
		int r = next_line(rd), n;

		if (r < 0)
			return -1;
		if (r == 0)
			return rd->line++, rd_error(rd, "unexpected end of input: %ld grains declared, %ld found",
			    ngr, k);
		n = split(rd->buf, tok, MAXTOK);
		if (n != 8)
			return rd_error(rd, "grain line: expected 8 columns (id x y z r E nu rho), found %d", n);
		if (num_parse_long(tok[0], &id))
			return rd_error(rd, "grain id '%s' is not an integer", tok[0]);
		if (parse_numbers(rd, tok + 1, 7, v, "grain"))
			return -1;
		pack_add_grain(p, id, v, v[3], v[4], v[5], v[6]);
		if (check_grain_values(p, p->n - 1, why, sizeof why))
			return rd_error(rd, "%s", why);
	}
	*sorted = sort_by_id(p, &dup);
	if (!*sorted)
		return rd_error(rd, "out of memory");
	if (dup != (size_t)-1) {
		rd->line = first + (long)dup;
		return rd_error(rd, "duplicate grain id %ld", p->id[dup]);
	}
	return 0;
}

static int
parse_end(struct pack_reader *rd, const struct pack *p, const size_t *sorted, const char *s,
    long *out, int allow_wall)
{
	long id;
	int w;

	if (allow_wall)
		for (w = 0; w < NWALLS; w++)
			if (strcmp(s, pack_wall_names[w]) == 0) {
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

static int
read_contacts(struct pack_reader *rd, struct pack *p, long nco, const size_t *sorted)
{
	char *tok[MAXTOK + 1];
	long k, first = rd->line + 1;
	size_t dup;

	for (k = 0; k < nco; k++) {
		struct pack_contact c;
		long i, j;
		double v[5];
		int r = next_line(rd), n;

		if (r < 0)
			return -1;
		if (r == 0)
			return rd->line++, rd_error(rd, "unexpected end of input: %ld contacts declared, %ld found",
			    nco, k);
		n = split(rd->buf, tok, MAXTOK);
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
		c.i = (size_t)i;
		c.j = j;
		c.P0 = v[0];
		memcpy(c.Q0, v + 1, sizeof c.Q0);
		c.M0 = v[4];
		if (pack_add_contact(p, &c))
			return rd_error(rd, "out of memory");
	}
	dup = find_duplicate_contact(p);
	if (dup != (size_t)-1) {
		rd->line = first + (long)dup;
		return rd_error(rd, "contact pair listed twice");
	}
	return 0;
}

int
pack_read_next(struct pack_reader *rd, struct pack *p)
{
	char *tok[MAXTOK + 1];
	long ngr = 0, nco = 0, version;
	size_t *sorted = NULL;
	int r, n, status;

	pack_init(p);
	if (rd->failed)
		return -1;
	r = next_line(rd);
	if (r <= 0) {
		if (r == 0 && rd->line == 0)
			return rd->line++, rd_error(rd, "empty input (expected '%s %d')", PACK_FORMAT_NAME,
			    PACK_FORMAT_VERSION);
		return r;
	}
	n = split(rd->buf, tok, MAXTOK);
	if (n < 1 || strcmp(tok[0], PACK_FORMAT_NAME) != 0)
		return rd_error(rd, "not a qusgm pack (first line must be '%s %d')", PACK_FORMAT_NAME,
		    PACK_FORMAT_VERSION);
	if (n != 2 || num_parse_long(tok[1], &version))
		return rd_error(rd, "%s: missing or malformed version", PACK_FORMAT_NAME);
	if (version > PACK_FORMAT_VERSION)
		return rd_error(rd, "pack format version %ld is newer than this qusgm reads (%d); upgrade qusgm",
		    version, PACK_FORMAT_VERSION);
	if (version != PACK_FORMAT_VERSION)
		return rd_error(rd, "unknown pack format version %ld", version);
	status = read_header(rd, p, &ngr, &nco);
	if (status == 0)
		status = read_grains(rd, p, ngr, &sorted);
	if (status == 0)
		status = read_contacts(rd, p, nco, sorted);
	free(sorted);
	if (status) {
		pack_free(p);
		return -1;
	}
	/* What follows must be another pack or nothing. */
	r = next_line(rd);
	if (r < 0) {
		pack_free(p);
		return -1;
	}
	if (r == 1) {
		if (strncmp(rd->buf, PACK_FORMAT_NAME, strlen(PACK_FORMAT_NAME)) != 0) {
			pack_free(p);
			return rd_error(rd, "unexpected line after the last contact (counts in the header are %ld grains, %ld contacts)",
			    ngr, nco);
		}
		rd->have_pushback = 1;
		rd->line--;
	}
	return 1;
}

int
pack_read_path(const char *path, struct pack *p)
{
	const char *name;
	FILE *fp = file_in_open(path, &name);
	struct pack_reader *rd;
	struct pack extra;
	int r;

	pack_init(p);
	if (!fp)
		return -1;
	rd = pack_reader_open(fp, name);
	if (!rd) {
		if (fp != stdin)
			fclose(fp);
		return -1;
	}
	r = pack_read_next(rd, p);
	if (r == 1) {
		long line = rd->line + 1;
		int r2 = pack_read_next(rd, &extra);
		if (r2 == 1) {
			pack_free(&extra);
			pack_free(p);
			msg_seterr("%s:%ld: a second pack follows; this tool reads one pack", name, line);
			r = -1;
		} else if (r2 < 0) {
			pack_free(p);
			r = -1;
		}
	} else if (r == 0) {
		msg_seterr("%s:1: empty input", name);
		r = -1;
	}
	pack_reader_close(rd);
	if (fp != stdin)
		fclose(fp);
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

static void
format_pack(const struct pack *p, struct sbuf *b)
{
	size_t k;
	double v[7];

	sb_printf(b, "%s %d\n", PACK_FORMAT_NAME, PACK_FORMAT_VERSION);
	for (k = 0; k < p->nhist; k++)
		sb_printf(b, "history %s\n", p->history[k]);
	for (k = 0; k < p->nmeta; k++)
		sb_printf(b, "meta %s %s\n", p->meta[k].key, p->meta[k].value);
	sb_puts(b, "units SI\nbox ");
	sb_nums(b, p->box, 6);
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
	sb_printf(b, "grains %zu\ncontacts %zu\nend\n", p->n, p->nc);
	for (k = 0; k < p->n && !b->oom; k++) {
		sb_printf(b, "%ld ", p->id[k]);
		memcpy(v, p->x + 3 * k, 3 * sizeof *v);
		v[3] = p->r[k];
		v[4] = p->E[k];
		v[5] = p->nu[k];
		v[6] = p->rho[k];
		sb_nums(b, v, 7);
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
	if (!(p->wall_E > 0) || !(p->wall_nu > -1 && p->wall_nu < 0.5) || !(p->wall_mu >= 0) || !(p->mu >= 0)) {
		msg_seterr("walls or friction out of range");
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
	s = sort_by_id(p, &dup);
	free(s);
	if (dup != (size_t)-1) {
		msg_seterr("duplicate grain id %ld", p->id[dup]);
		return -1;
	}
	return 0;
}
