/* SPDX-License-Identifier: GPL-3.0-or-later */
/* platestep: the cost of one explicit DEM step of a spheroplate pack (lib/dem/engine.c).
 *
 * usage: platestep PACK [STEPS]
 *
 * From the pack as read (normally packgen --shape spheroplate's static pack), STEPS steps
 * (default 200) of forces and leapfrog, P's contact law, no local damping.  One TSV row on
 * stdout: grains, steps, interactions (with at least one element) and element contacts at
 * the last step, CPU time per step (the process's, neighbour-list rebuilds included; on one
 * thread what a step costs whatever else the machine runs),
 * time per step per grain, element contacts per second (elements visited over time). */
#include "dem/engine.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <stdio.h>
#include <stdlib.h>
#include "bench.h"

int
main(int argc, char **argv)
{
	struct pack p;
	struct engine d;
	struct engine_params pp;
	long steps = argc > 2 ? atol(argv[2]) : 200, s;
	double t0, t, elements = 0;

	msg_init(argv[0]);
	if (argc < 2 || steps < 1) {
		fprintf(stderr, "usage: platestep PACK [STEPS]\n");
		return 2;
	}
	if (pack_read_path(argv[1], &p))
		msg_die_err(1);
	engine_params_default(&pp);
	if (engine_init(&d, &p, &pp) || engine_forces(&d))
		msg_die_err(1);
	t0 = bench_cpu();
	for (s = 0; s < steps; s++) {
		engine_integrate(&d);
		if (engine_forces(&d))
			msg_die_err(1);
		elements += (double)d.nelem;
	}
	t = bench_cpu() - t0;
	printf("# grains\tsteps\tinteractions\telements\ts_per_step\tus_per_step_per_grain\telements_per_s\n");
	printf("%zu\t%ld\t%zu\t%zu\t%.6f\t%.4f\t%.4g\n", d.n, steps, d.ninter, d.nelem, t / steps, 1e6 * t / steps / d.n,
	    elements / t);
	engine_free(&d);
	pack_free(&p);
	return 0;
}
