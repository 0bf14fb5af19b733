/* SPDX-License-Identifier: GPL-3.0-or-later */
/* par: threads and thread-count-independent sums (see par.h). */
#include "base/par.h"
#include "base/lanes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

int
par_cpus_busy(void)
{
	int k, least = -1;

	/* /proc/stat's procs_running: the tasks runnable at this moment, this one included; the
	 * least of three looks 1 ms apart counts those that stay busy (a compile, a `yes`), not
	 * the ones that happened to be awake */
	for (k = 0; k < 3; k++) {
		FILE *fp = fopen("/proc/stat", "r");
		char line[256];
		int n = -1;

		if (!fp)
			return -1;
		while (fgets(line, sizeof line, fp))
			if (sscanf(line, "procs_running %d", &n) == 1)
				break;
		fclose(fp);
		if (n < 1)
			return -1;
		if (least < 0 || n - 1 < least)
			least = n - 1;
		if (k < 2) {
			struct timespec ms = {0, 1000000};
			nanosleep(&ms, NULL);
		}
	}
	return least;
}

#ifdef _OPENMP
/* The default: OMP_NUM_THREADS when the user set it; else the cores this process may run on
 * (OpenMP's count, which follows the affinity mask a batch system sets) less those other tasks
 * keep busy across the whole machine, at least 1. */
static int
default_threads(void)
{
	int most = omp_get_max_threads(), busy, free;
	long online = sysconf(_SC_NPROCESSORS_ONLN);

	if (getenv("OMP_NUM_THREADS") || most <= 1 || (busy = par_cpus_busy()) < 0 || online < 1)
		return most;
	free = (int)(online - busy);
	return free < 1 ? 1 : free < most ? free : most;
}
#endif

int
par_default_threads(void)
{
#ifdef _OPENMP
	static int dflt;

	if (!dflt)
		dflt = default_threads();
	return dflt;
#else
	return 1;
#endif
}

void
par_set_threads(int n)
{
#ifdef _OPENMP
	omp_set_num_threads(n > 0 ? n : par_default_threads());
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

#if LANES_OK
/* op_term on elements k and k + 1 in two lanes: the same operations on each (no
 * contraction), so each lane's term has op_term's bytes. */
PAR_INLINE v2d
op_term2(const int op, size_t k, double *y, const double *x, const double *z, double f, double c)
{
	v2d X, Y, Z;

	if (op == OP_DOT) {
		memcpy(&X, x + k, sizeof X);
		memcpy(&Z, z + k, sizeof Z);
		return X * Z;
	}
	memcpy(&X, x + k, sizeof X);
	if (op == OP_NEG_DOT) {
		Y = -X;
	} else {
		memcpy(&Y, y + k, sizeof Y);
		Y = (v2d){c, c} * (Y + (v2d){f, f} * X);
	}
	memcpy(y + k, &Y, sizeof Y);
	memcpy(&Z, z + k, sizeof Z);
	return Z * Y;
}

/* Four blocks' chains, elements k and k + 1 of each at a time: the terms come in two lanes
 * per block, are regrouped (a 2x2 transpose) so that one register holds element k of blocks
 * 0 and 1, the next element k + 1 of both, and are added to the chains (t0, t1) and (t2, t3)
 * in that order: each chain still adds its block's terms one by one from its first element,
 * the bytes of the scalar walk, with half its instructions.  Returns the elements done (an
 * odd last one is left to the scalar walk). */
PAR_INLINE size_t
op_chains4(const int op, size_t bl, size_t k0, double t[4], double *y, const double *x, const double *z, double f,
    double c)
{
	size_t k, k1 = k0 + bl, k2 = k1 + bl, k3 = k2 + bl;
	v2d T01 = {0, 0}, T23 = {0, 0};

	for (k = 0; k + 2 <= bl; k += 2) {
		v2d p0 = op_term2(op, k0 + k, y, x, z, f, c), p1 = op_term2(op, k1 + k, y, x, z, f, c);
		v2d p2 = op_term2(op, k2 + k, y, x, z, f, c), p3 = op_term2(op, k3 + k, y, x, z, f, c);
		T01 += (v2d){p0[0], p1[0]};
		T23 += (v2d){p2[0], p3[0]};
		T01 += (v2d){p0[1], p1[1]};
		T23 += (v2d){p2[1], p3[1]};
	}
	t[0] = T01[0], t[1] = T01[1], t[2] = T23[0], t[3] = T23[1];
	return k;
}
#endif

/* Blocks q0 <= q < q1 of n elements in blocks of bl into part[q]. */
PAR_INLINE void
op_blocks(const int op, size_t n, size_t bl, size_t q0, size_t q1, double *part, double *y, const double *x,
    const double *z, double f, double c)
{
	size_t q = q0, k;

	for (; q + 4 <= q1 && (q + 4) * bl <= n; q += 4) {
		size_t k0 = q * bl, k1 = k0 + bl, k2 = k1 + bl, k3 = k2 + bl;
		double t0 = 0, t1 = 0, t2 = 0, t3 = 0;
		k = 0;
#if LANES_OK
		if (op != OP_QUAD3) {
			double t[4];
			k = op_chains4(op, bl, k0, t, y, x, z, f, c);
			t0 = t[0], t1 = t[1], t2 = t[2], t3 = t[3];
		}
#endif
		for (; k < bl; k++) {
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

#if LANES_OK
/* par_diff_dots' elements k and k + 1 of block k0's run in lanes: s, y written, the terms
 * s y and y y into *sy and *yy (each lane op for op as the scalar walk). */
PAR_INLINE void
diff_term2(size_t k, double *s, const double *a, const double *b, double *y, const double *u, const double *v,
    v2d *sy, v2d *yy)
{
	v2d A, B, U, V, S, Y;

	memcpy(&A, a + k, sizeof A), memcpy(&B, b + k, sizeof B);
	memcpy(&U, u + k, sizeof U), memcpy(&V, v + k, sizeof V);
	S = A - B, Y = U - V;
	memcpy(s + k, &S, sizeof S), memcpy(y + k, &Y, sizeof Y);
	*sy = S * Y, *yy = Y * Y;
}
#endif

void
par_diff_dots(double *s, const double *a, const double *b, double *y, const double *u, const double *v, size_t n,
    double *sy, double *yy)
{
	double p1[PAR_MAXBLOCKS], p2[PAR_MAXBLOCKS], s1 = 0, s2 = 0;
	size_t bl = vec_block(n), nb = (n + bl - 1) / bl, q2;

#pragma omp parallel if (n >= PAR_MIN_VEC && nb > 1)
	{
		size_t T = (size_t)par_team(), t = (size_t)par_tid(), q0 = nb * t / T, q1 = nb * (t + 1) / T, q = q0, k;

		/* four blocks' chains at a time in lanes, as op_chains4 (the same order per chain) */
		for (; q + 4 <= q1 && (q + 4) * bl <= n; q += 4) {
			size_t k0 = q * bl, kb[4] = {k0, k0 + bl, k0 + 2 * bl, k0 + 3 * bl};
			double t1[4] = {0, 0, 0, 0}, t2[4] = {0, 0, 0, 0};
			int w;
			k = 0;
#if LANES_OK
			{
				v2d A01 = {0, 0}, A23 = {0, 0}, B01 = {0, 0}, B23 = {0, 0};
				for (; k + 2 <= bl; k += 2) {
					v2d sy0, yy0, sy1, yy1, sy2, yy2, sy3, yy3;
					diff_term2(kb[0] + k, s, a, b, y, u, v, &sy0, &yy0);
					diff_term2(kb[1] + k, s, a, b, y, u, v, &sy1, &yy1);
					diff_term2(kb[2] + k, s, a, b, y, u, v, &sy2, &yy2);
					diff_term2(kb[3] + k, s, a, b, y, u, v, &sy3, &yy3);
					A01 += (v2d){sy0[0], sy1[0]}, A23 += (v2d){sy2[0], sy3[0]};
					B01 += (v2d){yy0[0], yy1[0]}, B23 += (v2d){yy2[0], yy3[0]};
					A01 += (v2d){sy0[1], sy1[1]}, A23 += (v2d){sy2[1], sy3[1]};
					B01 += (v2d){yy0[1], yy1[1]}, B23 += (v2d){yy2[1], yy3[1]};
				}
				t1[0] = A01[0], t1[1] = A01[1], t1[2] = A23[0], t1[3] = A23[1];
				t2[0] = B01[0], t2[1] = B01[1], t2[2] = B23[0], t2[3] = B23[1];
			}
#endif
			for (; k < bl; k++)
				for (w = 0; w < 4; w++) {
					size_t e = kb[w] + k;
					s[e] = a[e] - b[e];
					y[e] = u[e] - v[e];
					t1[w] += s[e] * y[e];
					t2[w] += y[e] * y[e];
				}
			for (w = 0; w < 4; w++)
				p1[q + (size_t)w] = t1[w], p2[q + (size_t)w] = t2[w];
		}
		for (; q < q1; q++) {
			size_t k1 = (q + 1) * bl < n ? (q + 1) * bl : n;
			double t1 = 0, t2 = 0;
			for (k = q * bl; k < k1; k++) {
				s[k] = a[k] - b[k];
				y[k] = u[k] - v[k];
				t1 += s[k] * y[k];
				t2 += y[k] * y[k];
			}
			p1[q] = t1;
			p2[q] = t2;
		}
	}
	for (q2 = 0; q2 < nb; q2++) {
		s1 += p1[q2];
		s2 += p2[q2];
	}
	*sy = s1;
	*yy = s2;
}
