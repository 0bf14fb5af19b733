/* SPDX-License-Identifier: GPL-3.0-or-later */
/* packio: reading and writing qusgm-pack versions 1 and 2 (share/doc/pack-format.md).
 *
 * The reader is strict and reports the first problem as "file:line: what is wrong" in the
 * error slot (msg_geterr).  Input goes through the line reader (base/lines.h), so
 * gzip-compressed and plain packs share one code path and a truncated .gz is an error.  A
 * stream may hold several packs back to back.  The writer prints every number with num_format, so write(read(f)) == f byte for
 * byte, and compresses when the output name ends in ".gz".
 *
 * Public API (installed as <qusgm/pack/packio.h>, share/doc/library.md):
 * - Ownership: a pack read into a caller's struct pack (pack_read_next, pack_read_path) owns
 *   every array, string and contact in it; the caller frees them with pack_free.  After a
 *   failed read the pack holds nothing (pack_free on it is harmless).  The reader made by
 *   pack_reader_open reads a duplicate of fp's descriptor and reads ahead: the caller must not
 *   read fp meanwhile, and closes fp itself after pack_reader_close.  The writers only read p.
 * - Errors: every function returns its status (-1, or NULL for pack_reader_open) and fills
 *   the error slot of base/msg.h with one line, "FILE:LINE: what is wrong" for a reader error
 *   (msg_geterr); none prints or exits.
 * - Promises: what is read passed every check of share/doc/pack-format.md; what is written
 *   reads back to the same doubles; an output path is replaced atomically or left alone. */
#ifndef QUSGM_PACKIO_H
#define QUSGM_PACKIO_H

#include <stdio.h>
#include "base/cli.h"
#include "pack/pack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The ranges in which the reader takes a value, those where the physics of the tools holds
 * and the bounds their options already keep (share/doc/pack-format.md, "Ranges"):
 * - friction coefficients (the friction and walls lines) in [0, PACK_MU_MAX], the range of
 *   every tool's --mu and --friction (a header's friction 1e300 was taken);
 * - Young's moduli from PACK_E_MIN, 1 kPa, softer than the softest hydrogel bead of a
 *   granular experiment, to PACK_E_MAX, 1e13 Pa, eight times diamond's 1.2e12 Pa, for a grain,
 *   and to PACK_WALL_E_MAX, 1e15 Pa, for the walls, which the tools make 100 times stiffer
 *   than the grains (E = 1e-300 was taken, and densify squeezed that grain by 0.47 R);
 * - a grain no larger than the box: its radius at most the box length along each axis, so
 *   that it presses into the two walls of an axis by at most R together (packinfo printed
 *   porosity -inf for a grain larger than its box);
 * - a contact force no larger than Hertz's at an overlap as large as the contact's radius:
 *   P0 <= (4/3) E* R*^2, and |Q0| and |M0| / R* at most PACK_MU_MAX times that, far beyond
 *   the small strains Hertz's law is for (a P0 of 1e300 N was taken); a pack of another
 *   contact law (meta contact-law linear, the plate engine's) is not held to it. */
#define PACK_MU_MAX 10.0
#define PACK_E_MIN 1e3
#define PACK_E_MAX 1e13
#define PACK_WALL_E_MAX 1e15

struct pack_reader;

/* Wraps an open stream (stdin included); name is used in messages. */
struct pack_reader *pack_reader_open(FILE *fp, const char *name);
void pack_reader_close(struct pack_reader *rd);
/* 1: a pack was read into p (initialised here); 0: clean end of input; -1: error. */
int pack_read_next(struct pack_reader *rd, struct pack *p);
const char *pack_reader_name(const struct pack_reader *rd);

/* Read exactly one pack from path (NULL or "-" = stdin).  0 on success, -1 with the slot set. */
int pack_read_path(const char *path, struct pack *p);

/* The version a writer emits for p: the lowest that represents it, 1 for the standard
 * grain columns and six walls (byte for byte what qusgm wrote before version 2 existed,
 * readable by older readers), 2 for a periodic axis, the shape columns (has_shapes) or the
 * phase column (has_phase). */
int pack_format_version(const struct pack *p);

/* Write one pack to an open stream, compressed if gz; 0 on success. */
int pack_write_stream(const struct pack *p, FILE *fp, int gz);
/* Write atomically to path (NULL or "-" = stdout), compressed if the name ends in .gz. */
int pack_write_path(const struct pack *p, const char *path);

/* Validation shared with tools that build packs (packgen, packimport): 0 if p obeys every
 * rule the reader enforces; otherwise fills the slot (without a line number). */
int pack_validate(const struct pack *p);

/* The last step of every tool that writes a pack: append the tool's history line (its
 * command line and every option's value, cli_history_line) and write the pack to the
 * output of st, atomically.  0, or -1 with msg_seterr. */
int pack_write_tool(struct pack *p, const struct cli_tool *tool, const struct cli_state *st);
/* The same into o, opened here on st->output and left uncommitted, for a tool that commits
 * the pack with its other outputs, all or none (file_out_commit_all: a log that fails to
 * write leaves no pack either).  0, or -1 with msg_seterr and nothing left open. */
struct file_out;
int pack_write_tool_out(struct pack *p, const struct cli_tool *tool, const struct cli_state *st, struct file_out *o);
/* pack_write_tool with another output the tool has been writing (a log; NULL: none),
 * committed together, all or none: 0, or -1 with msg_seterr and neither committed (also
 * aborted when the pack could not be written). */
int pack_write_tool_with(struct pack *p, const struct cli_tool *tool, const struct cli_state *st, struct file_out *also);

#ifdef __cplusplus
}
#endif

#endif
