/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_lines: the line reader behind every qusgm reader (lib/base/lines.h).
 *
 * Each check writes a small file (plain, or gzip through zlib), reads it back through
 * lines_open_path or lines_open, and compares the lines, their numbers, the newline flag
 * and the error messages exactly. */
#include "base/lines.h"
#include "base/msg.h"
#include "unit.h"

#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

static char dir[] = "/tmp/qusgm-test-lines.XXXXXX";

/* dir/name, in a static buffer of its own per call site (callers copy when they need two). */
static const char *
path_of(const char *name)
{
	static char buf[256];

	snprintf(buf, sizeof buf, "%s/%s", dir, name);
	return buf;
}

static void
write_file(const char *path, const char *data, size_t len)
{
	FILE *fp = fopen(path, "wb");

	if (!fp || fwrite(data, 1, len, fp) != len || fclose(fp) != 0)
		CHECK(0, "write %s", path);
}

/* The gzip form of data in memory (a whole gzip file), length in *zlen. */
static char *
gzip_bytes(const char *data, size_t len, size_t *zlen)
{
	const char *tmp = path_of("gz.tmp");
	gzFile z = gzopen(tmp, "wb6");
	FILE *fp;
	char *buf;
	long n;

	if (!z || gzwrite(z, data, (unsigned)len) != (int)len || gzclose(z) != Z_OK)
		return NULL;
	fp = fopen(tmp, "rb");
	fseek(fp, 0, SEEK_END);
	n = ftell(fp);
	rewind(fp);
	buf = malloc((size_t)n);
	*zlen = fread(buf, 1, (size_t)n, fp);
	fclose(fp);
	unlink(tmp);
	return buf;
}

/* Every line of path, joined with '|', each followed by '$' when it ended with a newline
 * (a CR in a line written as the two characters \r);
 * the status of the last lines_next in *status and the number of lines in *count. */
static char *
read_all(const char *path, int *status, long *count)
{
	struct lines *in = lines_open_path(path);
	size_t cap = 64, used = 0, len;
	char *out = malloc(cap), *s;
	int r = -1;

	out[0] = 0;
	*count = 0;
	if (!in) {
		*status = -2;
		return out;
	}
	while ((r = lines_next(in, &s, &len)) == 1) {
		if (strlen(s) != len)
			CHECK(0, "lines_next: the length %zu is the string's (%zu)", len, strlen(s));
		if (used + 2 * len + 3 > cap) {
			cap = 2 * (used + 2 * len + 3);
			out = realloc(out, cap);
		}
		if (used)
			out[used++] = '|';
		for (; *s; s++)	/* a CR shown as \r, so that the report stays one line */
			if (*s == '\r') {
				out[used++] = '\\';
				out[used++] = 'r';
			} else {
				out[used++] = *s;
			}
		if (lines_newline(in))
			out[used++] = '$';
		out[used] = 0;
		if (lines_lineno(in) != ++*count)
			CHECK(0, "lines_lineno %ld after %ld lines", lines_lineno(in), *count);
	}
	*status = r;
	lines_close(in);
	return out;
}

/* The lines of data, read plain and gzipped, must be want ("|"-joined as read_all). */
static void
expect_lines(const char *what, const char *data, size_t len, const char *want, long nlines)
{
	size_t zlen = 0;
	char *z = gzip_bytes(data, len, &zlen), *got;
	int st, gz;
	long n;

	for (gz = 0; gz < 2; gz++) {
		const char *p = path_of(gz ? "in.gz" : "in.txt");
		if (gz)
			write_file(p, z, zlen);
		else
			write_file(p, data, len);
		got = read_all(p, &st, &n);
		CHECK(st == 0 && strcmp(got, want) == 0 && n == nlines, "%s%s: '%.60s' (status %d, %ld lines; want '%.60s', %ld)",
		    what, gz ? " (gzip)" : "", got, st, n, want, nlines);
		free(got);
		unlink(p);
	}
	free(z);
}

static void
test_shapes(void)
{
	expect_lines("LF lines", "a b\nc\n", 6, "a b$|c$", 2);
	expect_lines("CRLF lines: the CR before each LF is dropped", "a\r\nb\r\n", 6, "a$|b$", 2);
	expect_lines("a CR inside a line is kept", "a\rb\n", 4, "a\\rb$", 1);
	expect_lines("only one CR before the LF is dropped", "x\r\r\n", 4, "x\\r$", 1);
	expect_lines("last line without a newline: read, flagged", "a\nlast", 6, "a$|last", 2);
	expect_lines("last line without a newline, ending in CR", "a\r\nb\r", 5, "a$|b", 2);
	expect_lines("empty lines", "\n\n\n", 3, "$|$|$", 3);
	expect_lines("empty input", "", 0, "", 0);
	expect_lines("nothing after the last newline: no extra line", "x\n", 2, "x$", 1);
}

/* A line of 200 000 bytes (three 64 KiB read chunks and more) between two short ones. */
static void
test_long_line(void)
{
	size_t n = 200000, k;
	char *data = malloc(n + 16), *want = malloc(n + 16);

	memcpy(data, "first\n", 6);
	for (k = 0; k < n; k++)
		data[6 + k] = (char)('a' + k % 26);
	memcpy(data + 6 + n, "\r\nend\n", 6);
	memcpy(want, "first$|", 7);
	memcpy(want + 7, data + 6, n);
	strcpy(want + 7 + n, "$|end$");
	expect_lines("a 200000-byte line is read whole", data, n + 12, want, 3);
	free(data);
	free(want);
}

/* The first error of data, read plain: status, message. */
static void
expect_error(const char *what, const char *name, const char *data, size_t len, const char *msg)
{
	const char *p = path_of(name);
	char *got;
	int st;
	long n;

	write_file(p, data, len);
	got = read_all(p, &st, &n);
	CHECK(st == -1 && strcmp(msg_geterr(), msg) == 0, "%s: '%s' (status %d; want '%s')", what, msg_geterr(), st,
	    msg);
	free(got);
	unlink(p);
}

static void
test_nul(void)
{
	char want[300];

	snprintf(want, sizeof want, "%s/nul.txt:2: binary data (NUL byte) in a text file", dir);
	expect_error("a NUL byte inside a line", "nul.txt", "ok\na\0b\nc\n", 8, want);
	expect_error("a NUL byte at the end of a line", "nul.txt", "ok\nab\0\nc\n", 8, want);
	expect_error("a line that is one NUL byte", "nul.txt", "ok\n\0\n", 5, want);
	expect_error("a NUL byte in a last line without newline", "nul.txt", "ok\nab\0", 6, want);
}

/* A gzip file cut at several places: one error naming the file and the line being read,
 * never a clean end of a shortened input (cut in the 8-byte trailer, every line may have
 * come out before the error). */
static void
test_truncated_gz(void)
{
	char data[30000], want[400], *z, *got;
	size_t zlen, cuts[4], k;
	const char *p;
	int st, line_ok;
	long n;

	for (k = 0; k < 1000; k++)
		memcpy(data + 29 * k, "0.001 0.002 0.003 0.00040000\n", 29);
	z = gzip_bytes(data, 29000, &zlen);
	cuts[0] = 20;
	cuts[1] = zlen / 2;
	cuts[2] = zlen - 4;
	cuts[3] = zlen - 1;
	p = path_of("cut.gz");
	for (k = 0; k < 4; k++) {
		write_file(p, z, cuts[k]);
		got = read_all(p, &st, &n);
		snprintf(want, sizeof want, "%s:%ld: corrupt or truncated input (", p, n + 1);
		line_ok = strncmp(msg_geterr(), want, strlen(want)) == 0;
		CHECK(st == -1 && line_ok, "gzip cut at %zu of %zu bytes: '%s' after %ld whole lines", cuts[k],
		    zlen, msg_geterr(), n);
		free(got);
	}
	/* corrupt, not cut: the CRC of the data in the trailer is wrong */
	z[zlen - 6] ^= 0x55;
	write_file(p, z, zlen);
	got = read_all(p, &st, &n);
	snprintf(want, sizeof want, "%s:%ld: corrupt or truncated input (incorrect data check)", p, n + 1);
	CHECK(st == -1 && strcmp(msg_geterr(), want) == 0, "a gzip stream with a wrong CRC: '%s' after %ld lines",
	    msg_geterr(), n);
	free(got);
	unlink(p);
	free(z);
}

/* Several gzip members read as one stream, as gzip -d reads them; anything after the last
 * member that is not another one is refused, with its reason, after the lines before it
 * (zlib's gzread dropped a plain pack appended to a .gz one without a word). */
static void
test_gzip_members(void)
{
	const char *text = "a 1\nb 2\n", *p = path_of("cat.gz");
	size_t zlen, k;
	char *z = gzip_bytes(text, 8, &zlen), *buf = malloc(2 * zlen + 64), *got, want[400];
	int st;
	long n;
	static const struct {
		const char *what, *tail;
		size_t len;
	} tails[] = {
		{"a plain file appended to a gzip one", "c 3\n", 4},
		{"one byte after the gzip member", "x", 1},
		{"gzip's first magic byte alone after the member", "\x1f", 1},
	};

	memcpy(buf, z, zlen);
	memcpy(buf + zlen, z, zlen);
	write_file(p, buf, 2 * zlen);
	got = read_all(p, &st, &n);
	CHECK(st == 0 && strcmp(got, "a 1$|b 2$|a 1$|b 2$") == 0, "two gzip members read as one stream: '%s' (status %d)",
	    got, st);
	free(got);
	for (k = 0; k < sizeof tails / sizeof tails[0]; k++) {
		memcpy(buf + zlen, tails[k].tail, tails[k].len);
		write_file(p, buf, zlen + tails[k].len);
		got = read_all(p, &st, &n);
		snprintf(want, sizeof want, "%s:3: trailing data after the end of the gzip stream (not a gzip member; gzip -t calls it trailing garbage: a file appended to a .gz one?)", p);
		CHECK(st == -1 && n == 2 && strcmp(msg_geterr(), want) == 0, "%s: refused after the %ld lines before it: '%s'",
		    tails[k].what, n, msg_geterr());
		free(got);
	}
	/* zero padding after the last member (a tape block), as gzip -d accepts it: read; zero
	 * bytes then others are not padding (issue 59: the padding was refused) */
	memset(buf + zlen, 0, zlen + 32);
	write_file(p, buf, 2 * zlen + 32);
	got = read_all(p, &st, &n);
	CHECK(st == 0 && strcmp(got, "a 1$|b 2$") == 0, "zero padding after the gzip member: read ('%s', status %d)", got, st);
	free(got);
	buf[2 * zlen + 31] = 'x';
	write_file(p, buf, 2 * zlen + 32);
	got = read_all(p, &st, &n);
	snprintf(want, sizeof want, "%s:3: trailing data after the end of the gzip stream (zero bytes, then others: neither padding nor a gzip member)", p);
	CHECK(st == -1 && n == 2 && strcmp(msg_geterr(), want) == 0, "zero bytes, then a byte: refused: '%s'", msg_geterr());
	free(got);
	/* a second member cut short is as truncated as the first */
	memcpy(buf + zlen, z, zlen - 5);
	write_file(p, buf, 2 * zlen - 5);
	got = read_all(p, &st, &n);
	snprintf(want, sizeof want, "%s:", p);
	CHECK(st == -1 && strncmp(msg_geterr(), want, strlen(want)) == 0 && strstr(msg_geterr(), "corrupt or truncated input ("),
	    "a second gzip member cut short: '%s'", msg_geterr());
	free(got);
	unlink(p);
	free(buf);
	free(z);
}

/* Input that is not text, or not text of LF lines, named for what it is at line 1 (a NUL
 * byte said "binary data" of an xz file, "not a qusgm pack" of a BOM, "truncated" of a
 * CR-only file). */
static void
test_foreign(void)
{
	static const struct {
		const char *what, *data;
		size_t len;
		const char *msg;
	} cases[] = {
		{"xz data", "\xfd" "7zXZ\0\0\x04\xe6\xd6\xb4\x46", 12, "xz-compressed: decompress it first (xz -d FILE; qusgm reads plain text and gzip)"},
		{"bzip2 data", "BZh91AY&SY\x01\x02", 12, "bzip2-compressed: decompress it first (bzip2 -d FILE; qusgm reads plain text and gzip)"},
		{"zstd data", "\x28\xb5\x2f\xfd\x04\x58", 6, "zstd-compressed: decompress it first (zstd -d FILE; qusgm reads plain text and gzip)"},
		{"lz4 data", "\x04\x22\x4d\x18\x64\x40", 6, "lz4-compressed: decompress it first (lz4 -d FILE; qusgm reads plain text and gzip)"},
		{"compress (.Z) data", "\x1f\x9d\x90\x71", 4, "compressed by compress (.Z): decompress it first (gzip -d FILE; qusgm reads plain text and gzip)"},
		{"a zip archive", "PK\x03\x04\x14\x00", 6, "a zip archive: extract the file first (unzip)"},
		{"a UTF-8 byte-order mark", "\xef\xbb\xbfqusgm-pack 1\n", 16, "a UTF-8 byte-order mark (bytes EF BB BF) starts the file: save it without one (sed -i '1s/^\\xEF\\xBB\\xBF//' FILE)"},
		{"UTF-16LE text", "\xff\xfeq\0u\0\n\0", 8, "UTF-16 text (byte-order mark FF FE): convert it (iconv -f UTF-16 -t UTF-8 FILE)"},
		{"UTF-16BE text", "\xfe\xff\0q\0u\0\n", 8, "UTF-16 text (byte-order mark FE FF): convert it (iconv -f UTF-16 -t UTF-8 FILE)"},
		{"CR-only line endings", "qusgm-pack 1\runits SI\rend\r", 26, "CR line endings (old Mac): convert them (tr '\\r' '\\n' < FILE)"},
		{"CR-only line endings, no CR at the end", "a 1\rb 2", 7, "CR line endings (old Mac): convert them (tr '\\r' '\\n' < FILE)"},
	};
	char want[400], *got, *z;
	size_t k, zlen;
	int st;
	long n;

	for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		snprintf(want, sizeof want, "%s/foreign:1: %s", dir, cases[k].msg);
		expect_error(cases[k].what, "foreign", cases[k].data, cases[k].len, want);
	}
	/* inside gzip too: what the gzip holds is judged */
	z = gzip_bytes(cases[0].data, cases[0].len, &zlen);
	write_file(path_of("foreign.gz"), z, zlen);
	got = read_all(path_of("foreign.gz"), &st, &n);
	snprintf(want, sizeof want, "%s/foreign.gz:1: inside the gzip stream, %s", dir, cases[0].msg);
	CHECK(st == -1 && strcmp(msg_geterr(), want) == 0, "xz data inside gzip: '%s'", msg_geterr());
	free(got);
	free(z);
	unlink(path_of("foreign.gz"));
	/* "BZh" that is text, a lone CR in an LF file: still text */
	expect_lines("a file starting 'BZh' as text", "BZh is a word\n", 14, "BZh is a word$", 1);
	expect_lines("a one-line file ending in CR alone", "a 1\r", 4, "a 1", 1);
}

/* Line numbers in messages, lines_unread, the sticky failure, the name of stdin. */
static void
test_numbers(void)
{
	const char *p = path_of("num.txt");
	struct lines *in;
	char *s, want[300];
	int r;

	write_file(p, "one\ntwo\nthree\0\n", 15);
	in = lines_open_path(p);
	CHECK(in != NULL, "lines_open_path %s", p);
	if (!in)
		return;
	lines_error(in, "before any line");
	snprintf(want, sizeof want, "%s:1: before any line", p);
	CHECK(lines_lineno(in) == 0 && strcmp(msg_geterr(), want) == 0, "before the first line: number 0, errors at line 1 ('%s')",
	    msg_geterr());
	r = lines_next(in, &s, NULL);
	r += lines_next(in, &s, NULL);
	lines_error(in, "what is wrong with %s", s);
	snprintf(want, sizeof want, "%s:2: what is wrong with two", p);
	CHECK(r == 2 && strcmp(msg_geterr(), want) == 0, "lines_error: '%s'", msg_geterr());
	lines_error_at(in, 7, "elsewhere");
	snprintf(want, sizeof want, "%s:7: elsewhere", p);
	CHECK(strcmp(msg_geterr(), want) == 0, "lines_error_at: '%s'", msg_geterr());
	lines_unread(in);
	CHECK(lines_lineno(in) == 1, "lines_unread steps the number back (%ld)", lines_lineno(in));
	r = lines_next(in, &s, NULL);
	CHECK(r == 1 && strcmp(s, "two") == 0 && lines_lineno(in) == 2, "the unread line comes again, as line %ld: '%s'",
	    lines_lineno(in), r == 1 ? s : "");
	r = lines_next(in, &s, NULL);
	snprintf(want, sizeof want, "%s:3: binary data (NUL byte) in a text file", p);
	CHECK(r == -1 && strcmp(msg_geterr(), want) == 0, "the NUL byte on line 3: '%s'", msg_geterr());
	msg_seterr("cleared");
	r = lines_next(in, &s, NULL);
	CHECK(r == -1 && strcmp(msg_geterr(), "cleared") == 0, "after an error lines_next keeps failing (%d), the slot untouched",
	    r);
	lines_close(in);
	unlink(p);
	in = lines_open_path(p);
	snprintf(want, sizeof want, "%s: No such file or directory", p);
	CHECK(!in && strcmp(msg_geterr(), want) == 0, "a missing file: '%s'", msg_geterr());
	in = lines_open_path("-");
	CHECK(in && strcmp(lines_name(in), "<stdin>") == 0, "'-' is stdin, named <stdin>");
	lines_close(in);
}

/* lines_open on a stream the caller owns: the stream stays open, its descriptor too. */
static void
test_borrowed_stream(void)
{
	const char *p = path_of("own.txt");
	FILE *fp;
	struct lines *in;
	char *s;
	int r;

	write_file(p, "x\n", 2);
	fp = fopen(p, "rb");
	in = lines_open(fp, "named");
	r = lines_next(in, &s, NULL);
	CHECK(r == 1 && strcmp(lines_name(in), "named") == 0, "lines_open: the name given is the name in messages");
	lines_close(in);
	CHECK(fcntl(fileno(fp), F_GETFD) != -1 && fseek(fp, 0, SEEK_SET) == 0 && fgetc(fp) == 'x',
	    "lines_close leaves the caller's stream open and readable");
	fclose(fp);
	unlink(p);
}

int
main(void)
{
	if (!mkdtemp(dir)) {
		CHECK(0, "mkdtemp");
		return unit_summary();
	}
	test_shapes();
	test_long_line();
	test_nul();
	test_truncated_gz();
	test_gzip_members();
	test_foreign();
	test_numbers();
	test_borrowed_stream();
	rmdir(dir);
	return unit_summary();
}
