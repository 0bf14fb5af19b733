/* fabric: the microstructure descriptors of the platy-particle paper (P §IV; physics.md §12),
 * in the shear plane xy of its simple shear test.
 *
 * From a set of interactions (unit normal n, branch vector l between the centres, force F on
 * the grain the normal points to, and whether it is at the Coulomb limit) and the face normals
 * m of the plates, the tensors
 *     M      = <m m>                (P eq. 9, over the particles)
 *     F      = <n n>                (eq. 11)
 *     chi_ln = <l_n n n>,  chi_l = <sym(n l)>      (eqs. 15-17; l_n = l.n)
 *     chi_fn = <F_n n n>,  chi_f = <sym(n F)>      (eqs. 23-25; F_n = F.n)
 * (<> the mean over the interactions; n l = n_a l_b, whose tangential part is P's chi_lt =
 * <l_t n t>, likewise for F), and of each its anisotropy and direction in the xy plane:
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
 * K_s is the fraction of interactions at the Coulomb limit (P Fig. 21). */
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
	double a_n, theta_n;
	double a_ln, theta_ln, a_lt, theta_lt;
	double a_fn, theta_fn, a_ft, theta_ft;
	double K_s;
	double p, q, qp, theta_sigma;	/* from sigma */
	double qp_harmonic;		/* P eq. 28 */
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
