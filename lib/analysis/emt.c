/* SPDX-License-Identifier: GPL-3.0-or-later */
/* emt: effective-medium moduli (see emt.h). */
#include "analysis/emt.h"

#include <math.h>

void
emt_moduli(double mu_g, double nu, double phi, double Z, double P, struct emt *out)
{
	double c = Z * Z * (1 - phi) * (1 - phi) * mu_g * mu_g * P / (M_PI * M_PI * (1 - nu) * (1 - nu));

	out->K = cbrt(c / 18);
	out->G_rough = (5 - 4 * nu) / (5 * (2 - nu)) * cbrt(1.5 * c);
	out->G_smooth = 0.6 * out->K;
}
