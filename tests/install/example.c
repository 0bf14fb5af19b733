/* SPDX-License-Identifier: GPL-3.0-or-later */
/* example: a program of a user of the installed library (share/doc/library.md, "Using the
 * library"), built by tests/tools/install.sh as C and as C++ with
 *
 *	cc example.c $(pkg-config --cflags --libs qusgm)
 *	c++ -x c++ example.c $(pkg-config --cflags --libs qusgm)
 *
 * It reads one pack (plain or .gz, "-" for stdin), measures it as packinfo does, evaluates the
 * Hertz functional Pi at the grains' centres and its force-balance residual, and prints
 * "key value" lines in packinfo's number format: grains, porosity, sigma_c and residual
 * (packinfo's measures), then energy, qs_residual and qs_residual_mean (the functional's).
 * Exit status 1 with the library's message on any error, 2 on bad usage.
 *
 * It defines functions of its own named as functions internal to qusgm (table_read,
 * path_parse, file_is_gz) and calls them: the installed library exports its API alone, each
 * name prefixed qusgm_ (lib/qusgm.api), so these link, and the program's own are called. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <qusgm/qusgm.h>

/* The user's own functions, with qusgm's internal names and other signatures. */
int table_read(const char *s);
int path_parse(int x);
int file_is_gz(void);

int
table_read(const char *s)
{
	return (int)strlen(s);
}

int
path_parse(int x)
{
	return 2 * x;
}

int
file_is_gz(void)
{
	return 42;
}

static void
put(const char *key, double v)
{
	char buf[32];

	qusgm_num_format(buf, v);
	printf("%s %s\n", key, buf);
}

static int
fail(const char *what)
{
	fprintf(stderr, "example: %s: %s\n", what, qusgm_msg_geterr());
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
	/* the program's own functions, not qusgm's */
	if (table_read("abc") != 3 || path_parse(4) != 8 || file_is_gz() != 42) {
		fprintf(stderr, "example: a function of the program's own was not called\n");
		return 1;
	}
	qusgm_msg_gsl_handler_install();	/* a GSL error is a message in the slot, not abort() */
	if (qusgm_pack_read_path(argv[1], &p))	/* p is empty again on failure */
		return fail("reading");
	qusgm_contacts_init(&gc);
	if (qusgm_measure_pack(&p, &gc, &m))
		return fail("measuring");
	put("grains", (double)m.grains);
	put("porosity", m.porosity);
	put("sigma_c", m.sigma_c);
	put("residual", m.residual_max);
	qusgm_contacts_free(&gc);

	/* Pi and its gradient at the centres as stored (3N unknowns, qs/layout.h) */
	if (qusgm_qs_init(&s, &p, 0.3))
		return fail("qs_init");
	g = (double *)malloc(s.dim * sizeof *g);	/* the casts: C++ wants them */
	fmax = (double *)calloc(p.n, sizeof *fmax);
	if (!g || !fmax) {
		fprintf(stderr, "example: out of memory\n");
		return 1;
	}
	energy = qusgm_qs_energy(&s, p.x, g, fmax);
	if (isnan(energy))
		return fail("qs_energy");
	qusgm_qs_residual(&s, g, fmax, QS_RESIDUAL_FLOOR, &res_max, &res_mean);
	put("energy", energy);
	put("qs_residual", res_max);
	put("qs_residual_mean", res_mean);
	free(g);
	free(fmax);
	qusgm_qs_free(&s);
	qusgm_pack_free(&p);
	if (fflush(stdout) || ferror(stdout)) {
		perror("example: stdout");
		return 1;
	}
	return 0;
}
