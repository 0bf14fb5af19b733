/* vec3: the few 3-vector operations the physics modules share (inline, no state). */
#ifndef QUSGM_VEC3_H
#define QUSGM_VEC3_H

#include <math.h>

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
