/* par: threads and thread-count-independent sums (see par.h). */
#include "base/par.h"

#include <stdlib.h>
#include <string.h>

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

/* The dot products: each block of vec_block(n) summed in order from its first element, the
 * block sums then added in block order, so the value depends on n alone.  A block's sum is
 * one chain of dependent additions, as long as the add latency allows; the blocks' chains
 * are independent, so a thread walks up to four of its blocks side by side, element k of
 * each in turn, each chain still in its own order (the same bytes as one block after the
 * other, up to four times as fast).  op: y[k] (written first when op writes) and the term
 * z[k] y[k] of element k. */
enum { OP_DOT, OP_NEG_DOT, OP_AXPY_DOT, OP_QUAD3 };

#if defined(__GNUC__)
#define PAR_INLINE static inline __attribute__((always_inline))
#else
#define PAR_INLINE static inline
#endif

PAR_INLINE double
op_term(const int op, size_t k, double *y, const double *x, const double *z, double f, double c)
{
	if (op == OP_DOT)
		return x[k] * z[k];
	if (op == OP_QUAD3) {	/* x: the 3x3 blocks M; z[k] (M z)[k], (M z)[k] as precond_apply */
		size_t i = k / 3, u = k % 3;
		const double *Mr = x + 9 * i + 3 * u, *zi = z + 3 * i;
		return z[k] * (Mr[0] * zi[0] + Mr[1] * zi[1] + Mr[2] * zi[2]);
	}
	if (op == OP_NEG_DOT)
		y[k] = -x[k];
	else
		y[k] = c * (y[k] + f * x[k]);
	return z[k] * y[k];
}

/* Blocks q0 <= q < q1 of n elements in blocks of bl into part[q]. */
PAR_INLINE void
op_blocks(const int op, size_t n, size_t bl, size_t q0, size_t q1, double *part, double *y, const double *x,
    const double *z, double f, double c)
{
	size_t q = q0, k;

	for (; q + 4 <= q1 && (q + 4) * bl <= n; q += 4) {
		size_t k0 = q * bl, k1 = k0 + bl, k2 = k1 + bl, k3 = k2 + bl;
		double t0 = 0, t1 = 0, t2 = 0, t3 = 0;
		for (k = 0; k < bl; k++) {
			t0 += op_term(op, k0 + k, y, x, z, f, c);
			t1 += op_term(op, k1 + k, y, x, z, f, c);
			t2 += op_term(op, k2 + k, y, x, z, f, c);
			t3 += op_term(op, k3 + k, y, x, z, f, c);
		}
		part[q] = t0, part[q + 1] = t1, part[q + 2] = t2, part[q + 3] = t3;
	}
	for (; q + 2 <= q1 && (q + 2) * bl <= n; q += 2) {
		size_t k0 = q * bl, k1 = k0 + bl;
		double t0 = 0, t1 = 0;
		for (k = 0; k < bl; k++) {
			t0 += op_term(op, k0 + k, y, x, z, f, c);
			t1 += op_term(op, k1 + k, y, x, z, f, c);
		}
		part[q] = t0, part[q + 1] = t1;
	}
	for (; q < q1; q++) {
		size_t k0 = q * bl, kend = k0 + bl < n ? k0 + bl : n;
		double t = 0;
		for (k = k0; k < kend; k++)
			t += op_term(op, k, y, x, z, f, c);
		part[q] = t;
	}
}

/* The sum of op over n elements, on threads: each takes a run of blocks. */
PAR_INLINE double
op_sum(const int op, size_t n, double *y, const double *x, const double *z, double f, double c)
{
	double part[PAR_MAXBLOCKS], s = 0;
	size_t bl = vec_block(n), nb = (n + bl - 1) / bl, q;

#pragma omp parallel if (n >= PAR_MIN_VEC && nb > 1)
	{
		size_t T = (size_t)par_team(), t = (size_t)par_tid(), q0 = nb * t / T, q1 = nb * (t + 1) / T;
		/* op as a constant in each call: OpenMP outlines the region before inlining */
		if (op == OP_DOT)
			op_blocks(OP_DOT, n, bl, q0, q1, part, y, x, z, f, c);
		else if (op == OP_QUAD3)
			op_blocks(OP_QUAD3, n, bl, q0, q1, part, y, x, z, f, c);
		else if (op == OP_NEG_DOT)
			op_blocks(OP_NEG_DOT, n, bl, q0, q1, part, y, x, z, f, c);
		else
			op_blocks(OP_AXPY_DOT, n, bl, q0, q1, part, y, x, z, f, c);
	}
	for (q = 0; q < nb; q++)
		s += part[q];
	return s;
}

double
par_dot(const double *a, const double *b, size_t n)
{
	return op_sum(OP_DOT, n, NULL, a, b, 0, 0);
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

/* y = x, or y = 0 when x is NULL: each thread clears or copies its own run of whole
 * PAR_MIN_VEC-element pieces, the calling thread alone below PAR_MIN_VEC elements. */
static void
copy_pieces(double *y, const double *x, size_t n)
{
	long q, nq = (long)((n + PAR_MIN_VEC - 1) / PAR_MIN_VEC);

#pragma omp parallel for schedule(static) if (nq > 1)
	for (q = 0; q < nq; q++) {
		size_t k0 = (size_t)q * PAR_MIN_VEC, len = n - k0 < PAR_MIN_VEC ? n - k0 : PAR_MIN_VEC;
		if (x)
			memcpy(y + k0, x + k0, len * sizeof *y);
		else
			memset(y + k0, 0, len * sizeof *y);
	}
}

void
par_zero(double *y, size_t n)
{
	copy_pieces(y, NULL, n);
}

void
par_copy(double *y, const double *x, size_t n)
{
	copy_pieces(y, x, n);
}

double
par_quad3(const double *M, const double *y, size_t n)
{
	return op_sum(OP_QUAD3, n, NULL, M, y, 0, 0);
}

double
par_neg_dot(double *y, const double *x, const double *z, size_t n)
{
	return op_sum(OP_NEG_DOT, n, y, x, z, 0, 0);
}

double
par_axpy_scale_dot(double *y, double f, const double *x, double c, const double *z, size_t n)
{
	return op_sum(OP_AXPY_DOT, n, y, x, z, f, c);
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
