/* hertz: the normal contact law between elastic spheres and with walls (physics.md §2).
 *
 * R* = (1/R_i + 1/R_j)^-1 (wall: R_i), E* = ((1-nu_i^2)/E_i + (1-nu_j^2)/E_j)^-1, overlap h,
 * P = 4/3 E* sqrt(R*) h^(3/2), U = 8/15 E* sqrt(R*) h^(5/2), dU/dh = P, dP/dh = 2 E* a,
 * a = sqrt(R* h).  SI units. */
#ifndef QUSGM_HERTZ_H
#define QUSGM_HERTZ_H

#include <math.h>

static inline double
hertz_Rstar(double Ri, double Rj)
{
	return Ri * Rj / (Ri + Rj);
}

static inline double
hertz_Estar(double Ei, double nui, double Ej, double nuj)
{
	return 1.0 / ((1.0 - nui * nui) / Ei + (1.0 - nuj * nuj) / Ej);
}

/* Normal force for overlap h (0 when h <= 0). */
static inline double
hertz_force(double Es, double Rs, double h)
{
	return h > 0 ? 4.0 / 3.0 * Es * sqrt(Rs) * h * sqrt(h) : 0.0;
}

/* Elastic energy stored at overlap h. */
static inline double
hertz_energy(double Es, double Rs, double h)
{
	return h > 0 ? 8.0 / 15.0 * Es * sqrt(Rs) * h * h * sqrt(h) : 0.0;
}

/* Normal stiffness dP/dh = 2 E* sqrt(R* h). */
static inline double
hertz_stiffness(double Es, double Rs, double h)
{
	return h > 0 ? 2.0 * Es * sqrt(Rs * h) : 0.0;
}

/* Overlap that carries force P (the inverse of hertz_force). */
static inline double
hertz_overlap(double Es, double Rs, double P)
{
	return P > 0 ? cbrt(P * P * 9.0 / (16.0 * Es * Es * Rs)) : 0.0;
}

#endif
