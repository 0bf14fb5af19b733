/* moduli: Hooke's-law moduli of each interval of a loadtest curve (physics.md §8). */
#include "cli.h"
#include "curve.h"
#include "msg.h"
#include "table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static long window = 1;
static const char *stress_arg = "wall";

static struct cli_opt opts[] = {
	{"window", 'k', CLI_LONG, &window, "K", "increments per interval (fitted together by least squares)", NULL},
	{"stress", 0, CLI_STRING, &stress_arg, "KIND", "wall (normal forces on the walls) or lw (volume-averaged)", NULL},
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
};

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct cli_out out;
	struct table t;
	struct curve_cols cols;
	struct curve_interval *iv;
	size_t n, k;
	const char *display;
	FILE *in;
	int ncol = (int)(sizeof out_cols / sizeof out_cols[0]);

	msg_init(argv[0]);
	cli_parse(&tool, argc, argv, &st);
	if (window < 1)
		cli_usage_error("--window: must be positive");
	if (strcmp(stress_arg, "wall") && strcmp(stress_arg, "lw"))
		cli_usage_error("--stress: must be wall or lw");
	cli_usage_done();

	if (!(in = cli_in_open(st.input, &display)))
		msg_die_err(EXIT_DATA);
	if (table_read(in, display, &t))
		msg_die_err(EXIT_DATA);
	if (in != stdin)
		fclose(in);
	if (curve_columns(&t, display, strcmp(stress_arg, "lw") ? "sig" : "sig_lw", &cols) ||
	    curve_moduli(&t, &cols, display, window, &iv, &n))
		msg_die_err(EXIT_DATA);
	if (cli_out_open(&out, st.output))
		msg_die_err(EXIT_DATA);
	table_header(out.fp, out_cols, ncol);
	for (k = 0; k < n; k++) {
		const struct curve_interval *I = &iv[k];
		double v[12] = {I->seg, (double)I->inc_from, (double)I->inc_to, (double)I->n, I->sigma_c, I->sig_lat,
		    I->hk.K, I->hk.G, I->hk.lambda, I->hk.E, I->hk.nu, I->hk.rel};
		table_row(out.fp, v, ncol);
	}
	if (cli_out_commit(&out))
		msg_die_err(EXIT_DATA);
	free(iv);
	table_free(&t);
	return 0;
}
