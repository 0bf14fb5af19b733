/* SPDX-License-Identifier: GPL-3.0-or-later */
/* packinfo: describe packs as "key value" lines (or one TSV row per pack with --tsv). */
#include "base/cli.h"
#include "base/fileio.h"
#include "analysis/measure.h"
#include "pack/shape.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "pack/packio.h"
#include "base/table.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int tsv;
static double bulk_margin = NAN;	/* NaN: one mean grain diameter (measure_bulk) */

static struct cli_opt opts[] = {
	{"tsv", 't', CLI_FLAG, &tsv, NULL, "one header line and one row per pack, for scripts", NULL},
	{"bulk-margin", 0, CLI_DOUBLE, &bulk_margin, "M",
	    "the bulk keys: the box less M from each wall (default: one mean grain diameter)", "m"},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"packinfo", "[options] [FILE...]",
	"Report porosity, coordination, rattlers, radii, overlaps, stresses, residual, sliding ratio and fabric of packs (of plates: shape and nematic order).",
	opts, 1 << 20,
};

#define NKEYS 96

struct row {
	struct table_col col[NKEYS];
	double v[NKEYS];
	int n;
};

static void
add(struct row *r, const char *name, const char *unit, double v)
{
	assert(r->n < NKEYS);
	r->col[r->n].name = name;
	r->col[r->n].unit = unit;
	r->v[r->n++] = v;
}

/* The hydrate keys, right after the porosities of either report: always in the key set (NaN
 * without the phase column: left out of the key list, nan in --tsv), so that every --tsv row
 * has the header's columns whatever packs the stream mixes. */
static void
add_hydrate(const struct pack *p, struct row *r)
{
	struct hydrate_measures h;

	measure_hydrate(p, &h);
	add(r, "hydrate_grains", NULL, h.grains);
	add(r, "hydrate_volume_fraction", NULL, h.volume_fraction);
	add(r, "hydrate_saturation", NULL, h.saturation);
	add(r, "porosity_hydrate_as_pore", NULL, h.porosity_hydrate_as_pore);
}

static void
fill_row(const struct pack *p, const struct pack_measures *m, struct row *r)
{
	r->n = 0;
	add(r, "grains", NULL, (double)m->grains);
	add(r, "lx", "m", pack_box_length(p->box, 0));
	add(r, "ly", "m", pack_box_length(p->box, 1));
	add(r, "lz", "m", pack_box_length(p->box, 2));
	add(r, "porosity", NULL, m->porosity);
	add(r, "bulk_porosity", NULL, m->bulk_porosity);
	add_hydrate(p, r);
	add(r, "coordination", NULL, m->coordination);
	/* the bulk's keys are absent (NaN) together when the margin leaves no inner box */
	add(r, "bulk_coordination", NULL, m->bulk_coordination);
	add(r, "bulk_grains", NULL, m->has_bulk ? (double)m->bulk_grains : NAN);
	add(r, "bulk_margin", "m", m->has_bulk ? m->bulk_margin : NAN);
	add(r, "coordination_nr", NULL, m->coordination_nr);
	add(r, "contacts_gg", NULL, (double)m->contacts_gg);
	add(r, "contacts_gw", NULL, (double)m->contacts_gw);
	add(r, "under4", NULL, (double)m->under4);
	add(r, "rattlers", NULL, (double)m->rattlers);
	add(r, "rattler_min_contacts", NULL, (double)m->rattler_min_contacts);
	add(r, "r_mean", "m", m->r_mean);
	add(r, "r_std", "m", m->r_std);
	add(r, "r_min", "m", m->r_min);
	add(r, "r_max", "m", m->r_max);
	add(r, "overlap_max", NULL, m->overlap_max);
	add(r, "mu", NULL, p->mu);
	add(r, "history_contacts", NULL, (double)m->history);
	add(r, "stale_history", NULL, (double)m->stale_history);
	add(r, "sig_xx", "Pa", m->has_forces ? m->sig_wall[0] : NAN);
	add(r, "sig_yy", "Pa", m->has_forces ? m->sig_wall[1] : NAN);
	add(r, "sig_zz", "Pa", m->has_forces ? m->sig_wall[2] : NAN);
	add(r, "sigma_c", "Pa", m->has_forces ? m->sigma_c : NAN);
	add(r, "sig_lw_xx", "Pa", m->has_forces ? m->sig_lw[0] : NAN);
	add(r, "sig_lw_yy", "Pa", m->has_forces ? m->sig_lw[1] : NAN);
	add(r, "sig_lw_zz", "Pa", m->has_forces ? m->sig_lw[2] : NAN);
	add(r, "force_mean", "N", m->has_forces ? m->P_mean : NAN);
	add(r, "force_max", "N", m->has_forces ? m->P_max : NAN);
	add(r, "residual", NULL, m->has_forces ? m->residual_max : NAN);
	add(r, "residual_mean", NULL, m->has_forces ? m->residual_mean : NAN);
	add(r, "residual_strict", NULL, m->has_forces ? m->residual_strict : NAN);
	add(r, "residual_median", NULL, m->has_forces ? m->residual_median : NAN);
	{
		/* the increment that wrote the pack recorded its own count (lib/qs/loading.c); the
		 * lines only bound it from below */
		double rec;
		add(r, "sliding_ratio", NULL, pack_get_meta_double(p, "sliding_ratio", &rec) == 0 ? rec : m->sliding_ratio);
		add(r, "sliding_ratio_lines", NULL, m->sliding_ratio);
		/* always added (NaN when not recorded: left out of the key list, nan in --tsv),
		 * so that every --tsv row has the header's columns */
		add(r, "trial_slip_ratio", NULL, pack_get_meta_double(p, "trial_slip_ratio", &rec) == 0 ? rec : NAN);
	}
	add(r, "fabric_xx", NULL, m->fabric[0]);
	add(r, "fabric_yy", NULL, m->fabric[1]);
	add(r, "fabric_zz", NULL, m->fabric[2]);
	add(r, "fabric_xy", NULL, m->fabric[3]);
	add(r, "fabric_xz", NULL, m->fabric[4]);
	add(r, "fabric_yz", NULL, m->fabric[5]);
	add(r, "fabric_anisotropy", NULL, m->fabric_anisotropy);
}

/* A pack with spheroplates: measure_plates, the shapes and the interactions (measure.h);
 * keys that mean the same as a sphere pack's keep their names, the others are the plates'
 * own (packinfo.1 lists them). */
static void
fill_plate_row(const struct pack *p, const struct plate_measures *m, struct row *r)
{
	r->n = 0;
	add(r, "grains", NULL, (double)m->grains);
	add(r, "plates", NULL, (double)m->plates);
	add(r, "lx", "m", pack_box_length(p->box, 0));
	add(r, "ly", "m", pack_box_length(p->box, 1));
	add(r, "lz", "m", pack_box_length(p->box, 2));
	add(r, "porosity", NULL, m->porosity);
	add(r, "packing_fraction", NULL, m->packing_fraction);
	add_hydrate(p, r);
	add(r, "r_mean", "m", m->r_mean);
	add(r, "r_std", "m", m->r_std);
	add(r, "r_min", "m", m->r_min);
	add(r, "r_max", "m", m->r_max);
	add(r, "side_mean", "m", m->side_mean);
	add(r, "side_std", "m", m->side_std);
	add(r, "side_min", "m", m->side_min);
	add(r, "side_max", "m", m->side_max);
	add(r, "platyness", NULL, m->eta_mean);
	add(r, "platyness_min", NULL, m->eta_min);
	add(r, "platyness_max", NULL, m->eta_max);
	add(r, "aspect_ratio", NULL, m->aspect_mean);
	add(r, "aspect_ratio_min", NULL, m->aspect_min);
	add(r, "aspect_ratio_max", NULL, m->aspect_max);
	add(r, "nematic_order", NULL, m->nematic);
	add(r, "director_x", NULL, m->director[0]);
	add(r, "director_y", NULL, m->director[1]);
	add(r, "director_z", NULL, m->director[2]);
	add(r, "coordination", NULL, m->coordination);
	add(r, "contacts_gg", NULL, (double)m->contacts_gg);
	add(r, "contacts_gw", NULL, (double)m->contacts_gw);
	add(r, "floating", NULL, (double)m->floating);
	add(r, "floating_fraction", NULL, m->floating_fraction);
	add(r, "elements", NULL, (double)m->elements);
	add(r, "elements_per_interaction", NULL, m->elements_per_interaction);
	add(r, "interactions_m1", NULL, (double)m->by_elements[0]);
	add(r, "interactions_m2", NULL, (double)m->by_elements[1]);
	add(r, "interactions_m3", NULL, (double)m->by_elements[2]);
	add(r, "mu", NULL, p->mu);
	add(r, "history_contacts", NULL, (double)p->nc);
	add(r, "sig_xx", "Pa", m->sig_wall[0]);
	add(r, "sig_yy", "Pa", m->sig_wall[1]);
	add(r, "sig_zz", "Pa", m->sig_wall[2]);
	add(r, "sig_lw_xx", "Pa", m->sig_lw[0]);
	add(r, "sig_lw_yy", "Pa", m->sig_lw[1]);
	add(r, "sig_lw_zz", "Pa", m->sig_lw[2]);
	add(r, "sig_lw_xy", "Pa", m->sig_lw[3]);
	add(r, "sig_lw_xz", "Pa", m->sig_lw[4]);
	add(r, "sig_lw_yz", "Pa", m->sig_lw[5]);
	add(r, "force_mean", "N", m->force_mean);
	add(r, "force_max", "N", m->force_max);
	add(r, "residual_mean", NULL, m->residual_mean);
	add(r, "qp", NULL, m->fabric.qp);
	add(r, "theta_sigma", "deg", m->fabric.theta_sigma);
	add(r, "a_m", NULL, m->fabric.a_m);
	add(r, "theta_m", "deg", m->fabric.theta_m);
	add(r, "a_n", NULL, m->fabric.a_n);
	add(r, "theta_n", "deg", m->fabric.theta_n);
	add(r, "a_ln", NULL, m->fabric.a_ln);
	add(r, "theta_ln", "deg", m->fabric.theta_ln);
	add(r, "a_lt", NULL, m->fabric.a_lt);
	add(r, "theta_lt", "deg", m->fabric.theta_lt);
	add(r, "a_fn", NULL, m->fabric.a_fn);
	add(r, "theta_fn", "deg", m->fabric.theta_fn);
	add(r, "a_ft", NULL, m->fabric.a_ft);
	add(r, "theta_ft", "deg", m->fabric.theta_ft);
	add(r, "K_s", NULL, m->fabric.K_s);
	add(r, "qp_harmonic", NULL, m->fabric.qp_harmonic);
	/* the glued wall layers left out (plate_measures), and the descriptors beside the paper's
	 * formulas (analysis/fabric.h) */
	add(r, "glued", NULL, (double)m->glued);
	add(r, "coordination_free", NULL, m->coordination_free);
	add(r, "floating_free", NULL, (double)m->floating_free);
	add(r, "floating_fraction_free", NULL, m->floating_fraction_free);
	add(r, "a_m_3d", NULL, m->fabric.a_m_3d);
	add(r, "M1_M3", NULL, m->fabric.m1_m3);
	add(r, "nematic_S", NULL, m->fabric.nematic_S);
	add(r, "a_lt_direct", NULL, m->fabric.a_lt_direct);
	add(r, "theta_lt_direct", "deg", m->fabric.theta_lt_direct);
	add(r, "a_ft_direct", NULL, m->fabric.a_ft_direct);
	add(r, "theta_ft_direct", "deg", m->fabric.theta_ft_direct);
	add(r, "qp_harmonic_direct", NULL, m->fabric.qp_harmonic_direct);
}

/* One pack's row: spheres as ever (byte for byte), or plates (and packs of the linear law);
 * returns 1 for the plate report. */
static int
measure_row(const struct pack *p, const char *name, struct geo_contacts *gc, struct row *r)
{
	struct pack_measures m;
	struct plate_measures pm;
	enum shape_radius conv;
	int plates = measure_is_plate_pack(p);

	if (plates < 0)
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	/* the sphere report computes Hertz forces: a pack of the plate engine's linear law
	 * (spheres at --platyness 0 too) gets the plate report, whose forces are that law's */
	if (!plates) {
		if (measure_pack(p, gc, &m) || measure_bulk(p, gc, bulk_margin, &m))
			msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
		fill_row(p, &m, r);
		return 0;
	}
	if (pack_plate_radius(p, &conv) || measure_plates(p, conv, &pm))
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	fill_plate_row(p, &pm, r);
	return 1;
}

static void
print_keys(FILE *fp, const struct row *r)
{
	char buf[40];
	int k;

	for (k = 0; k < r->n; k++) {
		if (isnan(r->v[k]))
			continue;	/* absent: nothing to report, no number made up */
		num_format(buf, r->v[k]);
		fprintf(fp, "%s %s\n", r->col[k].name, buf);
	}
}

/* Every usage error before any work: -o writable and none of the inputs (packinfo -o X X
 * replaced its input). */
static void
check_args(const struct cli_state *st)
{
	int f;

	if (bulk_margin < 0)
		cli_usage_error("--bulk-margin: must be >= 0 (a length in m; 0: the box itself)");
	for (f = 0; f < st->noperands; f++) {
		struct file_role fr[] = {{st->output ? st->output : "-", "-o", 1}, {st->operands[f], "an input", 0}};
		if (file_roles_check(fr, 2)) {
			cli_usage_error("%s", msg_geterr());
			break;
		}
	}
	if (st->noperands == 0) {
		struct file_role fr = {st->output ? st->output : "-", "-o", 1};
		if (file_roles_check(&fr, 1))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
}

/* count: the packs before this one, in all the inputs; *first_plates is set by the first. */
static void
put_row(FILE *mem, const struct row *row, int plates, int count, int *first_plates, const char *name)
{
	if (tsv) {
		/* one header, so one kind: plate rows have other columns */
		if (count == 0) {
			table_header_text(mem, row->col, row->n, "file");
			*first_plates = plates;
		} else if (plates != *first_plates) {
			msg_die(EXIT_DATA, "%s: --tsv: pack %d has %s, the first %s: one table holds one kind of pack",
			    name, count + 1, plates ? "spheroplates" : "spheres only", plates ? "spheres only" : "spheroplates");
		}
		table_row_text(mem, row->v, row->n, name);
	} else {
		if (count > 0)
			fputc('\n', mem);
		print_keys(mem, row);
	}
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct file_out out;
	struct pack_reader *rd;
	struct geo_contacts gc;
	struct pack p;
	struct row row;
	const char *name;
	char *text = NULL;
	size_t textlen = 0;
	FILE *in, *mem;
	int r, f, count = 0, plates, first_plates = 0;

	msg_init(argv[0]);
	cli_parse(&tool, argc, argv, &st);
	check_args(&st);
	/* Everything is formatted in memory first: a bad pack later in the stream (or in a later
	 * FILE) must not leave the rows of the earlier ones behind. */
	if (!(mem = open_memstream(&text, &textlen)))
		msg_die(EXIT_DATA, "out of memory");
	contacts_init(&gc);
	/* each FILE in turn (none: standard input), every pack of each */
	for (f = 0; f < (st.noperands > 0 ? st.noperands : 1); f++) {
		int here = 0;

		if (!(in = file_in_open(st.noperands > 0 ? st.operands[f] : NULL, &name)) ||
		    !(rd = pack_reader_open(in, name)))
			msg_die_err(EXIT_DATA);
		while ((r = pack_read_next(rd, &p)) == 1) {
			plates = measure_row(&p, name, &gc, &row);
			put_row(mem, &row, plates, count, &first_plates, name);
			pack_free(&p);
			count++;
			here++;
		}
		if (r < 0)
			msg_die_err(EXIT_DATA);
		if (here == 0)
			msg_die(EXIT_DATA, "%s:1: empty input", name);
		pack_reader_close(rd);
		if (in != stdin)
			fclose(in);
	}
	contacts_free(&gc);
	fclose(mem);
	if (file_out_open(&out, st.output))
		msg_die_err(EXIT_DATA);
	fwrite(text, 1, textlen, out.fp);
	free(text);
	if (file_out_commit(&out))
		msg_die_err(EXIT_DATA);
	return 0;
}
