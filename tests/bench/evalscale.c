/* SPDX-License-Identifier: GPL-3.0-or-later */
/* evalscale: is the cost of one energy+gradient evaluation linear in N?
 *
 * usage: evalscale PACK M...
 *
 * For each M, the dense PACK is tiled M x M x M times (copies shifted by the box lengths, in
 * one box M times larger; the inner walls go, the grains of neighbouring copies meet where
 * they touched a wall), and the Hertz functional of the tiled pack is evaluated: one
 * evaluation to build the neighbour list, then timed evaluations at the same positions
 * (CLOCK_MONOTONIC) until a second has passed.  One TSV row per M: grains, contacts, time of
 * the first evaluation (neighbour list included) and of one later evaluation, and ns per
 * evaluation per contact, which is constant when the cost is linear.  This measures the
 * functional at sizes (1e5 grains and more) that packgen and densify take hours to reach;
 * it says nothing about how many iterations a minimisation needs there.
 *
 * usage: evalscale -o OUT PACK M
 *
 * writes the tiled pack instead (the tiled box its reference box, no contact history): the
 * tools' memory at 1e6 grains, in runs cut short by an iteration limit (bench/memory-1e6.md).
 * It is not an equilibrium where the inner walls were. */
#include "qs/functional.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"

static void
tile(const struct pack *p, int m, struct pack *t)
{
	double len[3];
	int a, i, j, k;
	size_t g;

	pack_init(t);
	for (a = 0; a < 3; a++) {
		len[a] = p->box[a + 3] - p->box[a];
		t->box[a] = p->box[a];
		t->box[a + 3] = p->box[a] + m * len[a];
	}
	t->wall_E = p->wall_E;
	t->wall_nu = p->wall_nu;
	t->mu = p->mu;
	t->wall_mu = p->wall_mu;
	if (pack_reserve(t, p->n * (size_t)m * m * m))
		msg_die(EXIT_DATA, "out of memory");
	for (i = 0; i < m; i++)
		for (j = 0; j < m; j++)
			for (k = 0; k < m; k++)
				for (g = 0; g < p->n; g++) {
					double x[3] = {p->x[3 * g] + i * len[0], p->x[3 * g + 1] + j * len[1],
					    p->x[3 * g + 2] + k * len[2]};
					if (pack_add_grain(t, (long)t->n, x, p->r[g], p->E[g], p->nu[g], p->rho[g]) == (size_t)-1)
						msg_die(EXIT_DATA, "out of memory");
				}
}

int
main(int argc, char **argv)
{
	struct pack p;
	int k;

	msg_init(argv[0]);
	if (argc == 5 && !strcmp(argv[1], "-o")) {
		struct pack t;
		int m = atoi(argv[4]);

		if (m < 1 || m > 20)
			msg_die(EXIT_USAGE, "M: '%s' is not in 1..20", argv[4]);
		if (pack_read_path(argv[3], &p))
			msg_die_err(EXIT_DATA);
		tile(&p, m, &t);
		memcpy(t.refbox, t.box, sizeof t.refbox);
		t.has_refbox = 1;
		if (pack_write_path(&t, argv[2]))
			msg_die_err(EXIT_DATA);
		pack_free(&t);
		pack_free(&p);
		return 0;
	}
	if (argc < 3)
		msg_die(EXIT_USAGE, "usage: evalscale PACK M... | evalscale -o OUT PACK M");
	if (pack_read_path(argv[1], &p))
		msg_die_err(EXIT_DATA);
	printf("# tiles\tgrains\tcontacts\tfirst_eval_s\teval_s\tns_per_eval_contact\n");
	for (k = 2; k < argc; k++) {
		struct pack t;
		struct qs_system s;
		double *x, *g, t0, t1, dt;
		long n = 0;
		int m = atoi(argv[k]);

		if (m < 1 || m > 20)
			msg_die(EXIT_USAGE, "M: '%s' is not in 1..20", argv[k]);
		tile(&p, m, &t);
		x = malloc(3 * t.n * sizeof *x);
		g = malloc(3 * t.n * sizeof *g);
		if (!x || !g || qs_init(&s, &t, 0.3))
			msg_die(EXIT_DATA, "out of memory");
		memcpy(x, t.x, 3 * t.n * sizeof *x);
		t0 = bench_now();
		qs_energy(&s, x, g, NULL);
		t1 = bench_now();
		do {
			qs_energy(&s, x, g, NULL);
			n++;
			dt = bench_now() - t1;
		} while (dt < 1.0);
		printf("%d\t%zu\t%zu\t%.4f\t%.6f\t%.2f\n", m * m * m, t.n, s.ncontacts, t1 - t0, dt / n,
		    1e9 * dt / n / (double)s.ncontacts);
		fflush(stdout);
		qs_free(&s);
		free(x), free(g);
		pack_free(&t);
	}
	pack_free(&p);
	return 0;
}
