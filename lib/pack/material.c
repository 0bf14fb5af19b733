/* SPDX-License-Identifier: GPL-3.0-or-later */
/* material: presets, preset files and sampling (see material.h). */
#include "pack/material.h"
#include "pack/packio.h"
#include "base/lines.h"
#include "base/msg.h"
#include "base/numfmt.h"

#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static const struct material presets[] = {
	{"glass", 70e9, 0.2, 2420, 0.1},
	{"quartz", 100e9, 0.15, 2650, 0.1},
	{"hydrate", 6.6e9, 0.32, 900, 0.1},
};

const char *const material_preset_names = "glass, quartz, hydrate";

/* The blanks of a preset file: what sscanf's %s stopped at, which the reader used to use. */
#define BLANKS " \t\n\v\f\r"

/* A "key value" line into m; *seen gets bit 1, 2, 4, 8 for E, nu, rho, spread.  A key given
 * twice is refused (the second E silently replaced the first); E is in the range a pack
 * takes (packio.h), so that a file never makes grains no reader would read back. */
static int
preset_line(struct lines *in, char *s, struct material *m, int *seen)
{
	static const char *const keys[] = {"E", "nu", "rho", "spread"};
	char *tok[2];
	double v;
	int n = lines_split(s, BLANKS, tok, 2), k;

	if (n != 2 || num_parse(tok[1], &v))
		return lines_error(in, "expected 'key value' with a finite number");
	for (k = 0; k < 4; k++)
		if (strcmp(tok[0], keys[k]) == 0 && (*seen & 1 << k))
			return lines_error(in, "%s given twice (each key once)", tok[0]);
	if (strcmp(tok[0], "E") == 0 && v > 0 && !(v >= PACK_E_MIN && v <= PACK_E_MAX))
		return lines_error(in, "E %s Pa is outside [%g, %g] Pa", tok[1], PACK_E_MIN, PACK_E_MAX);
	/* each key's range said with its refusal ("nu 0.5" never said it) */
	if (strcmp(tok[0], "E") == 0) {
		if (!(v > 0))
			return lines_error(in, "E %s Pa: must be in [%g, %g] Pa", tok[1], PACK_E_MIN, PACK_E_MAX);
		m->E = v, *seen |= 1;
	} else if (strcmp(tok[0], "nu") == 0) {
		if (!(v > -1 && v < 0.5))
			return lines_error(in, "nu %s: the Poisson ratio must be in (-1, 0.5)", tok[1]);
		m->nu = v, *seen |= 2;
	} else if (strcmp(tok[0], "rho") == 0) {
		if (!(v > 0))
			return lines_error(in, "rho %s: the density must be positive (kg/m^3)", tok[1]);
		m->rho = v, *seen |= 4;
	} else if (strcmp(tok[0], "spread") == 0) {
		if (!(v >= 0 && v < 1))
			return lines_error(in, "spread %s: must be in [0, 1)", tok[1]);
		m->spread = v, *seen |= 8;
	} else
		return lines_error(in, "unknown key: %s (the keys: E, nu, rho, spread)", tok[0]);
	return 0;
}

static int
read_preset_file(const char *path, struct material *m)
{
	struct lines *in = lines_open_path(path);
	int seen = 0, r;
	char *s;

	if (!in) {
		msg_seterr("%s: cannot open material file", path);
		return -1;
	}
	memset(m, 0, sizeof *m);
	snprintf(m->name, sizeof m->name, "%s", path);
	m->spread = 0.1;
	while ((r = lines_next(in, &s, NULL)) == 1) {
		if (s[0] == '#' || s[strspn(s, " \t\r\n")] == 0)
			continue;
		if ((r = preset_line(in, s, m, &seen)) < 0)
			break;
	}
	lines_close(in);
	if (r < 0)
		return -1;
	if ((seen & 7) != 7) {
		msg_seterr("%s: a material file needs E, nu and rho", path);
		return -1;
	}
	return 0;
}

int
material_is_file(const char *name)
{
	return strchr(name, '/') || strstr(name, ".mat");
}

int
material_lookup(const char *name, struct material *m)
{
	size_t k;

	for (k = 0; k < sizeof presets / sizeof presets[0]; k++)
		if (strcmp(name, presets[k].name) == 0) {
			*m = presets[k];
			return 0;
		}
	if (material_is_file(name))
		return read_preset_file(name, m);
	if (access(name, F_OK) == 0)	/* a file named without a slash or .mat: say how to name it */
		msg_seterr("unknown material '%s' (presets: %s): to read the file of that name, give its path as ./%s",
		    name, material_preset_names, name);
	else
		msg_seterr("unknown material '%s' (presets: %s; or a file path)", name, material_preset_names);
	return -1;
}

void
material_sample(const struct material *m, gsl_rng *rng, double *E, double *nu)
{
	do	/* in the range a pack takes, which for any real material is E > 0 */
		*E = m->E + gsl_ran_gaussian(rng, m->spread * m->E);
	while (!(*E >= PACK_E_MIN && *E <= PACK_E_MAX));
	do
		*nu = m->nu + gsl_ran_gaussian(rng, m->spread * fabs(m->nu));
	while (!(*nu > -1 && *nu < 0.5));
}
