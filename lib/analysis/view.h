/* SPDX-License-Identifier: GPL-3.0-or-later */
/* view: a pack as one self-contained HTML page, for any browser, offline (packview).
 *
 * The page holds the pack's grains, their fields and contacts as base64 float32 arrays in a
 * JSON block, the page's own script (view_page.html, compiled in), and the scripts of
 * three.js and its OrbitControls, which the caller reads (the tool from Debian's libjs-three)
 * and hands over as text: the page loads nothing from anywhere.
 *
 * The fields, one value per grain (SI units as in the pack, the legend says which):
 *   coordination  contacts of the grain (grain_forces's z: walls count, plates' interactions)
 *   radius        r (m): a sphere's radius, a spheroplate's spheroradius
 *   phase         0 mineral, 1 hydrate (a pack with the phase column)
 *   residual      the grain's unbalance over its largest contact force (grain_forces)
 *   fmax          its largest contact force |f| (N)
 *   side          a spheroplate's core side L (m; a pack with a plate)
 *   tilt          the angle of a plate's face normal from the z axis (degrees, 0 to 90;
 *                 NaN for a sphere)
 * and the contacts (grain_forces's links): both ends' grains, or the grain and its wall,
 * with the normal force P (N).  Positions are relative to the box centre.  The writer's
 * output is a function of the pack and the scripts alone. */
#ifndef QUSGM_VIEW_H
#define QUSGM_VIEW_H

#include <stdio.h>
#include "analysis/measure.h"
#include "pack/pack.h"

/* The page's scripts: three.js (a classic script defining THREE) and OrbitControls (a
 * classic script adding THREE.OrbitControls; NULL or "": the page's own small orbit
 * control serves), with a name each for the page's notes. */
struct view_scripts {
	const char *three, *three_name;
	const char *controls, *controls_name;
};

/* The page of p (g its measure_grain_forces record) into fp; title names it (the input
 * file's name).  0, or -1 with msg_seterr (a write error). */
int view_write_html(FILE *fp, const struct pack *p, const struct grain_forces *g, const char *title,
    const struct view_scripts *s);

/* The page template, view_page.html, as compiled in (the Makefile makes it a C string). */
extern const char view_page_html[];

#endif
