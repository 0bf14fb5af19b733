/* functional: Hertz energy and gradient over a pack (see functional.h). */
#include "qs/functional.h"
#include "qs/friction.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int
qs_init(struct qs_system *s, struct pack *p, double skin)
{
	size_t i;

	memset(s, 0, sizeof *s);
	s->p = p;
	s->n = p->n;
	s->dim = 3 * p->n;
	s->comp = malloc((p->n ? p->n : 1) * sizeof *s->comp);
	if (!s->comp) {
		msg_seterr("out of memory");
		return -1;
	}
	s->rmin = INFINITY;
	for (i = 0; i < p->n; i++) {
		s->comp[i] = (1 - p->nu[i] * p->nu[i]) / p->E[i];
		s->rmin = fmin(s->rmin, p->r[i]);
		s->rmax = fmax(s->rmax, p->r[i]);
	}
	s->wall_comp = (1 - p->wall_nu * p->wall_nu) / p->wall_E;
	s->skin = skin * s->rmin;
	nlist_init(&s->nl);
	return 0;
}

void
qs_free(struct qs_system *s)
{
	free(s->comp);
	nlist_free(&s->nl);
	memset(s, 0, sizeof *s);
}

double
qs_energy(struct qs_system *s, const double *x, double *g, double *fmax)
{
	const struct pack *p = s->p;
	const double *r = p->r, *box = p->box;
	double E = 0, sumf = 0;
	size_t i, k, n = s->n, nc = 0;
	int w;

	if (!s->nl.first || nlist_stale(&s->nl, x, box, box + 3))
		if (nlist_build(&s->nl, x, r, n, box, box + 3, s->rmax, s->skin))
			return NAN;
	s->evals++;
	if (g)
		memset(g, 0, s->dim * sizeof *g);
	if (fmax)
		memset(fmax, 0, n * sizeof *fmax);
	memset(s->wall_force, 0, sizeof s->wall_force);
	for (i = 0; i < n; i++) {
		const double *xi = x + 3 * i;
		double ri = r[i], ci = s->comp[i];

		for (k = s->nl.first[i]; k < s->nl.first[i + 1]; k++) {
			size_t j = s->nl.nbr[k];
			const double *xj = x + 3 * j;
			double d0 = xi[0] - xj[0], d1 = xi[1] - xj[1], d2 = xi[2] - xj[2];
			double sum = ri + r[j], dd = d0 * d0 + d1 * d1 + d2 * d2, d, h, Es, sRs, sh, P;

			if (dd >= sum * sum)
				continue;
			d = sqrt(dd);
			h = sum - d;
			Es = 1.0 / (ci + s->comp[j]);
			sRs = sqrt(ri * r[j] / sum);
			sh = sqrt(h);
			P = 4.0 / 3.0 * Es * sRs * h * sh;
			E += 0.4 * P * h;	/* 8/15 E* sqrt(R*) h^(5/2) = 2/5 P h */
			sumf += P;
			nc++;
			if (g) {
				double f = P / d;
				g[3 * i] -= f * d0;
				g[3 * i + 1] -= f * d1;
				g[3 * i + 2] -= f * d2;
				g[3 * j] += f * d0;
				g[3 * j + 1] += f * d1;
				g[3 * j + 2] += f * d2;
			}
			if (fmax) {
				if (P > fmax[i])
					fmax[i] = P;
				if (P > fmax[j])
					fmax[j] = P;
			}
		}
		for (w = 0; w < NWALLS; w++) {
			int a = w / 2;
			double dist = pack_wall_distance(box, xi, w), h = ri - dist, Es, P;

			if (h <= 0)
				continue;
			Es = 1.0 / (ci + s->wall_comp);
			P = 4.0 / 3.0 * Es * sqrt(ri) * h * sqrt(h);
			E += 0.4 * P * h;
			sumf += P;
			nc++;
			s->wall_force[w] += P;
			if (g)
				g[3 * i + a] += w % 2 ? P : -P;
			if (fmax && P > fmax[i])
				fmax[i] = P;
		}
	}
	s->ncontacts = nc;
	s->sum_force = sumf;
	if (s->fr)
		E += fr_energy(s->fr, s, x, g);
	return E;
}

void
qs_residual(const struct qs_system *s, const double *g, const double *fbig, double floor_rel, double *res_max,
    double *res_mean)
{
	double rmax = 0, sum = 0, fl;
	size_t i, nf = 0;

	fl = s->ncontacts ? floor_rel * s->sum_force / s->ncontacts : 0;
	if (s->force_floor > fl)
		fl = s->force_floor;
	for (i = 0; i < s->n; i++) {
		double f;
		if (!(fbig[i] > 0))
			continue;
		f = sqrt(g[3 * i] * g[3 * i] + g[3 * i + 1] * g[3 * i + 1] + g[3 * i + 2] * g[3 * i + 2]);
		if (s->dim > 3 * s->n) {
			const double *m = g + 3 * s->n + 3 * i;
			f = fmax(f, sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]));
		}
		if (f / fmax(fbig[i], fl) > rmax)
			rmax = f / fmax(fbig[i], fl);
		sum += f;
		nf++;
	}
	*res_max = rmax;
	*res_mean = nf && s->ncontacts ? (sum / nf) / (s->sum_force / s->ncontacts) : 0;
}

void
qs_wall_stress(const struct qs_system *s, double sig[3])
{
	const double *b = s->p->box;
	int a;

	for (a = 0; a < 3; a++) {
		int u = (a + 1) % 3, v = (a + 2) % 3;
		double area = (b[3 + u] - b[u]) * (b[3 + v] - b[v]);
		sig[a] = (s->wall_force[2 * a] + s->wall_force[2 * a + 1]) / (2 * area);
	}
}

void
qs_coordination(const struct qs_system *s, const double *x, unsigned *counts)
{
	const double *r = s->p->r, *box = s->p->box;
	size_t i, k;
	int w;

	memset(counts, 0, s->n * sizeof *counts);
	for (i = 0; i < s->n; i++) {
		for (k = s->nl.first[i]; k < s->nl.first[i + 1]; k++) {
			size_t j = s->nl.nbr[k];
			double d0 = x[3 * i] - x[3 * j], d1 = x[3 * i + 1] - x[3 * j + 1], d2 = x[3 * i + 2] - x[3 * j + 2];
			double sum = r[i] + r[j];
			if (d0 * d0 + d1 * d1 + d2 * d2 < sum * sum) {
				counts[i]++;
				counts[j]++;
			}
		}
		for (w = 0; w < NWALLS; w++) {
			double dist = pack_wall_distance(box, x + 3 * i, w);
			if (dist < r[i])
				counts[i]++;
		}
	}
}

void
qs_radii_changed(struct qs_system *s)
{
	size_t i;

	s->rmin = INFINITY;
	s->rmax = 0;
	for (i = 0; i < s->n; i++) {
		s->rmin = fmin(s->rmin, s->p->r[i]);
		s->rmax = fmax(s->rmax, s->p->r[i]);
	}
	nlist_free(&s->nl);
	nlist_init(&s->nl);
}

/* c <= 3 unit normals nc (rows) and overlaps h: the u of least length with nc[k].u = h[k],
 * u = sum lambda_k nc[k] with G lambda = h (G the Gram matrix).  0, or -1 when the normals
 * are nearly dependent (det G below 1e-2: two normals within about 6 degrees of each other
 * or of opposite directions). */
static int
release_move(unsigned c, const double nc[3][3], const double h[3], double u[3])
{
	double G[3][3], lam[3] = {0, 0, 0}, det;
	unsigned a, b;

	for (a = 0; a < c; a++)
		for (b = 0; b < c; b++)
			G[a][b] = nc[a][0] * nc[b][0] + nc[a][1] * nc[b][1] + nc[a][2] * nc[b][2];
	if (c == 1) {
		lam[0] = h[0];
	} else if (c == 2) {
		det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
		if (det < 1e-2)
			return -1;
		lam[0] = (G[1][1] * h[0] - G[0][1] * h[1]) / det;
		lam[1] = (G[0][0] * h[1] - G[1][0] * h[0]) / det;
	} else {
		double C[3][3];
		for (a = 0; a < 3; a++)
			for (b = 0; b < 3; b++)
				C[a][b] = G[(b + 1) % 3][(a + 1) % 3] * G[(b + 2) % 3][(a + 2) % 3] -
				    G[(b + 1) % 3][(a + 2) % 3] * G[(b + 2) % 3][(a + 1) % 3];
		det = G[0][0] * C[0][0] + G[0][1] * C[1][0] + G[0][2] * C[2][0];
		if (det < 1e-2)
			return -1;
		for (a = 0; a < 3; a++)
			lam[a] = (C[a][0] * h[0] + C[a][1] * h[1] + C[a][2] * h[2]) / det;
	}
	for (b = 0; b < 3; b++)
		u[b] = lam[0] * nc[0][b] + (c > 1 ? lam[1] * nc[1][b] : 0) + (c > 2 ? lam[2] * nc[2][b] : 0);
	return 0;
}

long
qs_release_unbraced(struct qs_system *s, double *x)
{
	const double *r = s->p->r, *box = s->p->box;
	size_t i, k, n = s->n, *first = NULL, *nbr = NULL, *fill = NULL;
	long moved = 0;

	if (s->fr || n == 0)
		return 0;
	/* a fresh list at x: every pair within the skin is listed, so a move shorter than a
	 * quarter of it cannot meet an unlisted grain */
	nlist_free(&s->nl);
	nlist_init(&s->nl);
	if (isnan(qs_energy(s, x, NULL, NULL)))
		return -1;
	first = calloc(n + 1, sizeof *first);
	fill = calloc(n, sizeof *fill);
	nbr = malloc((2 * s->nl.npairs + 1) * sizeof *nbr);
	if (!first || !fill || !nbr) {
		msg_seterr("out of memory");
		moved = -1;
		goto out;
	}
	/* both directions of the half list, rows in ascending order (deterministic) */
	for (i = 0; i < n; i++)
		for (k = s->nl.first[i]; k < s->nl.first[i + 1]; k++) {
			first[i + 1]++;
			first[s->nl.nbr[k] + 1]++;
		}
	for (i = 0; i < n; i++)
		first[i + 1] += first[i];
	for (i = 0; i < n; i++)
		for (k = s->nl.first[i]; k < s->nl.first[i + 1]; k++) {
			size_t j = s->nl.nbr[k];
			nbr[first[i] + fill[i]++] = j;
			nbr[first[j] + fill[j]++] = i;
		}
	for (i = 0; i < n; i++) {
		double nc[3][3], h[3], u[3], xn[3], uu;
		unsigned c = 0;
		int w, ok = 1;

		for (k = first[i]; k < first[i + 1] && c <= 3; k++) {
			size_t j = nbr[k];
			double d[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
			double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
			if (dist >= r[i] + r[j])
				continue;
			if (!(dist > 0)) {
				c = 4;	/* coincident centres: no normal; leave it to the minimiser */
				break;
			}
			if (c < 3) {
				nc[c][0] = d[0] / dist, nc[c][1] = d[1] / dist, nc[c][2] = d[2] / dist;
				h[c] = r[i] + r[j] - dist;
			}
			c++;
		}
		for (w = 0; w < NWALLS && c <= 3; w++) {
			int a = w / 2;
			double dist = pack_wall_distance(box, x + 3 * i, w);
			if (dist >= r[i])
				continue;
			if (c < 3) {
				nc[c][0] = nc[c][1] = nc[c][2] = 0;
				nc[c][a] = w % 2 ? -1 : 1;
				h[c] = r[i] - dist;
			}
			c++;
		}
		if (c == 0 || c > 3 || release_move(c, (const double(*)[3])nc, h, u))
			continue;
		uu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
		if (!(uu <= 0.25 * s->skin))
			continue;
		/* a hair beyond touching: rounding must not leave an overlap of 1e-16 that counts
		 * as a contact */
		u[0] *= 1 + 1e-8, u[1] *= 1 + 1e-8, u[2] *= 1 + 1e-8;
		xn[0] = x[3 * i] + u[0], xn[1] = x[3 * i + 1] + u[1], xn[2] = x[3 * i + 2] + u[2];
		/* u.n_c = h_c opens each contact to first order and |d + u| >= |d| + h_c exactly
		 * (u is longer than its projection); what remains is not to touch anything new */
		for (k = first[i]; k < first[i + 1] && ok; k++) {
			size_t j = nbr[k];
			double d[3] = {xn[0] - x[3 * j], xn[1] - x[3 * j + 1], xn[2] - x[3 * j + 2]};
			ok = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= (r[i] + r[j]) * (r[i] + r[j]);
		}
		for (w = 0; w < NWALLS && ok; w++) {
			int a = w / 2;
			ok = (w % 2 ? box[3 + a] - x[3 * i + a] - u[a] : x[3 * i + a] + u[a] - box[a]) >= r[i];
		}
		if (!ok)
			continue;
		memcpy(x + 3 * i, xn, sizeof xn);
		moved++;
	}
out:
	free(first), free(fill), free(nbr);
	return moved;
}
