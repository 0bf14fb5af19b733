/* SPDX-License-Identifier: GPL-3.0-or-later */
/* msg: one-line diagnostics on stderr, the exit-status table, verbosity.
 *
 * Every message is "tool: where: what" on one line.  Exit statuses are the same in every
 * tool: 0 success, 1 bad data or runtime failure, 2 usage error.  The library reports
 * failures through return values and msg_seterr(); only tools decide to exit.
 *
 * Public API (share/doc/library.md, "Errors"): a library function that fails returns -1 (a
 * pointer function NULL, an energy NAN: each header says which) and leaves one line saying
 * why in the error slot, read with msg_geterr() until the next failure overwrites it (the
 * slot is one static buffer: not thread-safe; "unknown error" when nothing set it).  A
 * program that links the library should call msg_gsl_handler_install() first, so that a GSL
 * error becomes a failure with a message instead of GSL's abort().  msg_die*, msg_warn and
 * msg_info print on stderr and are for programs, never called by the library's own
 * computations. */
#ifndef QUSGM_MSG_H
#define QUSGM_MSG_H

#include <stdarg.h>
#include <stddef.h>

/* A function that does not return, in C11 (_Noreturn), in C++ ([[noreturn]]) and in C99 (GCC's
 * and Clang's attribute; nothing elsewhere): the installed headers compile as each, clean
 * under -pedantic (share/doc/library.md, "Using the library"). */
#ifndef QUSGM_NORETURN
#if defined(__cplusplus)
#define QUSGM_NORETURN [[noreturn]]
#elif defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L
#define QUSGM_NORETURN _Noreturn
#elif defined(__GNUC__)
#define QUSGM_NORETURN __attribute__((noreturn))
#else
#define QUSGM_NORETURN
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* EXIT_STOPPED: a run stopped on purpose with its state saved (a checkpoint at a time limit),
 * to be rerun to go on; sysexits.h's EX_TEMPFAIL, which job schedulers read as "try again". */
enum { EXIT_DATA = 1, EXIT_USAGE = 2, EXIT_STOPPED = 75 };

extern const char *msg_progname;
extern int msg_verbosity;	/* -1 quiet, 0 default, 1 -v, 2 -vv */
/* Called before every message (NULL: none): cli.c ends its progress line there, so that a
 * message starts a line of its own and the status is drawn again below it. */
extern void (*msg_before)(void);

void msg_init(const char *argv0);

/* Print "prog: fmt" and exit with status.  A format ending in ':' gets ": strerror(errno)". */
QUSGM_NORETURN void msg_die(int status, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void msg_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void msg_info(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Library-side error slot: a function that fails fills it and returns nonzero; the tool
 * prints it with msg_die_err().  Keeps the library from printing. */
void msg_seterr(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Append an item to a list of names for a message ("a, b, c"): ", " and the printf of fmt
 * after what buf holds (nothing before the first), truncated to size.  The lists of a
 * table's rows (laws, methods) in their error messages. */
void msg_list_add(char *buf, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
const char *msg_geterr(void);
QUSGM_NORETURN void msg_die_err(int status);

/* Replace GSL's abort() handler with one that records the error in the slot. */
void msg_gsl_handler_install(void);

#ifdef __cplusplus
}
#endif

#endif
