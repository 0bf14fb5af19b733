/* SPDX-License-Identifier: GPL-3.0-or-later */
/* numfmt: round-trip-safe number formatting and strict parsing (see numfmt.h). */
#include "base/numfmt.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int
num_format(char *buf, double v)
{
	int prec, n = 0;

	for (prec = 15; prec <= 17; prec++) {
		n = snprintf(buf, 32, "%.*g", prec, v);
		if (strtod(buf, NULL) == v)
			break;
	}
	return n;
}

int
num_parse(const char *s, double *v)
{
	char *end;

	errno = 0;
	*v = strtod(s, &end);
	if (end == s || *end || !isfinite(*v))
		return -1;
	if (errno == ERANGE && fabs(*v) > 1)	/* overflow; underflow to a subnormal is fine */
		return -1;
	return 0;
}

int
num_parse_long(const char *s, long *v)
{
	char *end;

	errno = 0;
	*v = strtol(s, &end, 10);
	if (end == s || *end || errno)
		return -1;
	return 0;
}
