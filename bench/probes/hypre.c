/* SPDX-License-Identifier: GPL-3.0-or-later */
/* hypre probe (issue 16): BoomerAMG as the preconditioner of CG on a pack's Hessian, against
 * block Jacobi.  Not built by make: it needs hypre and MPI (libhypre-dev), which qusgm does not
 * depend on, because AMG lost to block Jacobi here (bench/newton.md, "Preconditioners tried").
 * Build and run from the repository root after `make`:
 *   mpicc -O2 -std=c11 -D_DEFAULT_SOURCE -fopenmp -Ilib -I/usr/include/hypre -o /tmp/amgprobe \
 *      bench/probes/hypre.c build/libqusgm.a -lHYPRE -lgsl -lgslcblas -lccd -lz -lm
 *   OMP_NUM_THREADS=1 /tmp/amgprobe PACK none|fric TOL
 * One 1e-4 uniaxial increment, the Hessian there shifted by SH (default 1e-3) of the mean
 * diagonal stiffness, a random right-hand side, CG to |r| <= TOL |b| with each preconditioner.
 * THETA, COARSEN, INTERP, AGG, NODAL set BoomerAMG's options (defaults 0.5, 10 = HMIS, 6, 0, off). */
#include <mpi.h>
#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
#include <HYPRE_krylov.h>
#include "qs/loading.h"
#include "qs/functional.h"
#include "qs/hessian.h"
#include "base/msg.h"
#include "pack/packio.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+1e-9*t.tv_nsec;}
static double dotp(const double*a,const double*b,size_t n){double s=0;for(size_t i=0;i<n;i++)s+=a[i]*b[i];return s;}
static void inv3(const double*D,double*M){double c00=D[4]*D[8]-D[5]*D[7],c01=D[5]*D[6]-D[3]*D[8],c02=D[3]*D[7]-D[4]*D[6];double det=D[0]*c00+D[1]*c01+D[2]*c02;
 M[0]=c00/det;M[1]=M[3]=c01/det;M[2]=M[6]=c02/det;M[4]=(D[0]*D[8]-D[2]*D[6])/det;M[5]=M[7]=(D[2]*D[3]-D[0]*D[5])/det;M[8]=(D[0]*D[4]-D[1]*D[3])/det;}
int main(int argc,char**argv){
 MPI_Init(&argc,&argv);
 struct pack p; struct loader L; struct load_params lp; struct load_row row; double de[3]={0,0,1e-4};
 msg_init(argv[0]);
 if(pack_read_path(argv[1],&p)) msg_die_err(1);
 int fr = argc>2 && !strcmp(argv[2],"fric");
 double tol = argc>3? atof(argv[3]) : 0.1;
 if(!fr) p.mu=p.wall_mu=0;
 load_params_default(&lp); lp.friction=fr;
 if(loader_open(&L,&p,&lp)) msg_die_err(1);
 loader_step(&L,de,&row);
 /* perturb: next increment's affine guess, then gradient there */
 size_t n3=L.s.dim, n=n3/3;
 struct qs_hessian H; qs_hessian_init(&H,n);
 if(qs_hessian(&L.s,L.x,&H)) msg_die_err(1);
 /* shift 1e-3 mean diag, per kind */
 double kc=0,kr=0; for(size_t i=0;i<n;i++){double k=fabs(H.diag[9*i]+H.diag[9*i+4]+H.diag[9*i+8])/3; if(i<L.s.n) kc+=k; else kr+=k;}
 kc/=L.s.n; kr/= (n>L.s.n? n-L.s.n:1);
 double sh=atof(getenv("SH")?getenv("SH"):"1e-3");
 for(size_t i=0;i<n;i++){double s=sh*(i<L.s.n?kc:kr); H.diag[9*i]+=s;H.diag[9*i+4]+=s;H.diag[9*i+8]+=s;}
 double *b=malloc(n3*8),*x=calloc(n3,8); srand(1); for(size_t i=0;i<n3;i++) b[i]=rand()/(double)RAND_MAX-0.5;
 /* block jacobi PCG */
 double *Minv=malloc(9*n*8),*r=malloc(n3*8),*z=malloc(n3*8),*q=malloc(n3*8),*Hq=malloc(n3*8);
 double t0=now(); for(size_t i=0;i<n;i++) inv3(H.diag+9*i,Minv+9*i);
 memcpy(r,b,n3*8); 
#define PAPPLY for(size_t i=0;i<n;i++){const double*M=Minv+9*i,*ri=r+3*i;double*zi=z+3*i;zi[0]=M[0]*ri[0]+M[1]*ri[1]+M[2]*ri[2];zi[1]=M[3]*ri[0]+M[4]*ri[1]+M[5]*ri[2];zi[2]=M[6]*ri[0]+M[7]*ri[1]+M[8]*ri[2];}
 PAPPLY; memcpy(q,z,n3*8); double rz=dotp(r,z,n3), bb=dotp(b,b,n3); int it;
 for(it=0;it<20000;it++){qs_hessian_mul(&H,q,Hq);double qHq=dotp(q,Hq,n3); if(qHq<=0){printf("negcurv at %d\n",it);break;} double a=rz/qHq; for(size_t k=0;k<n3;k++){x[k]+=a*q[k];r[k]-=a*Hq[k];} if(dotp(r,r,n3)<=tol*tol*bb)break; PAPPLY; double rz1=dotp(r,z,n3); for(size_t k=0;k<n3;k++) q[k]=z[k]+rz1/rz*q[k]; rz=rz1;}
 double t1=now();
 printf("n3 %zu np %zu fric %d tol %g  blockjacobi: %d it %.4f s\n",n3,H.np,fr,tol,it+1,t1-t0);
 /* hypre */
 HYPRE_IJMatrix A; HYPRE_ParCSRMatrix pA; HYPRE_IJVector vb,vx; HYPRE_ParVector pb,px;
 double t2=now();
 HYPRE_IJMatrixCreate(MPI_COMM_WORLD,0,n3-1,0,n3-1,&A); HYPRE_IJMatrixSetObjectType(A,HYPRE_PARCSR);
 HYPRE_IJMatrixInitialize(A);
 for(size_t i=0;i<n;i++) for(int u=0;u<3;u++){HYPRE_Int nc=3,row=3*i+u,cols[3]={3*i,3*i+1,3*i+2};double v[3]={H.diag[9*i+3*u],H.diag[9*i+3*u+1],H.diag[9*i+3*u+2]};HYPRE_IJMatrixAddToValues(A,1,&nc,&row,cols,v);}
 for(size_t k=0;k<H.np;k++){size_t i=H.pi[k],j=H.pj[k];const double*B=H.off+9*k;for(int u=0;u<3;u++){HYPRE_Int nc=3,row=3*i+u,cols[3]={3*j,3*j+1,3*j+2};double v[3]={B[3*u],B[3*u+1],B[3*u+2]};HYPRE_IJMatrixAddToValues(A,1,&nc,&row,cols,v);
   HYPRE_Int row2=3*j+u,cols2[3]={3*i,3*i+1,3*i+2};double v2[3]={B[u],B[3+u],B[6+u]};HYPRE_IJMatrixAddToValues(A,1,&nc,&row2,cols2,v2);}}
 HYPRE_IJMatrixAssemble(A); HYPRE_IJMatrixGetObject(A,(void**)&pA);
 HYPRE_IJVectorCreate(MPI_COMM_WORLD,0,n3-1,&vb);HYPRE_IJVectorSetObjectType(vb,HYPRE_PARCSR);HYPRE_IJVectorInitialize(vb);
 HYPRE_IJVectorCreate(MPI_COMM_WORLD,0,n3-1,&vx);HYPRE_IJVectorSetObjectType(vx,HYPRE_PARCSR);HYPRE_IJVectorInitialize(vx);
 HYPRE_Int *idx=malloc(n3*sizeof *idx); for(size_t i=0;i<n3;i++) idx[i]=i; double*zero=calloc(n3,8);
 HYPRE_IJVectorSetValues(vb,n3,idx,b);HYPRE_IJVectorSetValues(vx,n3,idx,zero);
 HYPRE_IJVectorAssemble(vb);HYPRE_IJVectorAssemble(vx);HYPRE_IJVectorGetObject(vb,(void**)&pb);HYPRE_IJVectorGetObject(vx,(void**)&px);
 double t3=now();
 HYPRE_Solver solver,pre; HYPRE_ParCSRPCGCreate(MPI_COMM_WORLD,&solver);
 HYPRE_PCGSetTol(solver,tol);HYPRE_PCGSetMaxIter(solver,2000);HYPRE_PCGSetTwoNorm(solver,1);
 HYPRE_BoomerAMGCreate(&pre); HYPRE_BoomerAMGSetMaxIter(pre,1);HYPRE_BoomerAMGSetTol(pre,0);
 HYPRE_BoomerAMGSetNumFunctions(pre,3);
 if(getenv("NODAL")) HYPRE_BoomerAMGSetNodal(pre,atoi(getenv("NODAL")));
 HYPRE_BoomerAMGSetStrongThreshold(pre,atof(getenv("THETA")?getenv("THETA"):"0.5"));
 HYPRE_BoomerAMGSetRelaxType(pre,6); HYPRE_BoomerAMGSetCoarsenType(pre,atoi(getenv("COARSEN")?getenv("COARSEN"):"10"));
 HYPRE_BoomerAMGSetAggNumLevels(pre,atoi(getenv("AGG")?getenv("AGG"):"0"));
 HYPRE_BoomerAMGSetInterpType(pre,atoi(getenv("INTERP")?getenv("INTERP"):"6"));
 HYPRE_BoomerAMGSetPMaxElmts(pre,4);
 HYPRE_PCGSetPrecond(solver,(HYPRE_PtrToSolverFcn)HYPRE_BoomerAMGSolve,(HYPRE_PtrToSolverFcn)HYPRE_BoomerAMGSetup,pre);
 HYPRE_ParCSRPCGSetup(solver,pA,pb,px); double t4=now();
 HYPRE_ParCSRPCGSolve(solver,pA,pb,px); double t5=now();
 HYPRE_Int its; HYPRE_PCGGetNumIterations(solver,&its);
 /* second solve reusing setup */
 HYPRE_IJVectorSetValues(vx,n3,idx,zero); HYPRE_ParCSRPCGSolve(solver,pA,pb,px); double t6=now();
 printf("hypre: build %.4f setup %.4f solve %.4f (%d it) resolve %.4f\n",t3-t2,t4-t3,t5-t4,(int)its,t6-t5);
 MPI_Finalize(); return 0;}
