/* SPDX-License-Identifier: GPL-3.0-or-later */
/* packexport: write a pack for ParaView/OVITO (VTK), LAMMPS or YADE. */
#include "base/cli.h"
#include "base/fileio.h"
#include "analysis/export.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

static int vtk, lammps, lammps_data, xyzr, periodic, tsv_grains, tsv_contacts;

static struct cli_opt opts[] = {
	{"vtk", 0, CLI_FLAG, &vtk, NULL, "VTK XML PolyData; -o NAME.vtm also writes NAME_grains.vtp and NAME_contacts.vtp, stdout gets the grains .vtp only; plates as closed boxes, their contacts as lines with normal and tangential forces", NULL},
	{"lammps", 0, CLI_FLAG, &lammps, NULL, "LAMMPS dump, one frame per pack of the input; plates with quaternion and shape", NULL},
	{"lammps-data", 0, CLI_FLAG, &lammps_data, NULL, "LAMMPS data file (atom_style sphere; spheres only)", NULL},
	{"xyzr", 0, CLI_FLAG, &xyzr, NULL, "'x y z r' lines, as YADE's SpherePack.load reads them (spheres only)", NULL},
	{"tsv-grains", 0, CLI_FLAG, &tsv_grains, NULL, "a table of the grains: id x y z r E nu rho [phase] contacts (share/doc/tables.md)", NULL},
	{"tsv-contacts", 0, CLI_FLAG, &tsv_contacts, NULL, "a table of the contacts: id1 id2, both ends' coordinates, normal_force, overlap", NULL},
	{"periodic", 0, CLI_FLAG, &periodic, NULL, "with --xyzr: first line '##PERIODIC:: Lx Ly Lz' (box lengths)", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"packexport", "--vtk | --lammps | --lammps-data | --xyzr | --tsv-grains | --tsv-contacts [--periodic] [-o FILE] [FILE]",
	"Write a pack in the formats of ParaView and OVITO (VTK), LAMMPS and YADE; spheroplates for ParaView and OVITO.",
	opts, 1,
};

/* Output is formatted in memory first, so that a failure leaves no partial file or
 * half-written stdout. */
struct text {
	char *s;
	size_t len;
	FILE *fp;
};

static FILE *
text_open(struct text *t)
{
	t->s = NULL;
	t->len = 0;
	if (!(t->fp = open_memstream(&t->s, &t->len)))
		msg_die(EXIT_DATA, "out of memory");
	return t->fp;
}

static void
text_close(struct text *t)
{
	if (fclose(t->fp) != 0)
		msg_die(EXIT_DATA, "out of memory");
}

/* t into out, opened on path (NULL or "-": stdout) and left uncommitted. */
static void
emit_into(struct file_out *out, const char *path, struct text *t)
{
	int bad;

	if (file_out_open(out, path))
		msg_die_err(EXIT_DATA);
	errno = 0;
	bad = fwrite(t->s, 1, t->len, out->fp) != t->len;
	free(t->s);
	t->s = NULL;
	if (bad) {
		int e = errno ? errno : EIO;
		file_out_abort(out);
		errno = e;
		msg_die(EXIT_DATA, "%s: write error:", path ? path : "<stdout>");
	}
}

/* Write t to path (NULL or "-": stdout) atomically; file_out_commit gzips a .gz name. */
static void
emit(const char *path, struct text *t)
{
	struct file_out out;

	emit_into(&out, path, t);
	if (file_out_commit(&out))
		msg_die_err(EXIT_DATA);
}

static int
has_suffix(const char *s, const char *suf)
{
	size_t n = strlen(s), m = strlen(suf);

	return n > m && strcmp(s + n - m, suf) == 0;
}

static const char *
base_name(const char *path)
{
	const char *s = strrchr(path, '/');

	return s ? s + 1 : path;
}

/* The names of the two .vtp files of -o NAME.vtm: NAME_grains.vtp and NAME_contacts.vtp
 * (the caller frees them). */
static void
vtp_names(const char *vtm, char **gname, char **cname)
{
	size_t n = strlen(vtm) - 4;

	*gname = malloc(n + 16);
	*cname = malloc(n + 16);
	if (!*gname || !*cname)
		msg_die(EXIT_DATA, "out of memory");
	snprintf(*gname, n + 16, "%.*s_grains.vtp", (int)n, vtm);
	snprintf(*cname, n + 16, "%.*s_contacts.vtp", (int)n, vtm);
}

/* -o NAME.vtm: the two .vtp files next to it and the .vtm that names them, all three or
 * none (the .vtp of the grains was left behind when the second file failed); the .vtm
 * renamed last, so that it never points at files that are not there. */
static void
write_vtm(const struct pack *p, const char *vtm, const char *name, int plates)
{
	struct text g, c, m;
	struct file_out go, co, mo, *outs[3] = {&go, &co, &mo};
	char *gname, *cname;

	vtp_names(vtm, &gname, &cname);
	if ((plates ? export_vtp_plates(p, text_open(&g)) : export_vtp_grains(p, text_open(&g))) ||
	    (plates ? export_vtp_plate_contacts(p, text_open(&c)) : export_vtp_contacts(p, text_open(&c))) ||
	    export_vtm(text_open(&m), base_name(gname), base_name(cname)))
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	text_close(&g);
	text_close(&c);
	text_close(&m);
	emit_into(&go, gname, &g);
	emit_into(&co, cname, &c);
	emit_into(&mo, vtm, &m);
	if (file_out_commit_all(outs, 3))
		msg_die_err(EXIT_DATA);
	free(gname);
	free(cname);
}

/* Every pack of the stream is a frame, numbered from 0. */
static void
write_lammps_frames(const char *input, struct text *t)
{
	struct pack_reader *rd;
	struct pack p;
	const char *name;
	FILE *in;
	long frame = 0;
	int r;

	if (!(in = file_in_open(input, &name)) || !(rd = pack_reader_open(in, name)))
		msg_die_err(EXIT_DATA);
	text_open(t);
	while ((r = pack_read_next(rd, &p)) == 1) {
		if (export_lammps_dump(&p, t->fp, frame++))
			msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
		pack_free(&p);
	}
	if (r < 0)
		msg_die_err(EXIT_DATA);
	if (frame == 0)
		msg_die(EXIT_DATA, "%s:1: empty input", name);
	pack_reader_close(rd);
	if (in != stdin)
		fclose(in);
	text_close(t);
}

/* Every usage error before any work, the files of a .vtm included. */
static void
check_args(const struct cli_state *st, const char *out)
{
	if ((vtk > 0) + (lammps > 0) + (lammps_data > 0) + (xyzr > 0) + (tsv_grains > 0) + (tsv_contacts > 0) != 1)
		cli_usage_error("give exactly one of --vtk, --lammps, --lammps-data, --xyzr, --tsv-grains, --tsv-contacts");
	if (periodic && !xyzr)
		cli_usage_error("--periodic goes with --xyzr only");
	if (vtk && out && !has_suffix(out, ".vtm") && !has_suffix(out, ".vtp"))
		cli_usage_error("--vtk: the output name must end in .vtm (grains, contacts and the .vtm) or .vtp (grains only)");
	else if (vtk && out && has_suffix(out, ".vtm")) {
		char *gname, *cname;
		vtp_names(out, &gname, &cname);
		{
			struct file_role fr[] = {{out, "-o", 1}, {gname, "the grains' .vtp of -o", 1},
			    {cname, "the contacts' .vtp of -o", 1}, {st->input, "the input", 0}};
			if (file_roles_check(fr, 4))
				cli_usage_error("%s", msg_geterr());
		}
		free(gname);
		free(cname);
	} else {
		struct file_role fr[] = {{st->output, "-o", 1}, {st->input, "the input", 0}};
		if (file_roles_check(fr, 2))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
}

/* The one-file formats, into t (closed here). */
static void
format_one(const struct pack *p, struct text *t, int plates, const char *name)
{
	int r;

	text_open(t);
	if (vtk)
		r = plates ? export_vtp_plates(p, t->fp) : export_vtp_grains(p, t->fp);
	else if (lammps_data)
		r = export_lammps_data(p, t->fp);
	else if (tsv_grains)
		r = export_tsv_grains(p, t->fp);
	else if (tsv_contacts)
		r = export_tsv_contacts(p, t->fp);
	else
		r = export_xyzr(p, t->fp, periodic);
	if (r)
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	text_close(t);
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct pack p;
	struct text t;
	const char *out, *name, *who;
	int plates;

	msg_init(argv[0]);
	cli_parse(&tool, argc, argv, &st);
	out = st.output && strcmp(st.output, "-") != 0 ? st.output : NULL;
	check_args(&st, out);

	if (lammps) {
		write_lammps_frames(st.input, &t);
		emit(out, &t);
		return 0;
	}
	if (pack_read_path(st.input, &p))
		msg_die_err(EXIT_DATA);
	name = file_display_name(st.input);
	plates = pack_first_plate(&p) != (size_t)-1;
	/* what cannot hold a plate: atom_style sphere, YADE's x y z r, and the contacts table
	 * (the .vtm's contacts file of plates is their interactions, export_vtp_plate_contacts) */
	who = lammps_data ? "--lammps-data" : xyzr ? "--xyzr" : tsv_contacts ? "--tsv-contacts" : NULL;
	if (who && pack_require_spheres(&p, who))
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	if (vtk && out && has_suffix(out, ".vtm")) {
		write_vtm(&p, out, name, plates);
		pack_free(&p);
		return 0;
	}
	format_one(&p, &t, plates, name);
	emit(out, &t);
	pack_free(&p);
	return 0;
}
