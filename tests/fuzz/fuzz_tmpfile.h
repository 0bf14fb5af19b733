/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_tmpfile: the material and size-table readers take a file name, so the fuzz input is
 * written to one temporary file per process (removed at exit) and read from there. */
#ifndef QUSGM_FUZZ_TMPFILE_H
#define QUSGM_FUZZ_TMPFILE_H
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char fuzz_tmp_path[64];

static void
fuzz_tmp_remove(void)
{
	if (fuzz_tmp_path[0])
		unlink(fuzz_tmp_path);
}

/* The path of a file holding exactly data[0..size), ending in suffix; NULL on failure. */
static const char *
fuzz_tmp_write(const uint8_t *data, size_t size, const char *suffix)
{
	FILE *fp;

	if (!fuzz_tmp_path[0]) {
		const char *dir = getenv("TMPDIR");
		int fd;

		snprintf(fuzz_tmp_path, sizeof fuzz_tmp_path, "%s/qusgm-fuzz-XXXXXX%s",
		    dir && strlen(dir) < 32 ? dir : "/tmp", suffix);
		fd = mkstemps(fuzz_tmp_path, (int)strlen(suffix));
		if (fd < 0) {
			fuzz_tmp_path[0] = 0;
			return NULL;
		}
		close(fd);
		atexit(fuzz_tmp_remove);
	}
	fp = fopen(fuzz_tmp_path, "wb");
	if (!fp)
		return NULL;
	if (size && fwrite(data, 1, size, fp) != size) {
		fclose(fp);
		return NULL;
	}
	if (fclose(fp) != 0)
		return NULL;
	return fuzz_tmp_path;
}
#endif
