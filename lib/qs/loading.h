/* SPDX-License-Identifier: GPL-3.0-or-later */
/* loading: moving the walls of a pack and carrying the grains along (physics.md §7-8).
 *
 * The loader (struct loader) is what frictionalize and loadtest share: it holds a pack and
 * its functional, and each loader_step applies one strain increment, finds the equilibrium
 * (6N unknowns with friction, 3N without), commits the contact history into the pack and
 * measures the new state.  Everything an increment depends on is in the pack (positions,
 * box, reference box, contact history; rotations restart from zero), and the neighbour
 * lists sum in a fixed order, so a test split into two runs through a written pack repeats
 * the rows of one run to the last digit.
 *
 * Strains are compression-positive: eps_l = (L_l^ref - L_l) / L_l^ref.  A strain
 * increment moves both walls of an axis symmetrically about the box centre; the grains
 * follow affinely, which is the papers' initial guess (F (A1)) for the next equilibrium.
 * An increment can be applied in sub-increments, k_inc minimiser iterations apart, with the
 * last one minimised to convergence. */
#ifndef QUSGM_LOADING_H
#define QUSGM_LOADING_H

#include "qs/friction.h"
#include "qs/minimize.h"
#include "pack/pack.h"

/* Scale the box by (1 - de[a]) on each axis about its centre, and x affinely. */
void load_strain_box(double box[6], double *x, size_t n, const double de[3]);

/* Apply the strain increment de in nsub sub-increments and minimise; x is updated, and the
 * box of s->p.  Returns the status of the last minimisation; rep sums iterations.
 * load_increment_in minimises with the caller's minimiser m (qs_minimize_in), or with a
 * minimiser of its own when m is NULL (load_increment). */
int load_increment_in(struct qs_system *s, struct qs_minimizer *m, double *x, const double de[3], int nsub, long k_inc,
    const struct qs_min_params *mp, struct qs_min_report *rep);
int load_increment(struct qs_system *s, double *x, const double de[3], int nsub, long k_inc,
    const struct qs_min_params *mp, struct qs_min_report *rep);

/* Current strain of box against the reference box (compression positive). */
void load_strain(const double box[6], const double refbox[6], double eps[3]);

struct load_params {
	int friction;		/* 0: frictionless (3N unknowns, no history kept) */
	enum fr_rule rule;
	int nsub;		/* sub-increments per increment (affine guess each) */
	long k_inc;		/* minimiser iterations between sub-increments */
	double skin;		/* the largest Verlet skin / smallest radius (contact_enum_skin_auto) */
	double inc_tol;		/* with friction: the residual the increment is minimised to before
				 * its commit (LOAD_INC_TOL; at most min.tol: min.tol), see settle */
	int settle_fresh;	/* with friction: each settle pass starts L-BFGS afresh instead of
				 * going on with the last pass's pairs and blocks (settle) */
	struct qs_min_params min;
};

/* The commit of a frictional increment puts the state out of balance by 1e-2 to 2e-1
 * whatever residual the increment reached (its sliding limits were frozen at the start); the
 * settle passes after it bring it to min.tol.  So the increment itself needs only to find
 * which contacts stick and slide, not the last digits.  1e-3 keeps the sliding contacts of
 * a 200-grain pack the same contact for contact and the wall stresses to 2e-6 (1e-2 moved 4
 * of 648); with the cut settle passes, 1.4-1.8 times fewer iterations at 2740 grains and 2.1
 * at 1e4 (bench/settle.md). */
#define LOAD_INC_TOL 1e-3

/* L-BFGS's stored steps in frictional increments, where load_params_default's lbfgs_m of 0
 * (the tools' default --lbfgs-m) leaves the choice to the loader; frictionless increments
 * and densify keep QS_LBFGS_M (8).  With friction 4 steps take as many iterations as 8 while
 * the two-loop recursion's passes over the 6N-vectors halve (an eighth of a frictional
 * increment's time): over the 2740-grain pack's 9-20 MPa uniaxial curve 87.1 iterations per
 * increment against 86.7, 8.2 s against 8.8 s; 1e4 grains 264 against 261 iterations, 11.2 s
 * against 11.6 s for ten (bench/kernels.md).  Not without friction: there 4 steps
 * led the frictionless probes of s-fig4 (G5036 at 20 MPa) and fig5-6's frictionless G5036
 * curve to other equilibria, through rearrangements (K 0.93 against 1.15 GPa, G 0.022 against
 * 0.139 GPa at 20 MPa), which the studies read as outliers. */
#define LOAD_LBFGS_M 4

/* The state after an increment (or at the start). */
struct load_row {
	long inc;
	int seg;		/* path segment (1, 2, ...; 0 for the starting state) */
	double eps[3];		/* strain against the reference box, compression positive */
	double sig[3];		/* wall stresses (Pa) */
	double sig_lw[6];	/* volume-averaged (Love-Weber) stress xx yy zz xy xz yz (Pa) */
	double sigma_c;		/* tr(sig)/3 */
	double porosity, coordination;
	double bulk_porosity, bulk_coordination;	/* of the grains a diameter off the walls (measure_bulk) */
	/* contacts committed at their Coulomb limit |Q0| >= mu P0 (the paper's sliding ratio),
	 * and contacts whose elastic trial force reached mu P (DEM codes' slip fraction); of all
	 * contacts, before the increment's settling (fr_commit, share/doc/friction.md) */
	double sliding_ratio, trial_slip_ratio;
	long iterations, evals;
	double res_max, res_mean;
	int status;		/* the minimiser's: 0 converged, 1 iteration limit */
};

struct loader {
	struct pack *p;
	struct load_params lp;
	struct qs_system s;
	struct qs_friction f;
	double *x;		/* 6N: centres then R_i Omega_i */
	long inc;
	/* the minimiser of every increment and settle pass, made at the first for s's unknowns
	 * (its memory and preconditioner kept: loading.c, settle) */
	struct qs_minimizer *min;
	size_t min_dim;
};

void load_params_default(struct load_params *lp);
/* Start loading p (which must have a reference box).  0 or -1. */
int loader_open(struct loader *L, struct pack *p, const struct load_params *lp);
/* The current state of the pack, as a row with inc = the increments so far; the residual is
 * that of the pack as it stands (its history forces included).  0 or -1. */
int loader_measure(struct loader *L, struct load_row *row);
/* One increment de of the strain against the reference box (compression positive per axis:
 * each box length shrinks by de times its reference length); row receives the new state.  Returns
 * -1 on error, else the minimiser's status (1: iteration limit; the pack holds the state
 * reached, committed). */
int loader_step(struct loader *L, const double de[3], struct load_row *row);
void loader_close(struct loader *L);
/* What a message about an increment stopped at its iteration limit adds: "" or "; N friction
 * history lines slipped to their limit at the commit" (fr_commit slips the lines that such a
 * commit far from equilibrium leaves beyond the reader's bound, so that the pack reads back).
 * Written to buf (n bytes), which is returned. */
const char *loader_limit_note(const struct loader *L, char *buf, size_t n);

/* The rows as TSV (share/doc/tables.md): inc, seg, strains, wall stresses, Love-Weber normal
 * stresses, sigma_c, the mean lateral stress sig_lat (of the two axes other than axis), porosity,
 * coordination, sliding_ratio, trial_slip_ratio, iterations, residual, res_mean, bulk_porosity,
 * bulk_coordination; with_moduli adds K and G of
 * the increment (NaN where the increment does not determine them, and on the first row). */
#include <stdio.h>
void load_table_header(FILE *fp, int with_moduli);
void load_table_row(FILE *fp, const struct load_row *row, int axis, int with_moduli, double K, double G);
/* frictionalize's log: the rows with K and G, then elapsed[s], the wall time since the run
 * started (the one column that differs between two runs of the same command). */
void load_log_header(FILE *fp);
void load_log_row(FILE *fp, const struct load_row *row, int axis, double K, double G, double elapsed);

#endif
