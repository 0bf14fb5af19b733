/* loading: moving the walls of a pack and carrying the grains along (physics.md §7-8).
 *
 * Strains are compression-positive: eps_l = (L_l^ref - L_l) / L_l^ref.  A strain
 * increment moves both walls of an axis symmetrically about the box centre; the grains
 * follow affinely, which is the papers' initial guess (F (A1)) for the next equilibrium.
 * An increment can be applied in sub-increments, k_inc minimiser iterations apart, with the
 * last one minimised to convergence. */
#ifndef QUSGM_LOADING_H
#define QUSGM_LOADING_H

#include "minimize.h"
#include "pack.h"

/* Scale the box by (1 - de[a]) on each axis about its centre, and x affinely. */
void load_strain_box(double box[6], double *x, size_t n, const double de[3]);

/* Apply the strain increment de in nsub sub-increments and minimise; x is updated, and the
 * box of s->p.  Returns the status of the last minimisation; rep sums iterations. */
int load_increment(struct qs_system *s, double *x, const double de[3], int nsub, long k_inc,
    const struct qs_min_params *mp, struct qs_min_report *rep);

/* Current strain of box against the reference box (compression positive). */
void load_strain(const double box[6], const double refbox[6], double eps[3]);

#endif
