/* SPDX-License-Identifier: GPL-3.0-or-later */
/* material: grain materials (presets and preset files) and sampling of per-grain moduli.
 *
 * A material is a mean Young's modulus E (Pa), Poisson ratio nu and density rho (kg/m^3),
 * with a relative spread (standard deviation / mean) of E and nu; the papers use 10 %.
 * Built-in presets: glass, quartz, hydrate (physics.md §10).  A preset file holds
 * "key value" lines: E, nu, rho, spread (and # comments, blank lines), read through
 * base/lines.h: lines of any length, plain or gzip, errors as "file:line: what". */
#ifndef QUSGM_MATERIAL_H
#define QUSGM_MATERIAL_H

#include <gsl/gsl_rng.h>

struct material {
	char name[64];
	double E, nu, rho;
	double spread;	/* relative standard deviation of E and nu */
};

/* Look up a built-in preset, or read a preset file if name contains '/' or ends in .mat;
 * 0 on success, -1 with the error slot set. */
int material_lookup(const char *name, struct material *m);
/* Whether material_lookup reads name as a file (it has a '/' or ".mat" in it; a preset
 * name otherwise): for a tool's check that no output replaces it. */
int material_is_file(const char *name);
/* Draw E and nu from normal distributions truncated to PACK_E_MIN <= E <= PACK_E_MAX (the
 * range a pack takes, pack/packio.h: for a real material simply E > 0) and -1 < nu < 0.5
 * (redrawn, so the distribution keeps its shape away from the bounds). */
void material_sample(const struct material *m, gsl_rng *rng, double *E, double *nu);
/* Names of the built-in presets, for --help. */
extern const char *const material_preset_names;

#endif
