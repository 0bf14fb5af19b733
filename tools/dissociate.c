/* SPDX-License-Identifier: GPL-3.0-or-later */
/* dissociate: hydrate dissociation, a drop dS of the hydrate saturation and an excess pore
 * pressure p_ex, then the new equilibrium (physics.md section 11; the rules in
 * qs/dissociate.h). */
#include "base/cli.h"
#include "base/fileio.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/packio.h"
#include "qs/dissociate.h"
#include "qs/loadpath.h"
#include "qs/minopts.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static struct opts {
	struct load_params lp;
	struct dissociation d;
	const char *rule;
	double mu, wall_mu;
	long nsub;
} o = {
	.mu = NAN, .wall_mu = NAN,
	.d = {0, 0, 0.8, NAN, 1e-5},
	.rule = "return-map",
	.nsub = 1,
};

static struct cli_opt opt_table[] = {
	{"dS", 0, CLI_DOUBLE, &o.d.dS, "DS", "change of the hydrate saturation S = V_hydrate / V_pores (<= 0)", NULL},
	{"pex", 0, CLI_DOUBLE, &o.d.pex, "PA", "excess pore pressure applied (>= 0)", "Pa"},
	{"alpha", 0, CLI_DOUBLE, &o.d.alpha, "A", "Biot-Willis coefficient alpha_b of the box expansion alpha_b p_ex / K", NULL},
	{"K", 0, CLI_DOUBLE, &o.d.K, "PA", "the pack's bulk modulus (default: measured by an isotropic probe)", "Pa"},
	{"probe-strain", 0, CLI_DOUBLE, &o.d.probe, "E", "the probe's isotropic extension per axis", NULL},
	{"mu", 'm', CLI_DOUBLE, &o.mu, "M", "grain-grain friction (default: the pack's; 0: frictionless)", NULL},
	{"wall-mu", 0, CLI_DOUBLE, &o.wall_mu, "M", "grain-wall friction (default: the pack's, or --mu when given)", NULL},
	QS_LOAD_OPTS(o.lp, o.rule, o.nsub),
	QS_MIN_OPTS(o.lp.min),
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"dissociate", "[options] [FILE]",
	"Dissociate hydrate in a pack: shrink the hydrate grains by dS / S, compress every grain by the excess pore pressure, expand the box by alpha_b p_ex / K, and find the new equilibrium.",
	opt_table, 1,
};

static void
parse_args(int argc, char **argv, struct cli_state *st)
{
	load_params_default(&o.lp);
	qs_min_opts_init();
	cli_parse(&tool, argc, argv, st);
	qs_min_opts_check(&o.lp.min);
	if (!(o.d.dS <= 0))
		cli_usage_error("--dS: must be <= 0 (dissociation; hydrate formation is not modelled)");
	if (!(o.d.pex >= 0 && isfinite(o.d.pex)))
		cli_usage_error("--pex: must be >= 0 (an excess pore pressure, Pa)");
	if (!(o.d.alpha > 0 && o.d.alpha <= 1))
		cli_usage_error("--alpha: must be in (0, 1]");
	if (!isnan(o.d.K) && !(o.d.K > 0 && isfinite(o.d.K)))
		cli_usage_error("--K: must be positive (Pa)");
	if (!(o.d.probe > 0 && o.d.probe <= 1e-3))
		cli_usage_error("--probe-strain: must be in (0, 1e-3]");
	qs_load_opts_check(&o.lp, o.rule, o.nsub, o.mu, o.wall_mu);
	{	/* before any work: -o writable (it may be the input: the pack updated in place) */
		struct file_role r[] = {{st->output ? st->output : "-", "-o", FILE_UPDATE}, {st->input, "the input", FILE_IN}};
		if (file_roles_check(r, 2))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
}

static void
set_meta_num(struct pack *p, const char *key, double v)
{
	char buf[40];

	num_format(buf, v);
	if (pack_set_meta(p, key, buf))
		msg_die(EXIT_DATA, "out of memory");
}

/* What the run did, in the pack's meta lines (share/doc/pack-format.md lists the keys): the
 * excess pore pressure accumulates over runs, the rest is this run's. */
static void
record(struct pack *p, const struct dissociation_report *rep, const char *in)
{
	double pex0 = 0;

	if (pack_get_meta(p, "pore_pressure_excess") && pack_get_meta_double(p, "pore_pressure_excess", &pex0))
		msg_die(EXIT_DATA, "%s: meta pore_pressure_excess: '%s' is not a number", in, pack_get_meta(p, "pore_pressure_excess"));
	set_meta_num(p, "pore_pressure_excess", pex0 + o.d.pex);
	set_meta_num(p, "biot_alpha", o.d.alpha);
	set_meta_num(p, "dissociation_dS", o.d.dS);
	set_meta_num(p, "dissociation_pex", o.d.pex);
	set_meta_num(p, "dissociation_S_before", rep->S_before);
	set_meta_num(p, "dissociation_S_after", rep->S_after);
	if (o.d.pex > 0) {
		set_meta_num(p, "dissociation_K", rep->K);
		if (pack_set_meta(p, "dissociation_K_from", rep->K_measured ? "probe" : "given"))
			msg_die(EXIT_DATA, "out of memory");
		set_meta_num(p, "dissociation_eps_kk", rep->eps_kk);
	}
	set_meta_num(p, "effective_stress_before", rep->sigma_before);
	set_meta_num(p, "effective_stress_after", rep->sigma_after);
	set_meta_num(p, "wall_stress_before", rep->sigma_wall_before);
	set_meta_num(p, "wall_stress_after", rep->sigma_wall_after);
	set_meta_num(p, "total_stress_after", rep->sigma_total_after);
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct dissociation_report rep;
	struct pack p;
	const char *in;
	size_t stale;
	int r;

	msg_init(argv[0]);
	parse_args(argc, argv, &st);
	in = file_display_name(st.input);
	if ((r = path_read_pack(st.input, tool.name, &p, &stale)))
		msg_die(EXIT_DATA, "%s%s%s", r > 0 ? in : "", r > 0 ? ": " : "", msg_geterr());
	if (stale)
		msg_warn("%s: %zu history lines name grains that do not touch: dropped", in, stale);
	o.lp.friction = path_set_friction(&p, o.mu, o.wall_mu);
	if (dissociate_run(&p, &o.lp, &o.d, &rep))
		msg_die(EXIT_DATA, "%s: %s", in, msg_geterr());
	if (o.d.dS != 0 || o.d.pex != 0) {
		record(&p, &rep, in);
		msg_info(1, "S %.6g -> %.6g; K %.6g Pa (%s), eps_kk %.6g; effective stress %.6g -> %.6g Pa (drop %.6g, alpha_b p_ex %.6g); total %.6g Pa; residual %.2e",
		    rep.S_before, rep.S_after, rep.K, o.d.pex > 0 ? (rep.K_measured ? "probe" : "given") : "not used", rep.eps_kk,
		    rep.sigma_before, rep.sigma_after, rep.sigma_before - rep.sigma_after, o.d.alpha * o.d.pex,
		    rep.sigma_total_after, rep.after.res_max);
	}
	if (pack_write_tool(&p, &tool, &st))
		msg_die_err(EXIT_DATA);
	pack_free(&p);
	return 0;
}
