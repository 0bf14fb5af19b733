/* SPDX-License-Identifier: GPL-3.0-or-later */
/* quat: unit quaternions for the orientation of non-spherical grains (inline, no state).
 *
 * q = (w, x, y, z) with w the scalar part.  A grain's quaternion turns its body frame into
 * the lab frame: a vector b in the body frame is R(q) b in the lab, and the columns of R(q)
 * are the body axes in lab coordinates.  For a spheroplate the body axes are e1, e2 along
 * the edges of its square core and e3 the face normal (pack/shape.h). */
#ifndef QUSGM_QUAT_H
#define QUSGM_QUAT_H

#include <math.h>

/* pi, the value of <math.h>'s M_PI, which strict C11 (-std=c11 without a feature macro)
 * does not define: the installed header compiles in a user's program either way. */
#define QUAT_PI 3.14159265358979323846

/* c = a b (Hamilton product): the rotation b, then a. */
static inline void
quat_mul(const double a[4], const double b[4], double c[4])
{
	double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
	double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
	double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
	double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];

	c[0] = w, c[1] = x, c[2] = y, c[3] = z;
}

static inline double
quat_norm(const double q[4])
{
	return sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
}

static inline void
quat_normalize(double q[4])
{
	double s = 1 / quat_norm(q);

	q[0] *= s, q[1] *= s, q[2] *= s, q[3] *= s;
}

/* The rotation matrix R(q), row-major (m[3 * row + col]), of a unit quaternion. */
static inline void
quat_to_matrix(const double q[4], double m[9])
{
	double w = q[0], x = q[1], y = q[2], z = q[3];

	m[0] = 1 - 2 * (y * y + z * z), m[1] = 2 * (x * y - w * z), m[2] = 2 * (x * z + w * y);
	m[3] = 2 * (x * y + w * z), m[4] = 1 - 2 * (x * x + z * z), m[5] = 2 * (y * z - w * x);
	m[6] = 2 * (x * z - w * y), m[7] = 2 * (y * z + w * x), m[8] = 1 - 2 * (x * x + y * y);
}

/* A uniformly random rotation from three uniform deviates in [0, 1) (Shoemake 1992). */
static inline void
quat_from_uniform(double u1, double u2, double u3, double q[4])
{
	double a = sqrt(1 - u1), b = sqrt(u1), t1 = 2 * QUAT_PI * u2, t2 = 2 * QUAT_PI * u3;

	q[0] = b * cos(t2), q[1] = a * sin(t1), q[2] = a * cos(t1), q[3] = b * sin(t2);
}

/* The rotation by angle |w| dt about w (body frame, right-multiplied: q <- q dq), by P's
 * App. A form dq0 = (1 - G)/(1 + G), dq = dt w / (2 (1 + G)), G = dt^2 |w|^2 / 16: a unit
 * quaternion for any step (a Cayley map, angle 4 atan(dt |w| / 4) = dt |w| + O(dt^3)). */
static inline void
quat_step_body(double q[4], const double w[3], double dt)
{
	double G = dt * dt * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) / 16, s = dt / (2 * (1 + G)), dq[4], out[4];

	dq[0] = (1 - G) / (1 + G), dq[1] = s * w[0], dq[2] = s * w[1], dq[3] = s * w[2];
	quat_mul(q, dq, out);
	q[0] = out[0], q[1] = out[1], q[2] = out[2], q[3] = out[3];
}

#endif
