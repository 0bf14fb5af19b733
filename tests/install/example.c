/* example: a program of a user of the installed library (share/doc/library.md, "Using the
 * library"), built by tests/tools/install.sh with
 *
 *	cc example.c $(pkg-config --cflags --libs qusgm)
 *
 * It reads one pack (plain or .gz, "-" for stdin), measures it as packinfo does, evaluates the
 * Hertz functional Pi at the grains' centres and its force-balance residual, and prints
 * "key value" lines in packinfo's number format: grains, porosity, sigma_c and residual
 * (packinfo's measures), then energy, qs_residual and qs_residual_mean (the functional's).
 * Exit status 1 with the library's message on any error, 2 on bad usage. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/measure.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/packio.h"
#include "qs/functional.h"

static void
put(const char *key, double v)
{
	char buf[32];

	num_format(buf, v);
	printf("%s %s\n", key, buf);
}

static int
fail(const char *what)
{
	fprintf(stderr, "example: %s: %s\n", what, msg_geterr());
	return 1;
}

int
main(int argc, char **argv)
{
	struct pack p;
	struct geo_contacts gc;
	struct pack_measures m;
	struct qs_system s;
	double *g, *fmax, energy, res_max, res_mean;

	if (argc != 2) {
		fprintf(stderr, "usage: example PACK\n");
		return 2;
	}
	msg_gsl_handler_install();	/* a GSL error is a message in the slot, not abort() */
	if (pack_read_path(argv[1], &p))	/* p is empty again on failure */
		return fail("reading");
	contacts_init(&gc);
	if (measure_pack(&p, &gc, &m))
		return fail("measuring");
	put("grains", (double)m.grains);
	put("porosity", m.porosity);
	put("sigma_c", m.sigma_c);
	put("residual", m.residual_max);
	contacts_free(&gc);

	/* Pi and its gradient at the centres as stored (3N unknowns, qs/layout.h) */
	if (qs_init(&s, &p, 0.3))
		return fail("qs_init");
	g = malloc(s.dim * sizeof *g);
	fmax = calloc(p.n, sizeof *fmax);
	if (!g || !fmax) {
		fprintf(stderr, "example: out of memory\n");
		return 1;
	}
	energy = qs_energy(&s, p.x, g, fmax);
	if (isnan(energy))
		return fail("qs_energy");
	qs_residual(&s, g, fmax, QS_RESIDUAL_FLOOR, &res_max, &res_mean);
	put("energy", energy);
	put("qs_residual", res_max);
	put("qs_residual_mean", res_mean);
	free(g);
	free(fmax);
	qs_free(&s);
	pack_free(&p);
	if (fflush(stdout) || ferror(stdout)) {
		perror("example: stdout");
		return 1;
	}
	return 0;
}
