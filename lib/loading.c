/* loading: strain increments with the affine guess (see loading.h). */
#include "loading.h"

#include <math.h>
#include <string.h>

void
load_strain_box(double box[6], double *x, size_t n, const double de[3])
{
	double c[3], f[3];
	size_t i;
	int a;

	for (a = 0; a < 3; a++) {
		c[a] = 0.5 * (box[a] + box[3 + a]);
		f[a] = 1 - de[a];
		box[a] = c[a] + (box[a] - c[a]) * f[a];
		box[3 + a] = c[a] + (box[3 + a] - c[a]) * f[a];
	}
	for (i = 0; i < n; i++)
		for (a = 0; a < 3; a++)
			x[3 * i + a] = c[a] + (x[3 * i + a] - c[a]) * f[a];
}

int
load_increment(struct qs_system *s, double *x, const double de[3], int nsub, long k_inc,
    const struct qs_min_params *mp, struct qs_min_report *rep)
{
	struct qs_min_params sub = *mp;
	struct qs_min_report r;
	long iter = 0, evals = 0;
	double part[3];
	int k, a, st = 0;

	if (nsub < 1)
		nsub = 1;
	/* equal parts of the total scale factor, so nsub parts compose to exactly 1 - de */
	for (a = 0; a < 3; a++)
		part[a] = 1 - pow(1 - de[a], 1.0 / nsub);
	for (k = 0; k < nsub; k++) {
		load_strain_box(s->p->box, x, s->n, part);
		sub.max_iter = k + 1 < nsub ? k_inc : mp->max_iter;
		st = qs_minimize(s, x, &sub, &r);
		iter += r.iter;
		evals += r.evals;
		if (st < 0)
			break;
		if (k + 1 < nsub && st == 1)
			st = 0;	/* a sub-increment stopped at k_inc iterations by design */
	}
	*rep = r;
	rep->iter = iter;
	rep->evals = evals;
	return st;
}

void
load_strain(const double box[6], const double refbox[6], double eps[3])
{
	int a;

	for (a = 0; a < 3; a++) {
		double lref = refbox[3 + a] - refbox[a];
		eps[a] = (lref - (box[3 + a] - box[a])) / lref;
	}
}
