/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hessian: the block-sparse Hessian of Pi over the centres (see hessian.h). */
#include "qs/hessian.h"
#include "base/msg.h"

#include <stdlib.h>
#include <string.h>

int
qs_hessian_init(struct qs_hessian *H, size_t n)
{
	memset(H, 0, sizeof *H);
	H->n = n;
	H->diag = calloc(9 * (n ? n : 1), sizeof *H->diag);
	if (!H->diag) {
		msg_seterr("out of memory for the Hessian");
		return -1;
	}
	return 0;
}

void
qs_hessian_free(struct qs_hessian *H)
{
	free(H->diag), free(H->pi), free(H->pj), free(H->off);
	memset(H, 0, sizeof *H);
}

void
qs_hessian_clear(struct qs_hessian *H)
{
	H->np = 0;
	memset(H->diag, 0, 9 * H->n * sizeof *H->diag);
}

int
qs_hessian_add_pair(struct qs_hessian *H, size_t i, size_t j, const double B[9])
{
	double *o;
	int u, v;

	if (H->diag_only)
		return 0;
	if (H->np == H->cap) {
		size_t cap = H->cap ? 2 * H->cap : 4 * H->n + 16;
		size_t *pi = realloc(H->pi, cap * sizeof *pi), *pj;
		double *off;

		if (pi)
			H->pi = pi;
		pj = realloc(H->pj, cap * sizeof *pj);
		if (pj)
			H->pj = pj;
		off = realloc(H->off, 9 * cap * sizeof *off);
		if (off)
			H->off = off;
		if (!pi || !pj || !off) {
			msg_seterr("out of memory for the Hessian");
			return -1;
		}
		H->cap = cap;
	}
	o = H->off + 9 * H->np;
	if (i < j) {
		memcpy(o, B, 9 * sizeof *o);
		H->pi[H->np] = i, H->pj[H->np] = j;
	} else {
		for (u = 0; u < 3; u++)
			for (v = 0; v < 3; v++)
				o[3 * u + v] = B[3 * v + u];
		H->pi[H->np] = j, H->pj[H->np] = i;
	}
	H->np++;
	return 0;
}

/* One pass over the blocks in storage order: the same bytes for any thread count. */
void
qs_hessian_mul(const struct qs_hessian *H, const double *v, double *y)
{
	size_t i, q;

	for (i = 0; i < H->n; i++) {
		const double *D = H->diag + 9 * i, *vi = v + 3 * i;
		double *yi = y + 3 * i;

		yi[0] = D[0] * vi[0] + D[1] * vi[1] + D[2] * vi[2];
		yi[1] = D[3] * vi[0] + D[4] * vi[1] + D[5] * vi[2];
		yi[2] = D[6] * vi[0] + D[7] * vi[1] + D[8] * vi[2];
	}
	for (q = 0; q < H->np; q++) {
		const double *A = H->off + 9 * q, *vi = v + 3 * H->pi[q], *vj = v + 3 * H->pj[q];
		double *yi = y + 3 * H->pi[q], *yj = y + 3 * H->pj[q];

		yi[0] += A[0] * vj[0] + A[1] * vj[1] + A[2] * vj[2];
		yi[1] += A[3] * vj[0] + A[4] * vj[1] + A[5] * vj[2];
		yi[2] += A[6] * vj[0] + A[7] * vj[1] + A[8] * vj[2];
		yj[0] += A[0] * vi[0] + A[3] * vi[1] + A[6] * vi[2];
		yj[1] += A[1] * vi[0] + A[4] * vi[1] + A[7] * vi[2];
		yj[2] += A[2] * vi[0] + A[5] * vi[1] + A[8] * vi[2];
	}
}
