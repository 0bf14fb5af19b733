/* SPDX-License-Identifier: GPL-3.0-or-later */
/* increment: the cost of one isotropic strain increment from a dense pack, per minimiser.
 *
 * usage: increment PACK [STRAIN]
 *
 * From the same start (the pack as read, normally densify's equilibrium), each method
 * applies one isotropic compression of STRAIN (default 1e-4) in one sub-increment with the
 * affine guess and minimises to the default residual (1e-4), as a loading step does.  One
 * TSV row per method on stdout: iterations, energy+gradient evaluations, wall time
 * (CLOCK_MONOTONIC, neighbour-list builds included), time per evaluation per contact, and
 * the residual reached.  Exit 1 if a method fails or stops at its iteration limit. */
#include "qs/functional.h"
#include "qs/loading.h"
#include "qs/minimize.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"

int
main(int argc, char **argv)
{
	struct pack p;
	double box0[6], *x, strain = 1e-4;
	size_t m;
	int bad = 0;

	msg_init(argv[0]);
	msg_gsl_handler_install();
	if (argc < 2 || argc > 3)
		msg_die(EXIT_USAGE, "usage: increment PACK [STRAIN]");
	if (argc == 3) {
		char *end;
		strain = strtod(argv[2], &end);
		if (*end || !(strain > -0.01 && strain < 0.01) || strain == 0)
			msg_die(EXIT_USAGE, "STRAIN: '%s' is not a number in (-0.01, 0.01) other than 0", argv[2]);
	}
	if (pack_read_path(argv[1], &p))
		msg_die_err(EXIT_DATA);
	memcpy(box0, p.box, sizeof box0);
	x = malloc(3 * p.n * sizeof *x);
	if (!x)
		msg_die(EXIT_DATA, "out of memory");
	printf("# method\tgrains\tcontacts\titerations\tevaluations\twall_s\tns_per_eval_contact\tresidual\tresidual_mean\tsigma_c[Pa]\n");
	for (m = 0; qs_methods[m]; m++) {
		struct qs_system s;
		struct qs_min_params mp;
		struct qs_min_report rep;
		double de[3] = {strain, strain, strain}, t0, t1, sig[3];
		int st;

		memcpy(p.box, box0, sizeof box0);
		memcpy(x, p.x, 3 * p.n * sizeof *x);
		qs_min_params_default(&mp);
		mp.method = qs_methods[m];
		t0 = bench_now();
		if (qs_init(&s, &p, 0.3))
			msg_die_err(EXIT_DATA);
		st = load_increment(&s, x, de, 1, 10, &mp, &rep);
		t1 = bench_now();
		if (st < 0)
			msg_die_err(EXIT_DATA);
		qs_wall_stress(&s, sig);
		printf("%s\t%zu\t%zu\t%ld\t%ld\t%.4f\t%.1f\t%.3g\t%.3g\t%.6g\n", mp.method->name, p.n,
		    s.ncontacts, rep.iter, rep.evals, t1 - t0,
		    s.ncontacts && rep.evals ? 1e9 * (t1 - t0) / rep.evals / s.ncontacts : 0.0, rep.res_max,
		    rep.res_mean, (sig[0] + sig[1] + sig[2]) / 3);
		if (st == 1) {
			msg_warn("%s stopped at its iteration limit", mp.method->name);
			bad = 1;
		}
		qs_free(&s);
	}
	free(x);
	pack_free(&p);
	if (fflush(stdout) || ferror(stdout))
		msg_die(EXIT_DATA, "write error");
	return bad;
}
