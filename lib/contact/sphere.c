/* SPDX-License-Identifier: GPL-3.0-or-later */
/* sphere: the narrow phase of two spheres and of a sphere on a wall (contact/narrow.h).  A
 * sphere's bounding sphere is the sphere: one element, exact, PLATE_SPHERE. */
#include "contact/narrow.h"
#include "base/vec3.h"

#include <math.h>
#include <string.h>

/* One element with h = r_i + r_j - |x_i - x_j| and n along x_i - x_j (e3 when the centres
 * coincide). */
int
sphere_pair_interaction(const struct plate_body *a, const struct plate_body *b, double gap,
    struct plate_interaction *out)
{
	double e[3] = {a->x[0] - b->x[0], a->x[1] - b->x[1], a->x[2] - b->x[2]}, d = vec3_norm(e);
	struct plate_element *el = &out->e[0];
	int k;

	out->d = d;
	for (k = 0; k < 3; k++)
		out->n[k] = d > 0 ? e[k] / d : k == 2;
	out->m = 0;
	el->h = a->r + b->r - d;
	if (!(el->h > -gap))
		return 0;
	memcpy(el->pi, a->x, sizeof el->pi);
	memcpy(el->pj, b->x, sizeof el->pj);
	plate_element_point(el, out->n, a->r, b->r);
	el->kind = PLATE_SPHERE;
	return out->m = 1;
}

/* Nothing to keep between steps: the exact element at gap 0. */
int
sphere_pair_cached(const struct plate_body *a, const struct plate_body *b, double margin, unsigned *cache,
    int build, struct plate_interaction *out)
{
	(void)margin, (void)build;
	*cache = 0;
	return sphere_pair_interaction(a, b, 0, out);
}

/* The centre's signed distance sd to the plane: one element of h = r - sd, its foot on the
 * plane. */
int
sphere_wall_interaction(const struct plate_body *a, const double w0[3], const double wn[3], double gap,
    struct plate_interaction *out)
{
	struct plate_element *e = &out->e[0];
	double sd = (a->x[0] - w0[0]) * wn[0] + (a->x[1] - w0[1]) * wn[1] + (a->x[2] - w0[2]) * wn[2];
	int k;

	memcpy(out->n, wn, sizeof out->n);
	out->d = sd;
	out->m = 0;
	e->h = a->r - sd;
	if (!(e->h > -gap))
		return 0;
	for (k = 0; k < 3; k++) {
		e->pi[k] = a->x[k];
		e->pj[k] = a->x[k] - sd * wn[k];
	}
	plate_element_point(e, wn, a->r, 0);
	e->kind = PLATE_SPHERE;
	return out->m = 1;
}
