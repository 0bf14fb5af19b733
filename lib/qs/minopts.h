/* SPDX-License-Identifier: GPL-3.0-or-later */
/* minopts: the minimiser's command-line options, shared by every tool that finds
 * equilibria (densify, frictionalize, loadtest), so that each option has one name, one
 * help line and one default everywhere.  Use QS_MIN_OPTS(mp) inside a cli_opt table, then
 * qs_min_opts_check(mp) after cli_parse. */
#ifndef QUSGM_MINOPTS_H
#define QUSGM_MINOPTS_H

#include "base/cli.h"
#include "qs/minimize.h"
#include "qs/loading.h"

extern const char *qs_method_arg;
/* --method's help line, made from the table of the methods (QS_METHODS) by
 * qs_min_opts_init. */
extern char qs_method_help[];

#define QS_MIN_OPTS(mp)                                                                                      \
	{"method", 0, CLI_STRING, &qs_method_arg, "NAME", qs_method_help, NULL},                               \
	{"tol", 0, CLI_DOUBLE, &(mp).tol, "RATIO", "equilibrium: largest per-grain |F_i| / largest contact force on i", NULL}, \
	{"tol-floor", 0, CLI_DOUBLE, &(mp).tol_floor, "RATIO", "--tol judges a grain against at least RATIO x the mean contact force", NULL}, \
	{"max-iter", 0, CLI_LONG, &(mp).max_iter, "N", "iteration limit of one minimisation", NULL},                 \
	{"cap", 0, CLI_DOUBLE, &(mp).cap, "RATIO", "largest displacement of a grain per iteration / its radius", NULL}, \
	{"k-sd", 0, CLI_LONG, &(mp).k_sd, "N", "cg: steepest-descent restart every N iterations", NULL},          \
	{"ls-sigma", 0, CLI_DOUBLE, &(mp).ls_sigma, "S", "cg: line search ends at |dPi/da| <= S |dPi/da(0)|", NULL}, \
	{"eps1", 0, CLI_DOUBLE, &(mp).eps1, "E", "papers' criterion: stop when Pi falls by less than E |Pi| (0: off)", NULL}, \
	{"eps2", 0, CLI_DOUBLE, &(mp).eps2, "E", "papers' criterion: stop when |grad Pi|^2 < E N (E R^2)^2 (0: off)", NULL}, \
	{"fire-dt", 0, CLI_DOUBLE, &(mp).fire_dt, "T", "fire: largest time step / (1/sqrt(stiffness bound)); with --precond in the preconditioned units", NULL}, \
	{"lbfgs-m", 0, CLI_LONG, &(mp).lbfgs_m, "M", "lbfgs: number of stored steps (0: 4 in frictional increments, 8 otherwise)", NULL},                      \
	{"precond", 0, CLI_DOUBLE, &(mp).precond_shift, "S", "lbfgs, fire: scale each grain's step by its stiffness block, shifted by S x the mean (0: off)", NULL}

/* Before cli_parse: --method's help line from the table of the methods, "minimiser: cg (the
 * papers' modified CG), fire (FIRE 2.0), ... or newton (...)", each name and its
 * description. */
void qs_min_opts_init(void);
/* Validate the values and resolve --method (an unknown name lists the methods); reports
 * through cli_usage_error. */
void qs_min_opts_check(struct qs_min_params *mp);
/* The options of a loading (loadtest, frictionalize, dissociate) inside a cli_opt table: lp a
 * struct load_params, rule a const char *, nsub a long; qs_load_opts_check after cli_parse. */
#define QS_LOAD_OPTS(lp, rule, nsub)                                                                         \
	{"rule", 0, CLI_STRING, &(rule), "NAME", "sliding rule: return-map (exact potential) or paper (F (6)-(7b))", NULL}, \
	{"sub-increments", 0, CLI_LONG, &(nsub), "N", "sub-increments per increment (affine guess each)", NULL}, \
	{"k-inc", 0, CLI_LONG, &(lp).k_inc, "N", "minimiser iterations between sub-increments", NULL},            \
	{"skin", 0, CLI_DOUBLE, &(lp).skin, "RATIO", "largest Verlet skin / smallest radius", NULL},           \
	{"inc-tol", 0, CLI_DOUBLE, &(lp).inc_tol, "RATIO", "friction: residual of an increment before its commit; the settle passes then reach --tol", NULL}, \
	{"settle-fresh", 0, CLI_FLAG, &(lp).settle_fresh, NULL, "friction: start each settle pass's L-BFGS afresh, not from the last pass's steps and blocks", NULL}

/* The loading options of loadtest, frictionalize and dissociate: --mu and --wall-mu in [0, 10]
 * or NaN (not given), --rule resolved into lp->rule, --sub-increments (1 to 1000, into
 * lp->nsub) and --k-inc positive, --skin in (0, 2], --inc-tol in (0, 1); reports through
 * cli_usage_error. */
void qs_load_opts_check(struct load_params *lp, const char *rule, long nsub, double mu, double wall_mu);

#endif
