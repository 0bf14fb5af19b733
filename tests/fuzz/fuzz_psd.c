/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_psd: the size-table reader (pack/psd.h, "table:FILE") on arbitrary bytes, through a
 * temporary file; an accepted table is sampled a few times. */
#include <math.h>
#include <gsl/gsl_rng.h>
#include "fuzz_tmpfile.h"
#include "pack/psd.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static gsl_rng *rng;
	const char *path = fuzz_tmp_write(data, size, ".txt");
	char spec[96];
	struct psd d;

	if (!path)
		return 0;
	if (!rng)
		rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 1);
	snprintf(spec, sizeof spec, "table:%s", path);
	if (psd_parse(spec, &d) == 0) {
		for (int i = 0; i < 4; i++)
			if (!isfinite(psd_draw(&d, rng)))
				abort();
		psd_free(&d);
	}
	return 0;
}
