/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench: what the benchmark programs share: a monotonic wall clock and the process's CPU clock. */
#ifndef QUSGM_BENCH_H
#define QUSGM_BENCH_H

#include <time.h>

/* Seconds on CLOCK_MONOTONIC: differences are wall time, immune to clock changes. */
static inline double
bench_now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Seconds of CPU time of the process (all its threads), CLOCK_PROCESS_CPUTIME_ID. */
static inline double
bench_cpu(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

#endif
