/* SPDX-License-Identifier: GPL-3.0-or-later */
/* servo: the wall servo and the unbalanced force the DEM compactions share (see servo.h). */
#include "dem/servo.h"
#include "base/par.h"
#include "pack/pack.h"

#include <math.h>

double
dem_servo(double lo[3], double hi[3], const double wallf[6], double ptarget, double rate, const int *periodic,
    double *x, size_t n)
{
	double de[3] = {0, 0, 0}, c[3], rs = 0;
	size_t i;
	int a, nw = 0;

	for (a = 0; a < 3; a++)
		nw += !(periodic && periodic[a]);
	for (a = 0; a < 3; a++) {
		double ratio, g;

		c[a] = 0.5 * (lo[a] + hi[a]);
		if (periodic && periodic[a])
			continue;
		ratio = pack_wall_stress(lo, hi, a, wallf[2 * a] + wallf[2 * a + 1]) / ptarget;
		rs += ratio / nw;
		g = fmax(-1, fmin(1, 1 - ratio));
		de[a] = g * rate;
		lo[a] = c[a] + (lo[a] - c[a]) * (1 - de[a]);
		hi[a] = c[a] + (hi[a] - c[a]) * (1 - de[a]);
	}
#pragma omp parallel for schedule(static) if (n >= PAR_MIN)
	for (i = 0; i < n; i++) {
		int b;
		for (b = 0; b < 3; b++)
			x[3 * i + b] = c[b] + (x[3 * i + b] - c[b]) * (1 - de[b]);
	}
	return rs;
}

double
dem_unbalanced(const double *f, size_t n, double sum_f, size_t ncontacts)
{
	double s = 0;
	size_t i;

	if (ncontacts == 0 || sum_f == 0)
		return INFINITY;
	for (i = 0; i < n; i++)
		s += sqrt(f[3 * i] * f[3 * i] + f[3 * i + 1] * f[3 * i + 1] + f[3 * i + 2] * f[3 * i + 2]);
	return (s / n) / (sum_f / ncontacts);
}
