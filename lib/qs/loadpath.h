/* SPDX-License-Identifier: GPL-3.0-or-later */
/* loadpath: the loading paths of loadtest, their text form and the driver that walks them
 * (physics.md §8; share/man/man1/loadtest.1 documents the grammar).
 *
 * A path is one or more segments separated by ';'.  A segment is a kind followed by
 * key=value settings, separated by spaces:
 *
 *     uniaxial  [axis=z]                 strain along one axis, the others fixed
 *     isotropic                          the same strain on the three axes
 *     triaxial  [axis=z] [lateral=R]     axial strain, both lateral strains R times it
 *     triaxial  [axis=z] hold=PA|hold    axial strain; the lateral walls keep the mean lateral
 *                                        stress at PA (hold: at its value when the segment starts)
 *     polyaxial ratio=A:B:C              strain increments in the proportions A:B:C (x:y:z)
 *     probe     steps=N                  uniaxial along x, then y, then z, N increments each:
 *                                        three uniaxial segments (moduli --pool-segments fits
 *                                        them together, averaging the axes; share/doc/tables.md)
 *
 * and, for any kind: step=D (strain per increment along the axis, or per axis for isotropic,
 * or of the largest ratio; negative unloads), then the stop: steps=N, to-stress=PA (sigma_c
 * reaches PA: from below when loading, from above when unloading), to-strain=E (the
 * controlling strain, measured from the reference box, reaches E).  Missing settings come
 * from the defaults (the tool's --strain-step, --steps, --to-stress, --axis).
 * Example: a loading-unloading cycle of a uniaxial test,
 *     "uniaxial to-stress=20e6; uniaxial step=-1e-4 to-stress=5e6"
 *
 * Constant lateral stress is held by a servo: each increment's lateral strain is predicted
 * from the segment's own increments so far (d sig_lat = A de_axial + B de_lat, A from the
 * first, uniaxial increment, B learnt by damped secants) so as to bring the mean lateral stress
 * back to its target; the rows report the lateral stress reached. */
#ifndef QUSGM_LOADPATH_H
#define QUSGM_LOADPATH_H

#include "qs/loading.h"

enum path_kind { PATH_UNIAXIAL, PATH_ISOTROPIC, PATH_TRIAXIAL, PATH_POLYAXIAL };

struct path_seg {
	enum path_kind kind;
	int axis;
	double step;		/* NaN: default */
	double ratio[3];	/* strain increment per unit of step, per axis */
	int hold;		/* triaxial: 0 strain ratio, 1 hold a given stress, 2 hold the start stress */
	double hold_stress;
	long steps;		/* 0: none */
	double to_stress, to_strain;	/* NaN: none */
};

struct load_path {
	size_t n;
	struct path_seg seg[64];
};

struct path_defaults {
	double step;
	long steps;
	double to_stress, to_strain;
	int axis;
};

/* Parse spec into path with the defaults filled in; every segment must have a stop.
 * 0, or -1 with msg_seterr naming the segment and the word that does not parse. */
int path_parse(const char *spec, const struct path_defaults *def, struct load_path *path);
const char *path_kind_name(enum path_kind k);
/* "x", "y" or "z" to 0, 1 or 2 (the axis= of a segment, and a tool's --axis); 0 or -1. */
int path_parse_axis(const char *s, int *axis);

struct path_limits {
	long max_steps;		/* per segment */
	double max_strain;	/* |strain| on any axis */
};

/* Called with each row: segment index (-1 for the starting row) and the row. */
/* Read the pack a loading starts from (loadtest's path, frictionalize's uniaxial run; input
 * NULL or "-" is stdin) and check it: spheres only (pack_require_spheres), at least 5 grains
 * (who, the tool, is named in those messages), a reference box, and a contact history its friction coefficients allow
 * (fr_check_history).  *stale gets the number of history lines that name grains which do not
 * touch, which the first increment drops.  0; 1 with msg_seterr saying what is wrong with the
 * pack, for the tool to prefix the input's name; -1 with msg_seterr when reading (the message
 * names the input) or measuring fails. */
int path_read_pack(const char *input, const char *who, struct pack *p, size_t *stale);
/* The friction of a loading (loadtest, dissociate): mu and wall_mu NaN keep the pack's; mu
 * alone sets the wall's coefficient too.  Returns whether the loading is frictional; with
 * both 0 it is not, and runs on 3N unknowns. */
int path_set_friction(struct pack *p, double mu, double wall_mu);

typedef int (*path_row_fn)(int seg, const struct load_row *row, void *ctx);

/* Walk the path from the loader's current state.  Returns 0 when every segment reached its
 * stop; 1 when a minimisation hit its iteration limit, 2 when a segment ran into a limit
 * (max_steps, max_strain) before its stress or strain target, 3 when fn asked to stop (nonzero);
 * -1 on error (msg_seterr says which), among them a segment whose to-stress or to-strain is
 * already passed where it starts (it would run no increment): for the first segment before
 * fn sees the starting row, so that a test that cannot start writes nothing. */
int path_run(struct loader *L, const struct load_path *path, const struct path_limits *lim, path_row_fn fn,
    void *ctx);

#endif
