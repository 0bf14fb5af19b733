/* SPDX-License-Identifier: GPL-3.0-or-later */
/* par_start: the tools' wait policy for idle threads, given to the OpenMP runtime before it
 * reads its environment (par.h, "Waits").
 *
 * Linked into the tools alone (the Makefile's TOOL_START), never into the library: a library
 * does not change its program's environment.  GCC's libgomp reads OMP_WAIT_POLICY and
 * GOMP_SPINCOUNT once, in a constructor of its own; the Makefile links libgomp into each tool
 * (OMP_STATIC), so that constructor is one of the tool's, run after this one (priority 101
 * comes before every constructor without a priority).  LLVM's libomp reads its environment at
 * the first parallel region, later still.  Nothing is started again: the process keeps its
 * name, its arguments and the way it was started. */
#include <stdlib.h>

static void par_start_wait_policy(void) __attribute__((constructor(101)));

static void
par_start_wait_policy(void)
{
	/* a user's own setting of either is kept (OMP_WAIT_POLICY=active restores the spinning) */
	if (!getenv("OMP_WAIT_POLICY") && !getenv("GOMP_SPINCOUNT"))
		setenv("OMP_WAIT_POLICY", "passive", 0);
}
