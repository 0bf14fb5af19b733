/* SPDX-License-Identifier: GPL-3.0-or-later */
/* export: VTK, LAMMPS and YADE writers and the "x y z r" reader (see export.h). */
#include "analysis/export.h"
#include "analysis/measure.h"
#include "contact/contacts.h"
#include "base/lines.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "base/quat.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Print v with num_format, then the separator. */
static void
put_num(FILE *fp, double v, int sep)
{
	char buf[40];

	num_format(buf, v);
	fputs(buf, fp);
	fputc(sep, fp);
}

/* n numbers separated by sep, then a newline */
static void
put_nums_sep(FILE *fp, const double *v, int n, int sep)
{
	int k;

	for (k = 0; k < n; k++)
		put_num(fp, v[k], k + 1 < n ? sep : '\n');
}

static void
put_nums(FILE *fp, const double *v, int n)
{
	put_nums_sep(fp, v, n, ' ');
}

/* The writers print without checking each call; the stream's error flag, checked once at
 * the end, catches every failed write. */
static int
finish(FILE *fp)
{
	if (fflush(fp) != 0 || ferror(fp)) {
		msg_seterr("write error");
		return -1;
	}
	return 0;
}

/* VTK XML, ascii (OVITO refuses the appended raw encoding).  File version 1.0: cell
 * offsets are the end of each cell, as every VTK and ParaView release reads them, and a
 * .vtm of version 0.1 would be read with the old group/dataset layout, as nothing. */
static void
vtk_open(FILE *fp, const char *type)
{
	fprintf(fp, "<?xml version=\"1.0\"?>\n"
	    "<VTKFile type=\"%s\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
	    type);
}

static void
vtk_array_open(FILE *fp, const char *type, const char *name, int ncomp)
{
	fprintf(fp, "<DataArray type=\"%s\"", type);
	if (name)
		fprintf(fp, " Name=\"%s\"", name);
	if (ncomp > 1)
		fprintf(fp, " NumberOfComponents=\"%d\"", ncomp);
	fputs(" format=\"ascii\">\n", fp);
}

static void
vtk_array_doubles(FILE *fp, const char *name, const double *v, size_t n)
{
	size_t k;

	vtk_array_open(fp, "Float64", name, 1);
	for (k = 0; k < n; k++)
		put_num(fp, v[k], '\n');
	fputs("</DataArray>\n", fp);
}

/* connectivity 0 1 2 ... and offsets k, 2k, 3k ...: n cells of k consecutive points. */
static void
vtk_cells(FILE *fp, const char *kind, size_t n, int k)
{
	size_t c;

	fprintf(fp, "<%s>\n", kind);
	vtk_array_open(fp, "Int64", "connectivity", 1);
	for (c = 0; c < n * (size_t)k; c++)
		fprintf(fp, "%zu\n", c);
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Int64", "offsets", 1);
	for (c = 1; c <= n; c++)
		fprintf(fp, "%zu\n", c * (size_t)k);
	fprintf(fp, "</DataArray>\n</%s>\n", kind);
}

static void
vtk_piece_open(FILE *fp, size_t npoints, size_t nverts, size_t nlines, size_t npolys)
{
	fprintf(fp, "<PolyData>\n<Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"%zu\" "
	    "NumberOfLines=\"%zu\" NumberOfStrips=\"0\" NumberOfPolys=\"%zu\">\n",
	    npoints, nverts, nlines, npolys);
}

static void
vtk_close(FILE *fp)
{
	fputs("</Piece>\n</PolyData>\n</VTKFile>\n", fp);
}

int
export_vtp_grains(const struct pack *p, FILE *fp)
{
	size_t i;

	vtk_open(fp, "PolyData");
	vtk_piece_open(fp, p->n, p->n, 0, 0);
	fputs("<PointData Scalars=\"radius\">\n", fp);
	vtk_array_open(fp, "Int64", "id", 1);
	for (i = 0; i < p->n; i++)
		fprintf(fp, "%ld\n", p->id[i]);
	fputs("</DataArray>\n", fp);
	vtk_array_doubles(fp, "radius", p->r, p->n);
	vtk_array_doubles(fp, "E", p->E, p->n);
	vtk_array_doubles(fp, "nu", p->nu, p->n);
	if (p->has_phase) {
		vtk_array_open(fp, "Int32", "phase", 1);
		for (i = 0; i < p->n; i++)
			fprintf(fp, "%d\n", p->phase[i]);
		fputs("</DataArray>\n", fp);
	}
	fputs("</PointData>\n<Points>\n", fp);
	vtk_array_open(fp, "Float64", "Points", 3);
	for (i = 0; i < p->n; i++)
		put_nums(fp, p->x + 3 * i, 3);
	fputs("</DataArray>\n</Points>\n", fp);
	vtk_cells(fp, "Verts", p->n, 1);
	vtk_close(fp);
	return finish(fp);
}

/* The six faces of a box whose corner k (0..7) is at (+-a, +-a, +-c) with bit 0 of k the sign
 * of x, bit 1 of y and bit 2 of z: each face counter-clockwise seen from outside, so that its
 * normal by the right-hand rule points out (ParaView lights and culls by it). */
static const int box_faces[6][4] = {
	{0, 2, 3, 1}, {4, 5, 7, 6},	/* z = -c, z = +c: the plate's faces */
	{0, 1, 5, 4}, {2, 6, 7, 3},	/* y = -a, y = +a */
	{0, 4, 6, 2}, {1, 3, 7, 5},	/* x = -a, x = +a */
};

/* The cell arrays of the plates file: one value per grain, repeated over its six faces. */
static void
vtk_cell_doubles(FILE *fp, const char *name, const double *v, size_t n, int ncomp)
{
	size_t i;
	int f;

	vtk_array_open(fp, "Float64", name, ncomp);
	for (i = 0; i < n; i++)
		for (f = 0; f < 6; f++)
			put_nums(fp, v + (size_t)ncomp * i, ncomp);
	fputs("</DataArray>\n", fp);
}

/* R(q) of grain i; the identity for a pack without shape columns. */
static void
grain_rotation(const struct pack *p, size_t i, double R[9])
{
	static const double one[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

	if (p->has_shapes)
		quat_to_matrix(p->q + 4 * i, R);
	else
		memcpy(R, one, sizeof one);
}

int
export_vtp_plates(const struct pack *p, FILE *fp)
{
	double *nrm = malloc(3 * (p->n ? p->n : 1) * sizeof *nrm), *side = malloc((p->n ? p->n : 1) * sizeof *side);
	double R[9], b[3], x[3];
	size_t i;
	int k, f, a;

	if (!nrm || !side) {
		free(nrm), free(side);
		msg_seterr("out of memory");
		return -1;
	}
	for (i = 0; i < p->n; i++) {
		side[i] = p->has_shapes ? p->side[i] : 0;
		grain_rotation(p, i, R);
		nrm[3 * i] = R[2], nrm[3 * i + 1] = R[5], nrm[3 * i + 2] = R[8];
	}
	vtk_open(fp, "PolyData");
	vtk_piece_open(fp, 8 * p->n, 0, 0, 6 * p->n);
	fputs("<CellData Scalars=\"side\">\n", fp);
	vtk_array_open(fp, "Int64", "id", 1);
	for (i = 0; i < p->n; i++)
		for (f = 0; f < 6; f++)
			fprintf(fp, "%ld\n", p->id[i]);
	fputs("</DataArray>\n", fp);
	vtk_cell_doubles(fp, "side", side, p->n, 1);
	vtk_cell_doubles(fp, "radius", p->r, p->n, 1);
	vtk_cell_doubles(fp, "E", p->E, p->n, 1);
	vtk_cell_doubles(fp, "nu", p->nu, p->n, 1);
	vtk_cell_doubles(fp, "normal", nrm, p->n, 3);
	if (p->has_phase) {
		vtk_array_open(fp, "Int32", "phase", 1);
		for (i = 0; i < p->n; i++)
			for (f = 0; f < 6; f++)
				fprintf(fp, "%d\n", p->phase[i]);
		fputs("</DataArray>\n", fp);
	}
	if (p->has_glue) {	/* 0 free, 1 + w glued to wall w */
		vtk_array_open(fp, "Int32", "glued", 1);
		for (i = 0; i < p->n; i++)
			for (f = 0; f < 6; f++)
				fprintf(fp, "%d\n", p->glue[i]);
		fputs("</DataArray>\n", fp);
	}
	fputs("</CellData>\n<Points>\n", fp);
	vtk_array_open(fp, "Float64", "Points", 3);
	for (i = 0; i < p->n; i++) {
		double half[3];

		shape_of(pack_grain_shape(p, i))->extent(p->r[i], side[i], half);
		grain_rotation(p, i, R);
		for (k = 0; k < 8; k++) {
			b[0] = k & 1 ? half[0] : -half[0];
			b[1] = k & 2 ? half[1] : -half[1];
			b[2] = k & 4 ? half[2] : -half[2];
			for (a = 0; a < 3; a++)
				x[a] = p->x[3 * i + a] + R[3 * a] * b[0] + R[3 * a + 1] * b[1] + R[3 * a + 2] * b[2];
			put_nums(fp, x, 3);
		}
	}
	fputs("</DataArray>\n</Points>\n<Polys>\n", fp);
	vtk_array_open(fp, "Int64", "connectivity", 1);
	for (i = 0; i < p->n; i++)
		for (f = 0; f < 6; f++)
			fprintf(fp, "%zu %zu %zu %zu\n", 8 * i + (size_t)box_faces[f][0], 8 * i + (size_t)box_faces[f][1],
			    8 * i + (size_t)box_faces[f][2], 8 * i + (size_t)box_faces[f][3]);
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Int64", "offsets", 1);
	for (i = 1; i <= 6 * p->n; i++)
		fprintf(fp, "%zu\n", 4 * i);
	fputs("</DataArray>\n</Polys>\n", fp);
	vtk_close(fp);
	free(nrm);
	free(side);
	return finish(fp);
}

/* The far end of contact c: centre j, or the foot of the perpendicular from centre i on
 * the wall (c->n points out of the wall, c->d is the centre's distance to it). */
static void
contact_end(const struct pack *p, const struct geo_contact *c, double e[3])
{
	int a;

	for (a = 0; a < 3; a++)
		e[a] = PACK_IS_WALL(c->j) ? p->x[3 * c->i + a] - c->d * c->n[a] :
		    p->x[3 * (size_t)c->j + a];
}

int
export_vtp_contacts(const struct pack *p, FILE *fp)
{
	struct geo_contacts gc;
	size_t k;
	double e[3];

	contacts_init(&gc);
	if (contacts_find(p, &gc)) {
		contacts_free(&gc);
		return -1;
	}
	vtk_open(fp, "PolyData");
	vtk_piece_open(fp, 2 * gc.n, 0, gc.n, 0);
	fputs("<CellData Scalars=\"normal_force\">\n", fp);
	vtk_array_open(fp, "Int64", "id1", 1);
	for (k = 0; k < gc.n; k++)
		fprintf(fp, "%ld\n", p->id[gc.c[k].i]);
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Int64", "id2", 1);
	for (k = 0; k < gc.n; k++)
		fprintf(fp, "%ld\n", PACK_IS_WALL(gc.c[k].j) ?
		    EXPORT_VTK_WALL_ID(PACK_WALL_INDEX(gc.c[k].j)) : p->id[gc.c[k].j]);
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Float64", "normal_force", 1);
	for (k = 0; k < gc.n; k++)
		put_num(fp, gc.c[k].P, '\n');
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Float64", "overlap", 1);
	for (k = 0; k < gc.n; k++)
		put_num(fp, gc.c[k].h, '\n');
	fputs("</DataArray>\n</CellData>\n<Points>\n", fp);
	vtk_array_open(fp, "Float64", "Points", 3);
	for (k = 0; k < gc.n; k++) {
		put_nums(fp, p->x + 3 * gc.c[k].i, 3);
		contact_end(p, &gc.c[k], e);
		put_nums(fp, e, 3);
	}
	fputs("</DataArray>\n</Points>\n", fp);
	vtk_cells(fp, "Lines", gc.n, 2);
	vtk_close(fp);
	contacts_free(&gc);
	return finish(fp);
}

int
export_vtp_plate_contacts(const struct pack *p, FILE *fp)
{
	struct plate_contact *c;
	size_t n, k;
	double v[3];
	int a, forces;

	if (measure_plate_contact_list(p, &c, &n))
		return -1;
	forces = n > 0 && !isnan(c[0].P);
	vtk_open(fp, "PolyData");
	vtk_piece_open(fp, 2 * n, 0, n, 0);
	fprintf(fp, "<CellData Scalars=\"%s\">\n", forces ? "normal_force" : "overlap");
	vtk_array_open(fp, "Int64", "id1", 1);
	for (k = 0; k < n; k++)
		fprintf(fp, "%ld\n", p->id[c[k].i]);
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Int64", "id2", 1);
	for (k = 0; k < n; k++)
		fprintf(fp, "%ld\n", PACK_IS_WALL(c[k].j) ? EXPORT_VTK_WALL_ID(PACK_WALL_INDEX(c[k].j)) : p->id[c[k].j]);
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Float64", "normal", 3);
	for (k = 0; k < n; k++)
		put_nums(fp, c[k].n, 3);
	fputs("</DataArray>\n", fp);
	if (forces) {
		vtk_array_open(fp, "Float64", "normal_force", 1);
		for (k = 0; k < n; k++)
			put_num(fp, c[k].P, '\n');
		fputs("</DataArray>\n", fp);
		vtk_array_open(fp, "Float64", "tangential_force", 3);
		for (k = 0; k < n; k++)
			put_nums(fp, c[k].Q, 3);
		fputs("</DataArray>\n", fp);
		vtk_array_open(fp, "Float64", "tangential_force_magnitude", 1);
		for (k = 0; k < n; k++)
			put_num(fp, sqrt(c[k].Q[0] * c[k].Q[0] + c[k].Q[1] * c[k].Q[1] + c[k].Q[2] * c[k].Q[2]), '\n');
		fputs("</DataArray>\n", fp);
		vtk_array_open(fp, "Float64", "force", 3);
		for (k = 0; k < n; k++) {
			for (a = 0; a < 3; a++)
				v[a] = c[k].P * c[k].n[a] + c[k].Q[a];
			put_nums(fp, v, 3);
		}
		fputs("</DataArray>\n", fp);
	}
	vtk_array_open(fp, "Float64", "overlap", 1);
	for (k = 0; k < n; k++)
		put_num(fp, c[k].overlap, '\n');
	fputs("</DataArray>\n", fp);
	vtk_array_open(fp, "Int32", "elements", 1);
	for (k = 0; k < n; k++)
		fprintf(fp, "%d\n", c[k].elements);
	fputs("</DataArray>\n</CellData>\n<Points>\n", fp);
	vtk_array_open(fp, "Float64", "Points", 3);
	for (k = 0; k < n; k++) {
		put_nums(fp, c[k].a, 3);
		put_nums(fp, c[k].b, 3);
	}
	fputs("</DataArray>\n</Points>\n", fp);
	vtk_cells(fp, "Lines", n, 2);
	vtk_close(fp);
	free(c);
	return finish(fp);
}

int
export_tsv_grains(const struct pack *p, FILE *fp)
{
	struct geo_contacts gc;
	size_t i, k, *nc = NULL;
	double v[7], R[9];
	/* sphere contacts only: the plates' interactions are the plate engine's (not in lib/
	 * for a pack at rest), so a pack with plates gets side and normal instead */
	int plates = pack_first_plate(p) != (size_t)-1;

	contacts_init(&gc);
	if (!plates) {
		if (contacts_find(p, &gc)) {
			contacts_free(&gc);
			return -1;
		}
		if (!(nc = calloc(p->n ? p->n : 1, sizeof *nc))) {
			contacts_free(&gc);
			msg_seterr("out of memory");
			return -1;
		}
		for (k = 0; k < gc.n; k++) {
			nc[gc.c[k].i]++;
			if (!PACK_IS_WALL(gc.c[k].j))
				nc[gc.c[k].j]++;
		}
	}
	fprintf(fp, "# id\tx[m]\ty[m]\tz[m]\tr[m]\tE[Pa]\tnu\trho[kg/m^3]%s%s\n", p->has_phase ? "\tphase" : "",
	    plates ? "\tside[m]\tnx\tny\tnz" : "\tcontacts");
	for (i = 0; i < p->n; i++) {
		fprintf(fp, "%ld\t", p->id[i]);
		memcpy(v, p->x + 3 * i, 3 * sizeof *v);
		v[3] = p->r[i], v[4] = p->E[i], v[5] = p->nu[i], v[6] = p->rho[i];
		for (k = 0; k < 7; k++)
			put_num(fp, v[k], '\t');
		if (p->has_phase)
			fprintf(fp, "%d\t", p->phase[i]);
		if (plates) {	/* the face normal R(q) e3 */
			grain_rotation(p, i, R);
			v[0] = p->side[i], v[1] = R[2], v[2] = R[5], v[3] = R[8];
			put_nums_sep(fp, v, 4, '\t');
		} else {
			fprintf(fp, "%zu\n", nc[i]);
		}
	}
	free(nc);
	contacts_free(&gc);
	return finish(fp);
}

int
export_tsv_contacts(const struct pack *p, FILE *fp)
{
	struct geo_contacts gc;
	size_t k;
	double v[8];
	int a;

	contacts_init(&gc);
	if (contacts_find(p, &gc)) {
		contacts_free(&gc);
		return -1;
	}
	fputs("# id1\tid2\tx1[m]\ty1[m]\tz1[m]\tx2[m]\ty2[m]\tz2[m]\tnormal_force[N]\toverlap[m]\n", fp);
	for (k = 0; k < gc.n; k++) {
		const struct geo_contact *c = &gc.c[k];

		fprintf(fp, "%ld\t%ld\t", p->id[c->i], PACK_IS_WALL(c->j) ? EXPORT_VTK_WALL_ID(PACK_WALL_INDEX(c->j)) : p->id[c->j]);
		/* the other end from grain 1 along the normal: right across a periodic boundary */
		for (a = 0; a < 3; a++) {
			v[a] = p->x[3 * c->i + a];
			v[3 + a] = v[a] - c->d * c->n[a];
		}
		v[6] = c->P, v[7] = c->h;
		put_nums_sep(fp, v, 8, '\t');
	}
	contacts_free(&gc);
	return finish(fp);
}

/* File names go into an attribute: escape what XML would misread. */
static void
put_xml_attr(FILE *fp, const char *s)
{
	for (; *s; s++)
		switch (*s) {
		case '&':
			fputs("&amp;", fp);
			break;
		case '<':
			fputs("&lt;", fp);
			break;
		case '>':
			fputs("&gt;", fp);
			break;
		case '"':
			fputs("&quot;", fp);
			break;
		default:
			fputc(*s, fp);
		}
}

int
export_vtm(FILE *fp, const char *grains_vtp, const char *contacts_vtp)
{
	vtk_open(fp, "vtkMultiBlockDataSet");
	fputs("<vtkMultiBlockDataSet>\n<DataSet index=\"0\" name=\"grains\" file=\"", fp);
	put_xml_attr(fp, grains_vtp);
	fputs("\"/>\n<DataSet index=\"1\" name=\"contacts\" file=\"", fp);
	put_xml_attr(fp, contacts_vtp);
	fputs("\"/>\n</vtkMultiBlockDataSet>\n</VTKFile>\n", fp);
	return finish(fp);
}

static int
lammps_check_ids(const struct pack *p)
{
	size_t i;

	for (i = 0; i < p->n; i++)
		if (p->id[i] < 1) {
			msg_seterr("grain id %ld: LAMMPS atom ids must be positive", p->id[i]);
			return -1;
		}
	return 0;
}

static void
lammps_bounds(FILE *fp, const struct pack *p, const char *suffix)
{
	int a;

	for (a = 0; a < 3; a++) {
		put_num(fp, p->box[a], ' ');
		put_num(fp, p->box[a + 3], *suffix ? ' ' : '\n');
		if (*suffix)
			fprintf(fp, "%clo %chi\n", 'x' + a, 'x' + a);
	}
}

int
export_lammps_dump(const struct pack *p, FILE *fp, long timestep)
{
	int plates = pack_first_plate(p) != (size_t)-1;
	size_t i;
	double v[10], half[3];
	const struct shape_ops *sh;

	if (lammps_check_ids(p))
		return -1;
	fprintf(fp, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ATOMS\n%zu\nITEM: BOX BOUNDS ff ff ff\n",
	    timestep, p->n);
	lammps_bounds(fp, p, "");
	fputs(plates ? "ITEM: ATOMS id type x y z quatw quati quatj quatk shapex shapey shapez\n" :
	    "ITEM: ATOMS id type x y z radius\n", fp);
	for (i = 0; i < p->n; i++) {
		memcpy(v, p->x + 3 * i, 3 * sizeof *v);
		if (!plates) {
			v[3] = p->r[i];
			fprintf(fp, "%ld %d ", p->id[i], 1 + pack_grain_phase(p, i));
			put_nums(fp, v, 4);
			continue;
		}
		/* LAMMPS's quaternion (w, i, j, k) turns the body frame into the lab frame, as
		 * ours does; shape is the full extent along each body axis, as LAMMPS writes
		 * shapex (a diameter): twice the shape's extent.  Its type is the shape's
		 * (struct shape_ops's lammps_type: 2 marks a sphere, for OVITO's per-type shape). */
		sh = shape_of(pack_grain_shape(p, i));
		memcpy(v + 3, p->q + 4 * i, 4 * sizeof *v);
		sh->extent(p->r[i], p->side[i], half);
		v[7] = 2 * half[0], v[8] = 2 * half[1], v[9] = 2 * half[2];
		fprintf(fp, "%ld %d ", p->id[i], sh->lammps_type + 2 * pack_grain_phase(p, i));
		put_nums(fp, v, 10);
	}
	return finish(fp);
}

int
export_lammps_data(const struct pack *p, FILE *fp)
{
	size_t i;
	double v[5];

	if (lammps_check_ids(p))
		return -1;
	/* LAMMPS skips the first line; the rest is its header grammar, then the section. */
	fprintf(fp, "LAMMPS data file: qusgm pack, atom_style sphere, SI units\n\n"
	    "%zu atoms\n%d atom types\n\n", p->n, p->has_phase ? 2 : 1);
	lammps_bounds(fp, p, "lohi");
	fputs("\nAtoms # sphere\n\n", fp);
	for (i = 0; i < p->n; i++) {
		v[0] = 2 * p->r[i];
		v[1] = p->rho[i];
		memcpy(v + 2, p->x + 3 * i, 3 * sizeof *v);
		fprintf(fp, "%ld %d ", p->id[i], 1 + pack_grain_phase(p, i));
		put_nums(fp, v, 5);
	}
	return finish(fp);
}

int
export_xyzr(const struct pack *p, FILE *fp, int periodic)
{
	size_t i;
	double v[4];
	int a;

	if (periodic) {
		fputs("##PERIODIC:: ", fp);
		for (a = 0; a < 3; a++)
			put_num(fp, pack_box_length(p->box, a), a < 2 ? ' ' : '\n');
	}
	for (i = 0; i < p->n; i++) {
		memcpy(v, p->x + 3 * i, 3 * sizeof *v);
		v[3] = p->r[i];
		put_nums(fp, v, 4);
	}
	return finish(fp);
}

/* The "x y z r" reader, on base/lines (plain and gzip input share one path). */
static int
in_sphere(struct lines *in, char *s, const double *box, struct pack *p)
{
	char *tok[4];
	double v[4];
	int n, k;

	n = lines_split(s, " \t", tok, 4);
	if (n != 4)
		return lines_error(in, "expected 4 columns (x y z r), found %d", n);
	for (k = 0; k < 4; k++)
		if (num_parse(tok[k], &v[k]))
			return lines_error(in, "'%s' is not a finite number", tok[k]);
	if (!(v[3] > 0))
		return lines_error(in, "radius %s is not positive", tok[3]);
	if (box)
		for (k = 0; k < 3; k++)
			if (v[k] < box[k] || v[k] > box[k + 3]) {
				char lo[40], hi[40];
				num_format(lo, box[k]);
				num_format(hi, box[k + 3]);
				return lines_error(in, "centre %c = %s is outside the box [%s, %s]", 'x' + k, tok[k],
				    lo, hi);
			}
	if (pack_add_grain(p, (long)p->n + 1, v, v[3], 0, 0, 0) == (size_t)-1)
		return lines_error(in, "out of memory");
	return 0;
}

static void
fit_box(struct pack *p)
{
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		p->box[a] = p->x[a] - p->r[0];
		p->box[a + 3] = p->x[a] + p->r[0];
	}
	for (i = 1; i < p->n; i++)
		for (a = 0; a < 3; a++) {
			double x = p->x[3 * i + a], r = p->r[i];
			if (x - r < p->box[a])
				p->box[a] = x - r;
			if (x + r > p->box[a + 3])
				p->box[a + 3] = x + r;
		}
	/* x - r rounds: a sphere that touches a wall would overlap it by an ulp and make a
	 * contact that is not there.  Move each wall out until h = r - d <= 0 holds exactly as
	 * contacts_find computes it. */
	for (i = 0; i < p->n; i++)
		for (a = 0; a < 3; a++) {
			double x = p->x[3 * i + a], r = p->r[i];
			while (r - (x - p->box[a]) > 0)
				p->box[a] = nextafter(p->box[a], -HUGE_VAL);
			while (r - (p->box[a + 3] - x) > 0)
				p->box[a + 3] = nextafter(p->box[a + 3], HUGE_VAL);
		}
}

/* YADE's periodic cell line, "##PERIODIC:: Lx Ly Lz" (SpherePack.save, packexport --xyzr
 * --periodic), its text after the marker in s: 0 with the three lengths in L, or -1. */
static int
cell_line(struct lines *in, char *s, double L[3])
{
	char *tok[4];
	int n = lines_split(s, " \t", tok, 4), k;

	if (n != 3)
		return lines_error(in, "##PERIODIC:: expected 3 cell lengths (Lx Ly Lz), found %d", n);
	for (k = 0; k < 3; k++)
		if (num_parse(tok[k], &L[k]) || !(L[k] > 0))
			return lines_error(in, "##PERIODIC:: cell length '%s' is not a positive number", tok[k]);
	return 0;
}

/* The box of a periodic cell of lengths L, each axis periodic: [0, L] where it holds every
 * centre (YADE's cell starts at the origin); else from the lowest centre, moved down by
 * at most 64 ulps until hi - lo is L exactly and the box holds every centre (packexport
 * writes a box's lengths, not where it starts: so the round trip gives back the same
 * lengths); else, centres spread over more than a period, [0, L] with the centres wrapped
 * into it. */
static void
cell_box(struct pack *p, const double L[3])
{
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		double lo = p->x[a], hi = p->x[a], b;
		int k, wrap[3] = {0, 0, 0};

		for (i = 1; i < p->n; i++) {
			lo = fmin(lo, p->x[3 * i + a]);
			hi = fmax(hi, p->x[3 * i + a]);
		}
		p->periodic[a] = 1;
		p->box[a] = 0;
		p->box[a + 3] = L[a];
		if (lo >= 0 && hi <= L[a])
			continue;
		for (k = 0, b = lo; k < 64; k++, b = nextafter(b, -HUGE_VAL))
			if ((b + L[a]) - b == L[a] && b + L[a] >= hi) {
				p->box[a] = b;
				p->box[a + 3] = b + L[a];
				break;
			}
		if (k < 64)
			continue;
		wrap[a] = 1;
		pack_wrap_centres(p->x, p->n, p->box, p->box + 3, wrap);
	}
}

int
xyzr_read(FILE *fp, const char *name, const double *box, struct pack *p)
{
	struct lines *in;
	char *s;
	double L[3];
	long cell = 0;	/* the line of the ##PERIODIC:: cell, 0 for none */
	int r;

	pack_init(p);
	if (!(in = lines_open(fp, name)))
		return -1;
	while ((r = lines_next(in, &s, NULL)) == 1) {
		s += strspn(s, " \t");
		if (strncmp(s, "##PERIODIC::", 12) == 0) {
			if (cell) {
				r = lines_error(in, "a second ##PERIODIC:: line (the first is line %ld)", cell);
				break;
			}
			if ((r = cell_line(in, s + 12, L)) < 0)
				break;
			cell = lines_lineno(in);
			continue;
		}
		if (*s == 0 || *s == '#')
			continue;	/* blank or comment */
		if ((r = in_sphere(in, s, box, p)) < 0)
			break;
	}
	if (r == 0 && p->n == 0) {
		if (lines_lineno(in) == 0)
			lines_error_at(in, 1, "empty input");
		else
			lines_error_at(in, lines_lineno(in) + 1, "no spheres (only blank and comment lines)");
		r = -1;
	}
	if (r == 0 && cell && box) {
		int a;

		for (a = 0; a < 3; a++)
			if (pack_box_length(box, a) != L[a]) {
				char b1[40], b2[40];
				num_format(b1, L[a]);
				num_format(b2, pack_box_length(box, a));
				r = lines_error_at(in, cell, "##PERIODIC:: cell length %s along %c differs from --box's %s",
				    b1, 'x' + a, b2);
				break;
			}
	}
	lines_close(in);
	if (r < 0) {
		pack_free(p);
		return -1;
	}
	if (box) {
		memcpy(p->box, box, sizeof p->box);
		if (cell)
			p->periodic[0] = p->periodic[1] = p->periodic[2] = 1;
	} else if (cell) {
		cell_box(p, L);
	} else {
		fit_box(p);
	}
	return 0;
}
