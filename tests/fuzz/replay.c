/* SPDX-License-Identifier: GPL-3.0-or-later */
/* replay: runs a fuzz harness's LLVMFuzzerTestOneInput on every file of its seed corpus and
 * of its crash reproducers (FUZZ_CORPUS/NAME and FUZZ_CRASHES/NAME, compiled in), without
 * libFuzzer, so make check replays them as a regression test under the normal cc and the
 * sanitizer build.  Prints "PASS NAME: N inputs" (tests/run.sh counts it); a crash or a
 * sanitizer report ends the program, which run.sh counts as a failure. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef FUZZ_NAME
#error "FUZZ_NAME must be defined"
#endif
#ifndef FUZZ_CORPUS
#error "FUZZ_CORPUS must be defined"
#endif
#ifndef FUZZ_CRASHES
#error "FUZZ_CRASHES must be defined"
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int
cmp(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Replays every regular file of dir; the count, or -1 when dir is missing and must exist. */
static long
replay_dir(const char *dir, int must_exist, const char **bad)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	char **names = NULL;
	size_t n = 0, cap = 0;
	long count = 0;

	if (!d)
		return must_exist ? -1 : 0;
	while ((e = readdir(d))) {
		if (e->d_name[0] == '.')
			continue;
		if (n == cap) {
			cap = cap ? 2 * cap : 64;
			names = realloc(names, cap * sizeof *names);
			if (!names)
				abort();
		}
		names[n] = strdup(e->d_name);
		if (!names[n++])
			abort();
	}
	closedir(d);
	qsort(names, n, sizeof *names, cmp);
	for (size_t i = 0; i < n; i++) {
		char path[4096];
		FILE *fp;
		uint8_t *buf;
		long len;

		snprintf(path, sizeof path, "%s/%s", dir, names[i]);
		fp = fopen(path, "rb");
		if (!fp || fseek(fp, 0, SEEK_END) != 0 || (len = ftell(fp)) < 0 || fseek(fp, 0, SEEK_SET) != 0) {
			*bad = names[i];
			if (fp)
				fclose(fp);
			return -1;
		}
		buf = malloc((size_t)len + 1);
		if (!buf || fread(buf, 1, (size_t)len, fp) != (size_t)len)
			abort();
		fclose(fp);
		fprintf(stderr, "replay %s\n", path);	/* the last one names a crashing input */
		LLVMFuzzerTestOneInput(buf, (size_t)len);
		free(buf);
		free(names[i]);
		count++;
	}
	free(names);
	return count;
}

int
main(void)
{
	const char *bad = NULL;
	long nc = replay_dir(FUZZ_CORPUS "/" FUZZ_NAME, 1, &bad);
	long nx;

	if (nc <= 0) {
		printf("FAIL %s corpus: %s/%s %s\n", FUZZ_NAME, FUZZ_CORPUS, FUZZ_NAME,
		    nc < 0 ? (bad ? "has an unreadable file" : "is missing") : "is empty");
		return 1;
	}
	printf("PASS %s corpus: %ld inputs\n", FUZZ_NAME, nc);
	nx = replay_dir(FUZZ_CRASHES "/" FUZZ_NAME, 0, &bad);
	if (nx < 0) {
		printf("FAIL %s crashes: unreadable %s\n", FUZZ_NAME, bad);
		return 1;
	}
	printf("PASS %s crashes: %ld reproducers\n", FUZZ_NAME, nx);
	return 0;
}
