/* nlist: Verlet lists over the cell grid (see nlist.h). */
#include "contact/nlist.h"
#include "base/par.h"
#include "base/msg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void
nlist_init(struct nlist *nl)
{
	memset(nl, 0, sizeof *nl);
	cell_init(&nl->grid);
}

void
nlist_free(struct nlist *nl)
{
	free(nl->first);
	free(nl->nbr);
	free(nl->xb);
	free(nl->fill);
	cell_free(&nl->grid);
	memset(nl, 0, sizeof *nl);
}

struct pass_ctx {
	struct nlist *nl;
	int pass;
};

static int
on_pair(size_t i, size_t j, double dx[3], double d2, void *vctx)
{
	struct pass_ctx *c = vctx;

	(void)dx;
	(void)d2;
	if (c->pass == 0)
		c->nl->first[i + 1]++;
	else
		c->nl->nbr[c->nl->fill[i]++] = j;
	return 0;
}

int
nlist_build(struct nlist *nl, const double *x, const double *r, size_t n, const double lo[3], const double hi[3],
    double rmax, double skin, const int *periodic)
{
	struct pass_ctx c = {nl, 0};
	size_t i, k;

	if (n != nl->n || !nl->first) {
		free(nl->first), free(nl->xb), free(nl->fill);
		nl->first = malloc((n + 1) * sizeof *nl->first);
		nl->xb = malloc(3 * n * sizeof *nl->xb);
		nl->fill = malloc((n ? n : 1) * sizeof *nl->fill);
		nl->n = n;
		if (!nl->first || !nl->xb || !nl->fill) {
			msg_seterr("out of memory for the neighbour list");
			return -1;
		}
	}
	nl->skin = skin;
	nl->rmax = rmax;
	if (cell_build(&nl->grid, x, n, lo, hi, 2 * rmax + skin, periodic))
		return -1;
	memset(nl->first, 0, (n + 1) * sizeof *nl->first);
	cell_for_pairs(&nl->grid, x, r, skin, on_pair, &c);
	for (i = 0; i < n; i++)
		nl->first[i + 1] += nl->first[i];
	if (nl->first[n] > nl->cap || !nl->nbr) {
		size_t cap = nl->first[n] + nl->first[n] / 4 + 16;
		free(nl->nbr);
		nl->nbr = malloc(cap * sizeof *nl->nbr);
		if (!nl->nbr) {
			msg_seterr("out of memory for the neighbour list");
			return -1;
		}
		nl->cap = cap;
	}
	memcpy(nl->fill, nl->first, n * sizeof *nl->fill);
	c.pass = 1;
	cell_for_pairs(&nl->grid, x, r, skin, on_pair, &c);
	/* rows sorted by j: deterministic order of summation, and merges of two lists */
	for (i = 0; i < n; i++)
		for (k = nl->first[i] + 1; k < nl->first[i + 1]; k++) {
			size_t v = nl->nbr[k], q = k;
			while (q > nl->first[i] && nl->nbr[q - 1] > v) {
				nl->nbr[q] = nl->nbr[q - 1];
				q--;
			}
			nl->nbr[q] = v;
		}
	nl->npairs = nl->first[n];
	memcpy(nl->xb, x, 3 * n * sizeof *x);
	memcpy(nl->blo, lo, sizeof nl->blo);
	memcpy(nl->bhi, hi, sizeof nl->bhi);
	nl->builds++;
	return 0;
}

int
nlist_stale(const struct nlist *nl, const double *x, const double lo[3], const double hi[3])
{
	double maxd2 = 0, shrink = 0, s[3];
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		s[a] = (hi[a] - lo[a]) / (nl->bhi[a] - nl->blo[a]);
		shrink = fmax(shrink, 1 - s[a]);
	}
	/* a largest value is exact in any order: threads (base/par.h) cannot change it */
#pragma omp parallel for schedule(static) reduction(max : maxd2) if (nl->n >= PAR_MIN)
	for (i = 0; i < nl->n; i++) {
		double e2 = 0;
		int b;
		for (b = 0; b < 3; b++) {
			double ref = lo[b] + (nl->xb[3 * i + b] - nl->blo[b]) * s[b];
			double e = x[3 * i + b] - ref;
			e2 += e * e;
		}
		if (e2 > maxd2)
			maxd2 = e2;
	}
	return 2 * sqrt(maxd2) + shrink * (2 * nl->rmax + nl->skin) > nl->skin;
}
