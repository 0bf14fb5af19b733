/* psd: radius distributions (see psd.h). */
#include "pack/psd.h"
#include "base/msg.h"
#include "base/numfmt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int
parse_list(const char *s, double *v, int max)
{
	char buf[256], *tok, *save = NULL;
	int n = 0;

	snprintf(buf, sizeof buf, "%s", s);
	for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
		if (n == max || num_parse(tok, &v[n]))
			return -1;
		n++;
	}
	return n;
}

static int
read_table(const char *path, struct psd *d)
{
	FILE *fp = fopen(path, "r");
	char line[256];
	long ln = 0;
	size_t cap = 0;
	double *w = NULL;

	if (!fp) {
		msg_seterr("%s: cannot open size table", path);
		return -1;
	}
	while (fgets(line, sizeof line, fp)) {
		char a[64], b[64], c[8];
		double r, wt = 1;
		int n;

		ln++;
		if (line[0] == '#' || strspn(line, " \t\r\n") == strlen(line))
			continue;
		n = sscanf(line, "%63s %63s %7s", a, b, c);
		if (n < 1 || n > 2 || num_parse(a, &r) || (n == 2 && num_parse(b, &wt)) || !(r > 0) || !(wt >= 0)) {
			msg_seterr("%s:%ld: expected 'radius [weight]' with radius > 0 and weight >= 0", path, ln);
			goto fail;
		}
		if (d->ntable == cap) {
			cap = cap ? 2 * cap : 64;
			d->table = realloc(d->table, cap * sizeof *d->table);
			w = realloc(w, cap * sizeof *w);
			if (!d->table || !w) {
				msg_seterr("out of memory");
				goto fail;
			}
		}
		d->table[d->ntable] = r;
		w[d->ntable++] = wt;
	}
	fclose(fp);
	fp = NULL;
	if (d->ntable == 0) {
		msg_seterr("%s: the size table is empty", path);
		goto fail;
	}
	d->disc = gsl_ran_discrete_preproc(d->ntable, w);
	if (!d->disc) {
		msg_seterr("%s: the weights do not define a distribution", path);
		goto fail;
	}
	free(w);
	return 0;
fail:
	if (fp)
		fclose(fp);
	free(w);
	return -1;
}

int
psd_parse(const char *spec, struct psd *d)
{
	double v[4];
	int n;

	memset(d, 0, sizeof *d);
	if (strncmp(spec, "uniform:", 8) == 0) {
		n = parse_list(spec + 8, v, 2);
		if (n != 2 || !(v[0] > 0) || !(v[1] >= v[0])) {
			msg_seterr("--psd %s: expected uniform:RMIN,RMAX with 0 < RMIN <= RMAX", spec);
			return -1;
		}
		d->kind = PSD_UNIFORM;
		d->lo = v[0];
		d->hi = v[1];
		return 0;
	}
	if (strncmp(spec, "lognormal:", 10) == 0) {
		n = parse_list(spec + 10, v, 4);
		if ((n != 2 && n != 4) || !(v[0] > 0) || !(v[1] >= 0)) {
			msg_seterr("--psd %s: expected lognormal:MEDIAN,SIGMA[,RMIN,RMAX]", spec);
			return -1;
		}
		d->kind = PSD_LOGNORMAL;
		d->a = v[0];
		d->b = v[1];
		d->lo = n == 4 ? v[2] : v[0] / 5;
		d->hi = n == 4 ? v[3] : v[0] * 5;
		if (!(d->lo > 0) || !(d->hi >= d->lo) || d->a < d->lo || d->a > d->hi) {
			msg_seterr("--psd %s: need 0 < RMIN <= MEDIAN <= RMAX", spec);
			return -1;
		}
		return 0;
	}
	if (strncmp(spec, "table:", 6) == 0) {
		d->kind = PSD_TABLE;
		return read_table(spec + 6, d);
	}
	msg_seterr("--psd %s: unknown distribution (uniform:RMIN,RMAX, lognormal:MEDIAN,SIGMA, table:FILE)", spec);
	return -1;
}

double
psd_draw(const struct psd *d, gsl_rng *rng)
{
	double r;

	switch (d->kind) {
	case PSD_UNIFORM:
		return d->lo + (d->hi - d->lo) * gsl_rng_uniform(rng);
	case PSD_LOGNORMAL:
		do
			r = d->a * exp(d->b * gsl_ran_gaussian(rng, 1.0));
		while (r < d->lo || r > d->hi);
		return r;
	case PSD_TABLE:
		return d->table[gsl_ran_discrete(rng, d->disc)];
	}
	return 0;
}

void
psd_free(struct psd *d)
{
	free(d->table);
	if (d->disc)
		gsl_ran_discrete_free(d->disc);
	memset(d, 0, sizeof *d);
}
