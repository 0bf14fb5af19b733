/* SPDX-License-Identifier: GPL-3.0-or-later */
/* msg: diagnostics and the error slot (see msg.h). */
#include "base/msg.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_errno.h>

const char *msg_progname = "qusgm";
int msg_verbosity = 0;
void (*msg_before)(void);
static char errbuf[1024];

void
msg_init(const char *argv0)
{
	const char *s = argv0 ? strrchr(argv0, '/') : NULL;

	msg_progname = s ? s + 1 : (argv0 ? argv0 : "qusgm");
	msg_gsl_handler_install();
}

static void
vmsg(const char *fmt, va_list ap)
{
	int saved = errno;
	size_t n = strlen(fmt);

	if (msg_before)
		msg_before();
	fprintf(stderr, "%s: ", msg_progname);
	vfprintf(stderr, fmt, ap);
	if (n > 0 && fmt[n - 1] == ':')
		fprintf(stderr, " %s", strerror(saved));
	fputc('\n', stderr);
}

void
msg_die(int status, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vmsg(fmt, ap);
	va_end(ap);
	exit(status);
}

void
msg_warn(const char *fmt, ...)
{
	va_list ap;

	if (msg_verbosity < 0)
		return;
	va_start(ap, fmt);
	vmsg(fmt, ap);
	va_end(ap);
}

void
msg_info(int level, const char *fmt, ...)
{
	va_list ap;

	if (msg_verbosity < level)
		return;
	va_start(ap, fmt);
	vmsg(fmt, ap);
	va_end(ap);
}

void
msg_seterr(const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(errbuf, sizeof errbuf, fmt, ap);
	va_end(ap);
}

const char *
msg_geterr(void)
{
	return errbuf[0] ? errbuf : "unknown error";
}

void
msg_die_err(int status)
{
	msg_die(status, "%s", msg_geterr());
}

static void
gsl_handler(const char *reason, const char *file, int line, int gsl_errno)
{
	(void)file;
	(void)line;
	msg_seterr("GSL: %s (%s)", reason, gsl_strerror(gsl_errno));
}

void
msg_gsl_handler_install(void)
{
	gsl_set_error_handler(gsl_handler);
}

void
msg_list_add(char *buf, size_t size, const char *fmt, ...)
{
	size_t at = strlen(buf);
	va_list ap;

	if (at + 1 >= size)
		return;
	if (at)
		at += (size_t)snprintf(buf + at, size - at, ", ");
	if (at + 1 >= size)
		return;
	va_start(ap, fmt);
	vsnprintf(buf + at, size - at, fmt, ap);
	va_end(ap);
}
