/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fabric: the microstructure descriptors of the platy-particle paper (P §IV; physics.md §12),
 * in the shear plane xy of its simple shear test.
 *
 * From a set of interactions (unit normal n, branch vector l between the centres, force F on
 * the grain the normal points to, and whether it is at the Coulomb limit) and the face normals
 * m of the plates, the tensors
 *     M      = <m m>                (P eq. 9, over the particles)
 *     F      = <n n>                (eq. 11)
 *     chi_ln = <l_n n n>,  chi_l = chi_ln + chi_lt     (eqs. 15-17; l_n = l.n)
 *     chi_fn = <F_n n n>,  chi_f = chi_fn + chi_ft     (eqs. 23-25; F_n = F.n)
 * (<> the mean over the interactions; chi_lt and chi_ft below), and of each its anisotropy
 * and direction in the xy plane:
 * a = 2 (T1 - T3) / (T1 + T3), T1 >= T3 the eigenvalues of the tensor's xy block, theta the
 * direction of T1's eigenvector, in degrees in [0, 180) from x towards y.  That is P's
 * definition for a distribution restricted to the plane (for in-plane vectors T1 + T3 = 1 and
 * a = 2 (T1 - T3), P's a_m and a_n); in 3D the xy block counts each vector by the square of
 * its projection on the plane.  Then, as P eqs. 18-19 and 26-27 (whose a_c is a_n):
 *     a_ln = a(chi_ln) - a_n,   a_lt = a(chi_l) - a_n - a_ln,
 *     a_fn = a(chi_fn) - a_n,   a_ft = a(chi_f) - a_n - a_fn,
 * with theta_ln, theta_lt, theta_fn, theta_ft the directions of chi_ln, chi_l, chi_fn, chi_f.
 * These subtractions neglect the products of anisotropies (P's assumption): for P_n(theta) =
 * (1 + a_n cos 2 theta)/pi and <l_n>(theta) = L (1 + b cos 2 theta), a(chi_ln) is
 * (a_n + b)/(1 + a_n b / 2), not a_n + b (test_fabric.c checks the closed forms).
 *
 * From the stress tensor sigma (compression positive): p = (s1 + s3)/2, q = (s1 - s3)/2 of
 * its xy block, theta_sigma the direction of s1, and P eq. 28's harmonic approximation
 *     q/p ~ (1/2) [a_n cos 2(theta_n - theta_s) + a_ln cos 2(theta_ln - theta_s)
 *                  + a_lt cos 2(theta_lt - theta_s) + a_fn cos 2(theta_fn - theta_s)
 *                  + a_ft cos 2(theta_ft - theta_s)].
 * K_s is the fraction of interactions at the Coulomb limit (P Fig. 21).
 *
 * The tangential parts follow P eqs. 12, 16 and 24 literally: t is the direction of the
 * interaction's tangential force F_t = F - F_n n, l_t = l . t (the branch vector's
 * projection on it, not its whole tangential part) and F_t = |F_t|, so
 *     chi_lt = <l_t sym(n t)>,  chi_ft = <F_t sym(n t)>,
 * an interaction without tangential force adding nothing to either (and without any force
 * t is unknown: a_lt is then NaN, see measure.c).  Eqs. 19 and 27 take chi_l = chi_ln + chi_lt
 * and chi_f = chi_fn + chi_ft to be co-axial with F; beside them, each tangential tensor's
 * own anisotropy and direction (the "direct" ones): with T1 >= T3 the eigenvalues of the xy
 * block of chi_lt (chi_ft),
 *     a_lt_direct = 2 (T1 - T3) / tr_xy chi_ln,   a_ft_direct = 2 (T1 - T3) / tr_xy chi_fn,
 * theta the direction of T1.  For <F_t>(theta) = <F_n> a sin 2(theta - theta_ft) (P eq. 22)
 * over a fabric of any a_n, to first order, a_ft_direct = a; when chi_ft is co-axial with
 * chi_fn, a(chi_f) = a(chi_fn) + a_ft_direct and eq. 27's a_ft is a_ft_direct (likewise for
 * the branches).  qp_harmonic_direct is eq. 28 with the direct tangential terms (a_lt_direct,
 * theta_lt_direct, a_ft_direct, theta_ft_direct) in place of eqs. 19 and 27's.
 *
 * Beside the planar a_m (the xy block, as P's Fig. 11 restricts P_m to the plane), the 3D
 * nematic tensor's own measures: with M1 >= M2 >= M3 its eigenvalues, a_m_3d = 2 (M1 - M3)
 * (P's formula read on the 3D tensor), M1 - M3, and the nematic order parameter
 * S = (3 M1 - 1)/2 (the largest eigenvalue of <(3 m m - I)/2>: 1 for parallel normals, 1/4
 * for normals spread evenly over a plane, 0 isotropic). */
#ifndef QUSGM_FABRIC_H
#define QUSGM_FABRIC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

struct fabric_interaction {
	double n[3];	/* unit normal */
	double l[3];	/* branch vector, from the other centre to this one's (along n) */
	double F[3];	/* force on this one */
	int sliding;	/* at the Coulomb limit */
};

struct fabric_desc {
	size_t interactions, particles;
	double a_m, theta_m;		/* NaN without particles */
	double a_m_3d, m1_m3, nematic_S;	/* of the 3D tensor M; NaN without particles */
	double a_n, theta_n;
	double a_ln, theta_ln, a_lt, theta_lt;
	double a_fn, theta_fn, a_ft, theta_ft;
	double a_lt_direct, theta_lt_direct, a_ft_direct, theta_ft_direct;
	double K_s;
	double p, q, qp, theta_sigma;	/* from sigma */
	double qp_harmonic;		/* P eq. 28 */
	double qp_harmonic_direct;	/* eq. 28 with the direct tangential terms */
};

/* The anisotropy a and direction theta (degrees, [0, 180)) in the xy plane of the symmetric
 * tensor t (xx yy zz xy xz yz); a = NaN when its xy block has no positive trace. */
void fabric_planar(const double t[6], double *a, double *theta);
/* The descriptors of n interactions and np face normals m (3 each; NULL when np is 0) under
 * stress sig (xx yy zz xy xz yz, or NULL: no p, q, theta_sigma, qp_harmonic).  With n = 0
 * every interaction descriptor is NaN. */
void fabric_describe(const struct fabric_interaction *it, size_t n, const double *m, size_t np, const double sig[6],
    struct fabric_desc *d);

#ifdef __cplusplus
}
#endif

#endif
