/* SPDX-License-Identifier: GPL-3.0-or-later */
/* friction: Mindlin-Deresiewicz tangential forces and torsional couples (physics.md §3-6).
 *
 * With friction the unknowns of an equilibrium are 6N lengths: the grain centres x (3N) and
 * the small rotation vectors of the increment times the radius, R_i Omega_i (3N), stored
 * after the centres.  Rotations are measured from the start of the increment and are zero
 * there; orientation itself is not tracked (spheres), the history forces carry the memory.
 *
 * An increment starts (fr_begin) from a committed equilibrium, the reference configuration:
 * every contact touching there gets its tangent plane T = I - n n, lever arms R_ij and R_ji,
 * stick stiffness k*, sliding limit Q_max = mu P, torsional stiffness k*_t and M_max, all from
 * the reference overlap and frozen for the increment (F, after (7b)), and its history force
 * Q0 turned into that tangent plane with its magnitude kept (Q^p) and clamped to Q_max.
 * Contacts that form during the increment carry only their Hertz normal force (P0 = 0 at the
 * reference).  The tangential and torsional terms of a reference contact stay in Pi for the
 * whole increment, even if that contact opens: the linearised increment keeps Pi one smooth
 * potential; the history of a contact that has opened is dropped at the commit.
 *
 * Sliding rule: FR_RETURN_MAP (default) clamps the trial force q = Q^p - k* u_s to the disc
 * |Q| <= Q_max, which has the exact potential phi_s = (g(|q|) - |Q^p|^2) / (2 k*),
 * grad phi_s = -Q; FR_PAPER reduces the stiffness so that |Q^p - k u_s| = Q_max (F (6)-(7b)
 * corrected as physics.md §4 says), whose "energy" -Q^p.u_s + k |u_s|^2 / 2 (F (17a)) is not an
 * antiderivative of the force: the minimisers use the gradient, so that rule still works, but
 * an energy-based stopping test (eps1) means little with it.  Torsion uses the
 * one-dimensional clamp in both rules (they coincide in 1-D).
 *
 * fr_commit ends an increment: the final forces become the history (P0, Q0, M0) of every
 * contact that still touches, new contacts get P0 with Q0 = M0 = 0, opened ones are dropped,
 * and the pack's positions are updated.  The committed forces are the equilibrium's, exactly:
 * a contact whose normal force fell during the increment can end it with |Q0| a little above
 * mu P0 (the limit was frozen at the start); it slips to the new limit when the next
 * increment starts (fr_begin's clamp), as the linearised model has it. */
#ifndef QUSGM_FRICTION_H
#define QUSGM_FRICTION_H

#include "contact/contacts.h"
#include "contact/law.h"
#include "qs/functional.h"
#include "pack/pack.h"

enum fr_rule { FR_RETURN_MAP, FR_PAPER };

struct fr_contact {
	size_t i;
	long j;			/* grain index or PACK_WALL(w) */
	double n[3];		/* reference normal on i, from j to i */
	/* the lever arms centre -> contact of i and of j lie along the normal (spheres):
	 * R_ij = -li n and R_ji = lj n (lj = 0 for a wall); over the radii, ai = li / R_i,
	 * aj = lj / R_j, bi = 1 / R_i, bj = 1 / R_j (0 for a wall), so that the kernel works on
	 * the unknowns w = R Omega without a division or a cross product per lever arm */
	double li, lj, ai, aj, bi, bj;
	double k, qmax, qp[3];	/* stick stiffness, sliding limit, reference force on i */
	double kt, mmax, mp;	/* torsion: stiffness, limit, reference couple on i about n */
	double pp, mpp;		/* |Q^p|^2 and (M^p)^2, for the energy */
	double Q[3], M;		/* force and couple on i at the last evaluation */
	double qtrial;		/* |Q^p - k* u_s| at the last evaluation (the elastic trial) */
};

struct qs_friction {
	size_t n, cap;
	struct fr_contact *c;
	struct law_pair *lp;	/* each contact's pair constants (n; out of c, whose walks are hot) */
	double *x0;		/* reference centres (3N) */
	double *gs;		/* per grain at an evaluation, FR_GS apart: x - x0, then w = R Omega */
	/* the index of the contacts (fr_begin), for the threads: per grain i the range of the
	 * pairs (i, j) and of its walls in c (CSR, n + 1 offsets each), and per grain j the
	 * pairs (m < j, j) ascending (col_first, col_k) */
	size_t *row_first, *wall_first, *col_first, *col_k;
	double *blk;		/* energy per block of grains */
	size_t blk_cap;
	size_t ngrains;
	enum fr_rule rule;
	/* from fr_begin: history lines that matched no touching contact (dropped), and
	 * reference forces clamped to the sliding limit (|Q0| > Q_max or |M0| > M_max) with the
	 * largest excess |Q0| / Q_max - 1 */
	size_t stale, clamped;
	double clamp_excess;
	/* from fr_commit: the contacts whose elastic trial force reached the limit of their
	 * final normal force (ntrial_slip), and the history lines committed at that limit,
	 * |Q0| >= mu P0 (nlimit); see fr_commit */
	size_t ntrial_slip, nlimit;
	/* from fr_commit: lines beyond what a commit of an equilibrium leaves (fr_check_history's
	 * bound), slipped to their limit at P0 so that the pack reads back; nonzero only when
	 * the increment ended far from equilibrium */
	size_t ncommit_slipped;
	/* fr_keep_found: a commit's contacts, kept for the next fr_begin at the same positions */
	int keep_found, found_ok;
	struct geo_contacts found;
};

void fr_init(struct qs_friction *f, enum fr_rule rule);
void fr_free(struct qs_friction *f);
/* Parse "return-map" / "paper"; 0 or -1. */
int fr_rule_parse(const char *name, enum fr_rule *rule);
const char *fr_rule_name(enum fr_rule rule);

/* Check a pack's history against its friction coefficients, by law's limits (its tangent at
 * the line's normal force: law_contact_limits).  A committed line can exceed its
 * sliding limit mu P0 by the slip its normal force's fall in the last increment calls for
 * (see fr_commit), which is small against the limit of an average contact; a line with
 * |Q0| > mu (P0 + P_mean) (or |M0| above M_max(P0) + M_max(P_mean)) cannot come from a
 * commit and is refused as corrupt.  Lines below that are repaired by fr_begin's clamp.
 * Returns 0, or -1 with msg_seterr naming the first offending contact by grain ids. */
int fr_check_history(const struct contact_law *law, const struct pack *p);

/* Start an increment from the pack's positions p->x and contact history p->c (friction
 * coefficients p->mu, p->wall_mu), with the stiffnesses of s->law.  Adds f's term to s's
 * functional (replacing any other but the normal one): qs_energy then works on 6N unknowns.
 * The caller's x must hold p->x followed by 3N zeros.  0 or -1. */
int fr_begin(struct qs_friction *f, struct qs_system *s);
/* End the increment at x (6N): evaluate, write the history into p->c, move p->x to x, zero the
 * rotations in x.  Counts two kinds of sliding contact (share/doc/friction.md):
 *  - f->ntrial_slip, the slip count of DEM codes: contacts whose elastic trial force reaches
 *    the limit of their normal force at the end, |Q^p - k* u_s| >= mu P_end, i.e. that slipped
 *    somewhere in the increment.  Under uniaxial compression it levels off near 0.43 of the
 *    contacts: most of them slip a little in every increment while their normal force rises.
 *  - f->nlimit, the paper's count (F Fig. 4): history lines committed at their Coulomb limit,
 *    |Q0| >= mu P0 with P0 the new normal force, i.e. contacts that end the increment fully
 *    mobilised.  It rises fast and levels off near 0.07-0.08 on glass packs at mu 0.3.
 * |Q| = Q_max with the limit frozen at the start (fr_sliding) is neither: it also counts a
 * contact whose normal force rose faster than its tangential load (it sticks under the
 * updated limit), half the contacts of a pack under uniaxial compression.  0 or -1. */
int fr_commit(struct qs_friction *f, struct qs_system *s, double *x);
/* fr_commit of a state where the functional was last evaluated (the contacts' forces are x's,
 * as a minimiser leaves them: qs_minimizer_current), without evaluating it again. */
int fr_commit_evaluated(struct qs_friction *f, struct qs_system *s, double *x);
/* With on, each commit keeps the contacts it found at its positions (contacts_store_found)
 * and the next fr_begin starts from them instead of walking the contacts again: the caller
 * promises that the pack (positions, radii, box, moduli, history) does not change between
 * the two, as in a settle pass that begins where the last commit ended.  Off drops a kept
 * list.  The list lives only between a commit and the next start, where fr_begin would
 * hold one anyway, so the peak memory is unchanged. */
void fr_keep_found(struct qs_friction *f, int on);
/* The evaluation's kernel takes four contacts at a time where the processor has AVX2, else
 * two (lanes.h), with the same bytes; n = 2 makes it take two (a test hook: the two-lane
 * kernel is then checked on machines with AVX2 too), 4 restores the default. */
void fr_set_lanes(int n);
/* Contacts of the last evaluation at the sliding limit (Q_max > 0 and
 * |Q| >= Q_max (1 - 1e-9)). */
size_t fr_sliding(const struct qs_friction *f);
/* The friction term's energy at x (6N), its gradient added into g (unless NULL) and each
 * contact's Q, M and trial force, one contact at a time on one thread: the reference that
 * the evaluation's two-lane kernel must equal to the bit (tests/unit/test_friction.c). */
double fr_energy_scalar(struct qs_friction *f, const struct qs_system *s, const double *x, double *g);
/* The increment's frictional term, once fr_begin has added it to the functional: its
 * energy at x (6N) with the gradient (updating each contact's Q and M), and each grain's
 * stiffness k* + k*_t / R_i^2 in the minimisers' bound.  fr_detach removes it and makes the
 * unknowns the 3N centres again. */
void fr_detach(struct qs_system *s);
/* The friction attached to s, or NULL. */
struct qs_friction *fr_attached(const struct qs_system *s);

#endif
