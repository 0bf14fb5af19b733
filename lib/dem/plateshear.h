/* SPDX-License-Identifier: GPL-3.0-or-later */
/* plateshear: the platy-particle paper's simple shear test (P §II C, Fig. 4b), for packs of
 * spheroplates and of spheres, under any law of the table (shear_params.dyn.law: P's linear
 * law, or Hertz-Mindlin with the grains' moduli; dem/engine.h).  Under Hertz the time step
 * is made for the overlaps sigma_w makes (ENGINE_OVERLAP_KAPPA / kappa, engine_kappa).
 *
 * Shear direction x, gradient direction y, neutral direction z.  x and z are periodic (a pack
 * compacted between six walls has those walls replaced, its lengths kept as the periods; a
 * pack already periodic there is taken as it is); y keeps its walls.  The grains touching the
 * bottom or the top wall at the start are glued to it, as in P, "to avoid strain localization
 * at the boundaries": they move with their wall without turning and are no longer in contact
 * with it.  The pack's frictional history (its contact lines) is read back for the pairs it
 * names.  The bottom wall is fixed.  The top wall and its glued grains are one rigid body
 * of their mass: it moves along x at the constant velocity v_w and along y under the
 * difference of the pack's push and the constant normal stress sigma_w times the wall area,
 * so the volume follows the shear (P: "allowing for the volume of the sample to vary").
 *
 * v_w is set by the inertial number I = gamma_dot r sqrt(rho / sigma_w) (P eq. 6: about 1e-3
 * in P), with r the mean spheroradius, rho the mean density and gamma_dot = v_w / H0, H0 the
 * initial height.  The shear strain is P's gamma = x_w / y_w: the top wall's displacement
 * over its current height above the bottom wall.
 *
 * Reported, each averaged over the steps since the last row: tau_w / sigma_w (tau_w the
 * shear stress on the top body, minus its x force over the area; sigma_w the applied
 * stress), the normal stress on it over sigma_w, the stress tensor of P eq. 7 (the sum over
 * grain pairs of branch vector (x) interaction force, over the volume) with its partial mean
 * and deviatoric stresses in the shear plane, p = (s1 + s3)/2, q = (s1 - s3)/2 (s1, s3 the
 * principal stresses of its xy block) and q/p, the packing fraction, the coordination Z
 * (interactions per grain, grain-grain at both ends plus grain-wall) and the element
 * contacts per interaction; the pairs of two glued grains, parts of a wall, are in none of
 * these, and Z is over the free grains.  From a chosen strain on, the velocity profile: <v_x>(y) / v_w
 * in bins of y / y_w over every grain (P Fig. 6). */
#ifndef QUSGM_PLATESHEAR_H
#define QUSGM_PLATESHEAR_H

#include "dem/engine.h"
#include "pack/pack.h"

#include <stdio.h>

struct shear_params {
	struct engine_params dyn;	/* the contact law and step (damping: Cundall's, 0 in P) */
	double sigma_w;		/* normal stress on the top wall (Pa) */
	double inertial;	/* I, sets v_w ... */
	double velocity;	/* ... unless this is positive: v_w (m/s) outright */
	double strain;		/* final gamma */
	double every;		/* a row every this much strain */
	double profile_from;	/* average the velocity profile from this strain on (> strain: none) */
	int profile_bins;
	long max_steps;
	/* The start (P says nothing of it): before the strain, the pack made periodic on x and z
	 * relaxes at sigma_w under the y walls' servo, with Cundall's local damping relax_damping,
	 * until static (platepack_settle: the unbalanced force below relax_tol of the mean
	 * interaction force, the wall stress within 5 %; relax_tol 0: no relaxation); then the top
	 * body's normal motion gets the same local damping up to gamma start_strain, so that the
	 * shear's onset does not set it oscillating on the pack (the undamped start swung Z
	 * between 2.3 and 5.2 up to gamma 0.8 at 8000 plates). */
	double relax_tol, relax_damping, start_strain;
	long relax_steps_max;
};

/* One row of the time series (SI where there is a unit). */
struct shear_row {
	long step;
	double time;		/* s */
	double gamma;		/* x_w / y_w at the row */
	double tau_ratio;	/* tau_w / sigma_w */
	double sigma_ratio;	/* the pack's normal push on the top wall over sigma_w */
	double sig[6];		/* P eq. 7, Pa, compression positive: xx yy zz xy xz yz */
	double p, q, qp;	/* in the xy plane */
	double phi, z, elements;
	double height;		/* y_w, m */
	/* the velocity profile's sums so far (profile_bins of each; samples 0 before
	 * profile_from): the mean of bin b is profile_sum[b] / profile_n[b] */
	const double *profile_sum, *profile_n;
};

/* Called at every row; nonzero stops the run (and the run returns -1).  d is the engine
 * (engine_write_back(d, p) turns it into a pack: a snapshot). */
typedef int (*shear_row_fn)(const struct shear_row *row, struct engine *d, void *ctx);

/* The result beside the rows. */
struct shear_result {
	double v_w;		/* m/s */
	double inertial;	/* I of v_w at the start */
	double gamma_dot;	/* 1/s */
	double kappa;		/* the stiffness number of sigma_w (engine.h's engine_kappa) */
	size_t glued_bottom, glued_top;
	long relax_steps;	/* steps of the relaxation (0: none, or going on from a checkpoint) */
	double relax_phi, relax_z;	/* the packing fraction and Z (interactions per grain) at its end */
	double *profile;	/* profile_bins means of v_x / v_w (NaN where a bin saw no grain), or NULL */
	double *profile_n;	/* samples per bin */
};

/* Defaults: P's law (engine.h) without Cundall damping, I = 1e-3, gamma 2.5, a row every
 * 0.01, the profile from gamma 1.5 in 20 bins, at most 1e8 steps; the relaxation to 1e-3
 * with damping 0.3 (packgen's), at most 2e6 steps, the top body damped up to gamma 0.05. */
void shear_params_default(struct shear_params *sp);

/* What a user chose for a shear's law (shear's options; NaN or NULL: not given). */
struct shear_law_choice {
	const char *law;	/* a law's name, or NULL: the pack's (contact_law_choose) */
	double kn, kt;		/* a spring law's stiffnesses (N/m) */
	double restitution, mu, wall_mu;
	double kappa;		/* the stiffness number, or NaN: sp->sigma_w as set */
};
/* The run's law and its constants into sp->dyn (and sp->sigma_w from a kappa), each from the
 * choice, else pack p's meta lines (kn, kt, restitution, sigma0; its mu and wall mu), else
 * the law's or P's defaults, checked against the law's range (law->stress_in_range); p
 * records the law and, under a spring law, the k_n and k_t the run uses (so that packinfo
 * measures the output with them).  The contact law into *law.  0; -1 with the error slot set
 * on a pack that lacks what the law needs; -2 on a choice the law does not take (--kn under
 * a law of the grains' moduli). */
int plateshear_choose_law(struct pack *p, const struct shear_law_choice *c, struct shear_params *sp,
    const struct contact_law **law);
/* Shear pack p (walls on y; see above) to sp->strain; p receives the final state.  0, or -1
 * with msg_seterr.  res->profile and res->profile_n are allocated (free them with
 * shear_result_free). */
int plateshear_run(struct pack *p, const struct shear_params *sp, shear_row_fn fn, void *ctx, struct shear_result *res);
void shear_result_free(struct shear_result *res);
/* Where a run stands after a row (the engine and the loop's counters and sums), and what
 * saves it: a checkpoint (plateshear_state_write: text of hex floats, so that it reads back to
 * the bit; engine.h's engine_state_write is its engine part). */
struct shear_state;
int plateshear_state_write(const struct shear_state *s, FILE *fp);
/* Called after every row but the last (after shear_row_fn) with the run's state: 0 goes on,
 * 1 stops the run (plateshear_run_resumable returns 2: a checkpoint at a time limit), -1 is
 * an error (message set). */
typedef int (*shear_checkpoint_fn)(const struct shear_state *s, void *ctx);
/* plateshear_run, with ck after every row (NULL: none), going on from a state read from
 * `from` (NULL: the start), a reader positioned at what plateshear_state_write wrote for a
 * run of the same pack p and parameters: the rows, the profile and the final pack are then
 * those of the run that wrote it, to the bit.  0, 2 when ck stopped it, -1 (msg_seterr), -2
 * when `from` could not be read (a file:line message). */
struct lines;
int plateshear_run_resumable(struct pack *p, const struct shear_params *sp, shear_row_fn fn, void *ctx,
    shear_checkpoint_fn ck, struct lines *from, struct shear_result *res);

/* The engine's state into p, the centres wrapped into the box along the periodic axes there
 * (not in the engine, so that a run with snapshots is the run without them).  0 or -1. */
int plateshear_snapshot(struct engine *d, struct pack *p);

#endif
