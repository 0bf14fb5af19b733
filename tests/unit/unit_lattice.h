/* SPDX-License-Identifier: GPL-3.0-or-later */
/* unit_lattice: blocks of identical spheres on a simple cubic or face-centred cubic lattice
 * between walls, and the Newton reference that brings them to equilibrium (the exact Hessian of
 * an O(N^2) Hertz energy written here, independent of lib/qs/functional.c and lib/qs/minimize.c),
 * shared by test_lattice and test_lattice_moduli. */
#ifndef QUSGM_UNIT_LATTICE_H
#define QUSGM_UNIT_LATTICE_H

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "contact/hertz.h"
#include "pack/pack.h"
#include "unit_hertz.h"

enum { SC, FCC };

/* m^3 sites at spacing 2R (SC) or the sites (i, j, k) sqrt2 R with i + j + k even (FCC, the
 * conventional cubic cell of edge 2 sqrt2 R), 0 <= i, j, k < m, grains of radius R, modulus E,
 * Poisson's ratio nu; walls at R from the outer layers (touching), of modulus wall_E and
 * Poisson's ratio wall_nu. */
static void __attribute__((unused))
lattice_pack(struct pack *p, int kind, int m, double R, double E, double nu, double wall_E, double wall_nu)
{
	double step = kind == SC ? 2 * R : sqrt(2.0) * R;
	int i, j, k, a;

	pack_init(p);
	for (k = 0; k < m; k++)
		for (j = 0; j < m; j++)
			for (i = 0; i < m; i++) {
				double x[3] = {R + i * step, R + j * step, R + k * step};
				if (kind == FCC && (i + j + k) % 2)
					continue;
				pack_add_grain(p, (long)p->n, x, R, E, nu, 2420);
			}
	for (a = 0; a < 3; a++) {
		p->box[a] = 0;
		p->box[3 + a] = 2 * R + (m - 1) * step;
	}
	p->wall_E = wall_E;
	p->wall_nu = wall_nu;
}

/* Gradient g (3n) of the O(N^2) Hertz energy at x and, unless H is NULL, its Hessian
 * (3n x 3n); the normal force on each wall into wf. */
static void __attribute__((unused))
lattice_ref_eval(const struct pack *p, const double *x, double *g, gsl_matrix *H, double wf[NWALLS])
{
	size_t n = p->n, i, j;
	int a, b, w;

	memset(g, 0, 3 * n * sizeof *g);
	memset(wf, 0, NWALLS * sizeof *wf);
	if (H)
		gsl_matrix_set_zero(H);
	for (i = 0; i < n; i++) {
		for (j = i + 1; j < n; j++) {
			double d[3], dist, h, Es, Rs, P, k, nv[3];
			if (!unit_pair_overlap(p, x, i, j, d, &dist, &h))
				continue;
			Es = hertz_Estar(p->E[i], p->nu[i], p->E[j], p->nu[j]);
			Rs = hertz_Rstar(p->r[i], p->r[j]);
			P = hertz_force(Es, Rs, h);
			k = hertz_stiffness(Es, Rs, h);
			for (a = 0; a < 3; a++) {
				nv[a] = d[a] / dist;
				g[3 * i + a] -= P * nv[a];
				g[3 * j + a] += P * nv[a];
			}
			if (H)
				for (a = 0; a < 3; a++)
					for (b = 0; b < 3; b++) {
						/* d(-P n_a)/dx_ib = k n_a n_b - (P/d)(delta_ab - n_a n_b) */
						double B = k * nv[a] * nv[b] - P / dist * ((a == b) - nv[a] * nv[b]);
						*gsl_matrix_ptr(H, 3 * i + a, 3 * i + b) += B;
						*gsl_matrix_ptr(H, 3 * j + a, 3 * j + b) += B;
						*gsl_matrix_ptr(H, 3 * i + a, 3 * j + b) -= B;
						*gsl_matrix_ptr(H, 3 * j + a, 3 * i + b) -= B;
					}
		}
		for (w = 0; w < NWALLS; w++) {
			double Es, P, h = unit_wall_contact(p, x, i, w, &Es, &P);
			if (h <= 0)
				continue;
			a = w / 2;
			g[3 * i + a] += w % 2 ? P : -P;
			wf[w] += P;
			if (H)
				*gsl_matrix_ptr(H, 3 * i + a, 3 * i + a) += hertz_stiffness(Es, p->r[i], h);
		}
	}
}

/* Newton from x (in place): x -= H^-1 g until the step is below stop (m) and stops shrinking
 * (quadratic convergence ends at rounding), at most 40 steps.  Returns the last step (m). */
static double __attribute__((unused))
lattice_newton(const struct pack *p, double *x, double stop)
{
	size_t n3 = 3 * p->n, k;
	gsl_matrix *H = gsl_matrix_alloc(n3, n3);
	gsl_vector *gv = gsl_vector_alloc(n3), *dx = gsl_vector_alloc(n3);
	gsl_permutation *perm = gsl_permutation_alloc(n3);
	double *g = malloc(n3 * sizeof *g), wf[NWALLS], step = INFINITY, prev;
	int it, sgn;

	for (it = 0; it < 40; it++) {
		lattice_ref_eval(p, x, g, H, wf);
		for (k = 0; k < n3; k++)
			gsl_vector_set(gv, k, g[k]);
		gsl_linalg_LU_decomp(H, perm, &sgn);
		gsl_linalg_LU_solve(H, perm, gv, dx);
		prev = step;
		step = 0;
		for (k = 0; k < n3; k++) {
			x[k] -= gsl_vector_get(dx, k);
			step = fmax(step, fabs(gsl_vector_get(dx, k)));
		}
		if (step < stop && step >= 0.5 * prev)
			break;
	}
	gsl_matrix_free(H);
	gsl_vector_free(gv);
	gsl_vector_free(dx);
	gsl_permutation_free(perm);
	free(g);
	return step;
}

/* The normal stress on each axis from the wall forces wf: the mean force on its two walls over
 * the area of the box's face. */
static void __attribute__((unused))
lattice_wall_stress(const double box[6], const double wf[NWALLS], double sig[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		int u = (a + 1) % 3, v = (a + 2) % 3;
		sig[a] = (wf[2 * a] + wf[2 * a + 1]) / (2 * (box[3 + u] - box[u]) * (box[3 + v] - box[v]));
	}
}

#endif
