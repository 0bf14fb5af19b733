/* SPDX-License-Identifier: GPL-3.0-or-later */
/* lanes: two doubles side by side in one SSE register (GCC and clang vector extensions),
 * for the hot kernels that evaluate two contacts or two grains at once (friction.c; the DEM
 * engine's sphere pass, dem/engine_spheres.c; functional.c's residual and minimize.c's step cap; par.c's dot products),
 * and four in an AVX2 register for the friction kernel where the processor has AVX2 (below:
 * chosen at run time, so the build stays the baseline x86-64 one).  Every operation is IEEE
 * arithmetic on each lane, with no contraction (the Makefile's -ffp-contract=off, which GCC's
 * ISO C mode implies and clang's default is not), so a lane computes the bytes its scalar code
 * would.  The point is the divider: on the AMD and Intel cores this runs on, a two-lane
 * division or square root costs what one scalar does, and these kernels are bound by them.  LANES_OK says the extensions exist;
 * without them the callers keep their scalar loops. */
#ifndef QUSGM_LANES_H
#define QUSGM_LANES_H

#include <math.h>

#if defined(__GNUC__)
#define LANES_OK 1
typedef double v2d __attribute__((vector_size(16)));
typedef long long v2m __attribute__((vector_size(16)));

/* q0 = a0 / b0 and q1 = a1 / b1 as one two-lane division (each lane correctly rounded). */
#define V2_DIV2(q0, q1, a0, a1, b0, b1) do { \
		v2d v2_n_ = {(a0), (a1)}, v2_d_ = {(b0), (b1)}, v2_q_ = v2_n_ / v2_d_; \
		(q0) = v2_q_[0]; \
		(q1) = v2_q_[1]; \
	} while (0)
/* lane by lane: a where the mask m (a comparison's result: all ones or zero) is set, else b */
#define V2_SELECT(m, a, b) ((v2d)(((v2m)(a) & (m)) | ((v2m)(b) & ~(m))))
#define V2_ABS(a) ((v2d)((v2m)(a) & (v2m){0x7fffffffffffffffLL, 0x7fffffffffffffffLL}))
#if defined(__SSE2__)
#include <emmintrin.h>
/* both lanes' square roots in one instruction, each correctly rounded (two sqrt calls' bytes) */
#define V2_SQRT(a) ((v2d)_mm_sqrt_pd((__m128d)(a)))
#else
#define V2_SQRT(a) ((v2d){sqrt((a)[0]), sqrt((a)[1])})
#endif
/* c = a x b, lane by lane (three-vectors of v2d) */
#define V2_CROSS(a, b, c) do { \
		(c)[0] = (a)[1] * (b)[2] - (a)[2] * (b)[1]; \
		(c)[1] = (a)[2] * (b)[0] - (a)[0] * (b)[2]; \
		(c)[2] = (a)[0] * (b)[1] - (a)[1] * (b)[0]; \
	} while (0)
/* Four lanes (AVX2), for the friction kernel: code in functions marked AVX2_FN (or inlined
 * into them, AVX2_INLINE), called only where lanes4_ok() says the processor has AVX2.  The
 * same lane-by-lane IEEE arithmetic as v2d, so the same bytes. */
#if defined(__x86_64__) && (defined(__clang__) || __GNUC__ >= 5)
#define LANES4_OK 1
#include <immintrin.h>
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4m __attribute__((vector_size(32)));
#define AVX2_FN __attribute__((target("avx2")))
#define AVX2_INLINE static inline __attribute__((always_inline, target("avx2")))
#define V4_SELECT(m, a, b) ((v4d)(((v4m)(a) & (m)) | ((v4m)(b) & ~(m))))
#define V4_ABS(a) ((v4d)((v4m)(a) & (v4m){0x7fffffffffffffffLL, 0x7fffffffffffffffLL, 0x7fffffffffffffffLL, \
		0x7fffffffffffffffLL}))
#define V4_SQRT(a) ((v4d)_mm256_sqrt_pd((__m256d)(a)))
#define V4_CROSS(a, b, c) V2_CROSS(a, b, c)
static inline int
lanes4_ok(void)
{
	static int ok = -1;

	if (ok < 0)
		ok = __builtin_cpu_supports("avx2") ? 1 : 0;
	return ok;
}
#else
#define LANES4_OK 0
#endif
#else
#define LANES_OK 0
#define LANES4_OK 0
#define V2_DIV2(q0, q1, a0, a1, b0, b1) do { \
		(q0) = (a0) / (b0); \
		(q1) = (a1) / (b1); \
	} while (0)
#endif

#endif
