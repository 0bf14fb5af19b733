/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_densify: densify_run's end conditions with the release of unbraced grains done both
 * ways, restarting the minimiser after each release (the default) and keeping its memory
 * (release_keep, through qs_minimizer_moved): from the same loose pack, each run ends at the
 * target stress within stress_tol, with every grain at 4 contacts or more, and at the
 * residual tolerance; releases every 50 iterations make sure both paths are taken.
 * Checkpoints: a run stopped after every stage, its state written into a pack file and read
 * back (densify_resume_put, pack_write_path, pack_read_path, densify_resume_get) and gone on
 * from, ends with the uninterrupted run's centres and radii to the bit. */
#include "qs/densify.h"
#include "base/msg.h"
#include "pack/packio.h"
#include "unit.h"
#include "unit_pack.h"

#include <gsl/gsl_randist.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void
copy_loose(struct pack *p, const struct pack *loose)
{
	size_t i;

	pack_init(p);
	for (i = 0; i < loose->n; i++)
		pack_add_grain(p, loose->id[i], loose->x + 3 * i, loose->r[i], loose->E[i], loose->nu[i], loose->rho[i]);
	memcpy(p->box, loose->box, sizeof p->box);
	p->wall_E = loose->wall_E, p->wall_nu = loose->wall_nu;
}

/* The log rows so far (one per stage, as the checkpoint must hold them), and the file. */
struct ck_ctx {
	char rows[65536];
	const char *path;
};

static void
on_stage(const struct densify_stage *st, void *ctx)
{
	struct ck_ctx *c = ctx;
	size_t l = strlen(c->rows);

	snprintf(c->rows + l, sizeof c->rows - l, "%s %ld\n", st->stage, st->round);
}

/* The checkpoint callback: the state into the file, and stop. */
static int
stop_after_stage(const struct pack *p, const struct densify_resume *at, void *ctx)
{
	struct ck_ctx *c = ctx;

	if (densify_resume_put((struct pack *)p, at, "unit", c->rows) || pack_write_path(p, c->path))
		return -1;
	return 1;
}

static void
resumed(const struct pack *loose)
{
	char path[] = "/tmp/test_densify_ckXXXXXX";
	static struct ck_ctx c;
	struct pack whole, p;
	struct densify_params dp;
	struct densify_resume at;
	struct densify_stage last;
	char *run, *rows;
	int fd = mkstemp(path), r, stops = 0, same, rows_bad = 0;

	CHECK(fd >= 0, "a temporary file");
	if (fd < 0)
		return;
	close(fd);
	densify_params_default(&dp);
	dp.stress = 1e6;
	dp.release_after = 50;
	copy_loose(&whole, loose);
	r = densify_run(&whole, &dp, NULL, NULL, &last);
	copy_loose(&p, loose);
	c.path = path;
	r = densify_run_resumable(&p, &dp, on_stage, &c, stop_after_stage, NULL, &last);
	while (r == 2 && stops < 10000) {
		stops++;
		pack_free(&p);
		if (pack_read_path(path, &p) || densify_resume_get(&p, &at, &run, &rows)) {
			CHECK(0, "the checkpoint reads back: %s", msg_geterr());
			break;
		}
		rows_bad += strcmp(rows, c.rows) != 0;
		free(run), free(rows);
		r = densify_run_resumable(&p, &dp, on_stage, &c, stop_after_stage, &at, &last);
	}
	CHECK(r == 0, "resumed: the run ends (%d) after %d stops", r, stops);
	CHECK(stops > 10, "resumed: stopped after every stage (%d stops)", stops);
	CHECK(rows_bad == 0, "resumed: every checkpoint gives back the log rows written (%d differ)", rows_bad);
	same = p.n == whole.n && memcmp(p.x, whole.x, 3 * p.n * sizeof *p.x) == 0 &&
	       memcmp(p.r, whole.r, p.n * sizeof *p.r) == 0 && memcmp(p.box, whole.box, sizeof p.box) == 0 &&
	       memcmp(p.refbox, whole.refbox, sizeof p.refbox) == 0;
	CHECK(same, "resumed: centres, radii, box and reference box are the uninterrupted run's to the bit");
	pack_free(&p);
	pack_free(&whole);
	unlink(path);
}

static void
run(const struct pack *loose, int keep)
{
	struct pack p;
	struct densify_params dp;
	struct densify_stage last;
	int r;

	copy_loose(&p, loose);
	densify_params_default(&dp);
	dp.stress = 1e6;
	dp.release_after = 50;
	dp.release_keep = keep;
	r = densify_run(&p, &dp, NULL, NULL, &last);
	CHECK(r == 0, "%s: densify_run ends without error or limit (%d)", keep ? "keep" : "restart", r);
	CHECK(fabs(last.sigma_c / dp.stress - 1) <= dp.stress_tol, "%s: sigma_c %.6g Pa within %.3g of the target",
	    keep ? "keep" : "restart", last.sigma_c, dp.stress_tol);
	CHECK(last.under4 == 0, "%s: no grain under 4 contacts (%zu)", keep ? "keep" : "restart", last.under4);
	CHECK(last.res_max <= dp.min.tol, "%s: the last equilibrium at the tolerance (residual %.3g)",
	    keep ? "keep" : "restart", last.res_max);
	pack_free(&p);
}

int
main(void)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	struct pack loose;

	gsl_rng_set(rng, 5);
	random_pack(&loose, rng, 250, 1e-4, 0.5, 0.001);
	run(&loose, 0);
	run(&loose, 1);
	resumed(&loose);
	pack_free(&loose);
	gsl_rng_free(rng);
	return unit_summary();
}
