/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hessian: the sparse Hessian of Pi over the unknowns, for Newton's method (minimize.h).
 *
 * Block storage over nodes of three unknowns: the N centres (node i), and with friction the N
 * scaled rotations R Omega after them (node N + i, layout.h), so that the matrix is 3n x 3n
 * with n = N or 2N nodes.  One 3x3 block per node on the diagonal and a list of off-diagonal
 * blocks H_ab with a < b (H_ba is its transpose), in the order the terms add them; a node
 * pair may appear more than once (the normal and the frictional part of a contact), the
 * product sums them.  Each term of Pi that has second derivatives adds its blocks (struct
 * qs_term's hessian); qs_hessian (functional.h) fails when a term has none (the paper's
 * sliding rule, which has no potential).  The friction term's blocks, the return map's
 * consistent tangent, are described at friction_hessian (friction.c).
 *
 * The normal term's contact at overlap h = r_i + r_j - d along n = (x_i - x_j) / d, with
 * force P = U'(h) and stiffness k = U''(h) (the law's), gives
 *     B = k n n^T - (P / d) (I - n n^T),   H_ii += B, H_jj += B, H_ij = -B;
 * the second part is the geometric stiffness of a compressed pair (a chain that can buckle),
 * so H is indefinite where grains are nearly free; a wall contact adds k e_a e_a^T to its
 * grain.  Tested against finite differences of the gradient (tests/unit/test_hessian.c). */
#ifndef QUSGM_HESSIAN_H
#define QUSGM_HESSIAN_H

#include <stddef.h>

struct qs_hessian {
	size_t n;		/* nodes: the matrix is 3n x 3n */
	double *diag;		/* 9 n: block i row-major at 9 i */
	size_t np, cap;		/* off-diagonal blocks */
	size_t *pi, *pj;	/* their nodes, i < j */
	double *off;		/* 9 np: H_ij row-major */
	int diag_only;		/* keep the diagonal blocks only (add_pair adds nothing) */
	/* the caller's promise that the functional's last evaluation was at the x of
	 * qs_hessian, so that a term may take its contacts' state (forces, stick or slip) from
	 * it instead of evaluating them again (the preconditioner's assembly at an iterate) */
	int at_last_eval;
};

/* 0 or -1 (out of memory, message set). */
int qs_hessian_init(struct qs_hessian *H, size_t n);
void qs_hessian_free(struct qs_hessian *H);
/* No blocks, zero diagonal. */
void qs_hessian_clear(struct qs_hessian *H);
/* Append the pair block H_ij = B (9, row-major; i != j, stored with the smaller index first,
 * transposed when i > j).  0 or -1 (out of memory). */
int qs_hessian_add_pair(struct qs_hessian *H, size_t i, size_t j, const double B[9]);
/* y = H v (3n each). */
void qs_hessian_mul(const struct qs_hessian *H, const double *v, double *y);

#endif
