/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_pack: the pack reader (pack/packio.h) on arbitrary bytes, and the round trip the
 * reader promises: when a pack is accepted, write(read(write(p))) == write(p) byte for byte
 * (abort() otherwise).  Every pack of a multi-pack stream is checked (the first 8).  The
 * readers take a stream with a file descriptor (gzip goes through zlib), so the input goes
 * through a temporary file. */
#include "fuzz_tmpfile.h"
#include "base/msg.h"
#include "pack/pack.h"
#include "pack/packio.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Write p to a temporary file; its bytes in *buf (malloc'ed), their count in *len, and the
 * file, rewound, in *out; 0 or -1. */
static int
write_tmp(const struct pack *p, char **buf, size_t *len, FILE **out)
{
	FILE *fp = tmpfile();
	long n;

	*buf = NULL;
	*out = NULL;
	if (!fp)
		return -1;
	if (pack_write_stream(p, fp, 0) != 0 || fflush(fp) != 0 || (n = ftell(fp)) < 0) {
		fclose(fp);
		return -1;
	}
	rewind(fp);
	*buf = malloc((size_t)n + 1);
	if (!*buf || fread(*buf, 1, (size_t)n, fp) != (size_t)n) {
		free(*buf);
		fclose(fp);
		return -1;
	}
	/* the reader reads the descriptor (a dup of it, through zlib): put it back at the start,
	 * which rewind() alone need not do when the bytes are still in the stdio buffer */
	rewind(fp);
	if (lseek(fileno(fp), 0, SEEK_SET) != 0) {
		free(*buf);
		fclose(fp);
		return -1;
	}
	*len = (size_t)n;
	*out = fp;
	return 0;
}

/* Read exactly one pack from fp; 0 or -1. */
static int
read_one(FILE *fp, struct pack *p)
{
	struct pack_reader *rd = pack_reader_open(fp, "roundtrip");
	int rc;

	if (!rd)
		return -1;
	rc = pack_read_next(rd, p);
	pack_reader_close(rd);
	return rc == 1 ? 0 : -1;
}

static void
roundtrip(const struct pack *p)
{
	char *w1, *w2;
	size_t n1 = 0, n2 = 0;
	FILE *f1, *f2;
	struct pack q;

	if (write_tmp(p, &w1, &n1, &f1) != 0) {
		fprintf(stderr, "fuzz_pack: an accepted pack could not be written\n");
		abort();
	}
	if (read_one(f1, &q) != 0) {
		fprintf(stderr, "fuzz_pack: the writer's output of an accepted pack was refused: %s\n", msg_geterr());
		abort();
	}
	if (write_tmp(&q, &w2, &n2, &f2) != 0) {
		fprintf(stderr, "fuzz_pack: a pack read back could not be written\n");
		abort();
	}
	if (n1 != n2 || memcmp(w1, w2, n1) != 0) {
		fprintf(stderr, "fuzz_pack: write(read(write(p))) differs from write(p)\n");
		abort();
	}
	fclose(f1);
	fclose(f2);
	pack_free(&q);
	free(w1);
	free(w2);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *path = fuzz_tmp_write(data, size, ".pack");
	FILE *fp;
	struct pack_reader *rd;
	struct pack p;
	int n;

	if (!path || !(fp = fopen(path, "rb")))
		return 0;
	rd = pack_reader_open(fp, "fuzz");
	if (!rd) {
		fclose(fp);
		return 0;
	}
	for (n = 0; n < 8 && pack_read_next(rd, &p) == 1; n++) {
		roundtrip(&p);
		pack_free(&p);
	}
	pack_reader_close(rd);
	fclose(fp);
	return 0;
}
