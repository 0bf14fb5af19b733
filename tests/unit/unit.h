/* SPDX-License-Identifier: GPL-3.0-or-later */
/* unit: a minimal test harness for lib/.  Each check prints one "PASS name" or
 * "FAIL name: detail" line; main returns unit_summary(), nonzero when anything failed.
 * tests/run.sh counts the lines. */
#ifndef QUSGM_UNIT_H
#define QUSGM_UNIT_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

static int unit_failed, unit_passed;

static void unit_report(int ok, const char *fmt, ...) __attribute__((format(printf, 2, 3), unused));

static void
unit_report(int ok, const char *fmt, ...)
{
	va_list ap;

	fputs(ok ? "PASS " : "FAIL ", stdout);
	va_start(ap, fmt);
	vprintf(fmt, ap);
	va_end(ap);
	putchar('\n');
	fflush(stdout);
	if (ok)
		unit_passed++;
	else
		unit_failed++;
}

#define CHECK(cond, ...) unit_report(!!(cond), __VA_ARGS__)

/* UNIT_SANITIZED: 1 in the sanitizer build (make check's build-san, -fsanitize=address), where
 * a test may run a smaller case of the same code (the sanitizers find memory errors and
 * undefined behaviour on a small case as on a large one, at ten times the cost per step); the
 * checks whose tolerance depends on the size keep the size, and each test says what it
 * changes. */
#if defined(__SANITIZE_ADDRESS__)
#define UNIT_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNIT_SANITIZED 1
#endif
#endif
#ifndef UNIT_SANITIZED
#define UNIT_SANITIZED 0
#endif

/* |a - b| <= tol * max(|b|, floor): a relative tolerance with an absolute floor. */
static int __attribute__((unused))
unit_close(double a, double b, double tol, double floor_)
{
	double s = fabs(b) > floor_ ? fabs(b) : floor_;

	return isfinite(a) && fabs(a - b) <= tol * s;
}

#define CHECK_CLOSE(a, b, tol, name)                                                            \
	do {                                                                                    \
		double ua_ = (a), ub_ = (b);                                                     \
		unit_report(unit_close(ua_, ub_, (tol), 0), "%s: %.17g vs %.17g (rel %.3g, tol %.3g)", \
		    name, ua_, ub_, fabs(ua_ - ub_) / (fabs(ub_) > 0 ? fabs(ub_) : 1), (double)(tol)); \
	} while (0)

static int __attribute__((unused))
unit_summary(void)
{
	return unit_failed != 0;
}

#endif
