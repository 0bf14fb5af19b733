/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_signals: a termination signal that comes while an output's temporary file is being
 * created (lib/base/fileio.c, file_out_open) leaves no temporary behind, whether it comes to
 * the main thread or to another thread (one of OpenMP's workers).  make killtest once found a
 * .NAME.XXXXXX left after a HUP: the file was recorded for removal only after mkstemp had made
 * it, and the handler could run on a worker thread beside the main one.  Deterministic: this
 * program's mkstemp (which fileio.c's call reaches, the library being linked statically) makes
 * the file, then sends the signal at that very moment, before file_out_open can record it. */
#include "base/fileio.h"
#include "base/msg.h"
#include "unit.h"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char dir[] = "/tmp/qusgm-test-signals.XXXXXX";

/* Where mkstemp sends the signal: 0 none, 1 this thread, 2 the other thread. */
static int send_to;
static int send_sig;
static volatile pid_t other_tid;

int mkstemp(char *tmpl);

/* mkstemp: the file made as the C library's would (O_EXCL, 0600), then the signal. */
int
mkstemp(char *tmpl)
{
	size_t n = strlen(tmpl);
	unsigned seed = (unsigned)getpid();
	int tries, fd = -1, k;

	for (tries = 0; tries < 100 && fd < 0; tries++) {
		for (k = 1; k <= 6; k++) {
			seed = seed * 1103515245u + 12345u;
			tmpl[n - (size_t)k] = "abcdefghijklmnopqrstuvwxyz"[(seed >> 16) % 26];
		}
		fd = open(tmpl, O_RDWR | O_CREAT | O_EXCL, 0600);
	}
	if (fd >= 0 && send_to == 1) {
		raise(send_sig);
	} else if (fd >= 0 && send_to == 2) {
		struct timespec t = {0, 200000000};

		syscall(SYS_tgkill, (pid_t)getpid(), other_tid, send_sig);
		/* the other thread's handler has the time to run (and, handing the signal on to this
		 * one, to come back): before the fix it removed what was recorded, without this
		 * file, and the process died here with the file left */
		nanosleep(&t, NULL);
	}
	return fd;
}

static void *
other_thread(void *arg)
{
	(void)arg;
	other_tid = (pid_t)syscall(SYS_gettid);
	for (;;)
		pause();
	return NULL;
}

/* The entries of dir other than . and .. */
static int
count_files(void)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	int n = 0;

	if (!d)
		return -1;
	while ((e = readdir(d)))
		if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
			n++;
	closedir(d);
	return n;
}

/* A child opens DIR/out.pack with the signal sent from inside mkstemp (to this thread or to
 * the other); it must die of the signal and leave dir empty. */
static void
one_case(int to, int sig, const char *name)
{
	char path[256];
	pid_t pid;
	int status = 0, left;

	snprintf(path, sizeof path, "%s/out.pack", dir);
	fflush(stdout);
	pid = fork();
	if (pid == 0) {
		struct file_out o;
		pthread_t th;

		file_catch_signals();	/* as cli_parse does, on the main thread */
		if (pthread_create(&th, NULL, other_thread, NULL) != 0)
			_exit(3);
		while (!other_tid)
			sched_yield();
		send_to = to;
		send_sig = sig;
		if (file_out_open(&o, path) != 0)
			_exit(4);
		_exit(0);	/* not reached: the signal is handled when file_out_open records the file */
	}
	if (pid < 0 || waitpid(pid, &status, 0) != pid) {
		CHECK(0, "%s: fork and wait", name);
		return;
	}
	left = count_files();
	CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sig, "%s: the tool dies of the signal (status %#x)", name,
	    (unsigned)status);
	CHECK(left == 0, "%s: no temporary file left (%d in the directory)", name, left);
	if (left > 0) {	/* clean for the next case */
		DIR *d = opendir(dir);
		struct dirent *e;
		char p[512];

		while (d && (e = readdir(d)))
			if (e->d_name[0] == '.' && strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
				snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
				unlink(p);
			}
		if (d)
			closedir(d);
	}
}

int
main(void)
{
	if (!mkdtemp(dir)) {
		CHECK(0, "mkdtemp");
		return unit_summary();
	}
	one_case(1, SIGTERM, "TERM on the main thread as the temporary is made");
	one_case(1, SIGHUP, "HUP on the main thread as the temporary is made");
	one_case(2, SIGTERM, "TERM on another thread as the temporary is made");
	one_case(2, SIGHUP, "HUP on another thread as the temporary is made");
	one_case(2, SIGINT, "INT on another thread as the temporary is made");
	rmdir(dir);
	return unit_summary();
}
