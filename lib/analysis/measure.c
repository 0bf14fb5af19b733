/* measure: porosity, coordination, stresses, residual, fabric (see measure.h). */
#include "analysis/measure.h"
#include "base/msg.h"
#include "qs/functional.h"
#include "base/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
measure_coordination(const struct pack *p, const struct geo_contacts *gc, unsigned *counts)
{
	size_t k;

	memset(counts, 0, p->n * sizeof *counts);
	for (k = 0; k < gc->n; k++) {
		counts[gc->c[k].i]++;
		if (!PACK_IS_WALL(gc->c[k].j))
			counts[gc->c[k].j]++;
	}
}

size_t
measure_rattlers(const struct pack *p, const struct geo_contacts *gc, unsigned char *flag)
{
	unsigned *cnt = malloc((p->n ? p->n : 1) * sizeof *cnt);
	size_t k, nr = 0;
	int changed = 1;

	if (!cnt)
		return 0;
	memset(flag, 0, p->n);
	measure_coordination(p, gc, cnt);
	/* iterate to a fixed point; each sweep removes at least one grain or stops */
	while (changed) {
		changed = 0;
		for (k = 0; k < p->n; k++)
			if (!flag[k] && cnt[k] < 4) {
				flag[k] = 1;
				nr++;
				changed = 1;
			}
		if (!changed)
			break;
		measure_coordination(p, gc, cnt);
		for (k = 0; k < gc->n; k++) {
			size_t i = gc->c[k].i;
			long j = gc->c[k].j;
			if (PACK_IS_WALL(j))
				continue;
			/* a contact with a removed grain no longer counts */
			if (flag[i] && !flag[j])
				cnt[j]--;
			else if (flag[j] && !flag[i])
				cnt[i]--;
		}
	}
	free(cnt);
	return nr;
}

/* Lever arm lengths from centres to the contact plane (physics.md §3). */
static void
lever_lengths(const struct pack *p, const struct geo_contact *c, double *li, double *lj)
{
	double Ri = p->r[c->i], Rj, d = c->d, A2;

	if (PACK_IS_WALL(c->j)) {
		*li = Ri - c->h;
		*lj = 0;
		return;
	}
	Rj = p->r[c->j];
	A2 = (d - Ri + Rj) * (d + Ri - Rj) * (Ri + Rj - d) * (Ri + Rj + d) / (4 * d * d);
	if (A2 < 0)
		A2 = 0;
	*li = sqrt(fmax(Ri * Ri - A2, 0));
	*lj = sqrt(fmax(Rj * Rj - A2, 0));
}

int
measure_pack(const struct pack *p, struct geo_contacts *gc, struct pack_measures *m)
{
	unsigned *cnt;
	unsigned char *rat;
	double *F, *M, *fbig;
	double sumr = 0, sumr2 = 0, Psum = 0, fsum = 0, Fsum = 0;
	size_t k, nsl = 0, nfr = 0, nres = 0, nnr = 0, cnr = 0;
	int a;

	memset(m, 0, sizeof *m);
	m->sliding_ratio = NAN;
	if (contacts_find(p, gc))
		return -1;
	cnt = malloc(p->n * sizeof *cnt);
	rat = malloc(p->n);
	F = calloc(3 * p->n, sizeof *F);
	M = calloc(3 * p->n, sizeof *M);
	fbig = calloc(p->n, sizeof *fbig);
	if (!cnt || !rat || !F || !M || !fbig) {
		free(cnt), free(rat), free(F), free(M), free(fbig);
		msg_seterr("out of memory");
		return -1;
	}
	m->grains = p->n;
	m->volume = pack_box_volume(p->box);
	m->porosity = 1 - pack_grain_volume(p) / m->volume;
	m->r_min = INFINITY;
	for (k = 0; k < p->n; k++) {
		sumr += p->r[k];
		sumr2 += p->r[k] * p->r[k];
		m->r_min = fmin(m->r_min, p->r[k]);
		m->r_max = fmax(m->r_max, p->r[k]);
	}
	m->r_mean = sumr / p->n;
	m->r_std = p->n > 1 ? sqrt(fmax(sumr2 - sumr * sumr / p->n, 0) / (p->n - 1)) : 0;

	measure_coordination(p, gc, cnt);
	m->rattlers = measure_rattlers(p, gc, rat);
	for (k = 0; k < p->n; k++) {
		m->under4 += cnt[k] < 4;
		m->coordination += cnt[k];
	}
	m->coordination /= p->n;

	for (k = 0; k < gc->n; k++) {
		const struct geo_contact *c = &gc->c[k];
		double Rmin = PACK_IS_WALL(c->j) ? p->r[c->i] : fmin(p->r[c->i], p->r[c->j]);
		double f[3], Q[3] = {0, 0, 0}, Mt = 0, li, lj, t[3], fm;
		size_t i = c->i;

		if (PACK_IS_WALL(c->j)) {
			m->contacts_gw++;
		} else {
			m->contacts_gg++;
			m->fabric[0] += c->n[0] * c->n[0];
			m->fabric[1] += c->n[1] * c->n[1];
			m->fabric[2] += c->n[2] * c->n[2];
			m->fabric[3] += c->n[0] * c->n[1];
			m->fabric[4] += c->n[0] * c->n[2];
			m->fabric[5] += c->n[1] * c->n[2];
			if (!rat[i] && !rat[c->j])
				cnr += 2;
		}
		if (PACK_IS_WALL(c->j) && !rat[i])
			cnr++;
		m->overlap_max = fmax(m->overlap_max, c->h / Rmin);
		if (c->hist >= 0) {
			memcpy(Q, p->c[c->hist].Q0, sizeof Q);
			Mt = p->c[c->hist].M0;
		}
		for (a = 0; a < 3; a++)
			f[a] = c->P * c->n[a] + Q[a];
		fm = vec3_norm(f);
		Psum += c->P;
		fsum += fm;
		m->P_max = fmax(m->P_max, c->P);
		lever_lengths(p, c, &li, &lj);
		/* Love-Weber: sum over contacts of branch (x) force, compression positive */
		{
			double l = li + lj, ff[3];
			for (a = 0; a < 3; a++)
				ff[a] = c->P * c->n[a] + Q[a];
			m->sig_lw[0] += l * c->n[0] * ff[0];
			m->sig_lw[1] += l * c->n[1] * ff[1];
			m->sig_lw[2] += l * c->n[2] * ff[2];
			m->sig_lw[3] += l * 0.5 * (c->n[0] * ff[1] + c->n[1] * ff[0]);
			m->sig_lw[4] += l * 0.5 * (c->n[0] * ff[2] + c->n[2] * ff[0]);
			m->sig_lw[5] += l * 0.5 * (c->n[1] * ff[2] + c->n[2] * ff[1]);
		}
		if (PACK_IS_WALL(c->j))
			m->sig_wall[PACK_WALL_INDEX(c->j) / 2] += c->P;
		/* balance of grain i: force f, moment of Q about the centre plus torsion */
		for (a = 0; a < 3; a++)
			F[3 * i + a] += f[a];
		{
			double arm[3] = {-c->n[0] * li, -c->n[1] * li, -c->n[2] * li};
			vec3_cross(arm, Q, t);
			for (a = 0; a < 3; a++)
				M[3 * i + a] += t[a] + Mt * c->n[a];
		}
		fbig[i] = fmax(fbig[i], fm);
		if (!PACK_IS_WALL(c->j)) {
			size_t j = (size_t)c->j;
			double arm[3] = {c->n[0] * lj, c->n[1] * lj, c->n[2] * lj}, mQ[3] = {-Q[0], -Q[1], -Q[2]};
			for (a = 0; a < 3; a++)
				F[3 * j + a] -= f[a];
			vec3_cross(arm, mQ, t);
			for (a = 0; a < 3; a++)
				M[3 * j + a] += t[a] - Mt * c->n[a];
			fbig[j] = fmax(fbig[j], fm);
		}
	}
	for (k = 0; k < p->n; k++)
		if (!rat[k])
			nnr++;
	m->coordination_nr = nnr ? (double)cnr / nnr : 0;
	if (m->contacts_gg) {
		double d[6], dd;
		for (a = 0; a < 6; a++)
			m->fabric[a] /= m->contacts_gg;
		memcpy(d, m->fabric, sizeof d);
		for (a = 0; a < 3; a++)
			d[a] -= 1.0 / 3.0;
		dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5]);
		m->fabric_anisotropy = 7.5 * sqrt(1.5 * dd);
	}
	m->has_forces = gc->n > 0 && m->P_max > 0;
	if (m->has_forces) {
		size_t nct = gc->n;
		for (a = 0; a < 3; a++) {
			double area = pack_box_length(p->box, (a + 1) % 3) * pack_box_length(p->box, (a + 2) % 3);
			m->sig_wall[a] /= 2 * area;
		}
		m->sigma_c = (m->sig_wall[0] + m->sig_wall[1] + m->sig_wall[2]) / 3;
		for (a = 0; a < 6; a++)
			m->sig_lw[a] /= m->volume;
		m->P_mean = Psum / nct;
		for (k = 0; k < p->n; k++) {
			double fr, mr, floor_ = QS_RESIDUAL_FLOOR * m->P_mean;
			if (!(fbig[k] > 0))
				continue;
			fr = vec3_norm(F + 3 * k);
			mr = vec3_norm(M + 3 * k) / p->r[k];
			m->residual_strict = fmax(m->residual_strict, fmax(fr, mr) / fbig[k]);
			m->residual_max = fmax(m->residual_max, fmax(fr, mr) / fmax(fbig[k], floor_));
			Fsum += fr;
			nres++;
		}
		m->residual_mean = nres ? (Fsum / nres) / (fsum / nct) : 0;
	}
	m->history = p->nc;
	for (k = 0; k < gc->n; k++)
		if (gc->c[k].hist >= 0) {
			const struct pack_contact *h = &p->c[gc->c[k].hist];
			double mu = PACK_IS_WALL(h->j) ? p->wall_mu : p->mu, qmax = mu * h->P0;
			nfr++;
			if (qmax > 0 && vec3_norm(h->Q0) >= qmax * (1 - 1e-9))
				nsl++;
		}
	m->stale_history = p->nc - nfr;
	if (p->nc > 0)
		m->sliding_ratio = gc->n ? (double)nsl / gc->n : 0;
	free(cnt), free(rat), free(F), free(M), free(fbig);
	return 0;
}
