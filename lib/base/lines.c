/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lines: text lines of any length from plain or gzip input (see lines.h). */
#include "base/lines.h"
#include "base/fileio.h"
#include "base/msg.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#define CHUNK (1 << 16)

struct lines {
	int fd;			/* a duplicate of the stream's descriptor, read with read(2) */
	FILE *owned;		/* opened by lines_open_path, closed by lines_close */
	char *name;
	long line;		/* number of the line in buf */
	/* The raw bytes: the input as it is, gzip or plain (mode, decided by its first two
	 * bytes); a gzip input is inflated member by member. */
	unsigned char *raw;
	size_t raw_len;
	int raw_eof;
	enum { MODE_UNKNOWN, MODE_PLAIN, MODE_GZIP } mode;
	z_stream zs;
	int zs_live;		/* inflateInit2 was called */
	int member_end;		/* a gzip member has just ended: another one, or the end, follows */
	const char *pend_what;	/* an error found after some bytes were decoded: reported once */
	const char *pend_why;	/* they have been handed out */
	char *chunk;		/* decoded bytes not yet cut into lines */
	size_t chunk_len, chunk_pos;
	int eof, failed, sniffed;
	char *buf;		/* the current line */
	size_t len, cap;
	int newline;		/* the line in buf ended with "\n" */
	int unread;		/* buf is to be returned again */
};

struct lines *
lines_open(FILE *fp, const char *name)
{
	struct lines *in = calloc(1, sizeof *in);

	if (!in) {
		msg_seterr("out of memory");
		return NULL;
	}
	in->fd = -1;
	in->name = strdup(name);
	in->chunk = malloc(CHUNK);
	in->raw = malloc(CHUNK);
	if (!in->name || !in->chunk || !in->raw) {
		msg_seterr("out of memory");
		lines_close(in);
		return NULL;
	}
	if ((in->fd = dup(fileno(fp))) < 0) {
		msg_seterr("%s: cannot open for reading: %s", name, strerror(errno));
		lines_close(in);
		return NULL;
	}
	return in;
}

struct lines *
lines_open_path(const char *path)
{
	const char *name;
	FILE *fp = file_in_open(path, &name);
	struct lines *in;

	if (!fp)
		return NULL;
	in = lines_open(fp, name);
	if (!in) {
		if (fp != stdin)
			fclose(fp);
		return NULL;
	}
	if (fp != stdin)
		in->owned = fp;
	return in;
}

void
lines_close(struct lines *in)
{
	if (!in)
		return;
	if (in->zs_live)
		inflateEnd(&in->zs);
	if (in->fd >= 0)
		close(in->fd);
	if (in->owned)
		fclose(in->owned);
	free(in->name);
	free(in->chunk);
	free(in->raw);
	free(in->buf);
	free(in);
}

long
lines_lineno(const struct lines *in)
{
	return in->line;
}

int
lines_newline(const struct lines *in)
{
	return in->newline;
}

const char *
lines_name(const struct lines *in)
{
	return in->name;
}

static int
verror(const struct lines *in, long line, const char *fmt, va_list ap)
{
	char what[1024];

	vsnprintf(what, sizeof what, fmt, ap);
	msg_seterr("%s:%ld: %s", in->name, line > 0 ? line : 1, what);
	return -1;
}

int
lines_error(const struct lines *in, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	verror(in, in->line, fmt, ap);
	va_end(ap);
	return -1;
}

int
lines_error_at(const struct lines *in, long line, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	verror(in, line, fmt, ap);
	va_end(ap);
	return -1;
}

/* An error of the reader itself at the line being read: every later call fails too. */
static int
fail_at_next(struct lines *in, const char *what, const char *why)
{
	in->failed = 1;
	return lines_error_at(in, in->line + 1, "%s%s%s%s", what, why ? " (" : "", why ? why : "",
	    why ? ")" : "");
}

/* More raw bytes after the raw_len kept ones, up to CHUNK: 1 when some came, 0 at the end
 * of the input, -1 on a read error (failed). */
static int
read_raw(struct lines *in)
{
	ssize_t n;

	if (in->raw_eof)
		return 0;
	if (in->raw_len == CHUNK)
		return 1;
	do
		n = read(in->fd, in->raw + in->raw_len, CHUNK - in->raw_len);
	while (n < 0 && errno == EINTR);
	if (n < 0)
		return fail_at_next(in, "read error", strerror(errno));
	if (n == 0) {
		in->raw_eof = 1;
		return 0;
	}
	in->raw_len += (size_t)n;
	return 1;
}

/* At least want raw bytes kept, unless the input ends first: 0, or -1 (failed). */
static int
raw_at_least(struct lines *in, size_t want)
{
	int r;

	while (in->raw_len < want)
		if ((r = read_raw(in)) <= 0)
			return r;
	return 0;
}

/* Plain input: the raw bytes are the text. */
static size_t
fill_plain(struct lines *in)
{
	size_t n = 0;

	while (n < CHUNK) {
		if (in->raw_len == 0 && read_raw(in) <= 0)
			break;
		{
			size_t take = in->raw_len < CHUNK - n ? in->raw_len : CHUNK - n;
			memcpy(in->chunk + n, in->raw, take);
			memmove(in->raw, in->raw + take, in->raw_len - take);
			in->raw_len -= take;
			n += take;
		}
	}
	return n;
}

/* An error met while inflating, after out bytes were decoded: those are handed out first
 * and the error comes with the next fill (so it is reported at the line being read when the
 * data stopped). */
static size_t
gz_stop(struct lines *in, size_t out, const char *what, const char *why)
{
	in->pend_what = what;
	in->pend_why = why;
	return out;
}

/* Gzip input: inflate member after member, as gzip -d does; anything after a member that
 * is not another member is refused (zlib's gzread skips it without a word, so a plain pack
 * appended to a .gz one vanished). */
static size_t
fill_gzip(struct lines *in)
{
	z_stream *zs = &in->zs;
	size_t out = 0;
	int ret;

	while (out < CHUNK) {
		if (in->member_end) {
			/* the next member's magic, or the end of the input */
			if (raw_at_least(in, 2) < 0)
				return out;
			if (in->raw_len == 0) {
				in->eof = 1;
				return out;
			}
			while (in->raw[0] == 0) {	/* zero padding (a tape block), as gzip -d accepts */
				size_t j;

				for (j = 0; j < in->raw_len; j++)
					if (in->raw[j])
						return gz_stop(in, out, "trailing data after the end of the gzip stream",
						    "zero bytes, then others: neither padding nor a gzip member");
				in->raw_len = 0;
				if (read_raw(in) < 0)
					return out;
				if (in->raw_len == 0) {
					in->eof = 1;
					return out;
				}
				if (in->raw[0] != 0)
					return gz_stop(in, out, "trailing data after the end of the gzip stream",
					    "zero bytes, then others: neither padding nor a gzip member");
			}
			if (in->raw_len < 2 || in->raw[0] != 0x1f || in->raw[1] != 0x8b)
				return gz_stop(in, out, "trailing data after the end of the gzip stream",
				    "not a gzip member; gzip -t calls it trailing garbage: a file appended to a .gz one?");
			if (inflateReset(zs) != Z_OK)
				return gz_stop(in, out, "corrupt or truncated input", "cannot restart zlib");
			in->member_end = 0;
			zs->next_in = in->raw;
			zs->avail_in = (uInt)in->raw_len;
		}
		if (zs->avail_in == 0) {
			/* the bytes zs has consumed are gone from raw: keep raw as its unread input */
			in->raw_len = 0;
			if (read_raw(in) < 0)
				return out;
			if (in->raw_len == 0)
				return gz_stop(in, out, "corrupt or truncated input", "unexpected end of compressed data");
			zs->next_in = in->raw;
			zs->avail_in = (uInt)in->raw_len;
		}
		zs->next_out = (Bytef *)in->chunk + out;
		zs->avail_out = (uInt)(CHUNK - out);
		ret = inflate(zs, Z_NO_FLUSH);
		out = CHUNK - zs->avail_out;
		if (ret == Z_STREAM_END) {
			/* what is left of raw goes to its front for the member check */
			memmove(in->raw, zs->next_in, zs->avail_in);
			in->raw_len = zs->avail_in;
			zs->avail_in = 0;
			in->member_end = 1;
		} else if (ret != Z_OK && ret != Z_BUF_ERROR) {
			return gz_stop(in, out, "corrupt or truncated input", zs->msg ? zs->msg : "corrupt data");
		}
	}
	if (zs->avail_in > 0) {	/* keep the unread input at raw's front */
		memmove(in->raw, zs->next_in, zs->avail_in);
		in->raw_len = zs->avail_in;
		zs->next_in = in->raw;
	}
	return out;
}

/* Plain or gzip, by the first two bytes (gzip's magic 1f 8b), as zlib's gzread decided. */
static int
start(struct lines *in)
{
	if (raw_at_least(in, 2) < 0)
		return -1;
	if (in->raw_len >= 2 && in->raw[0] == 0x1f && in->raw[1] == 0x8b) {
		memset(&in->zs, 0, sizeof in->zs);
		if (inflateInit2(&in->zs, 16 + MAX_WBITS) != Z_OK)
			return fail_at_next(in, "out of memory", NULL);
		in->zs_live = 1;
		in->zs.next_in = in->raw;
		in->zs.avail_in = (uInt)in->raw_len;
		in->mode = MODE_GZIP;
	} else {
		in->mode = MODE_PLAIN;
	}
	return 0;
}

/* 1: new bytes in chunk; 0: the end of the input; -1: a corrupt or truncated stream. */
static int
fill_chunk(struct lines *in)
{
	size_t n;

	if (in->pend_what)
		return fail_at_next(in, in->pend_what, in->pend_why);
	if (in->eof)
		return 0;
	if (in->mode == MODE_UNKNOWN && start(in) < 0)
		return -1;
	n = in->mode == MODE_GZIP ? fill_gzip(in) : fill_plain(in);
	if (in->failed)
		return -1;
	if (n > 0) {
		in->chunk_len = n;
		in->chunk_pos = 0;
		return 1;
	}
	if (in->pend_what)
		return fail_at_next(in, in->pend_what, in->pend_why);
	in->eof = 1;
	return 0;
}

/* What the first bytes of the text say when they are not text: another compression, an
 * archive, UTF-16, a byte-order mark.  NULL for anything else (the readers judge it). */
static const char *
foreign_start(const unsigned char *b, size_t n)
{
	static const struct {
		const char *magic;
		size_t len;
		const char *what;
	} known[] = {
		{"\xfd" "7zXZ\0", 6, "xz-compressed: decompress it first (xz -d FILE; qusgm reads plain text and gzip)"},
		{"BZh", 3, "bzip2-compressed: decompress it first (bzip2 -d FILE; qusgm reads plain text and gzip)"},
		{"\x28\xb5\x2f\xfd", 4, "zstd-compressed: decompress it first (zstd -d FILE; qusgm reads plain text and gzip)"},
		{"\x04\x22\x4d\x18", 4, "lz4-compressed: decompress it first (lz4 -d FILE; qusgm reads plain text and gzip)"},
		{"\x1f\x9d", 2, "compressed by compress (.Z): decompress it first (gzip -d FILE; qusgm reads plain text and gzip)"},
		{"PK\x03\x04", 4, "a zip archive: extract the file first (unzip)"},
		{"\xef\xbb\xbf", 3, "a UTF-8 byte-order mark (bytes EF BB BF) starts the file: save it without one (sed -i '1s/^\\xEF\\xBB\\xBF//' FILE)"},
		{"\xff\xfe", 2, "UTF-16 text (byte-order mark FF FE): convert it (iconv -f UTF-16 -t UTF-8 FILE)"},
		{"\xfe\xff", 2, "UTF-16 text (byte-order mark FE FF): convert it (iconv -f UTF-16 -t UTF-8 FILE)"},
	};
	size_t k;

	/* zlib's own format (RFC 1950: CM 8, the header a multiple of 31; "x\x9c" and the
	 * like), which is no text: gzip's header is another */
	if (n >= 2 && (b[0] & 0x0f) == 8 && (b[0] >> 4) <= 7 && ((unsigned)b[0] << 8 | b[1]) % 31 == 0 && !(b[1] & 0x20) &&
	    (memchr(b, 0, n < 64 ? n : 64) || b[1] < 0x20 || b[1] >= 0x7f))
		return "zlib-compressed data (no gzip header): only gzip is read; decompress it first (pigz -dz FILE, or "
		    "python3 -c 'import sys, zlib; sys.stdout.buffer.write(zlib.decompress(sys.stdin.buffer.read()))' <FILE)";
	for (k = 0; k < sizeof known / sizeof known[0]; k++)
		if (n >= known[k].len && memcmp(b, known[k].magic, known[k].len) == 0) {
			/* bzip2: "BZh", a block size 1-9, then the block magic (pi's digits) */
			if (known[k].magic[0] == 'B' && (n < 10 || b[3] < '1' || b[3] > '9' ||
			                                    memcmp(b + 4, "\x31\x41\x59\x26\x53\x59", 6) != 0))
				continue;
			return known[k].what;
		}
	return NULL;
}

/* Append the next piece of the current line from chunk to buf; 1 when it ended the line. */
static int
take_piece(struct lines *in)
{
	const char *from = in->chunk + in->chunk_pos;
	size_t avail = in->chunk_len - in->chunk_pos, take;
	const char *nl = memchr(from, '\n', avail);

	take = nl ? (size_t)(nl - from) : avail;
	if (in->len + take + 1 > in->cap) {
		size_t cap = 2 * (in->len + take + 1);
		char *b = realloc(in->buf, cap);
		if (!b)
			return fail_at_next(in, "out of memory", NULL);
		in->buf = b;
		in->cap = cap;
	}
	memcpy(in->buf + in->len, from, take);
	in->len += take;
	in->chunk_pos += take + (nl ? 1 : 0);
	in->newline = nl != NULL;
	return nl != NULL;
}

int
lines_next(struct lines *in, char **line, size_t *len)
{
	int got = 0, r;

	if (in->failed)
		return -1;
	if (in->unread) {
		in->unread = 0;
		in->line++;
		goto give;
	}
	in->len = 0;
	for (;;) {
		if (in->chunk_pos == in->chunk_len) {
			r = fill_chunk(in);
			if (r < 0)
				return -1;
			if (r == 0)
				break;
			if (!in->sniffed) {
				const unsigned char *b = (const unsigned char *)in->chunk;
				const char *why = foreign_start(b, in->chunk_len);
				in->sniffed = 1;
				if (in->mode == MODE_GZIP && in->chunk_len >= 2 && b[0] == 0x1f && b[1] == 0x8b) {
					in->failed = 1;
					return lines_error_at(in, 1, "a gzip inside a gzip (compressed twice): decompress it once "
					    "(gzip -d FILE), and the inner gzip is read");
				}
				if (why) {
					in->failed = 1;
					return lines_error_at(in, 1, "%s%s", in->mode == MODE_GZIP ? "inside the gzip stream, " : "", why);
				}
			}
		}
		got = 1;
		r = take_piece(in);
		if (r < 0)
			return -1;
		if (r)
			break;
	}
	if (!got)
		return 0;
	in->buf[in->len] = 0;
	if (in->len > 0 && in->buf[in->len - 1] == '\r')
		in->buf[--in->len] = 0;
	in->line++;
	if (memchr(in->buf, 0, in->len)) {
		in->failed = 1;
		return lines_error(in, "binary data (NUL byte) in a text file");
	}
	/* a first line that runs to the end of the input through carriage returns: a file of
	 * old Mac line endings, which would read as one line */
	if (in->line == 1 && !in->newline && memchr(in->buf, '\r', in->len)) {
		in->failed = 1;
		return lines_error(in, "CR line endings (old Mac): convert them (tr '\\r' '\\n' < FILE)");
	}
give:
	*line = in->buf;
	if (len)
		*len = in->len;
	return 1;
}

void
lines_unread(struct lines *in)
{
	if (in->line > 0 && !in->unread) {
		in->unread = 1;
		in->line--;
	}
}

int
lines_split(char *s, const char *blanks, char **tok, int max)
{
	int n = 0;

	for (;;) {
		s += strspn(s, blanks);
		if (!*s)
			return n;
		if (n < max)
			tok[n] = s;
		n++;
		s += strcspn(s, blanks);
		if (*s)
			*s++ = 0;
	}
}
