/* dem: explicit DEM compaction for loose packs (see dem.h). */
#include "dem/dem.h"
#include "contact/cell.h"
#include "contact/nlist.h"
#include "base/msg.h"
#include "base/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KT_RATIO 0.888888888888889	/* 2(1-nu)/(2-nu) at nu = 0.2: Mindlin stick over Hertz stiffness */
#define ZETA 0.3			/* viscous normal damping ratio */
#define E_WALL 2.0			/* grain-wall E* over grain-grain E* for rigid walls */

struct dem {
	size_t n;
	double *x, *v, *w, *f, *t, *r, *m, *I;
	double lo[3], hi[3];
	double rmax, skin, dt, mu, damping, rate, viscous;
	int unloading;		/* slow, quasi-static expansion towards the final stress */
	/* two Verlet lists, the current one and the next build, each with the tangential
	 * spring of every listed pair, so springs carry over a rebuild */
	struct nlist list[2];
	double *spring[2];
	size_t spring_cap[2];
	int cur;
	size_t *first, *nbr;	/* the current list's rows */
	double *xi;		/* the current list's springs */
	double *xiw;			/* wall springs, 6 x 3 per grain */
	double wallf[NWALLS];
	struct cell_grid grid;
	size_t ncontacts;
	double sum_cf;			/* sum of contact force magnitudes */
};

static void
dem_free(struct dem *d)
{
	free(d->x), free(d->v), free(d->w), free(d->f), free(d->t), free(d->r), free(d->m), free(d->I);
	nlist_free(&d->list[0]), nlist_free(&d->list[1]);
	free(d->spring[0]), free(d->spring[1]), free(d->xiw);
	cell_free(&d->grid);
}

void
dem_params_default(struct dem_params *dp)
{
	dp->mu = 0.3;
	dp->overlap = 1e-4;
	dp->damping = 0.7;
	dp->phi0 = 0.3;
	dp->aspect[0] = dp->aspect[1] = dp->aspect[2] = 1;
	dp->rest_tol = 2e-2;
	dp->rate = 2e-5;
	dp->viscous = 0;
	dp->preload = 200;
	dp->max_steps = 2000000;
}

/* Random sequential placement without overlap, largest grains first. */
static int
place_random(struct dem *d, gsl_rng *rng, const double *rs, size_t *order)
{
	struct cell_grid *g = &d->grid;
	double edge = 2 * d->rmax, lo[3], inv[3];
	int nc[3], a;
	size_t ncells = 1, k, *head, *next;

	for (a = 0; a < 3; a++) {
		double len = d->hi[a] - d->lo[a];
		nc[a] = (int)fmax(1, fmin(1024, floor(len / edge)));
		lo[a] = d->lo[a];
		inv[a] = nc[a] / len;
		ncells *= (size_t)nc[a];
	}
	(void)g;
	head = malloc(ncells * sizeof *head);
	next = malloc(d->n * sizeof *next);
	if (!head || !next) {
		free(head), free(next);
		msg_seterr("out of memory placing grains");
		return -1;
	}
	for (k = 0; k < ncells; k++)
		head[k] = (size_t)-1;
	for (k = 0; k < d->n; k++) {
		size_t i = order[k];
		double ri = rs[i];
		long tries;

		for (tries = 0; tries < 100000; tries++) {
			double y[3];
			int c[3], ok = 1, dz, dy, dx;

			for (a = 0; a < 3; a++) {
				y[a] = d->lo[a] + ri + (d->hi[a] - d->lo[a] - 2 * ri) * gsl_rng_uniform(rng);
				c[a] = (int)floor((y[a] - lo[a]) * inv[a]);
				c[a] = c[a] < 0 ? 0 : c[a] >= nc[a] ? nc[a] - 1 : c[a];
			}
			for (dz = -1; dz <= 1 && ok; dz++)
				for (dy = -1; dy <= 1 && ok; dy++)
					for (dx = -1; dx <= 1 && ok; dx++) {
						int ox = c[0] + dx, oy = c[1] + dy, oz = c[2] + dz;
						size_t q;
						if (ox < 0 || oy < 0 || oz < 0 || ox >= nc[0] || oy >= nc[1] || oz >= nc[2])
							continue;
						for (q = head[((size_t)oz * nc[1] + oy) * nc[0] + ox]; q != (size_t)-1; q = next[q]) {
							double e0 = y[0] - d->x[3 * q], e1 = y[1] - d->x[3 * q + 1],
							    e2 = y[2] - d->x[3 * q + 2], s = ri + rs[q];
							if (e0 * e0 + e1 * e1 + e2 * e2 < s * s) {
								ok = 0;
								break;
							}
						}
					}
			if (ok) {
				size_t cell = ((size_t)c[2] * nc[1] + c[1]) * nc[0] + c[0];
				memcpy(d->x + 3 * i, y, sizeof y);
				next[i] = head[cell];
				head[cell] = i;
				break;
			}
		}
		if (tries == 100000) {
			free(head), free(next);
			msg_seterr("cannot place grain %zu of %zu at random: lower the initial packing fraction", k + 1, d->n);
			return -1;
		}
	}
	free(head), free(next);
	return 0;
}

/* Renumber the grains in cell order, so that neighbours sit close in memory (a 3-4x
 * speed-up at 1e5 grains); perm[k] receives the caller's index of internal grain k. */
static int
sort_spatially(struct dem *d, size_t *perm)
{
	size_t n = d->n, k, *tmp = malloc(n * sizeof *tmp);
	double *buf = malloc(3 * n * sizeof *buf);
	int a;

	if (!tmp || !buf || cell_build(&d->grid, d->x, n, d->lo, d->hi, 2 * d->rmax)) {
		free(tmp), free(buf);
		msg_seterr("out of memory sorting grains");
		return -1;
	}
	memcpy(perm, d->grid.idx, n * sizeof *perm);
	memcpy(buf, d->x, 3 * n * sizeof *buf);
	for (k = 0; k < n; k++)
		for (a = 0; a < 3; a++)
			d->x[3 * k + a] = buf[3 * perm[k] + a];
#define PERMUTE(arr)                                  \
	do {                                          \
		memcpy(buf, arr, n * sizeof *buf);   \
		for (k = 0; k < n; k++)               \
			arr[k] = buf[perm[k]];        \
	} while (0)
	PERMUTE(d->r);
	PERMUTE(d->m);
	PERMUTE(d->I);
#undef PERMUTE
	free(tmp), free(buf);
	return 0;
}

/* Build the next list and carry the springs of pairs that were already listed. */
static int
build_list(struct dem *d)
{
	int nx = 1 - d->cur;
	struct nlist *old = &d->list[d->cur], *nl = &d->list[nx];
	size_t i, k, n = d->n;

	if (nlist_build(nl, d->x, d->r, n, d->lo, d->hi, d->rmax, d->skin))
		return -1;
	if (nl->npairs > d->spring_cap[nx] || !d->spring[nx]) {
		size_t cap = nl->npairs + nl->npairs / 4 + 16;
		free(d->spring[nx]);
		d->spring[nx] = malloc(3 * cap * sizeof *d->spring[nx]);
		if (!d->spring[nx]) {
			msg_seterr("out of memory for the neighbour list");
			return -1;
		}
		d->spring_cap[nx] = cap;
	}
	for (i = 0; i < n; i++) {
		size_t o = old->first ? old->first[i] : 0, oe = old->first ? old->first[i + 1] : 0;
		for (k = nl->first[i]; k < nl->first[i + 1]; k++) {
			double *to = d->spring[nx] + 3 * k;
			while (o < oe && old->nbr[o] < nl->nbr[k])
				o++;
			if (o < oe && old->nbr[o] == nl->nbr[k])
				memcpy(to, d->spring[d->cur] + 3 * o, 3 * sizeof *to);
			else
				to[0] = to[1] = to[2] = 0;
		}
	}
	d->cur = nx;
	d->first = nl->first;
	d->nbr = nl->nbr;
	d->xi = d->spring[nx];
	return 0;
}

/* Tangential spring update and Coulomb limit; returns the tangential force on i in ft. */
static void
tangential(double *xi, const double n[3], const double vt[3], double dt, double kt, double fmaxt, double ft[3])
{
	double xn = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2], old, now, s;
	int a;

	old = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	for (a = 0; a < 3; a++)
		xi[a] -= xn * n[a];	/* turn the spring into the current tangent plane */
	now = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
	s = now > 0 ? old / now : 0;
	for (a = 0; a < 3; a++) {
		xi[a] = xi[a] * s + vt[a] * dt;
		ft[a] = -kt * xi[a];
	}
	now = sqrt(ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
	if (now > fmaxt && now > 0) {
		s = fmaxt / now;
		for (a = 0; a < 3; a++) {
			ft[a] *= s;
			xi[a] = -ft[a] / kt;
		}
	}
}

static void
forces(struct dem *d)
{
	size_t i, k, n = d->n;
	int a, wl;

	memset(d->f, 0, 3 * n * sizeof *d->f);
	memset(d->t, 0, 3 * n * sizeof *d->t);
	memset(d->wallf, 0, sizeof d->wallf);
	d->ncontacts = 0;
	d->sum_cf = 0;
	for (i = 0; i < n; i++) {
		const double *xi_ = d->x + 3 * i;
		double ri = d->r[i];
		for (k = d->first[i]; k < d->first[i + 1]; k++) {
			size_t j = d->nbr[k];
			double dx[3], d2, sum = ri + d->r[j], dist, h, nn[3], Rs, kn, fn, meff, vr[3], ca[3], cb[3], wr[3],
			    vn, vt[3], ft[3], F[3], c[3];

			for (a = 0; a < 3; a++)
				dx[a] = xi_[a] - d->x[3 * j + a];
			d2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
			if (d2 >= sum * sum) {
				d->xi[3 * k] = d->xi[3 * k + 1] = d->xi[3 * k + 2] = 0;
				continue;
			}
			dist = sqrt(d2);
			h = sum - dist;
			for (a = 0; a < 3; a++)
				nn[a] = dx[a] / dist;
			Rs = ri * d->r[j] / sum;
			kn = 2 * sqrt(Rs * h);
			fn = kn * h * (2.0 / 3.0);
			meff = d->m[i] * d->m[j] / (d->m[i] + d->m[j]);
			for (a = 0; a < 3; a++)
				wr[a] = -ri * nn[a];
			vec3_cross(d->w + 3 * i, wr, ca);
			for (a = 0; a < 3; a++)
				wr[a] = d->r[j] * nn[a];
			vec3_cross(d->w + 3 * j, wr, cb);
			for (a = 0; a < 3; a++)
				vr[a] = d->v[3 * i + a] + ca[a] - d->v[3 * j + a] - cb[a];
			vn = vr[0] * nn[0] + vr[1] * nn[1] + vr[2] * nn[2];
			fn -= 2 * ZETA * sqrt(meff * kn) * vn;
			if (fn < 0)
				fn = 0;
			for (a = 0; a < 3; a++)
				vt[a] = vr[a] - vn * nn[a];
			tangential(d->xi + 3 * k, nn, vt, d->dt, KT_RATIO * kn, d->mu * fn, ft);
			for (a = 0; a < 3; a++) {
				F[a] = fn * nn[a] + ft[a];
				d->f[3 * i + a] += F[a];
				d->f[3 * j + a] -= F[a];
			}
			vec3_cross(nn, ft, c);
			for (a = 0; a < 3; a++) {
				d->t[3 * i + a] -= ri * c[a];
				d->t[3 * j + a] -= d->r[j] * c[a];
			}
			d->ncontacts++;
			d->sum_cf += sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
		}
		for (wl = 0; wl < NWALLS; wl++) {
			int ax = wl / 2;
			double nn[3] = {0, 0, 0}, dist, h, kn, fn, vr[3], wr[3], ca[3], vn, vt[3], ft[3], c[3];
			double *spring = d->xiw + 18 * i + 3 * wl;

			nn[ax] = wl % 2 ? -1 : 1;
			dist = wl % 2 ? d->hi[ax] - xi_[ax] : xi_[ax] - d->lo[ax];
			h = ri - dist;
			if (h <= 0) {
				spring[0] = spring[1] = spring[2] = 0;
				continue;
			}
			kn = 2 * E_WALL * sqrt(ri * h);
			fn = kn * h * (2.0 / 3.0);
			d->wallf[wl] += fn;
			for (a = 0; a < 3; a++)
				wr[a] = -ri * nn[a];
			vec3_cross(d->w + 3 * i, wr, ca);
			for (a = 0; a < 3; a++)
				vr[a] = d->v[3 * i + a] + ca[a];
			vn = vr[ax] * nn[ax];
			fn -= 2 * ZETA * sqrt(d->m[i] * kn) * vn;
			if (fn < 0)
				fn = 0;
			for (a = 0; a < 3; a++)
				vt[a] = vr[a] - vn * nn[a];
			tangential(spring, nn, vt, d->dt, KT_RATIO * kn, d->mu * fn, ft);
			for (a = 0; a < 3; a++)
				d->f[3 * i + a] += fn * nn[a] + ft[a];
			vec3_cross(nn, ft, c);
			for (a = 0; a < 3; a++)
				d->t[3 * i + a] -= ri * c[a];
			d->ncontacts++;
			d->sum_cf += fn;
		}
	}
}

/* Mean |net force| over grains with contacts, over the mean contact force. */
static double
unbalanced(const struct dem *d)
{
	double s = 0;
	size_t i;

	if (d->ncontacts == 0 || d->sum_cf == 0)
		return INFINITY;
	for (i = 0; i < d->n; i++)
		s += sqrt(d->f[3 * i] * d->f[3 * i] + d->f[3 * i + 1] * d->f[3 * i + 1] + d->f[3 * i + 2] * d->f[3 * i + 2]);
	return (s / d->n) / (d->sum_cf / d->ncontacts);
}

static void
integrate(struct dem *d)
{
	size_t k, n3 = 3 * d->n;
	double dt = d->dt, al = d->damping, keep = 1 - d->viscous;

	for (k = 0; k < n3; k++) {
		size_t i = k / 3;
		double f = d->f[k], t = d->t[k];
		/* Cundall's local damping: remove a fraction of the force that drives the motion */
		f -= al * fabs(f) * (d->v[k] > 0 ? 1 : d->v[k] < 0 ? -1 : 0);
		t -= al * fabs(t) * (d->w[k] > 0 ? 1 : d->w[k] < 0 ? -1 : 0);
		/* background viscous damping: free flight decays, so no granular gas builds up
		 * whose kinetic pressure the wall servo would mistake for a force network */
		d->v[k] = d->v[k] * keep + f / d->m[i] * dt;
		d->w[k] = d->w[k] * keep + t / d->I[i] * dt;
		d->x[k] += d->v[k] * dt;
	}
}

/* Move the walls of each axis towards the target stress and map the grains affinely. */
static void
servo(struct dem *d, double ptarget, double *ratio_mean)
{
	double de[3], c[3], rs = 0;
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		int b = (a + 1) % 3, e = (a + 2) % 3;
		double area = (d->hi[b] - d->lo[b]) * (d->hi[e] - d->lo[e]);
		double sig = (d->wallf[2 * a] + d->wallf[2 * a + 1]) / (2 * area), ratio = sig / ptarget, g;

		rs += ratio / 3;
		g = fmax(-1, fmin(1, 1 - ratio));
		/* proportional control: full rate far from the target, slowing down near it */
		de[a] = g * (d->unloading ? d->rate * 0.05 : d->rate);
		c[a] = 0.5 * (d->lo[a] + d->hi[a]);
		d->lo[a] = c[a] + (d->lo[a] - c[a]) * (1 - de[a]);
		d->hi[a] = c[a] + (d->hi[a] - c[a]) * (1 - de[a]);
	}
	for (i = 0; i < d->n; i++)
		for (a = 0; a < 3; a++)
			d->x[3 * i + a] = c[a] + (d->x[3 * i + a] - c[a]) * (1 - de[a]);
	*ratio_mean = rs;
}

static double
max_overlap(const struct dem *d, double *coord)
{
	size_t i, k, nc = 0;
	double mo = 0;
	int a, wl;

	for (i = 0; i < d->n; i++) {
		for (k = d->first[i]; k < d->first[i + 1]; k++) {
			size_t j = d->nbr[k];
			double e2 = 0, s = d->r[i] + d->r[j];
			for (a = 0; a < 3; a++) {
				double e = d->x[3 * i + a] - d->x[3 * j + a];
				e2 += e * e;
			}
			if (e2 < s * s) {
				mo = fmax(mo, (s - sqrt(e2)) / fmin(d->r[i], d->r[j]));
				nc += 2;
			}
		}
		for (wl = 0; wl < NWALLS; wl++) {
			int ax = wl / 2;
			double dist = wl % 2 ? d->hi[ax] - d->x[3 * i + ax] : d->x[3 * i + ax] - d->lo[ax];
			if (dist < d->r[i]) {
				mo = fmax(mo, (d->r[i] - dist) / d->r[i]);
				nc++;
			}
		}
	}
	*coord = (double)nc / d->n;
	return mo;
}

/* Time step from the stiffest likely contact: the two smallest grains, or the smallest
 * grain on a wall, at overlap h (relative to the radius). */
static void
dt_for_overlap(struct dem *d, double mmin, double rmin, double h)
{
	double k = fmax(2 * sqrt(0.5 * rmin * h * rmin), 2 * E_WALL * sqrt(rmin * h * rmin));

	d->dt = 0.2 * sqrt(0.5 * mmin / k);
}

int
dem_loose_pack(struct pack *p, const struct dem_params *dp, gsl_rng *rng, dem_progress_fn fn, void *ctx,
    struct dem_status *st)
{
	struct dem d;
	size_t n = p->n, i, *order = NULL;
	double rmean = 0, vol = 0, L0, ptarget, pfinal, mmin = INFINITY, rmin = INFINITY;
	int a, status = -1, rebuilds = 0;
	long step;

	memset(&d, 0, sizeof d);
	memset(st, 0, sizeof *st);
	if (n == 0) {
		msg_seterr("no grains to place");
		return -1;
	}
	for (i = 0; i < n; i++)
		rmean += p->r[i];
	rmean /= n;
	d.n = n;
	d.x = calloc(3 * n, sizeof *d.x);
	d.v = calloc(3 * n, sizeof *d.v);
	d.w = calloc(3 * n, sizeof *d.w);
	d.f = calloc(3 * n, sizeof *d.f);
	d.t = calloc(3 * n, sizeof *d.t);
	d.r = malloc(n * sizeof *d.r);
	d.m = malloc(n * sizeof *d.m);
	d.I = malloc(n * sizeof *d.I);
	nlist_init(&d.list[0]);
	nlist_init(&d.list[1]);
	d.xiw = calloc(18 * n, sizeof *d.xiw);
	order = malloc(n * sizeof *order);
	cell_init(&d.grid);
	if (!d.x || !d.v || !d.w || !d.f || !d.t || !d.r || !d.m || !d.I || !d.xiw || !order) {
		msg_seterr("out of memory for %zu grains", n);
		goto out;
	}
	for (i = 0; i < n; i++) {
		d.r[i] = p->r[i] / rmean;
		d.m[i] = 4.0 / 3.0 * M_PI * d.r[i] * d.r[i] * d.r[i];
		d.I[i] = 0.4 * d.m[i] * d.r[i] * d.r[i];
		vol += d.m[i];
		d.rmax = fmax(d.rmax, d.r[i]);
		rmin = fmin(rmin, d.r[i]);
		mmin = fmin(mmin, d.m[i]);
		order[i] = i;
	}
	{
		/* largest first, so random placement rarely fails: counting sort of radii into 256 bins, descending */
		size_t bins[257] = {0}, *tmp = malloc(n * sizeof *tmp);
		if (!tmp) {
			msg_seterr("out of memory");
			goto out;
		}
		for (i = 0; i < n; i++)
			bins[255 - (int)fmin(255, floor((d.r[i] - rmin) / (d.rmax - rmin + 1e-300) * 255.999)) + 1]++;
		for (i = 0; i < 256; i++)
			bins[i + 1] += bins[i];
		for (i = 0; i < n; i++)
			tmp[bins[255 - (int)fmin(255, floor((d.r[i] - rmin) / (d.rmax - rmin + 1e-300) * 255.999))]++] = i;
		memcpy(order, tmp, n * sizeof *order);
		free(tmp);
	}
	L0 = cbrt(vol / dp->phi0 / (dp->aspect[0] * dp->aspect[1] * dp->aspect[2]));
	for (a = 0; a < 3; a++) {
		d.lo[a] = 0;
		d.hi[a] = L0 * dp->aspect[a];
	}
	if (place_random(&d, rng, d.r, order))
		goto out;
	if (sort_spatially(&d, order))
		goto out;
	d.mu = dp->mu;
	d.damping = dp->damping;
	d.rate = dp->rate;
	d.viscous = dp->viscous;
	d.skin = 0.3 * rmin;
	/* target stress from the mean overlap: Love-Weber p = Z phi <F> / (4 pi r^2) with
	 * Z ~ 4.5 and phi ~ 0.6 for a loose frictional pack, <F> the Hertz force at the overlap
	 * between two mean grains (E* = 1, R* = 1/2) */
	/* Target stress from the mean overlap: Love-Weber p = Z phi <F> / (4 pi r^2) with
	 * Z ~ 4.5 and phi ~ 0.6 for a loose frictional pack and <F> the Hertz force at that
	 * overlap between two mean grains (E* = 1, R* = 1/2).  Such a small stress cannot be
	 * told apart from the kinetic and drag stresses of a compacting gas, so the pack is
	 * first jammed at a stress 'preload' times larger (mean overlap ~ 30x) and then
	 * unloaded to the target: unloading is nearly elastic and the frictional contact
	 * network, hence the loose structure, survives it. */
	pfinal = 4.5 * 0.6 * (4.0 / 3.0 * sqrt(0.5) * pow(dp->overlap, 1.5)) / (4 * M_PI);
	ptarget = pfinal * dp->preload;
	dt_for_overlap(&d, mmin, rmin, fmax(dp->overlap, 1e-6) * pow(dp->preload, 2.0 / 3.0) * 10);
	if (build_list(&d))
		goto out;
	for (step = 1; step <= dp->max_steps; step++) {
		double ratio;

		if (nlist_stale(&d.list[d.cur], d.x, d.lo, d.hi)) {
			if (build_list(&d))
				goto out;
			rebuilds++;
		}
		forces(&d);
		if (step % 100 == 0 || step == dp->max_steps) {
			double coord, ub = unbalanced(&d);
			st->step = step;
			st->unbalanced = ub;
			st->max_overlap = max_overlap(&d, &coord);
			st->coordination = coord;
			st->phi = vol / ((d.hi[0] - d.lo[0]) * (d.hi[1] - d.lo[1]) * (d.hi[2] - d.lo[2]));
			{
				double s = 0;
				for (a = 0; a < 3; a++) {
					int b = (a + 1) % 3, e = (a + 2) % 3;
					s += (d.wallf[2 * a] + d.wallf[2 * a + 1]) / (2 * (d.hi[b] - d.lo[b]) * (d.hi[e] - d.lo[e]));
				}
				st->p_ratio = s / 3 / ptarget;
				st->stage = ptarget > pfinal ? 1 : 2;
			}
			/* the stresses only set the overlap scale: within a factor of 1.25 of the preload
			 * and of 2 of the final target is close enough; rest is what matters */
			st->at_rest = fabs(log(st->p_ratio)) < log(ptarget > pfinal ? 1.25 : 2.0) && ub < dp->rest_tol;
			if (fn && step % 1000 == 0)
				fn(st, ctx);
			if (st->at_rest && ptarget > pfinal) {
				ptarget = pfinal;	/* jammed at the preload: now unload */
				d.unloading = 1;
				st->at_rest = 0;
			} else if (st->at_rest) {
				break;
			}
			dt_for_overlap(&d, mmin, rmin, fmax(st->max_overlap, dp->overlap));
		}
		integrate(&d);
		servo(&d, ptarget, &ratio);
	}
	if (!st->at_rest) {
		msg_seterr("the pack did not come to rest in %ld steps (stress/target %.3g, unbalanced %.3g)",
		    dp->max_steps, st->p_ratio, st->unbalanced);
		goto out;
	}
	/* The pack takes the spatial order too (ids 1..N along it): every later stage then
	 * walks memory in the order neighbours are met.  Radii and moduli were drawn
	 * independently, so renumbering loses nothing. */
	{
		double *tmp = malloc(n * sizeof *tmp);
		double *arrs[4] = {p->r, p->E, p->nu, p->rho};
		int q;

		if (!tmp) {
			msg_seterr("out of memory");
			goto out;
		}
		for (q = 0; q < 4; q++) {
			memcpy(tmp, arrs[q], n * sizeof *tmp);
			for (i = 0; i < n; i++)
				arrs[q][i] = tmp[order[i]];
		}
		free(tmp);
	}
	for (i = 0; i < n; i++) {
		p->id[i] = (long)i + 1;
		for (a = 0; a < 3; a++)
			p->x[3 * i + a] = d.x[3 * i + a] * rmean;
	}
	for (a = 0; a < 3; a++) {
		p->box[a] = d.lo[a] * rmean;
		p->box[a + 3] = d.hi[a] * rmean;
	}
	status = 0;
out:
	free(order);
	dem_free(&d);
	return status;
}
