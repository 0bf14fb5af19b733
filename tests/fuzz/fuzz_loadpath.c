/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fuzz_loadpath: the loading-path parser (qs/loadpath.h path_parse) on arbitrary bytes (as a
 * NUL-terminated string); an accepted path must respect the struct's bounds. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "qs/loadpath.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct path_defaults def = {1e-4, 0, NAN, NAN, 2};
	struct load_path *path;
	char *spec = malloc(size + 1);

	if (!spec)
		return 0;
	memcpy(spec, data, size);
	spec[size] = 0;
	path = malloc(sizeof *path);
	if (path && path_parse(spec, &def, path) == 0) {
		if (path->n < 1 || path->n > sizeof path->seg / sizeof path->seg[0])
			abort();
		for (size_t i = 0; i < path->n; i++) {
			const struct path_seg *s = &path->seg[i];

			if (s->axis < 0 || s->axis > 2 || !path_kind_name(s->kind))
				abort();
		}
	}
	free(path);
	free(spec);
	return 0;
}
