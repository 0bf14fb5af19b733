/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_material: the material preset file reader (pack/material.h) on arbitrary bytes,
 * through a temporary ".mat" file; an accepted material must be a physical one. */
#include <math.h>
#include "fuzz_tmpfile.h"
#include "pack/material.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *path = fuzz_tmp_write(data, size, ".mat");
	struct material m;

	if (!path)
		return 0;
	if (material_lookup(path, &m) == 0) {
		if (!isfinite(m.E) || !isfinite(m.nu) || !isfinite(m.rho) || !isfinite(m.spread))
			abort();
	}
	return 0;
}
