/* SPDX-License-Identifier: GPL-3.0-or-later */
/* qusgm.h: the umbrella header of the installed library, <qusgm/qusgm.h>.
 *
 * The public headers, whose functions and variables the installed libqusgm.a and
 * libqusgm.so export (lib/qusgm.api), each name prefixed qusgm_: the installed copies of the
 * headers declare each such name N of lib/ as qusgm_N (make install renames them).  The other
 * headers installed under include/qusgm/ are those these include, for their types; their
 * functions are internal to the library and not exported.  Compiles as C99, C11 and C++,
 * clean under -pedantic (share/doc/library.md, "Using the library"). */
#ifndef QUSGM_QUSGM_H
#define QUSGM_QUSGM_H

#include "base/msg.h"
#include "base/numfmt.h"
#include "base/par.h"
#include "pack/pack.h"
#include "pack/packio.h"
#include "contact/contacts.h"
#include "analysis/measure.h"
#include "qs/functional.h"

#endif
