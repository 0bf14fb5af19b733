/* par: threads and thread-count-independent sums (see par.h). */
#include "base/par.h"

#include <stdlib.h>

#ifdef _OPENMP
#include <omp.h>
#endif

void
par_set_threads(int n)
{
#ifdef _OPENMP
	static int dflt;

	if (!dflt)
		dflt = omp_get_max_threads();
	omp_set_num_threads(n > 0 ? n : dflt);
#else
	(void)n;
#endif
}

int
par_threads(void)
{
#ifdef _OPENMP
	return omp_get_max_threads();
#else
	return 1;
#endif
}

int
par_tid(void)
{
#ifdef _OPENMP
	return omp_get_thread_num();
#else
	return 0;
#endif
}

int
par_team(void)
{
#ifdef _OPENMP
	return omp_get_num_threads();
#else
	return 1;
#endif
}

size_t
par_block_min(void)
{
	static size_t bmin;

	if (!bmin) {
		const char *v = getenv("QUSGM_PAR_BLOCK");
		long b = v ? strtol(v, NULL, 10) : 0;
		bmin = b >= 1 && b <= 1 << 20 ? (size_t)b : 256;
	}
	return bmin;
}

size_t
par_min(void)
{
	return 4 * par_block_min();
}

size_t
par_block(size_t n)
{
	size_t b = (n + PAR_MAXBLOCKS - 1) / PAR_MAXBLOCKS, bmin = par_block_min();

	return b < bmin ? bmin : b;
}

/* A dot product's blocks are at least PAR_MIN_VEC long, so that vectors of packs under 1366
 * grains are summed in one block, in order, as before threads. */
static size_t
vec_block(size_t n)
{
	size_t b = par_block(n);

	return b < PAR_MIN_VEC ? PAR_MIN_VEC : b;
}

double
par_dot(const double *a, const double *b, size_t n)
{
	double part[PAR_MAXBLOCKS], s = 0;
	size_t bl = vec_block(n), nb = (n + bl - 1) / bl;
	long q;

#pragma omp parallel for schedule(static) if (n >= PAR_MIN_VEC)
	for (q = 0; q < (long)nb; q++) {
		size_t k, k0 = (size_t)q * bl, k1 = k0 + bl < n ? k0 + bl : n;
		double t = 0;
		for (k = k0; k < k1; k++)
			t += a[k] * b[k];
		part[q] = t;
	}
	for (size_t q2 = 0; q2 < nb; q2++)
		s += part[q2];
	return s;
}

void
par_axpy(double *y, double f, const double *x, size_t n)
{
	long k;

#pragma omp parallel for schedule(static) if (n >= PAR_MIN_VEC)
	for (k = 0; k < (long)n; k++)
		y[k] += f * x[k];
}

void
par_scale(double *y, double f, const double *x, size_t n)
{
	long k;

#pragma omp parallel for schedule(static) if (n >= PAR_MIN_VEC)
	for (k = 0; k < (long)n; k++)
		y[k] = f * x[k];
}

double
par_neg_dot(double *y, const double *x, const double *z, size_t n)
{
	double part[PAR_MAXBLOCKS], s = 0;
	size_t bl = vec_block(n), nb = (n + bl - 1) / bl;
	long q;

#pragma omp parallel for schedule(static) if (n >= PAR_MIN_VEC)
	for (q = 0; q < (long)nb; q++) {
		size_t k, k0 = (size_t)q * bl, k1 = k0 + bl < n ? k0 + bl : n;
		double t = 0;
		for (k = k0; k < k1; k++) {
			y[k] = -x[k];
			t += z[k] * y[k];
		}
		part[q] = t;
	}
	for (size_t q2 = 0; q2 < nb; q2++)
		s += part[q2];
	return s;
}

double
par_axpy_scale_dot(double *y, double f, const double *x, double c, const double *z, size_t n)
{
	double part[PAR_MAXBLOCKS], s = 0;
	size_t bl = vec_block(n), nb = (n + bl - 1) / bl;
	long q;

#pragma omp parallel for schedule(static) if (n >= PAR_MIN_VEC)
	for (q = 0; q < (long)nb; q++) {
		size_t k, k0 = (size_t)q * bl, k1 = k0 + bl < n ? k0 + bl : n;
		double t = 0;
		for (k = k0; k < k1; k++) {
			y[k] = c * (y[k] + f * x[k]);
			t += z[k] * y[k];
		}
		part[q] = t;
	}
	for (size_t q2 = 0; q2 < nb; q2++)
		s += part[q2];
	return s;
}

void
par_diff_dots(double *s, const double *a, const double *b, double *y, const double *u, const double *v, size_t n,
    double *sy, double *yy)
{
	double p1[PAR_MAXBLOCKS], p2[PAR_MAXBLOCKS], s1 = 0, s2 = 0;
	size_t bl = vec_block(n), nb = (n + bl - 1) / bl;
	long q;

#pragma omp parallel for schedule(static) if (n >= PAR_MIN_VEC)
	for (q = 0; q < (long)nb; q++) {
		size_t k, k0 = (size_t)q * bl, k1 = k0 + bl < n ? k0 + bl : n;
		double t1 = 0, t2 = 0;
		for (k = k0; k < k1; k++) {
			s[k] = a[k] - b[k];
			y[k] = u[k] - v[k];
			t1 += s[k] * y[k];
			t2 += y[k] * y[k];
		}
		p1[q] = t1;
		p2[q] = t2;
	}
	for (size_t q2 = 0; q2 < nb; q2++) {
		s1 += p1[q2];
		s2 += p2[q2];
	}
	*sy = s1;
	*yy = s2;
}
