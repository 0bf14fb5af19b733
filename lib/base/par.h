/* SPDX-License-Identifier: GPL-3.0-or-later */
/* par: the library's threads, and sums whose value does not depend on how many there are.
 *
 * The evaluations of the functional, the minimisers' vector algebra and (later) the DEM run
 * their loops on par_threads() threads (OpenMP; a build without it runs them on one).  Every
 * result must be the same bytes for any thread count (the standards ask for same inputs,
 * same output), so no floating-point sum is left to the threads' schedule: a sum over n
 * terms is cut into blocks whose bounds depend on n alone (par_blocks), each block summed in
 * order by whichever thread takes it, and the block sums added in block order.  Scatters
 * (a contact's force into both of its grains) are turned into gathers in a fixed order by
 * the callers (functional.c, friction.c), so no two threads write the same element.
 *
 * Thread count: par_set_threads(n) (the tools' --threads); 0 sets the default: OMP_NUM_THREADS
 * when set, else the cores this process may use less those other tasks keep busy when it
 * starts (par_cpus_busy), at least one.  Threads that share a core with another busy process
 * lose far more than they gain: each parallel region waits at its barrier for the thread the
 * scheduler left out (densify at 2740 grains beside other jobs: 17 times the wall time of one
 * thread, bench/threads.md), so the default never takes a core that is busy at the start.  Loops shorter than PAR_MIN
 * iterations run on the calling thread, where starting the others costs more than they save.
 * Blocks are short (256 grains) so that two threads share a 5000-grain pack's 20 blocks
 * evenly; with 1024 they got 2 and 3 of 5 and an increment ran only 1.47 times faster. */
#ifndef QUSGM_PAR_H
#define QUSGM_PAR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Loops over grains below this many are not split: par_min(), 4 par_block_min() (1024);
 * loops over vector elements below PAR_MIN_VEC, 16 par_block_min() (4096), where a
 * thread's share would cost less than waking it. */
#define PAR_MIN par_min()
#define PAR_MIN_VEC (16 * par_block_min())

/* The most blocks a sum is cut into (par_dot's partial sums live on the stack). */
#define PAR_MAXBLOCKS 1024

void par_set_threads(int n);
/* The count par_set_threads(0) sets (decided once, at the first call). */
int par_default_threads(void);
/* Waits: at the end of a parallel region, with libgomp's default an idle thread spins for
 * up to 300000 turns before it sleeps, and beside other busy processes the spinning threads
 * take the cores the working ones need (densify at 2740 grains on two threads beside other
 * jobs: 800 s of wall time, 47 s on one thread; passive waits: 19 s, bench/threads.md).  So
 * the tools wait passively: unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set (a user's own
 * setting is kept; OMP_WAIT_POLICY=active restores the spinning), a constructor linked into
 * each tool alone (par_start.c) sets OMP_WAIT_POLICY=passive before the OpenMP runtime reads
 * its environment (libgomp, linked into the tool, reads it in a constructor of its own that
 * runs after; the Makefile's OMP_STATIC).  A program that links the library keeps its
 * runtime's own policy. */
/* The tasks other than this one that keep a core busy now (the least of three looks at
 * /proc/stat's procs_running 1 ms apart), or -1 where that cannot be read. */
int par_cpus_busy(void);
/* The threads a loop of the library uses (1 without OpenMP). */
int par_threads(void);

/* Inside a parallel region: this thread's index and the number in the team (0 and 1
 * outside one, or without OpenMP). */
int par_tid(void);
int par_team(void);

/* The block length for a sum of n terms: at least par_block_min() (256), and at most
 * PAR_MAXBLOCKS blocks; a function of n only.  The environment variable QUSGM_PAR_BLOCK
 * sets the least block length instead (a test hook: the tests run the threads on packs of a
 * few hundred grains with QUSGM_PAR_BLOCK=16; the bytes then differ from the default's but
 * are again the same for any thread count). */
size_t par_block(size_t n);
size_t par_block_min(void);
size_t par_min(void);

/* sum a[k] b[k], by blocks of max(par_block(n), PAR_MIN_VEC) in order. */
double par_dot(const double *a, const double *b, size_t n);
/* y[k] += f x[k] (no sum: any split gives the same bytes). */
void par_axpy(double *y, double f, const double *x, size_t n);
/* y[k] = f x[k]. */
void par_scale(double *y, double f, const double *x, size_t n);
/* y[k] = 0, and y[k] = x[k]: memset and memcpy on the threads (no sums). */
void par_zero(double *y, size_t n);
void par_copy(double *y, const double *x, size_t n);

/* Fused passes for the minimisers, each the same bytes as the plain functions one after the
 * other (the same operations on each element, the sums by par_dot's blocks in order):
 *  - par_neg_dot: y[k] = -x[k], then par_dot(z, y, n);
 *  - par_axpy_scale_dot: y[k] = c (y[k] + f x[k]) (par_axpy then par_scale; c = 1 multiplies
 *    exactly), then par_dot(z, y, n);
 *  - par_diff_dots: s[k] = a[k] - b[k], y[k] = u[k] - v[k], then *sy = par_dot(s, y, n) and
 *    *yy = par_dot(y, y, n).
 *  - par_quad3: the quadratic form y.(M y) of the block-diagonal M (n/3 blocks of 3x3 in
 *    rows, 9 doubles apart), each (M y)[k] = M[3u] y0 + M[3u+1] y1 + M[3u+2] y2 of its node
 *    in that order: the bytes of forming d = M y node by node, then par_dot(y, d, n),
 *    without writing d.
 * z must not overlap y. */
double par_neg_dot(double *y, const double *x, const double *z, size_t n);
double par_axpy_scale_dot(double *y, double f, const double *x, double c, const double *z, size_t n);
double par_quad3(const double *M, const double *y, size_t n);
void par_diff_dots(double *s, const double *a, const double *b, double *y, const double *u, const double *v, size_t n,
    double *sy, double *yy);

#ifdef __cplusplus
}
#endif

#endif
