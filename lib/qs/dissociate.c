/* SPDX-License-Identifier: GPL-3.0-or-later */
/* dissociate: hydrate dissociation in a pack (see dissociate.h). */
#include "qs/dissociate.h"
#include "base/msg.h"

#include <math.h>
#include <string.h>

double
dissociate_grain_K(double E, double nu)
{
	return E / (3 * (1 - 2 * nu));
}

int
dissociate_check(const struct pack *p, const struct dissociation *d, double *S)
{
	double kmin = INFINITY;
	size_t i;

	*S = pack_hydrate_saturation(p);
	if (!(d->dS <= 0))
		return msg_seterr("--dS %g: must be <= 0 (dissociation; hydrate formation is not modelled)", d->dS), -1;
	if (!(d->pex >= 0 && isfinite(d->pex)))
		return msg_seterr("--pex %g: must be >= 0 (an excess pore pressure, Pa)", d->pex), -1;
	if (!(d->alpha > 0 && d->alpha <= 1))
		return msg_seterr("--alpha %g: must be in (0, 1]", d->alpha), -1;
	if (!isnan(d->K) && !(d->K > 0 && isfinite(d->K)))
		return msg_seterr("--K %g: must be positive (Pa)", d->K), -1;
	if (!(d->probe > 0 && d->probe <= 1e-3))
		return msg_seterr("--probe-strain %g: must be in (0, 1e-3]", d->probe), -1;
	if (d->dS < 0 && *S == 0)
		return msg_seterr("--dS %g: the pack has no hydrate grains (no phase column, or none tagged 1)", d->dS), -1;
	if (d->dS < 0 && !(d->dS > -*S))
		return msg_seterr("--dS %g: the pack's hydrate saturation is %.6g; dS must be above -S (-S removes all the hydrate)",
		    d->dS, *S), -1;
	for (i = 0; i < p->n; i++)
		kmin = fmin(kmin, dissociate_grain_K(p->E[i], p->nu[i]));
	if (d->pex > 0.01 * kmin)
		return msg_seterr("--pex %g: above 1 %% of the smallest grain bulk modulus (%g Pa): beyond small strain", d->pex, kmin),
		    -1;
	return 0;
}

void
dissociate_radii(struct pack *p, double dS, double S, double pex)
{
	double fh = dS < 0 ? cbrt(1 + dS / S) : 1;
	size_t i;

	for (i = 0; i < p->n; i++) {
		if (fh != 1 && pack_grain_phase(p, i) == PHASE_HYDRATE)
			p->r[i] *= fh;
		if (pex > 0)
			p->r[i] *= cbrt(1 - pex / dissociate_grain_K(p->E[i], p->nu[i]));
	}
}

static double
mean_lw(const struct load_row *row)
{
	return (row->sig_lw[0] + row->sig_lw[1] + row->sig_lw[2]) / 3;
}

/* The pack's state, measured by a loader that changes nothing. */
static int
measure_state(struct pack *p, const struct load_params *lp, struct load_row *row)
{
	struct loader L;
	int r;

	if (loader_open(&L, p, lp))
		return -1;
	r = loader_measure(&L, row);
	loader_close(&L);
	return r;
}

/* One loader increment de on p; the minimiser stopping at its iteration limit is an error
 * here: a dissociated state or a probe that is not an equilibrium is worth nothing. */
static int
step(struct pack *p, const struct load_params *lp, const double de[3], struct load_row *row, const char *what)
{
	struct loader L;
	int r;

	if (loader_open(&L, p, lp))
		return -1;
	r = loader_step(&L, de, row);
	loader_close(&L);
	if (r > 0)
		return msg_seterr("%s: no equilibrium within %ld iterations (residual %.3g; raise --max-iter)", what,
		    lp->min.max_iter, row->res_max), -1;
	return r;
}

int
dissociate_probe_K(const struct pack *p, const struct load_params *lp, double probe, struct load_row *before,
    double *K, long *iterations)
{
	struct pack q;
	struct load_row after;
	double de[3];
	int a, r;

	if (pack_copy(&q, p))
		return -1;
	/* de is against the reference lengths (loader_step): -probe L/L_ref extends each
	 * current length by the fraction probe */
	for (a = 0; a < 3; a++)
		de[a] = -probe * pack_box_length(q.box, a) / pack_box_length(q.refbox, a);
	r = measure_state(&q, lp, before);
	if (r == 0)
		r = step(&q, lp, de, &after, "the probe of the bulk modulus");
	pack_free(&q);
	if (r)
		return -1;
	/* against the current lengths, each of which grew by the fraction probe: the modulus
	 * that step (c) divides by, which also changes the current lengths (the tables' strains
	 * are against the reference box, longer by the densification strain) */
	*K = (mean_lw(&after) - mean_lw(before)) / (-3 * probe);
	*iterations = after.iterations;
	if (!(*K > 0 && isfinite(*K)))
		return msg_seterr("the probe measured a bulk modulus of %g Pa (mean stress %g Pa before): no skeleton to unload; give --K",
		    *K, mean_lw(before)), -1;
	return 0;
}

int
dissociate_run(struct pack *p, const struct load_params *lp, const struct dissociation *d,
    struct dissociation_report *rep)
{
	double de[3], S;
	int a;

	memset(rep, 0, sizeof *rep);
	rep->K = d->K;
	rep->sigma_before = rep->sigma_after = rep->sigma_wall_before = rep->sigma_wall_after = NAN;
	rep->sigma_total_after = NAN;
	if (dissociate_check(p, d, &S))
		return -1;
	rep->S_before = rep->S_after = S;
	if (d->dS == 0 && d->pex == 0)
		return 0;
	if (d->pex > 0 && isnan(d->K)) {
		if (dissociate_probe_K(p, lp, d->probe, &rep->before, &rep->K, &rep->probe_iterations))
			return -1;
		rep->K_measured = 1;
	} else if (measure_state(p, lp, &rep->before)) {
		return -1;
	}
	rep->eps_kk = d->pex > 0 ? d->alpha * d->pex / rep->K : 0;
	dissociate_radii(p, d->dS, S, d->pex);
	for (a = 0; a < 3; a++)	/* each current length grows by eps_kk / 3 */
		de[a] = -rep->eps_kk / 3 * pack_box_length(p->box, a) / pack_box_length(p->refbox, a);
	if (step(p, lp, de, &rep->after, "the dissociated pack"))
		return -1;
	rep->S_after = pack_hydrate_saturation(p);
	rep->sigma_before = mean_lw(&rep->before);
	rep->sigma_after = mean_lw(&rep->after);
	rep->sigma_wall_before = rep->before.sigma_c;
	rep->sigma_wall_after = rep->after.sigma_c;
	rep->sigma_total_after = rep->sigma_after + d->alpha * d->pex;
	return 0;
}
