/* functional: Hertz energy and gradient over a pack (see functional.h). */
#include "functional.h"
#include "friction.h"
#include "msg.h"

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
			double dist = w % 2 ? box[3 + a] - xi[a] : xi[a] - box[a], h = ri - dist, Es, P;

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
			int a = w / 2;
			double dist = w % 2 ? box[3 + a] - x[3 * i + a] : x[3 * i + a] - box[a];
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
