/* material: presets, preset files and sampling (see material.h). */
#include "pack/material.h"
#include "base/msg.h"
#include "base/numfmt.h"

#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const struct material presets[] = {
	{"glass", 70e9, 0.2, 2420, 0.1},
	{"quartz", 100e9, 0.15, 2650, 0.1},
	{"hydrate", 6.6e9, 0.32, 900, 0.1},
};

const char *const material_preset_names = "glass, quartz, hydrate";

static int
read_preset_file(const char *path, struct material *m)
{
	FILE *fp = fopen(path, "r");
	char line[512];
	long ln = 0;
	int seen = 0;

	if (!fp) {
		msg_seterr("%s: cannot open material file", path);
		return -1;
	}
	memset(m, 0, sizeof *m);
	snprintf(m->name, sizeof m->name, "%s", path);
	m->spread = 0.1;
	while (fgets(line, sizeof line, fp)) {
		char key[64], val[128], extra[8];
		double v;
		int n;

		ln++;
		if (line[0] == '#' || strspn(line, " \t\r\n") == strlen(line))
			continue;
		n = sscanf(line, "%63s %127s %7s", key, val, extra);
		if (n != 2 || num_parse(val, &v)) {
			msg_seterr("%s:%ld: expected 'key value' with a finite number", path, ln);
			fclose(fp);
			return -1;
		}
		if (strcmp(key, "E") == 0 && v > 0)
			m->E = v, seen |= 1;
		else if (strcmp(key, "nu") == 0 && v > -1 && v < 0.5)
			m->nu = v, seen |= 2;
		else if (strcmp(key, "rho") == 0 && v > 0)
			m->rho = v, seen |= 4;
		else if (strcmp(key, "spread") == 0 && v >= 0 && v < 1)
			m->spread = v;
		else {
			msg_seterr("%s:%ld: unknown key or value out of range: %s %s", path, ln, key, val);
			fclose(fp);
			return -1;
		}
	}
	fclose(fp);
	if (seen != 7) {
		msg_seterr("%s: a material file needs E, nu and rho", path);
		return -1;
	}
	return 0;
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
	if (strchr(name, '/') || strstr(name, ".mat"))
		return read_preset_file(name, m);
	msg_seterr("unknown material '%s' (presets: %s; or a file path)", name, material_preset_names);
	return -1;
}

void
material_sample(const struct material *m, gsl_rng *rng, double *E, double *nu)
{
	do
		*E = m->E + gsl_ran_gaussian(rng, m->spread * m->E);
	while (!(*E > 0));
	do
		*nu = m->nu + gsl_ran_gaussian(rng, m->spread * fabs(m->nu));
	while (!(*nu > -1 && *nu < 0.5));
}
