/* SPDX-License-Identifier: GPL-3.0-or-later */
/* minopts: validation of the shared minimiser options (see minopts.h). */
#include "qs/minopts.h"
#include "base/msg.h"

#include <math.h>
#include <stdio.h>

const char *qs_method_arg = "lbfgs";
/* room for a few more methods than the table has; a longer line is cut, not overrun */
char qs_method_help[512] = "minimiser";

void
qs_min_opts_init(void)
{
	const struct qs_method_type *const *t;
	size_t at = 0, size = sizeof qs_method_help;
	int k = snprintf(qs_method_help, size, "minimiser:");

	for (t = qs_methods; *t && k >= 0 && (at += (size_t)k) < size; t++) {
		/* "a (...)", "a (...) or b (...)", "a (...), b (...) or c (...)" */
		const char *sep = t == qs_methods ? "" : t[1] ? "," : " or";

		k = snprintf(qs_method_help + at, size - at, "%s %s (%s)", sep, (*t)->name, (*t)->description);
	}
}

void
qs_min_opts_check(struct qs_min_params *mp)
{
	const struct qs_method_type *t = qs_method_find(qs_method_arg);

	if (t)
		mp->method = t;
	else
		cli_usage_error("--method: %s", msg_geterr());
	if (!(mp->tol > 0 && mp->tol < 1))
		cli_usage_error("--tol: must be in (0, 1)");
	if (!(mp->tol_floor >= 0 && mp->tol_floor <= 1))
		cli_usage_error("--tol-floor: must be in [0, 1]");
	if (mp->max_iter < 1)
		cli_usage_error("--max-iter: must be positive");
	if (!(mp->cap > 0 && mp->cap <= 0.5))
		cli_usage_error("--cap: must be in (0, 0.5]");
	if (mp->k_sd < 1)
		cli_usage_error("--k-sd: must be positive");
	if (!(mp->ls_sigma > 0 && mp->ls_sigma < 1))
		cli_usage_error("--ls-sigma: must be in (0, 1)");
	if (!(mp->eps1 >= 0) || !(mp->eps2 >= 0))
		cli_usage_error("--eps1, --eps2: must be non-negative");
	if (mp->lbfgs_m < 0 || mp->lbfgs_m > 100)
		cli_usage_error("--lbfgs-m: must be in [0, 100] (0: the tool's choice)");
	if (!(mp->precond_shift >= 0 && mp->precond_shift <= 100))
		cli_usage_error("--precond: must be in [0, 100]");
	if (!(mp->fire_dt > 0 && mp->fire_dt <= 10))
		cli_usage_error("--fire-dt: must be in (0, 10]");
}

void
qs_load_opts_check(struct load_params *lp, const char *rule, long nsub, double mu, double wall_mu)
{
	if (!isnan(mu) && !(mu >= 0 && mu <= 10))
		cli_usage_error("--mu: must be in [0, 10]");
	if (!isnan(wall_mu) && !(wall_mu >= 0 && wall_mu <= 10))
		cli_usage_error("--wall-mu: must be in [0, 10]");
	if (fr_rule_parse(rule, &lp->rule))
		cli_usage_error("--rule: must be return-map or paper");
	if (nsub < 1 || nsub > 1000 || lp->k_inc < 1)
		cli_usage_error("--sub-increments (<= 1000) and --k-inc must be positive");
	if (!(lp->skin > 0 && lp->skin <= 2))
		cli_usage_error("--skin: must be in (0, 2]");
	if (!(lp->inc_tol > 0 && lp->inc_tol < 1))
		cli_usage_error("--inc-tol: must be in (0, 1)");
	lp->nsub = (int)nsub;
}
