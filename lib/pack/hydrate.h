/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hydrate: which grains of a pack are gas hydrate (the phase column, pack.h).
 *
 * packgen --hydrate-volume F makes the smallest grains hydrate, the pore-filling hydrate of
 * the paper modelled as grains of their own.  Volumes in m^3, F and the fraction reached
 * dimensionless. */
#ifndef QUSGM_HYDRATE_H
#define QUSGM_HYDRATE_H

#include <gsl/gsl_rng.h>
#include "pack/material.h"
#include "pack/pack.h"

/* Tag the smallest grains of p PHASE_HYDRATE until they hold the fraction F (0 <= F < 1) of
 * the grain volume.  The rule, exactly: order the grains by radius, ascending, ties by index
 * (the lower first); sum their volumes (4/3 pi r^3, spheres only) in that order; the hydrate
 * grains are the shortest prefix whose sum is >= F times the sum over all grains.  F = 0
 * tags none.  p gets the phase column (pack_set_phases; a fresh pack, every grain mineral)
 * and every other grain is left as it is.  Each tagged grain, in index order, gets E and nu drawn from hyd by material_sample
 * (rng) and the density hyd->rho.  0 with *ntag (the number tagged) and *reached (their
 * fraction of the grain volume) set when not NULL; -1 (msg_seterr) for F outside [0, 1),
 * a pack with a spheroplate, or out of memory. */
int pack_tag_hydrate(struct pack *p, double F, const struct material *hyd, gsl_rng *rng, size_t *ntag,
    double *reached);

#endif
