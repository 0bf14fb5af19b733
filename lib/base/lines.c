/* lines: text lines of any length from plain or gzip input (see lines.h). */
#include "base/lines.h"
#include "base/fileio.h"
#include "base/msg.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#define CHUNK (1 << 16)

struct lines {
	gzFile gz;
	FILE *owned;		/* opened by lines_open_path, closed by lines_close */
	char *name;
	long line;		/* number of the line in buf */
	char *chunk;		/* bytes from gzread not yet cut into lines */
	size_t chunk_len, chunk_pos;
	int eof, failed;
	char *buf;		/* the current line */
	size_t len, cap;
	int newline;		/* the line in buf ended with "\n" */
	int unread;		/* buf is to be returned again */
};

struct lines *
lines_open(FILE *fp, const char *name)
{
	struct lines *in = calloc(1, sizeof *in);
	int fd;

	if (!in) {
		msg_seterr("out of memory");
		return NULL;
	}
	in->name = strdup(name);
	in->chunk = malloc(CHUNK);
	if (!in->name || !in->chunk) {
		msg_seterr("out of memory");
		lines_close(in);
		return NULL;
	}
	fd = dup(fileno(fp));
	if (fd < 0 || !(in->gz = gzdopen(fd, "rb"))) {
		msg_seterr("%s: cannot open for reading", name);
		if (fd >= 0)
			close(fd);
		lines_close(in);
		return NULL;
	}
	gzbuffer(in->gz, 2 * CHUNK);
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
	if (in->gz)
		gzclose(in->gz);
	if (in->owned)
		fclose(in->owned);
	free(in->name);
	free(in->chunk);
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

/* zlib's message, without its "<fd:N>: " prefix, which would make the text depend on
 * descriptor numbers; a stream that stops early is said so plainly. */
static const char *
gz_why(gzFile gz, int *err)
{
	const char *m = gzerror(gz, err), *c;

	if (*err == Z_BUF_ERROR)
		return "unexpected end of compressed data";
	if (strncmp(m, "<fd:", 4) == 0 && (c = strstr(m, ">: ")))
		return c + 3;
	return m;
}

/* 1: new bytes in chunk; 0: the end of the input; -1: a corrupt or truncated stream. */
static int
fill_chunk(struct lines *in)
{
	const char *why;
	int n, err;

	if (in->eof)
		return 0;
	n = gzread(in->gz, in->chunk, CHUNK);
	if (n > 0) {
		in->chunk_len = (size_t)n;
		in->chunk_pos = 0;
		return 1;
	}
	/* zlib reports a truncated gzip stream as -1, or as the end of the data plus an error
	 * state once the bytes decoded before the break have been handed out */
	why = gz_why(in->gz, &err);
	if (n < 0 || (err != Z_OK && err != Z_STREAM_END))
		return fail_at_next(in, "corrupt or truncated input", why);
	in->eof = 1;
	return 0;
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
