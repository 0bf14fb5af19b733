/* SPDX-License-Identifier: GPL-3.0-or-later */
/* numfmt: the one way qusgm prints a double in its files and tables.
 *
 * The shortest of %.15g, %.16g, %.17g that reads back (strtod) to the same double, so that
 * write -> read -> write is byte-identical and files stay readable. */
#ifndef QUSGM_NUMFMT_H
#define QUSGM_NUMFMT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes into buf (at least 32 bytes); returns the length. */
int num_format(char *buf, double v);
/* Parse a whole token as a finite double; 0 on success, -1 otherwise. */
int num_parse(const char *s, double *v);
/* Parse a whole token as a long; 0 on success. */
int num_parse_long(const char *s, long *v);

#ifdef __cplusplus
}
#endif

#endif
