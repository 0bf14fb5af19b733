/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fincrement: the cost of uniaxial strain increments with and without friction.
 *
 * usage: fincrement PACK [STEPS [STRAIN [METHOD]]]
 *
 * From the same start (the pack as read, normally frictionalize's output, whose history is
 * developed), STEPS uniaxial compressions of STRAIN along z (defaults 5 and 1e-4) through the
 * loader that loadtest uses, per minimiser, frictional (6N unknowns, the pack's mu) and
 * frictionless (3N, mu 0).  One TSV row per case on stdout: mean iterations, evaluations
 * and wall time per increment (CLOCK_MONOTONIC; neighbour lists, the commit of the history
 * and the row's measures included), time per evaluation per contact, the largest residual,
 * and last the process's CPU time per evaluation per contact (CLOCK_PROCESS_CPUTIME_ID: on a
 * shared machine with one thread, steadier than the wall time).  METHOD (lbfgs, fire, cg or newton)
 * runs that minimiser alone, both cases; FINCREMENT_CASE=mu or none in the environment runs
 * only the frictional or the frictionless case (for profiling one of them), and
 * FINCREMENT_SKIN the Verlet skin (loadtest's --skin; default 0.3), FINCREMENT_LBFGS_M
 * L-BFGS's stored steps (--lbfgs-m; default the loader's, 4 with friction and 8 without).
 * Exit 1 if a case fails or stops at its iteration limit. */
#include "qs/loading.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"

int
main(int argc, char **argv)
{
	static const struct qs_method_type *const methods[] = {&qs_method_lbfgs, &qs_method_fire, &qs_method_cg,
	    &qs_method_newton};
	struct pack p0;
	double strain = 1e-4;
	long steps = 5;
	const struct qs_method_type *only = &qs_method_lbfgs;
	size_t m;
	int fr, bad = 0;
	const char *only_case = getenv("FINCREMENT_CASE");

	msg_init(argv[0]);
	msg_gsl_handler_install();
	if (argc < 2 || argc > 5)
		msg_die(EXIT_USAGE, "usage: fincrement PACK [STEPS [STRAIN [METHOD]]]");
	if (argc >= 3 && ((steps = atol(argv[2])) < 1 || steps > 10000))
		msg_die(EXIT_USAGE, "STEPS: '%s' is not a count in [1, 10000]", argv[2]);
	if (argc >= 4 && !((strain = atof(argv[3])) > 0 && strain < 0.01))
		msg_die(EXIT_USAGE, "STRAIN: '%s' is not in (0, 0.01)", argv[3]);
	if (argc == 5 && !(only = qs_method_find(argv[4])))
		msg_die(EXIT_USAGE, "METHOD: %s", msg_geterr());
	if (pack_read_path(argv[1], &p0))
		msg_die_err(EXIT_DATA);
	if (!p0.has_refbox)
		msg_die(EXIT_DATA, "%s: no reference box", argv[1]);
	printf("# friction\tmethod\tgrains\tcontacts\tincrements\titerations\tevaluations\twall_s\tns_per_eval_contact\tresidual\tsliding_ratio\tsigma_c[Pa]\tcpu_ns_per_eval_contact\n");
	for (fr = 1; fr >= 0; fr--)
		for (m = 0; m < sizeof methods / sizeof methods[0]; m++) {
			struct pack p;
			struct loader L;
			struct load_params lp;
			struct load_row row;
			double de[3] = {0, 0, strain}, t0, t1, c0, c1, resmax = 0;
			long k, iters = 0, evals = 0;
			size_t nc;
			int st = 0;

			if (argc == 5 && methods[m] != only)
				continue;
			if (only_case && strcmp(only_case, fr ? "mu" : "none"))
				continue;
			/* a fresh copy of the start: read it again */
			if (pack_read_path(argv[1], &p))
				msg_die_err(EXIT_DATA);
			if (!fr)
				p.mu = p.wall_mu = 0;
			load_params_default(&lp);
			lp.friction = fr;
			lp.min.method = methods[m];
			if (getenv("FINCREMENT_SKIN"))
				lp.skin = atof(getenv("FINCREMENT_SKIN"));
			if (getenv("FINCREMENT_LBFGS_M"))
				lp.min.lbfgs_m = atol(getenv("FINCREMENT_LBFGS_M"));
			if (loader_open(&L, &p, &lp))
				msg_die_err(EXIT_DATA);
			t0 = bench_now();
			c0 = bench_cpu();
			for (k = 0; k < steps && st == 0; k++) {
				st = loader_step(&L, de, &row);
				if (st < 0)
					msg_die_err(EXIT_DATA);
				iters += row.iterations;
				evals += row.evals;
				if (row.res_max > resmax)
					resmax = row.res_max;
			}
			t1 = bench_now();
			c1 = bench_cpu();
			nc = p.nc;
			printf("%s\t%s\t%zu\t%zu\t%ld\t%.1f\t%.1f\t%.4f\t%.1f\t%.3g\t%.4f\t%.6g\t%.1f\n", fr ? "mu" : "none",
			    methods[m]->name, p.n, nc, k, (double)iters / k, (double)evals / k, (t1 - t0) / k,
			    nc && evals ? 1e9 * (t1 - t0) / evals / nc : 0.0, resmax, row.sliding_ratio, row.sigma_c,
			    nc && evals ? 1e9 * (c1 - c0) / evals / nc : 0.0);
			fflush(stdout);
			if (st == 1) {
				fprintf(stderr, "fincrement: %s %s: iteration limit\n", fr ? "friction" : "frictionless",
				    methods[m]->name);
				bad = 1;
			}
			loader_close(&L);
			pack_free(&p);
		}
	pack_free(&p0);
	return bad;
}
