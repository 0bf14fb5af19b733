/* SPDX-License-Identifier: GPL-3.0-or-later */
/* moduli: Hooke's-law moduli of each interval of a loadtest curve (physics.md §8). */
#include "base/cli.h"
#include "base/fileio.h"
#include "analysis/curve.h"
#include "analysis/emt.h"
#include "pack/material.h"
#include "base/msg.h"
#include "base/table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static long window = 1;
static int pool;
/* The volume-averaged stress by default, whatever the walls' friction: it is the stress the
 * grains carry, and with frictionless walls it equals the wall stresses at equilibrium; with
 * frictional walls the wall normal forces miss what the walls' friction carries (isotropic
 * probe of a frictional 1000-grain pack: K 1.30 GPa from the walls, 0.82 GPa inside, the
 * same 0.83 for both once the walls are frictionless; share/doc/friction.md).  A table
 * without the sig_lw columns (written by hand, or by another code) is fitted on its sig
 * columns. */
static const char *stress_arg, *emt_arg;

static struct cli_opt opts[] = {
	{"window", 'k', CLI_LONG, &window, "K", "increments per interval (fitted together by least squares)", NULL},
	{"stress", 0, CLI_STRING, &stress_arg, "KIND", "lw (volume-averaged; the default where the table has it) or wall (normal forces on the walls)", NULL},
	{"pool-segments", 0, CLI_FLAG, &pool, NULL, "intervals run across path segments (a probe's x, y and z fitted together)", NULL},
	{"emt", 0, CLI_STRING, &emt_arg, "MATERIAL", "add effective-medium K and G from each interval's porosity, coordination and sigma_c (grains of MATERIAL)", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"moduli", "[options] [FILE]",
	"Fit Hooke's law to each interval of a loadtest curve: K, G, lambda, E, nu versus confining stress.",
	opts, 1,
};

static const struct table_col out_cols[] = {
	{"seg", NULL}, {"inc_from", NULL}, {"inc_to", NULL}, {"n", NULL},
	{"sigma_c", "Pa"}, {"sig_lat", "Pa"}, {"K", "Pa"}, {"G", "Pa"}, {"lambda", "Pa"}, {"E", "Pa"}, {"nu", NULL},
	{"fit_rel", NULL},
	{"porosity", NULL}, {"coordination", NULL}, {"K_emt", "Pa"}, {"G_emt_rough", "Pa"}, {"G_emt_smooth", "Pa"},
	{"K_se", "Pa"}, {"G_se", "Pa"},
};
/* The columns written: the first 12, the 5 of --emt, then the standard errors, last so that
 * the columns before them keep their places (13-14 without --emt, 18-19 with it). */
#define NBASE 12
#define NEMT 5
#define NSE 2
_Static_assert(sizeof out_cols / sizeof out_cols[0] == NBASE + NEMT + NSE, "moduli: out_cols");

/* Every usage error before any work. */
static void
check_args(const struct cli_state *st, struct material *mat)
{
	if (window < 1)
		cli_usage_error("--window: must be positive");
	if (stress_arg && strcmp(stress_arg, "wall") && strcmp(stress_arg, "lw"))
		cli_usage_error("--stress: must be wall or lw");
	if (emt_arg && material_lookup(emt_arg, mat))
		cli_usage_error("--emt: %s", msg_geterr());
	{	/* -o writable, and neither the input table nor --emt's file */
		struct file_role r[] = {{st->output ? st->output : "-", "-o", 1}, {st->input, "the input", 0},
		    {emt_arg && material_is_file(emt_arg) ? emt_arg : NULL, "the --emt material file", 0}};
		if (file_roles_check(r, 3))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
}

static void
read_table(const char *input, struct table *t, const char **display)
{
	FILE *in;

	if (!(in = file_in_open(input, display)))
		msg_die_err(EXIT_DATA);
	if (table_read(in, *display, t))
		msg_die_err(EXIT_DATA);
	if (in != stdin)
		fclose(in);
}

static void
warn_negative(const struct table *t, const char *display, const struct curve_interval *iv, size_t n)
{
	size_t k;

	for (k = 0; k < n; k++) {
		const struct curve_interval *I = &iv[k];
		if (!isnan(I->K_negative) || !isnan(I->G_negative))
			msg_warn("%s:%ld: increments %ld-%ld: %s = %.4g Pa is negative: no modulus, written as nan",
			    display, t->line[I->row_to], I->inc_from, I->inc_to, isnan(I->G_negative) ? "K" : "G",
			    isnan(I->G_negative) ? I->K_negative : I->G_negative);
	}
}

/* cphi and cz: the table's porosity and coordination columns, read with --emt only. */
static void
put_rows(FILE *fp, const struct table *t, const struct curve_interval *iv, size_t n, const struct material *mat,
    int cphi, int cz, int ncol)
{
	size_t k;

	for (k = 0; k < n; k++) {
		const struct curve_interval *I = &iv[k];
		double v[NBASE + NEMT + NSE] = {I->seg, (double)I->inc_from, (double)I->inc_to, (double)I->n, I->sigma_c, I->sig_lat,
		    I->hk.K, I->hk.G, I->hk.lambda, I->hk.E, I->hk.nu, I->hk.rel};
		if (emt_arg) {
			struct emt e;
			/* the state at the interval's end row */
			double phi = t->v[I->row_to * t->ncol + cphi], Z = t->v[I->row_to * t->ncol + cz];
			emt_moduli(mat->E / (2 * (1 + mat->nu)), mat->nu, phi, Z, I->sigma_c, &e);
			v[12] = phi;
			v[13] = Z;
			v[14] = e.K;
			v[15] = e.G_rough;
			v[16] = e.G_smooth;
		}
		v[ncol - 2] = I->hk.K_se;
		v[ncol - 1] = I->hk.G_se;
		table_row(fp, v, ncol);
	}
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct file_out out;
	struct table t;
	struct curve_cols cols;
	struct curve_interval *iv;
	size_t n;
	const char *display;
	int ncol = NBASE + NEMT + NSE, cphi = -1, cz = -1;
	struct material mat;
	struct table_col cols_out[NBASE + NEMT + NSE];

	msg_init(argv[0]);
	cli_input_help("a loadtest table");
	cli_parse(&tool, argc, argv, &st);
	check_args(&st, &mat);
	memcpy(cols_out, out_cols, sizeof cols_out);
	if (!emt_arg) {
		ncol -= NEMT;
		memcpy(cols_out + NBASE, out_cols + NBASE + NEMT, NSE * sizeof *cols_out);
	}

	read_table(st.input, &t, &display);
	/* a window longer than the whole table would fit each segment as one interval */
	if (t.nrow >= 2 && (size_t)window > t.nrow - 1)
		msg_die(EXIT_DATA, "%s: --window %ld is longer than the table's %zu increments (%zu rows)",
		    display, window, t.nrow - 1, t.nrow);
	if (!stress_arg)
		stress_arg = table_find(&t, "sig_lw_xx") >= 0 ? "lw" : "wall";
	if (curve_columns(&t, display, strcmp(stress_arg, "lw") ? "sig" : "sig_lw", &cols))
		msg_die_err(EXIT_DATA);
	cols.pool = pool;
	if (curve_moduli(&t, &cols, display, window, &iv, &n))
		msg_die_err(EXIT_DATA);
	warn_negative(&t, display, iv, n);
	/* the effective medium is a model of the bulk: the state of the grains away from the
	 * walls where the table has it (loadtest's bulk_ columns), else of the whole box */
	if (emt_arg && ((cphi = table_find(&t, "bulk_porosity")) < 0 || (cz = table_find(&t, "bulk_coordination")) < 0) &&
	    ((cphi = table_find(&t, "porosity")) < 0 || (cz = table_find(&t, "coordination")) < 0))
		msg_die(EXIT_DATA, "%s: --emt needs the porosity and coordination columns", display);
	if (file_out_open(&out, st.output))
		msg_die_err(EXIT_DATA);
	table_header(out.fp, cols_out, ncol);
	put_rows(out.fp, &t, iv, n, &mat, cphi, cz, ncol);
	if (file_out_commit(&out))
		msg_die_err(EXIT_DATA);
	free(iv);
	table_free(&t);
	return 0;
}
