/* SPDX-License-Identifier: GPL-3.0-or-later */
/* vec3: the few 3-vector operations the physics modules share (inline, no state). */
#ifndef QUSGM_VEC3_H
#define QUSGM_VEC3_H

#include <math.h>

/* A loop over three (or nine) components unrolled whole (GCC does not at -O2): the same
 * operations in the same order, with small vectors kept in registers rather than on the
 * stack.  The frictional kernel (friction.c) took a third fewer instructions with it. */
#if defined(__GNUC__) && !defined(__clang__)
#define VEC3_UNROLL _Pragma("GCC unroll 9")
#elif defined(__clang__)
#define VEC3_UNROLL _Pragma("clang loop unroll(full)")
#else
#define VEC3_UNROLL
#endif

/* fmax(a, b) inline: the larger, and a NaN dropped for the other operand as fmax drops it
 * (GCC calls libm's fmax at -O2, a call per grain in the residual's and the step cap's loops,
 * 3 % of a frictional increment's instructions). */
static inline double
max_or_num(double a, double b)
{
	return a > b || b != b ? a : b;
}

static inline void
vec3_cross(const double a[3], const double b[3], double c[3])
{
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double
vec3_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline double
vec3_norm(const double a[3])
{
	return sqrt(vec3_dot(a, a));
}

#endif
