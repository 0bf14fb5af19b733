/* SPDX-License-Identifier: GPL-3.0-or-later */
/* packimport: make a qusgm pack from "x y z r" lines (YADE, LAMMPS scripts, anything). */
#include "base/cli.h"
#include "base/fileio.h"
#include "analysis/export.h"
#include "pack/material.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/packio.h"

#include <gsl/gsl_rng.h>
#include <stdlib.h>
#include <string.h>

static const char *box_arg;
static int fit_box;
static const char *material_name = "glass";
static long seed = 1;
static double friction = 0.3;
static const char *wall_E_arg;
static double wall_nu = 0.495;
static const char *wall_friction_arg;

static struct cli_opt opts[] = {
	{"box", 0, CLI_STRING, &box_arg, "XLO,YLO,ZLO,XHI,YHI,ZHI", "the box; must hold every centre", "m"},
	{"fit-box", 0, CLI_FLAG, &fit_box, NULL, "the tightest box holding every sphere (the default)", NULL},
	{"material", 0, CLI_STRING, &material_name, "NAME", "grain material: a preset (glass, quartz, hydrate) or a file", NULL},
	{"seed", 0, CLI_LONG, &seed, "S", "seed of the mt19937 generator that draws E and nu", NULL},
	{"friction", 0, CLI_DOUBLE, &friction, "MU", "grain-grain friction coefficient", NULL},
	{"wall-E", 0, CLI_STRING, &wall_E_arg, "PA", "wall Young's modulus [default: 100 times the material's E]", "Pa"},
	{"wall-nu", 0, CLI_DOUBLE, &wall_nu, "NU", "wall Poisson ratio", NULL},
	{"wall-friction", 0, CLI_STRING, &wall_friction_arg, "MU", "grain-wall friction coefficient [default: the --friction value]", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"packimport", "[--box XLO,YLO,ZLO,XHI,YHI,ZHI | --fit-box] [options] [FILE]",
	"Make a qusgm pack from 'x y z r' lines, drawing grain moduli from a material.",
	opts, 1,
};

/* Resolved values of the options whose default depends on another, written back into the
 * option strings so that the history line records what was used. */
static char wall_E_text[40], wall_friction_text[40];

static int
parse_box(const char *s, double box[6])
{
	char buf[512], *tok, *save = NULL;
	int n = 0, a;

	if (strlen(s) >= sizeof buf)
		return -1;
	strcpy(buf, s);
	for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
		if (n == 6 || num_parse(tok, &box[n++]))
			return -1;
	if (n != 6)
		return -1;
	for (a = 0; a < 3; a++)
		if (!(box[a + 3] > box[a]))
			return -1;
	return 0;
}

/* Checks every option; usage errors are collected, a bad material file is bad data. */
static void
check_options(const struct cli_state *st, double box[6], struct material *m, double *wall_E, double *wall_mu)
{
	int mat_ok;

	if (box_arg && fit_box)
		cli_usage_error("--box and --fit-box exclude each other");
	if (box_arg && parse_box(box_arg, box))
		cli_usage_error("--box: '%s' is not six numbers xlo,ylo,zlo,xhi,yhi,zhi with each hi above its lo",
		    box_arg);
	if (seed < 0)
		cli_usage_error("--seed: %ld is negative", seed);
	if (!(friction >= 0 && friction <= PACK_MU_MAX))
		cli_usage_error("--friction: %g is outside [0, %g] (the range of every tool's --mu)", friction, PACK_MU_MAX);
	if (!(wall_nu > -1 && wall_nu < 0.5))
		cli_usage_error("--wall-nu: %g is outside (-1, 0.5)", wall_nu);
	if (wall_friction_arg && (num_parse(wall_friction_arg, wall_mu) || !(*wall_mu >= 0 && *wall_mu <= PACK_MU_MAX)))
		cli_usage_error("--wall-friction: '%s' is not a number in [0, %g]", wall_friction_arg, PACK_MU_MAX);
	mat_ok = material_lookup(material_name, m) == 0;
	if (!mat_ok && !strchr(material_name, '/') && !strstr(material_name, ".mat"))
		cli_usage_error("--material: %s", msg_geterr());
	if (wall_E_arg && (num_parse(wall_E_arg, wall_E) || !(*wall_E > 0)))
		cli_usage_error("--wall-E: '%s' is not a positive number", wall_E_arg);
	else if (wall_E_arg && !(*wall_E >= PACK_E_MIN && *wall_E <= PACK_WALL_E_MAX))
		cli_usage_error("--wall-E: %s Pa is outside [%g, %g] Pa", wall_E_arg, PACK_E_MIN, PACK_WALL_E_MAX);
	{	/* before any work: -o writable, and neither the input nor the material file */
		struct file_role r[] = {{st->output ? st->output : "-", "-o", 1}, {st->input, "the input", 0},
		    {material_is_file(material_name) ? material_name : NULL, "the --material file", 0}};
		if (file_roles_check(r, 3))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
	if (!mat_ok)
		msg_die_err(EXIT_DATA);
	if (!box_arg)
		fit_box = 1;
	if (!wall_E_arg) {
		*wall_E = 100 * m->E;
		num_format(wall_E_text, *wall_E);
		wall_E_arg = wall_E_text;
	}
	if (!wall_friction_arg) {
		*wall_mu = friction;
		num_format(wall_friction_text, *wall_mu);
		wall_friction_arg = wall_friction_text;
	}
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct material m;
	struct pack p;
	gsl_rng *rng;
	const char *name;
	double box[6], wall_E, wall_mu;
	size_t i;
	FILE *in;

	msg_init(argv[0]);
	cli_input_help("'x y z r' lines");
	cli_parse(&tool, argc, argv, &st);
	check_options(&st, box, &m, &wall_E, &wall_mu);

	if (!(in = file_in_open(st.input, &name)) || xyzr_read(in, name, box_arg ? box : NULL, &p))
		msg_die_err(EXIT_DATA);
	if (in != stdin)
		fclose(in);
	/* Moduli are drawn in file order, so a seed names one pack. */
	if (!(rng = gsl_rng_alloc(gsl_rng_mt19937)))
		msg_die(EXIT_DATA, "out of memory");
	gsl_rng_set(rng, (unsigned long)seed);
	for (i = 0; i < p.n; i++) {
		material_sample(&m, rng, &p.E[i], &p.nu[i]);
		p.rho[i] = m.rho;
	}
	gsl_rng_free(rng);
	p.mu = friction;
	p.wall_E = wall_E;
	p.wall_nu = wall_nu;
	p.wall_mu = wall_mu;
	if (pack_validate(&p))
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	if (pack_write_tool(&p, &tool, &st))
		msg_die_err(EXIT_DATA);
	pack_free(&p);
	return 0;
}
