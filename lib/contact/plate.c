/* SPDX-License-Identifier: GPL-3.0-or-later */
/* plate: the element contacts of spheroplates (see plate.h; physics.md §12).
 *
 * The rules.  Everything is found from two enumerations done once per pair: each vertex of
 * one core against the other square (its clamped projection q, the vertex's closest point
 * there), and each edge of one against each edge of the other (segment closest points).  The
 * cores' distance d is the least of them, or 0 when an edge of one crosses the other square.
 * With the cores apart, n is the unit vector of the closest points (j to i), and the element
 * contacts, each kept when h_k = r_i + r_j - d_k > -gap with d_k = |vertex - q| or the edges'
 * distance, are:
 *   1. a vertex that lies over the other's closed square both along that square's normal
 *      (its foot) and along n (its shadow): always (vertex-face; vertex-edge or vertex-vertex
 *      when q is on the boundary).  These are the corners of a face-face or edge-face
 *      overlap that lie inside the other face.  The foot alone would, on two faces a little
 *      out of parallel, keep a corner of each at nearly one place (each inside the other
 *      along the other's normal); along the one direction n, only one of them is inside.
 *   2. an edge pair whose closest points are both strictly inside, edges not parallel: always
 *      (edge-edge): the crossings, the other corners of such an overlap.
 *   3. a vertex beyond exactly one edge e of the other square (by its foot, or by its shadow
 *      when the foot is inside): only when it ends a line contact, that is when neither of
 *      the vertex's own edges crosses e (rule 2 has that contact at the crossing) and the
 *      vertex's own face does not cover q (q's foot on the vertex's square lies outside it;
 *      otherwise q sits on the boundary of a face overlap whose corners rules 1 and 2 give).
 *      Two parallel edges side by side, coplanar or not, give the two ends of their overlap,
 *      and still two when turned a little; the edge-edge rule leaves parallel edges to this.
 *   4. a vertex beyond a corner of the other square: never; it lies past the end of whatever
 *      overlap it is near, whose ends the other rules give.
 *   5. the closest pair of the cores, if no element is at d yet.  A closest pair with a vertex
 *      is found by rule 1 (its shadow along n falls on the other core) and one between edge
 *      interiors by rule 2, so this adds only corner to corner (rule 1 drops it when the
 *      foot misses the other square) and vertex to edge from outside, and is the guarantee
 *      that the deepest overlap always has its element.
 * Ties (a vertex within PLATE_TOL * half of an edge's line, a parameter within PLATE_TOL of
 * an end, distances within PLATE_TOL times the pair's size) count as on the boundary, so a
 * vertex exactly on an edge or on a vertex is one element; two elements with the same two
 * points (a vertex-vertex pair seen from both sides) are one.  So stacked identical plates
 * give their 4 corners, stacked at 45 degrees the octagon's 8, stacked and shifted the
 * overlap rectangle's 4, crossed edges 1, corner to corner 1.  Rules 3 and 4 are where this
 * departs from "every vertex against its closest point": that one also gives the corners that
 * stick out of a face overlap, twice the count of a slightly shifted stack and 16 for the 45
 * degree one, and jumps by a multiple of k_n for a shift of a rounding error.
 *
 * A sphere (half = 0) is a point core: its one vertex, no edges; two spheres give the exact
 * sphere-sphere element.  When the cores intersect (d within the size tolerance) the closest
 * points say nothing of the normal: libccd's MPR on the two spheroplates gives the depth and
 * direction, as one element.
 *
 * The contact point is p = (pi + pj)/2 + (r_j - r_i)/2 n: halfway between the two surfaces
 * along n, the centre of the lens when pi - pj is along n, and the same point whichever of the
 * two is called i.  Work is done relative to a's centre so that a pair far from the origin
 * (a periodic image) loses no digits. */
#include "contact/plate.h"
#include "base/lanes.h"
#include "base/vec3.h"

#include <ccd/ccd.h>
#include <math.h>
#include <string.h>

#ifndef CCD_DOUBLE
#error "plate.c needs libccd built with CCD_DOUBLE"
#endif

/* Relative tolerance of the ties, and sin^2 of the angle below which edges are parallel:
 * round-off in the coordinates is ~1e-16 of the pair's size, and ill-conditioned segment
 * parameters of nearly parallel edges err by ~1e-16 / sin^2, so edges within 1e-5 rad are
 * parallel.  MPR stops at 1e-8 of the size (it is the fallback, not the rule). */
#define PLATE_TOL 1e-9
#define PLATE_PARALLEL 1e-10
#define PLATE_MPR_TOL 1e-8
#define PLATE_MPR_ITER 200

enum { FEAT_FACE, FEAT_EDGE, FEAT_VERTEX };

struct square {
	double c[3], u[3], v[3], w[3];	/* centre, edge directions, normal */
	double h, r, eps;		/* half side, spheroradius, tie tolerance on a coordinate */
	double V[4][3];			/* corners, counter-clockwise about w; edge k is V[k] V[k+1] */
	int nv;				/* 4, or 1 for a point core */
};

/* A point of one core against the other square. */
struct foot {
	double q[3];	/* the square's closest point */
	double d2;	/* squared distance to it (the roots are taken only where needed) */
	int out;	/* the foot on the plane: 0 in the closed square, 1 beyond one edge, 2 beyond a corner */
	int edge;	/* out == 1: that edge */
	int type;	/* where q lies, FEAT_* */
};

struct segs {
	double pa[3], pb[3], d2;
	int interior;	/* both parameters strictly inside, edges not parallel */
};

struct pair {
	struct square A, B;
	struct foot fa[4], fb[4];	/* A's vertices on B, B's on A */
	struct segs ee[4][4];		/* A's edge, B's edge */
	double d, pa[3], pb[3];		/* the cores' distance (squared while searching) and closest points */
	double tol;			/* length tolerance of ties */
	unsigned eedone;		/* bit 4 i + j: ee[i][j] computed (pair_set: all; the cached
					 * narrow phase: those its mask names, and any rule 3 asks for) */
};

static const double corner_s[4] = {-1, 1, 1, -1}, corner_t[4] = {-1, -1, 1, 1};

/* The index of the lowest set bit of m (m > 0): the loops over a mask's bits visit them in
 * ascending order, as loops over every index would. */
static int
lowest_bit(unsigned m)
{
#if defined(__GNUC__)
	return __builtin_ctz(m);
#else
	int b = 0;

	while (!(m & 1u))
		m >>= 1, b++;
	return b;
#endif
}

/* In two steps, which compilers turn into max and min without branches. */
static double
clampd(double x, double lo, double hi)
{
	x = x < lo ? lo : x;
	return x > hi ? hi : x;
}

static double
dist2(const double a[3], const double b[3])
{
	double e[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};

	return vec3_dot(e, e);
}

/* c + s u + t v: one expression for corners and projections, so that a projection clamped to
 * a corner is that corner to the bit. */
static void
square_point(const struct square *q, double s, double t, double p[3])
{
	int a;

	for (a = 0; a < 3; a++)
		p[a] = q->c[a] + s * q->u[a] + t * q->v[a];
}

/* The corners are square_point's c + s u + t v with s, t = -h or h, written out (the narrow
 * phase makes two squares per pair and step): (-h) u is -(h u) to the bit, and c + -(h u) is
 * c - h u, so the sums are square_point's, shared between corners. */
static void
square_set(struct square *q, const struct plate_body *b, const double origin[3])
{
	double h = b->half, hu, hv, cm, cp;
	int a;

	for (a = 0; a < 3; a++) {
		q->c[a] = b->x[a] - origin[a];
		q->u[a] = b->R[3 * a];
		q->v[a] = b->R[3 * a + 1];
		q->w[a] = b->R[3 * a + 2];
	}
	q->h = h;
	q->r = b->r;
	q->eps = PLATE_TOL * h;
	if (!(h > 0)) {
		q->nv = 1;
		square_point(q, corner_s[0] * h, corner_t[0] * h, q->V[0]);
		return;
	}
	q->nv = 4;
	for (a = 0; a < 3; a++) {
		hu = h * q->u[a], hv = h * q->v[a];
		cm = q->c[a] - hu, cp = q->c[a] + hu;
		q->V[0][a] = cm - hv;	/* corner_s, corner_t = -1, -1 */
		q->V[1][a] = cp - hv;	/* 1, -1 */
		q->V[2][a] = cp + hv;	/* 1, 1 */
		q->V[3][a] = cm + hv;	/* -1, 1 */
	}
}

/* The in-plane coordinates of p on square q. */
static void
square_coords(const struct square *q, const double p[3], double *s, double *t)
{
	double e[3] = {p[0] - q->c[0], p[1] - q->c[1], p[2] - q->c[2]};

	*s = vec3_dot(e, q->u);
	*t = vec3_dot(e, q->v);
}

/* Where the point with coordinates s, t (in the closed square) lies, ties on the boundary. */
static int
square_feature(const struct square *q, double s, double t)
{
	int bs = fabs(s) >= q->h - q->eps, bt = fabs(t) >= q->h - q->eps;

	if (q->nv == 1 || (bs && bt))
		return FEAT_VERTEX;
	return bs || bt ? FEAT_EDGE : FEAT_FACE;
}

static void
foot_set(struct foot *f, const struct square *q, const double p[3])
{
	double s, t;
	int os, ot;

	square_coords(q, p, &s, &t);
	square_point(q, clampd(s, -q->h, q->h), clampd(t, -q->h, q->h), f->q);
	f->d2 = dist2(p, f->q);
	os = fabs(s) > q->h + q->eps;
	ot = fabs(t) > q->h + q->eps;
	f->out = os + ot;
	f->edge = os ? (s > 0 ? 1 : 3) : (t > 0 ? 2 : 0);
	f->type = square_feature(q, s, t);
}

/* Closest points of segments p1 q1 and p2 q2, both of nonzero length (Ericson 5.1.9; parallel
 * ones start from the end of the first).  Ericson's two branches on t are folded into always
 * recomputing s from the clamped t, which changes nothing when t was inside (s is then already
 * the best for t) and spares the mispredicted branches that cost more than the arithmetic. */
static void
segs_set(struct segs *g, const double p1[3], const double q1[3], const double p2[3], const double q2[3])
{
	double d1[3], d2[3], r[3], a, e, b, c, f, den, s, t;
	int k, par;

	for (k = 0; k < 3; k++) {
		d1[k] = q1[k] - p1[k];
		d2[k] = q2[k] - p2[k];
		r[k] = p1[k] - p2[k];
	}
	a = vec3_dot(d1, d1), e = vec3_dot(d2, d2), b = vec3_dot(d1, d2);
	c = vec3_dot(d1, r), f = vec3_dot(d2, r);
	den = a * e - b * b;
	par = den <= PLATE_PARALLEL * a * e;
	s = par ? 0 : clampd((b * f - c * e) / den, 0, 1);
	t = clampd((b * s + f) / e, 0, 1);
	s = clampd((b * t - c) / a, 0, 1);
	for (k = 0; k < 3; k++) {
		g->pa[k] = p1[k] + s * d1[k];
		g->pb[k] = p2[k] + t * d2[k];
	}
	g->d2 = dist2(g->pa, g->pb);
	g->interior = !par && s > PLATE_TOL && s < 1 - PLATE_TOL && t > PLATE_TOL && t < 1 - PLATE_TOL;
}

/* Two edge pairs at once, one per lane of base/lanes.h: segs_set's operations lane by lane,
 * so each lane's numbers are segs_set's to the bit.  A pair's three divisions form one
 * dependent chain; two chains share the divider (a cached pair of small plates names about
 * four edge pairs: segs_set was 18 % of a shear's time at eta 0.14). */
#if LANES_OK
static inline v2d
clamp2(v2d x, v2d lo, v2d hi)
{
	x = V2_SELECT(x < lo, lo, x);
	return V2_SELECT(x > hi, hi, x);
}

static void
segs_set2(struct segs *g0, const double *p1, const double *q1, const double *p2, const double *q2,
    struct segs *g1, const double *P1, const double *Q1, const double *P2, const double *Q2)
{
	const v2d zero = {0, 0}, one = {1, 1};
	v2d o1[3], o2[3], d1[3], d2[3], r[3], a, e, b, c, f, den, s, t, w[3], dd;
	v2m par;
	int k;

	for (k = 0; k < 3; k++) {
		v2d e1 = {q1[k], Q1[k]}, e2 = {q2[k], Q2[k]};

		o1[k] = (v2d){p1[k], P1[k]}, o2[k] = (v2d){p2[k], P2[k]};
		d1[k] = e1 - o1[k];
		d2[k] = e2 - o2[k];
		r[k] = o1[k] - o2[k];
	}
	a = d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2];
	e = d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2];
	b = d1[0] * d2[0] + d1[1] * d2[1] + d1[2] * d2[2];
	c = d1[0] * r[0] + d1[1] * r[1] + d1[2] * r[2];
	f = d2[0] * r[0] + d2[1] * r[1] + d2[2] * r[2];
	den = a * e - b * b;
	par = den <= PLATE_PARALLEL * a * e;
	s = V2_SELECT(par, zero, clamp2((b * f - c * e) / den, zero, one));
	t = clamp2((b * s + f) / e, zero, one);
	s = clamp2((b * t - c) / a, zero, one);
	for (k = 0; k < 3; k++) {
		v2d pa = o1[k] + s * d1[k], pb = o2[k] + t * d2[k];

		g0->pa[k] = pa[0], g1->pa[k] = pa[1];
		g0->pb[k] = pb[0], g1->pb[k] = pb[1];
		w[k] = pa - pb;
	}
	dd = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
	g0->d2 = dd[0], g1->d2 = dd[1];
	g0->interior = !par[0] && s[0] > PLATE_TOL && s[0] < 1 - PLATE_TOL && t[0] > PLATE_TOL && t[0] < 1 - PLATE_TOL;
	g1->interior = !par[1] && s[1] > PLATE_TOL && s[1] < 1 - PLATE_TOL && t[1] > PLATE_TOL && t[1] < 1 - PLATE_TOL;
}
#endif

/* Edge pairs (i, j) and (k, l) of squares A and B into ee, both with segs_set's numbers. */
static void
edge_pairs_two(struct segs ee[4][4], const struct square *A, const struct square *B, int i, int j, int k, int l)
{
#if LANES_OK
	segs_set2(&ee[i][j], A->V[i], A->V[(i + 1) & 3], B->V[j], B->V[(j + 1) & 3],
	    &ee[k][l], A->V[k], A->V[(k + 1) & 3], B->V[l], B->V[(l + 1) & 3]);
#else
	segs_set(&ee[i][j], A->V[i], A->V[(i + 1) & 3], B->V[j], B->V[(j + 1) & 3]);
	segs_set(&ee[k][l], A->V[k], A->V[(k + 1) & 3], B->V[l], B->V[(l + 1) & 3]);
#endif
}

/* Does an edge of square p cross square q (into X)?  None can when p's corners are all on one
 * side of q's plane; an edge in q's plane is left to the vertex and edge pairs, which find its
 * contacts at distance 0. */
static int
edges_cross(const struct square *p, const struct square *q, double X[3])
{
	double sd[4], e[3], lam, s, t;
	int j, k, a, pos = 0, neg = 0;

	for (k = 0; k < 4; k++) {
		for (a = 0; a < 3; a++)
			e[a] = p->V[k][a] - q->c[a];
		sd[k] = vec3_dot(e, q->w);
		pos += sd[k] > 0, neg += sd[k] < 0;
	}
	if (pos == 4 || neg == 4)
		return 0;
	for (k = 0; k < 4; k++) {
		j = (k + 1) % 4;
		if ((sd[k] > 0 && sd[j] > 0) || (sd[k] < 0 && sd[j] < 0) || sd[k] == sd[j])
			continue;
		lam = sd[k] / (sd[k] - sd[j]);
		for (a = 0; a < 3; a++)
			X[a] = p->V[k][a] + lam * (p->V[j][a] - p->V[k][a]);
		square_coords(q, X, &s, &t);
		if (fabs(s) <= q->h && fabs(t) <= q->h)
			return 1;
	}
	return 0;
}

static void
pair_closest_take(struct pair *g, double d2, const double pa[3], const double pb[3])
{
	if (d2 < g->d) {
		g->d = d2;
		memcpy(g->pa, pa, sizeof g->pa);
		memcpy(g->pb, pb, sizeof g->pb);
	}
}

static void
pair_cross(struct pair *g)
{
	double X[3];

	if (edges_cross(&g->A, &g->B, X) || edges_cross(&g->B, &g->A, X)) {
		g->d = 0;
		memcpy(g->pa, X, sizeof X);
		memcpy(g->pb, X, sizeof X);
	}
}

static void
pair_set(struct pair *g, const struct plate_body *a, const struct plate_body *b)
{
	int i, j;

	square_set(&g->A, a, a->x);
	square_set(&g->B, b, a->x);
	g->tol = PLATE_TOL * (a->half + b->half + a->r + b->r);
	g->d = INFINITY;
	for (i = 0; i < g->A.nv; i++) {
		foot_set(&g->fa[i], &g->B, g->A.V[i]);
		pair_closest_take(g, g->fa[i].d2, g->A.V[i], g->fa[i].q);
	}
	for (j = 0; j < g->B.nv; j++) {
		foot_set(&g->fb[j], &g->A, g->B.V[j]);
		pair_closest_take(g, g->fb[j].d2, g->fb[j].q, g->B.V[j]);
	}
	g->eedone = 0;
	if (g->A.nv < 4 || g->B.nv < 4) {
		g->d = sqrt(g->d);
		return;
	}
	for (i = 0; i < 4; i++)	/* two at a time, then taken in order */
		for (j = 0; j < 4; j += 2) {
			edge_pairs_two(g->ee, &g->A, &g->B, i, j, i, j + 1);
			pair_closest_take(g, g->ee[i][j].d2, g->ee[i][j].pa, g->ee[i][j].pb);
			pair_closest_take(g, g->ee[i][j + 1].d2, g->ee[i][j + 1].pa, g->ee[i][j + 1].pb);
		}
	g->eedone = 0xffffu;
	g->d = sqrt(g->d);
	if (g->d > 0)
		pair_cross(g);
}

/* Edge pair (i, j), computed now if the cached narrow phase skipped it: the same numbers
 * pair_set would have (segs_set depends on the two edges alone). */
static const struct segs *
pair_edges(struct pair *g, int i, int j)
{
	unsigned bit = 1u << (4 * i + j);

	if (!(g->eedone & bit)) {
		segs_set(&g->ee[i][j], g->A.V[i], g->A.V[(i + 1) % 4], g->B.V[j], g->B.V[(j + 1) % 4]);
		g->eedone |= bit;
	}
	return &g->ee[i][j];
}

double
plate_core_distance(const struct plate_body *a, const struct plate_body *b, double pa[3], double pb[3])
{
	struct pair g;
	int k;

	pair_set(&g, a, b);
	for (k = 0; k < 3; k++) {
		if (pa)
			pa[k] = g.pa[k] + a->x[k];
		if (pb)
			pb[k] = g.pb[k] + a->x[k];
	}
	return g.d;
}

static int
element_kind(int ta, int tb)
{
	if (ta == FEAT_VERTEX)
		return tb == FEAT_FACE ? PLATE_VERTEX_FACE : tb == FEAT_EDGE ? PLATE_VERTEX_EDGE : PLATE_VERTEX_VERTEX;
	if (tb == FEAT_VERTEX)
		return ta == FEAT_FACE ? PLATE_FACE_VERTEX : PLATE_EDGE_VERTEX;
	return PLATE_EDGE_EDGE;
}

/* Appends an element (points relative to a's centre) unless it is out of range or already
 * there; when full, the shallowest gives way, so the deepest is never lost. */
static void
element_add(struct plate_interaction *out, const struct pair *g, const double pi[3], const double pj[3],
    double dk, int kind, double gap)
{
	double h = g->A.r + g->B.r - dk, same = 100 * g->tol * g->tol;
	struct plate_element *e;
	int k, low = 0;

	if (!(h > -gap))
		return;
	for (k = 0; k < out->m; k++) {
		if (dist2(out->e[k].pi, pi) <= same && dist2(out->e[k].pj, pj) <= same)
			return;
		if (out->e[k].h < out->e[low].h)
			low = k;
	}
	if (out->m == PLATE_MAX_ELEMENTS && !(h > out->e[low].h))
		return;
	e = &out->e[out->m < PLATE_MAX_ELEMENTS ? out->m++ : low];
	e->h = h;
	memcpy(e->pi, pi, sizeof e->pi);
	memcpy(e->pj, pj, sizeof e->pj);
	e->kind = kind;
}

/* Does one of vertex k's edges (on its own square, side 0 = A) cross edge e of the other? */
static int
vertex_superseded(struct pair *g, int side, int k, int e)
{
	int k0 = (k + 3) % 4;

	return side ? pair_edges(g, e, k)->interior || pair_edges(g, e, k0)->interior :
	    pair_edges(g, k, e)->interior || pair_edges(g, k0, e)->interior;
}

/* Does the closed square of `own` cover point q (of the other core) along its normal? */
static int
square_covers(const struct square *own, const double q[3])
{
	double s, t;

	square_coords(own, q, &s, &t);
	return fabs(s) <= own->h + own->eps && fabs(t) <= own->h + own->eps;
}

/* Does the line through p along n meet the closed square q?  0 if it does, else 1 when it
 * passes beyond one edge (into *edge) and 2 beyond a corner.  Each test is a support
 * inequality of q's shadow on the plane normal to n: n x v and n x u bound the shadow across
 * its edges, u and v less their n parts bound it along them, which is what is left when q's
 * plane holds n and the shadow is a segment. */
static int
shadow_status(const struct square *q, const double n[3], const double p[3], int *edge)
{
	double e[3], k[4][3], ue = vec3_dot(q->u, n), ve = vec3_dot(q->v, n), ke[4], ku[4], kv[4];
	int a, j, os = 0, ot = 0, ss = 1, st = 1;

	vec3_cross(n, q->v, k[0]);
	vec3_cross(n, q->u, k[1]);
	for (a = 0; a < 3; a++) {
		e[a] = p[a] - q->c[a];
		k[2][a] = q->u[a] - ue * n[a];
		k[3][a] = q->v[a] - ve * n[a];
	}
	for (j = 0; j < 4; j++) {
		ke[j] = vec3_dot(k[j], e), ku[j] = vec3_dot(k[j], q->u), kv[j] = vec3_dot(k[j], q->v);
		if (!(fabs(ke[j]) > q->h * (fabs(ku[j]) + fabs(kv[j])) + q->eps * vec3_norm(k[j])))
			continue;
		if (j % 2 == 0)
			os = 1, ss = (j == 0 ? ke[j] * ku[j] : ke[j]) > 0;
		else
			ot = 1, st = (j == 1 ? ke[j] * kv[j] : ke[j]) > 0;
	}
	*edge = os ? (ss ? 1 : 3) : (st ? 2 : 0);
	return os + ot;
}

/* Rules 1, 3 and 4 for vertex k of side 0 (A on B) or 1 (B on A). */
static int
vertex_kept(struct pair *g, const double n[3], int side, int k)
{
	const struct foot *f = side ? &g->fb[k] : &g->fa[k];
	const struct square *own = side ? &g->B : &g->A, *other = side ? &g->A : &g->B;
	int out = f->out, edge = f->edge;

	if (out == 0 && (out = shadow_status(other, n, own->V[k], &edge)) == 0)
		return 1;
	if (out == 2)
		return 0;
	return !vertex_superseded(g, side, k, edge) && !square_covers(own, f->q);
}

/* The element contacts of cores apart (rules 1-5), n the interaction's normal.  A point core
 * has one element, the closest pair.  feet: the vertices whose feet pair_set computed (bits
 * 0-3 A's, 4-7 B's; the others are farther than any element kept, see plate_cached). */
static void
elements_find(struct pair *g, const double n[3], double gap, unsigned feet, struct plate_interaction *out)
{
	double s, t;
	unsigned left;
	int k, ta, tb;

	if (g->A.nv == 4 && g->B.nv == 4) {
		for (k = 0; k < 4; k++)
			if ((feet & (1u << k)) && vertex_kept(g, n, 0, k))
				element_add(out, g, g->A.V[k], g->fa[k].q, sqrt(g->fa[k].d2),
				    element_kind(FEAT_VERTEX, g->fa[k].type), gap);
		for (k = 0; k < 4; k++)
			if ((feet & (1u << (4 + k))) && vertex_kept(g, n, 1, k))
				element_add(out, g, g->fb[k].q, g->B.V[k], sqrt(g->fb[k].d2),
				    element_kind(g->fb[k].type, FEAT_VERTEX), gap);
		for (left = g->eedone; left; left &= left - 1) {	/* by ascending 4 i + j */
			const struct segs *ee = &g->ee[0][0] + lowest_bit(left);

			if (ee->interior)
				element_add(out, g, ee->pa, ee->pb, sqrt(ee->d2), PLATE_EDGE_EDGE, gap);
		}
	}
	for (k = 0; k < out->m; k++)
		if (g->A.r + g->B.r - out->e[k].h <= g->d + g->tol)
			return;
	square_coords(&g->A, g->pa, &s, &t);
	ta = square_feature(&g->A, s, t);
	square_coords(&g->B, g->pb, &s, &t);
	tb = square_feature(&g->B, s, t);
	element_add(out, g, g->pa, g->pb, g->d, element_kind(ta, tb), gap);
}

static void
ccd_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *vec)
{
	const struct square *q = obj;
	double n = vec3_norm(dir->v), s = vec3_dot(dir->v, q->u) >= 0 ? q->h : -q->h;
	double t = vec3_dot(dir->v, q->v) >= 0 ? q->h : -q->h, p[3];
	int k;

	square_point(q, s, t, p);
	for (k = 0; k < 3; k++)
		vec->v[k] = p[k] + (n > 0 ? q->r / n * dir->v[k] : 0);
}

static void
ccd_center(const void *obj, ccd_vec3_t *c)
{
	const struct square *q = obj;

	memcpy(c->v, q->c, sizeof c->v);
}

/* The cores intersect: one element from MPR on the spheroplates; libccd's dir is the way to
 * push j out, so n = -dir.  Should MPR fail (it cannot when the cores meet, short of round-off),
 * the centres' direction and the depth r_i + r_j stand in. */
static void
overlap_find(const struct pair *g, double gap, struct plate_interaction *out)
{
	double size = g->tol / PLATE_TOL, depth = 0, n;
	struct plate_element *e = &out->e[0];
	ccd_vec3_t dir, pos;
	ccd_t ccd;
	int k;

	CCD_INIT(&ccd);
	ccd.support1 = ccd.support2 = ccd_support;
	ccd.center1 = ccd.center2 = ccd_center;
	ccd.mpr_tolerance = PLATE_MPR_TOL * size;
	ccd.max_iterations = PLATE_MPR_ITER;
	if (ccdMPRPenetration(&g->A, &g->B, &ccd, &depth, &dir, &pos) != 0 || !(depth > 0) ||
	    !((n = vec3_norm(dir.v)) > 0)) {
		double e3[3] = {-g->A.w[0], -g->A.w[1], -g->A.w[2]};
		n = vec3_norm(g->B.c);
		depth = g->A.r + g->B.r;
		memcpy(dir.v, n > 0 ? g->B.c : e3, sizeof dir.v);
		n = n > 0 ? n : 1;
		memcpy(pos.v, g->pa, sizeof pos.v);
	}
	for (k = 0; k < 3; k++)
		out->n[k] = -dir.v[k] / n;
	out->m = 0;
	if (!(depth > -gap))
		return;
	e->h = depth;
	memcpy(e->pi, g->pa, sizeof e->pi);
	memcpy(e->pj, g->pb, sizeof e->pj);
	memcpy(e->p, pos.v, sizeof e->p);
	e->kind = PLATE_CORE_OVERLAP;
	out->m = 1;
}

/* A lower bound on the distance of the two cores from the six axes of their frames (the
 * face normals and the edge directions): along a unit axis the cores' projections are
 * intervals, and the gap between them bounds the distance from below.  Most pairs whose
 * bounding spheres overlap are told apart here, at a tenth of pair_set's cost (a DEM step of
 * 1000 plates at eta 0.5 spent 80 % of its time in pair_set and its helpers without it). */
static double
axes_separation(const struct plate_body *a, const struct plate_body *b)
{
	double dx[3] = {b->x[0] - a->x[0], b->x[1] - a->x[1], b->x[2] - a->x[2]}, best = 0;
	const struct plate_body *s[2] = {a, b};
	int k, ax, o;

	for (k = 0; k < 2; k++)
		for (ax = 0; ax < 3; ax++) {
			double e[3] = {s[k]->R[ax], s[k]->R[3 + ax], s[k]->R[6 + ax]}, ext = 0, c;

			for (o = 0; o < 2; o++) {	/* each core's half extent along e */
				const double *R = s[o]->R;
				double pu = fabs(e[0] * R[0] + e[1] * R[3] + e[2] * R[6]);
				double pv = fabs(e[0] * R[1] + e[1] * R[4] + e[2] * R[7]);
				ext += s[o]->half * (pu + pv);
			}
			c = fabs(dx[0] * e[0] + dx[1] * e[1] + dx[2] * e[2]) - ext;
			if (c > best)
				best = c;
		}
	return best;
}

double
plate_core_gap_bound(const struct plate_body *a, const struct plate_body *b)
{
	return axes_separation(a, b);
}

/* The interaction of a pair_set's cores (every feature, or those of a cache; feet as in
 * elements_find), its points moved back from a's centre to the lab frame. */
static int
interaction_finish(struct pair *g, const struct plate_body *a, const struct plate_body *b, double gap, unsigned feet,
    struct plate_interaction *out)
{
	int j, k;

	out->d = g->d;
	out->m = 0;
	if (g->d <= g->tol) {
		overlap_find(g, gap, out);
	} else {
		for (k = 0; k < 3; k++)
			out->n[k] = (g->pa[k] - g->pb[k]) / g->d;
		elements_find(g, out->n, gap, feet, out);
		for (j = 0; j < out->m; j++)
			plate_element_point(&out->e[j], out->n, a->r, b->r);
	}
	for (j = 0; j < out->m; j++)
		for (k = 0; k < 3; k++) {
			out->e[j].pi[k] += a->x[k];
			out->e[j].pj[k] += a->x[k];
			out->e[j].p[k] += a->x[k];
		}
	return out->m;
}

int
plate_interaction(const struct plate_body *a, const struct plate_body *b, double gap, struct plate_interaction *out)
{
	struct pair g;

	out->d = axes_separation(a, b);
	if (out->d >= a->r + b->r + gap) {
		out->m = 0;
		return 0;
	}
	pair_set(&g, a, b);
	return interaction_finish(&g, a, b, gap, 0xffu, out);
}

/* pair_set on the features of cache alone (in pair_set's order, so that the closest pair
 * and its ties come out the same), and the edge crossings only when the cache says the
 * cores may meet. */
static void
pair_set_cached(struct pair *g, const struct plate_body *a, const struct plate_body *b, unsigned cache)
{
	int i, j;

	square_set(&g->A, a, a->x);
	square_set(&g->B, b, a->x);
	g->tol = PLATE_TOL * (a->half + b->half + a->r + b->r);
	g->d = INFINITY;
	g->eedone = 0;
	for (i = 0; i < g->A.nv; i++)
		if (cache & (1u << i)) {
			foot_set(&g->fa[i], &g->B, g->A.V[i]);
			pair_closest_take(g, g->fa[i].d2, g->A.V[i], g->fa[i].q);
		}
	for (j = 0; j < g->B.nv; j++)
		if (cache & (1u << (4 + j))) {
			foot_set(&g->fb[j], &g->A, g->B.V[j]);
			pair_closest_take(g, g->fb[j].d2, g->fb[j].q, g->B.V[j]);
		}
	if (g->A.nv == 4 && g->B.nv == 4) {
		unsigned left = (cache >> 8) & 0xffffu;

		while (left) {	/* the named edge pairs, by ascending 4 i + j, two at a time */
			int bit = lowest_bit(left), bit2;
			struct segs *s = &g->ee[bit >> 2][bit & 3], *s2;

			i = bit >> 2, j = bit & 3;
			left &= left - 1;
			if (!left) {
				segs_set(s, g->A.V[i], g->A.V[(i + 1) & 3], g->B.V[j], g->B.V[(j + 1) & 3]);
				pair_closest_take(g, s->d2, s->pa, s->pb);
				break;
			}
			bit2 = lowest_bit(left);
			left &= left - 1;
			s2 = &g->ee[bit2 >> 2][bit2 & 3];
			edge_pairs_two(g->ee, &g->A, &g->B, i, j, bit2 >> 2, bit2 & 3);
			pair_closest_take(g, s->d2, s->pa, s->pb);
			pair_closest_take(g, s2->d2, s2->pa, s2->pb);
		}
		g->eedone = (cache >> 8) & 0xffffu;
	}
	g->d = sqrt(g->d);
	if (g->d > 0 && (cache & PLATE_CACHE_CROSS) && g->A.nv == 4 && g->B.nv == 4)
		pair_cross(g);
}

/* Why the cache gives pair_set's answer.  Every feature distance (a vertex to the other
 * square, an edge to an edge) is the distance between two sets that move rigidly with their
 * grains, so it changes by at most the sum of the largest displacements of the two cores'
 * points since the cache was made, which the caller keeps below margin.  A feature left out
 * was then farther than r_a + r_b + margin, so it is still farther than r_a + r_b: it cannot
 * be an element (h <= 0), nor the closest pair of cores that touch (that one is nearer than
 * r_a + r_b), nor come before it among equals.  Rule 3's test of a vertex's own edges against
 * an edge may name an edge pair left out: pair_edges computes it then.  The cores can meet
 * (an edge through the other square) only if they were within margin. */
int
plate_interaction_cached(const struct plate_body *a, const struct plate_body *b, double margin, unsigned *cache,
    int build, struct plate_interaction *out)
{
	struct pair g;
	unsigned c = 0;
	int i, j;

	if (build) {
		double lim = a->r + b->r + margin, lim2 = lim * lim;

		out->d = axes_separation(a, b);
		if (out->d >= lim) {
			*cache = 0;
			out->m = 0;
			return 0;
		}
		pair_set(&g, a, b);
		for (i = 0; i < g.A.nv; i++)
			c |= (unsigned)(g.fa[i].d2 < lim2) << i;
		for (j = 0; j < g.B.nv; j++)
			c |= (unsigned)(g.fb[j].d2 < lim2) << (4 + j);
		if (g.eedone)
			for (i = 0; i < 4; i++)
				for (j = 0; j < 4; j++)
					c |= (unsigned)(g.ee[i][j].d2 < lim2) << (8 + 4 * i + j);
		if (g.d <= margin + 2 * g.tol)
			c |= PLATE_CACHE_CROSS;
		*cache = c;
		return interaction_finish(&g, a, b, 0, 0xffu, out);
	}
	if (!(*cache & PLATE_CACHE_FEATURES)) {
		out->d = INFINITY;
		out->m = 0;
		return 0;
	}
	pair_set_cached(&g, a, b, *cache);
	if (!(g.d < a->r + b->r)) {	/* every element is at least as far: none */
		out->d = g.d;
		out->m = 0;
		return 0;
	}
	return interaction_finish(&g, a, b, 0, *cache & 0xffu, out);
}

int
plate_wall_interaction(const struct plate_body *a, const double w0[3], const double wn[3], double gap,
    struct plate_interaction *out)
{
	static const double zero[3] = {0, 0, 0};
	struct square q;
	int j, k;

	square_set(&q, a, zero);
	memcpy(out->n, wn, sizeof out->n);
	out->d = INFINITY;
	out->m = 0;
	for (j = 0; j < q.nv; j++) {
		struct plate_element *e = &out->e[out->m];
		double sd = (q.V[j][0] - w0[0]) * wn[0] + (q.V[j][1] - w0[1]) * wn[1] + (q.V[j][2] - w0[2]) * wn[2];
		out->d = fmin(out->d, sd);
		e->h = a->r - sd;
		if (!(e->h > -gap))
			continue;
		for (k = 0; k < 3; k++) {
			e->pi[k] = q.V[j][k];
			e->pj[k] = q.V[j][k] - sd * wn[k];
		}
		plate_element_point(e, wn, a->r, 0);
		e->kind = q.nv == 1 ? PLATE_SPHERE : PLATE_VERTEX_FACE;
		out->m++;
	}
	return out->m;
}
