/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_table: the TSV table reader (base/table.h) on arbitrary bytes; an accepted table must
 * be consistent (every named column, table_find finds it).  The reader needs a stream with
 * a file descriptor, so the input goes through a temporary file. */
#include "fuzz_tmpfile.h"
#include "base/table.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	FILE *fp;
	struct table t = {0};
	double sum = 0;
	const char *path = fuzz_tmp_write(data, size, ".tsv");

	if (!path || !(fp = fopen(path, "rb")))
		return 0;
	if (table_read(fp, "fuzz", &t) == 0) {
		for (int c = 0; c < t.ncol; c++)
			if (!t.names[c] || table_find(&t, t.names[c]) < 0)
				abort();
		for (size_t i = 0; i < t.nrow * (size_t)t.ncol; i++)
			sum += t.v[i];	/* every cell is readable */
		for (size_t i = 0; i < t.nrow; i++)
			if (t.line[i] <= 0)
				abort();
		(void)sum;
	}
	table_free(&t);
	fclose(fp);
	return 0;
}
