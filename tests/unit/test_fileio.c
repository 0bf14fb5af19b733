/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_fileio: the atomic outputs of lib/base/fileio.h as a tool with several outputs uses
 * them (a pack and its log, the three files of packexport --vtk -o NAME.vtm): committed all
 * or none, a failed write reported with its own errno, and the checks a tool makes on its
 * files before any work (file_roles_check). */
#include "base/fileio.h"
#include "base/msg.h"
#include "unit.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[] = "/tmp/qusgm-test-fileio.XXXXXX";

static const char *
path_of(const char *name)
{
	static char buf[4][256];
	static int k;

	k = (k + 1) % 4;
	snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
	return buf[k];
}

static int
exists(const char *path)
{
	struct stat st;

	return lstat(path, &st) == 0;
}

/* The files in dir other than the ones named: a temporary file left behind shows here. */
static int
count_files(void)
{
	char cmd[400];
	FILE *p;
	int n = -1;

	snprintf(cmd, sizeof cmd, "ls -A '%s' | wc -l", dir);
	if ((p = popen(cmd, "r"))) {
		if (fscanf(p, "%d", &n) != 1)
			n = -1;
		pclose(p);
	}
	return n;
}

/* Two outputs committed together: both reach their names. */
static void
test_commit_all(void)
{
	struct file_out a, b, *both[2] = {&a, &b};
	int r;

	r = file_out_open(&a, path_of("pack")) || file_out_open(&b, path_of("log"));
	CHECK(r == 0, "two outputs open");
	fputs("the pack\n", a.fp);
	fputs("the log\n", b.fp);
	r = file_out_commit_all(both, 2);
	CHECK(r == 0 && exists(path_of("pack")) && exists(path_of("log")) && count_files() == 2,
	    "file_out_commit_all: both outputs reach their names, no temporary file left (%d files)", count_files());
	unlink(path_of("pack"));
	unlink(path_of("log"));
}

/* The second output cannot be written (a link to /dev/full): the first, written without
 * fault, must not reach its name either, and the message is the failed write's own errno,
 * not whatever errno holds at the commit. */
static void
test_commit_all_fails(void)
{
	struct file_out a, b, *both[2] = {&a, &b};
	char want[300];
	int r;

	if (symlink("/dev/full", path_of("full")) != 0) {
		CHECK(0, "symlink to /dev/full");
		return;
	}
	r = file_out_open(&a, path_of("pack")) || file_out_open(&b, path_of("full"));
	CHECK(r == 0, "an output and a link to /dev/full open");
	fputs("the pack\n", a.fp);
	fputs("a row\n", b.fp);
	r = file_out_flush(&b);
	CHECK(r == -1 && b.err == ENOSPC, "file_out_flush on /dev/full fails with ENOSPC (%d, err %d)", r, b.err);
	/* the errno of a later call, as the stale message reported it */
	errno = ENOENT;
	fputs("another row\n", b.fp);
	r = file_out_commit_all(both, 2);
	snprintf(want, sizeof want, "%s: write error: No space left on device", path_of("full"));
	CHECK(r == -1 && strcmp(msg_geterr(), want) == 0, "file_out_commit_all fails with the write's own error: '%s'",
	    msg_geterr());
	CHECK(!exists(path_of("pack")) && count_files() == 1,
	    "file_out_commit_all: a failed output leaves the other uncommitted, no temporary file (%d files)", count_files());
	/* one output alone: the same error, not the errno of the moment */
	r = file_out_open(&b, path_of("full"));
	fputs("a row\n", b.fp);
	file_out_flush(&b);
	errno = ENOTTY;
	r = file_out_commit(&b);
	CHECK(r == -1 && strcmp(msg_geterr(), want) == 0, "file_out_commit after a failed flush: '%s'", msg_geterr());
	unlink(path_of("full"));
}

static void
expect_roles(const char *what, const struct file_role *r, int n, const char *want)
{
	int st = file_roles_check(r, n);

	if (!want)
		CHECK(st == 0, "%s: accepted (%s)", what, st ? msg_geterr() : "");
	else
		CHECK(st == -1 && strcmp(msg_geterr(), want) == 0, "%s: '%s' (want '%s')", what, st ? msg_geterr() : "accepted",
		    want);
}

static void
test_roles(void)
{
	char in[256], out[256], other[256], sub[256], want[600];
	FILE *fp;

	snprintf(in, sizeof in, "%s/in.pack", dir);
	snprintf(out, sizeof out, "%s/./in.pack", dir);
	snprintf(other, sizeof other, "%s/out.pack", dir);
	snprintf(sub, sizeof sub, "%s/no-such-dir/x.pack", dir);
	if ((fp = fopen(in, "w")))
		fclose(fp);
	{
		struct file_role r[] = {{other, "-o", 1}, {in, "the input", 0}};
		expect_roles("an output and an input", r, 2, NULL);
	}
	{
		struct file_role r[] = {{out, "-o", 1}, {in, "the input", 0}};
		snprintf(want, sizeof want, "-o '%s' is the input: write to another file (the input would be replaced)", out);
		expect_roles("-o the input by another path", r, 2, want);
	}
	{
		struct file_role r[] = {{other, "-o", 1}, {"./x.tsv", "--log", 1}, {in, "the input", 0}, {other, "--profile", 1}};
		snprintf(want, sizeof want, "-o and --profile name the same file '%s': one would replace the other; give each its own", other);
		expect_roles("two outputs, one file that does not exist yet", r, 4, want);
	}
	{
		struct file_role r[] = {{"-", "-o", 1}, {"-", "--log", 1}};
		expect_roles("two outputs on standard output", r, 2, "--log and -o both go to standard output; give one of them a file");
	}
	{
		struct file_role r[] = {{"-", "-o", 1}, {"-", "the input", 0}, {NULL, "--log", 1}};
		expect_roles("stdin and stdout, a role not given", r, 3, NULL);
	}
	{
		struct file_role r[] = {{"/dev/null", "-o", 1}, {"/dev/null", "--log", 1}};
		expect_roles("two outputs to /dev/null", r, 2, NULL);
	}
	{
		struct file_role r[] = {{sub, "--profile", 1}};
		snprintf(want, sizeof want, "--profile: cannot write in directory '%s/no-such-dir': No such file or directory", dir);
		expect_roles("an output in a missing directory", r, 1, want);
	}
	{
		struct file_role r[] = {{dir, "-o", 1}};
		snprintf(want, sizeof want, "-o: '%s' is a directory", dir);
		expect_roles("an output that is a directory", r, 1, want);
	}
	{
		char f[300];
		struct file_role r[] = {{f, "-o", 1}};
		snprintf(f, sizeof f, "%s/x.pack", in);	/* a "directory" that is a file */
		snprintf(want, sizeof want, "-o: cannot write in directory '%s': Not a directory", in);
		expect_roles("an output under a regular file", r, 1, want);
	}
	unlink(in);
}

int
main(void)
{
	if (!mkdtemp(dir)) {
		CHECK(0, "mkdtemp");
		return unit_summary();
	}
	test_commit_all();
	test_commit_all_fails();
	test_roles();
	rmdir(dir);
	return unit_summary();
}
