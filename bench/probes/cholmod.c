/* SPDX-License-Identifier: GPL-3.0-or-later */
/* cholmod probe (issue 16): the cost of a sparse Cholesky factor of a pack's Hessian, as
 * Newton's preconditioner.  Not built by make: it needs SuiteSparse (libsuitesparse-dev),
 * which qusgm does not depend on, because this probe showed the factor costs far more than
 * it saves (bench/newton.md, "Preconditioners tried").  Build and run from the repository root
 * after `make`:
 *   cc -O2 -std=c11 -D_DEFAULT_SOURCE -fopenmp -Ilib -I/usr/include/suitesparse -o /tmp/cholprobe \
 *      bench/probes/cholmod.c build/libqusgm.a -lcholmod -lgsl -lgslcblas -lccd -lz -lm
 *   OMP_NUM_THREADS=1 /tmp/cholprobe PACK [nofric]
 * It makes one 1e-4 uniaxial increment, assembles the Hessian there (hessian.h), factors
 * H + 1e-6 of the mean diagonal stiffness twice (the second reuses the symbolic analysis),
 * and solves ten times.  CHOL_ORD=3 orders with METIS instead of AMD (cholmod.h's numbers). */
#include "qs/hessian.h"
#include "qs/loading.h"
#include "qs/functional.h"
#include "pack/packio.h"
#include <stdio.h>
#include <time.h>
#include "base/msg.h"

#include <cholmod.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct qs_chol {
	cholmod_common cc;
	cholmod_sparse *A;	/* upper triangle of H + S, its pattern the one L was analysed for */
	cholmod_factor *L;
	cholmod_dense *B, *X, *Y, *E;
	double *dbase;		/* A's diagonal entries before the shift */
	size_t *dpos;		/* where they are in A->x */
	size_t n3;
	long nanalyse, nfactor;
};

static struct qs_chol *
qs_chol_alloc(void)
{
	struct qs_chol *c = calloc(1, sizeof *c);

	if (!c) {
		msg_seterr("out of memory for the Cholesky factor");
		return NULL;
	}
	cholmod_start(&c->cc);
	c->cc.print = 0;
	c->cc.error_handler = NULL;
	c->cc.quick_return_if_not_posdef = 1;
	/* AMD alone: METIS's nested dissection fills a little less on these graphs but costs more
	 * than the factorisation it saves at the sizes an increment is factored at */
	c->cc.nmethods = getenv("CHOL_NM") ? atoi(getenv("CHOL_NM")) : 1; if (getenv("CHOL_ORD")) c->cc.method[0].ordering = atoi(getenv("CHOL_ORD")); else
	c->cc.method[0].ordering = CHOLMOD_AMD;
	return c;
}

static void
qs_chol_free(struct qs_chol *c)
{
	if (!c)
		return;
	cholmod_free_sparse(&c->A, &c->cc);
	cholmod_free_factor(&c->L, &c->cc);
	cholmod_free_dense(&c->B, &c->cc);
	cholmod_free_dense(&c->X, &c->cc);
	cholmod_free_dense(&c->Y, &c->cc);
	cholmod_free_dense(&c->E, &c->cc);
	cholmod_finish(&c->cc);
	free(c->dbase), free(c->dpos);
	free(c);
}

/* The upper triangle of H as a CHOLMOD matrix, duplicates summed, columns sorted. */
static cholmod_sparse *
upper_of(struct qs_chol *c, const struct qs_hessian *H)
{
	size_t nz = 6 * H->n + 9 * H->np, a, q, k = 0;
	cholmod_triplet *T = cholmod_allocate_triplet(3 * H->n, 3 * H->n, nz, 1, CHOLMOD_REAL, &c->cc);
	cholmod_sparse *A;
	int *ti, *tj;
	double *tx;
	int u, v;

	if (!T)
		return NULL;
	ti = T->i, tj = T->j, tx = T->x;
	for (a = 0; a < H->n; a++)
		for (u = 0; u < 3; u++)
			for (v = u; v < 3; v++) {
				ti[k] = (int)(3 * a + u), tj[k] = (int)(3 * a + v);
				tx[k++] = 0.5 * (H->diag[9 * a + 3 * u + v] + H->diag[9 * a + 3 * v + u]);
			}
	for (q = 0; q < H->np; q++)
		for (u = 0; u < 3; u++)
			for (v = 0; v < 3; v++) {
				ti[k] = (int)(3 * H->pi[q] + u), tj[k] = (int)(3 * H->pj[q] + v);
				tx[k++] = H->off[9 * q + 3 * u + v];
			}
	T->nnz = k;
	A = cholmod_triplet_to_sparse(T, nz, &c->cc);
	cholmod_free_triplet(&T, &c->cc);
	return A;
}

static int
same_pattern(const cholmod_sparse *A, const cholmod_sparse *B)
{
	size_t ncol = A->ncol, nz;

	if (!B || A->ncol != B->ncol)
		return 0;
	nz = (size_t)((const int *)A->p)[ncol];
	return nz == (size_t)((const int *)B->p)[ncol] && !memcmp(A->p, B->p, (ncol + 1) * sizeof(int)) &&
	    !memcmp(A->i, B->i, nz * sizeof(int));
}

static int
qs_chol_factor(struct qs_chol *c, const struct qs_hessian *H, size_t ncentre, double shift, double *used)
{
	cholmod_sparse *A = upper_of(c, H);
	size_t j, n3 = 3 * H->n;
	double kc = 0, kr = 0, f;

	if (!A)
		goto oom;
	if (!same_pattern(A, c->A) || !c->L) {
		cholmod_free_factor(&c->L, &c->cc);
		c->L = cholmod_analyze(A, &c->cc);
		if (!c->L) {
			cholmod_free_sparse(&A, &c->cc);
			goto oom;
		}
		c->nanalyse++;
	}
	cholmod_free_sparse(&c->A, &c->cc);
	c->A = A;
	if (c->n3 != n3) {
		cholmod_free_dense(&c->B, &c->cc);
		cholmod_free_dense(&c->X, &c->cc);
		cholmod_free_dense(&c->Y, &c->cc);
		cholmod_free_dense(&c->E, &c->cc);
		free(c->dbase), free(c->dpos);
		c->B = cholmod_allocate_dense(n3, 1, n3, CHOLMOD_REAL, &c->cc);
		c->dbase = malloc((n3 ? n3 : 1) * sizeof *c->dbase);
		c->dpos = malloc((n3 ? n3 : 1) * sizeof *c->dpos);
		if (!c->B || !c->dbase || !c->dpos)
			goto oom;
		c->n3 = n3;
	}
	/* the diagonal is the last entry of each sorted upper column */
	for (j = 0; j < n3; j++) {
		size_t p = (size_t)((int *)A->p)[j + 1] - 1;
		double k = fabs(((double *)A->x)[p]);

		c->dpos[j] = p;
		c->dbase[j] = ((double *)A->x)[p];
		if (j < 3 * ncentre)
			kc += k;
		else
			kr += k;
	}
	kc /= (double)(ncentre ? 3 * ncentre : 1);
	kr /= (double)(n3 > 3 * ncentre ? n3 - 3 * ncentre : 1);
	for (f = shift; f <= 1; f *= 100) {
		for (j = 0; j < n3; j++)
			((double *)A->x)[c->dpos[j]] = c->dbase[j] + f * (j < 3 * ncentre ? kc : kr);
		c->cc.status = CHOLMOD_OK;
		c->nfactor++;
		if (cholmod_factorize(A, c->L, &c->cc) && c->cc.status == CHOLMOD_OK && c->L->minor == n3) {
			if (used)
				*used = f;
			return 0;
		}
		if (c->cc.status == CHOLMOD_OUT_OF_MEMORY)
			goto oom;
	}
	msg_seterr("the Hessian has no Cholesky factor even shifted by its mean stiffness");
	return -1;
oom:
	msg_seterr("out of memory for the Cholesky factor");
	return -1;
}

static void
qs_chol_solve(struct qs_chol *c, const double *r, double *z)
{
	memcpy(c->B->x, r, c->n3 * sizeof *r);
	cholmod_solve2(CHOLMOD_A, c->L, c->B, NULL, &c->X, NULL, &c->Y, &c->E, &c->cc);
	memcpy(z, c->X->x, c->n3 * sizeof *z);
}

static void
qs_chol_stats(const struct qs_chol *c, double *lnz, long *nanalyse, long *nfactor)
{
	*lnz = c->cc.lnz;
	*nanalyse = c->nanalyse;
	*nfactor = c->nfactor;
}
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+1e-9*t.tv_nsec;}
int main(int argc,char**argv){
 struct pack p; struct loader L; struct load_params lp; struct load_row row; double de[3]={0,0,1e-4};
 msg_init(argv[0]);
 if(pack_read_path(argv[1],&p)) msg_die_err(1);
 if(argc>2) p.mu=p.wall_mu=0;
 load_params_default(&lp); lp.friction=argc<=2;
 if(loader_open(&L,&p,&lp)) msg_die_err(1);
 loader_step(&L,de,&row);
 struct qs_hessian H; qs_hessian_init(&H, L.s.dim/3);
 double t0=now(); if(qs_hessian(&L.s,L.x,&H)) msg_die_err(1); double t1=now();
 struct qs_chol*c=qs_chol_alloc(); double used;
 int st=qs_chol_factor(c,&H,L.s.n,1e-6,&used); double t2=now();
 st|=qs_chol_factor(c,&H,L.s.n,1e-6,&used); double t3=now();
 double lnz; long na,nf; qs_chol_stats(c,&lnz,&na,&nf);
 double *r=calloc(L.s.dim,8),*z=calloc(L.s.dim,8); for(size_t i=0;i<L.s.dim;i++) r[i]=1;
 double t4=now(); for(int k=0;k<10;k++) qs_chol_solve(c,r,z); double t5=now();
 printf("dim %zu np %zu st %d used %g lnz %.0f na %ld nf %ld hess %.4f first %.4f refactor %.4f solve %.5f\n",L.s.dim,H.np,st,used,lnz,na,nf,t1-t0,t2-t1,t3-t2,(t5-t4)/10);
 return 0;}
