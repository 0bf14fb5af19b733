/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_loading: the loader's choices that the tools leave to it.  L-BFGS's stored steps
 * (--lbfgs-m 0, the tools' default): LOAD_LBFGS_M in frictional increments, QS_LBFGS_M
 * without friction (where 4 steps led frictionless probes to other equilibria,
 * loading.h), and a value the user gave kept either way. */
#include "unit.h"
#include "unit_pack.h"
#include "base/msg.h"
#include "qs/loading.h"

#include <gsl/gsl_rng.h>
#include <string.h>

static long
loader_memory(struct pack *p, int friction, long lbfgs_m)
{
	struct load_params lp;
	struct loader L;
	long m = -1;

	load_params_default(&lp);
	lp.friction = friction;
	if (lbfgs_m >= 0)
		lp.min.lbfgs_m = lbfgs_m;
	if (loader_open(&L, p, &lp) == 0)
		m = L.lp.min.lbfgs_m;
	loader_close(&L);
	return m;
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct load_params lp;
	struct pack p;

	msg_init("test_loading");
	gsl_rng_set(rng, 5);
	random_pack(&p, rng, 40, 1e-4, 0.6, 2e-3);
	memcpy(p.refbox, p.box, sizeof p.box);
	p.has_refbox = 1;
	load_params_default(&lp);
	CHECK(lp.min.lbfgs_m == 0, "load_params_default leaves L-BFGS's memory to the loader (lbfgs_m 0)");
	CHECK(loader_memory(&p, 1, -1) == LOAD_LBFGS_M && LOAD_LBFGS_M == 4,
	    "with friction the loader keeps LOAD_LBFGS_M = 4 steps");
	CHECK(loader_memory(&p, 0, -1) == QS_LBFGS_M && QS_LBFGS_M == 8, "without friction it keeps QS_LBFGS_M = 8 steps");
	CHECK(loader_memory(&p, 1, 6) == 6 && loader_memory(&p, 0, 3) == 3, "a memory given by the user is kept either way");
	pack_free(&p);
	gsl_rng_free(rng);
	return unit_summary();
}
