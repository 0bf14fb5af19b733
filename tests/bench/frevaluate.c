/* SPDX-License-Identifier: GPL-3.0-or-later */
/* frevaluate: the cost of one evaluation of the frictional functional, term by term.
 *
 * usage: frevaluate PACK [SECONDS]
 *
 * From PACK (normally frictionalize's output, whose history is developed) one uniaxial 1e-4
 * compression along z, minimised with friction to the residual 1e-3 as a loading increment
 * starts (so that the contacts hold tangential displacements and some slide), then, at those
 * positions, timed evaluations (CLOCK_MONOTONIC, each kind for SECONDS, default 1) of:
 *   - the whole functional with its gradient (qs_energy: Hertz and friction, 6N unknowns);
 *   - the normal (Hertz) term alone, and the friction term alone (struct qs_term's energy).
 * One TSV row each: evaluations timed, contacts it visits (the friction term's reference
 * contacts; Hertz's touching pairs and walls), ns per evaluation, ns per evaluation per
 * contact, and the sliding contacts at that state.  This is issue 16's "ns per contact per
 * evaluation" of the tangential term, apart from iteration counts and the passes around them.
 * Exit 1 if the pack cannot be read or the minimisation fails. */
#include "qs/friction.h"
#include "qs/loading.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"

/* Evaluations of what (0 all, 1 the normal term, 2 friction) for at least secs seconds;
 * their count into *count, ns per evaluation returned. */
static double
time_evals(struct qs_system *s, const double *x, double *g, double *fmax, int what, double secs, long *count)
{
	double t0 = bench_now(), t;
	long k = 0;

	do {
		long b;
		for (b = 0; b < 10; b++) {
			memset(g, 0, s->dim * sizeof *g);
			if (what == 0)
				qs_energy(s, x, g, fmax);
			else
				s->term[what == 1 ? 0 : 1].energy(&s->term[what == 1 ? 0 : 1], s, x, g, fmax);
		}
		k += 10;
		t = bench_now() - t0;
	} while (t < secs);
	*count = k;
	return 1e9 * t / k;
}

int
main(int argc, char **argv)
{
	static const char *names[] = {"functional", "hertz", "friction"};
	struct pack p;
	struct qs_system s;
	struct qs_friction f;
	struct qs_min_params mp;
	struct qs_min_report rep;
	double *x, *g, *fmax, secs = 1, de[3] = {0, 0, 1e-4};
	size_t n3;
	int what;

	msg_init(argv[0]);
	msg_gsl_handler_install();
	if (argc < 2 || argc > 3)
		msg_die(EXIT_USAGE, "usage: frevaluate PACK [SECONDS]");
	if (argc == 3 && !((secs = atof(argv[2])) > 0 && secs <= 600))
		msg_die(EXIT_USAGE, "SECONDS: '%s' is not in (0, 600]", argv[2]);
	if (pack_read_path(argv[1], &p))
		msg_die_err(EXIT_DATA);
	if (qs_init(&s, &p, 0.3))
		msg_die_err(EXIT_DATA);
	fr_init(&f, FR_RETURN_MAP);
	n3 = 3 * p.n;
	x = calloc(2 * n3 + 1, sizeof *x);
	g = calloc(2 * n3 + 1, sizeof *g);
	fmax = calloc(p.n + 1, sizeof *fmax);
	if (!x || !g || !fmax)
		msg_die(EXIT_DATA, "out of memory");
	memcpy(x, p.x, n3 * sizeof *x);
	if (fr_begin(&f, &s))
		msg_die_err(EXIT_DATA);
	load_strain_box(p.box, x, p.n, de);
	qs_min_params_default(&mp);
	mp.tol = 1e-3;
	if (qs_minimize(&s, x, &mp, &rep) < 0)
		msg_die_err(EXIT_DATA);
	qs_energy(&s, x, g, fmax);
	printf("# kind\tgrains\tcontacts\tevaluations\tns_per_eval\tns_per_eval_contact\tsliding\n");
	for (what = 0; what < 3; what++) {
		long count;
		double ns = time_evals(&s, x, g, fmax, what, secs, &count);
		size_t nc = what == 2 ? f.n : s.ncontacts;

		printf("%s\t%zu\t%zu\t%ld\t%.0f\t%.1f\t%zu\n", names[what], p.n, nc, count, ns, nc ? ns / nc : 0,
		    fr_sliding(&f));
	}
	fr_free(&f);
	qs_free(&s);
	free(x), free(g), free(fmax);
	pack_free(&p);
	return 0;
}
