/* SPDX-License-Identifier: GPL-3.0-or-later */
/* fileio: inputs by name, atomic outputs (see fileio.h). */
#include "base/fileio.h"
#include "base/msg.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

/* The temporary files in flight (a tool may write a pack and a log at once), removed by
 * the signal handler and at exit unless committed. */
#define MAX_TMP 8
static volatile sig_atomic_t tmp_live[MAX_TMP];
static char tmp_pending[MAX_TMP][4096];

static void
remove_all_tmp(void)
{
	int k;

	for (k = 0; k < MAX_TMP; k++)
		if (tmp_live[k])
			unlink(tmp_pending[k]);
}

static void
forget_tmp(const char *path)
{
	int k;

	for (k = 0; k < MAX_TMP; k++)
		if (tmp_live[k] && strcmp(tmp_pending[k], path) == 0)
			tmp_live[k] = 0;
}

/* Record tmp for removal at exit or on a signal; -1 when MAX_TMP are in flight already. */
static int
remember_tmp(const char *tmp)
{
	int k;

	for (k = 0; k < MAX_TMP && tmp_live[k]; k++)
		;
	if (k == MAX_TMP)
		return -1;
	strcpy(tmp_pending[k], tmp);
	tmp_live[k] = 1;
	return 0;
}

void (*file_signal_hook)(void);

/* The thread that installed the handlers (the tools' main thread), which alone handles them. */
static volatile pid_t main_tid;

static pid_t
this_tid(void)
{
	return (pid_t)syscall(SYS_gettid);
}

/* On the main thread: the temporaries removed, the hook, then death by sig.  A signal that came
 * to another thread (one of OpenMP's workers: the kernel gives a process's signal to any thread
 * that does not block it) is handed to the main thread, so that the removal never runs beside
 * the main thread's creation of a temporary: while the main thread creates and records one it
 * blocks these signals (file_out_open), and the one handed on waits till it is recorded. */
static void
remove_tmp_on_signal(int sig)
{
	int saved = errno;

	if (main_tid && this_tid() != main_tid) {
		syscall(SYS_tgkill, (pid_t)getpid(), main_tid, sig);
		errno = saved;
		return;
	}
	if (file_signal_hook)
		file_signal_hook();
	remove_all_tmp();
	signal(sig, SIG_DFL);
	raise(sig);
	errno = saved;
}

static void
remove_tmp_at_exit(void)
{
	remove_all_tmp();
}

/* Catch sig to remove the temporaries, unless it was ignored at start: under nohup SIGHUP is
 * ignored, and a non-interactive shell starts `cmd &` with SIGINT ignored; those stay ignored
 * (the tool keeps running, as the caller asked). */
static void
catch_unless_ignored(int sig)
{
	struct sigaction old, sa;

	if (sigaction(sig, NULL, &old) == 0 && old.sa_handler == SIG_IGN)
		return;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = remove_tmp_on_signal;
	sigemptyset(&sa.sa_mask);
	sigaddset(&sa.sa_mask, SIGINT);
	sigaddset(&sa.sa_mask, SIGTERM);
	sigaddset(&sa.sa_mask, SIGHUP);
	sigaddset(&sa.sa_mask, SIGPIPE);
	sigaction(sig, &sa, NULL);
}

/* The termination signals blocked on this thread; *old gets the mask to put back. */
static void
block_term_signals(sigset_t *old)
{
	sigset_t set;

	sigemptyset(&set);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGHUP);
	sigaddset(&set, SIGPIPE);
	pthread_sigmask(SIG_BLOCK, &set, old);
}

void
file_catch_signals(void)
{
	static int hooked;

	if (hooked)
		return;
	main_tid = this_tid();
	atexit(remove_tmp_at_exit);
	catch_unless_ignored(SIGINT);
	catch_unless_ignored(SIGTERM);
	catch_unless_ignored(SIGHUP);
	catch_unless_ignored(SIGPIPE);
	hooked = 1;
}

void (*file_stdin_hook)(void);

const char *
file_display_name(const char *path)
{
	return !path || strcmp(path, "-") == 0 ? "<stdin>" : path;
}

FILE *
file_in_open(const char *path, const char **display)
{
	FILE *fp;

	*display = file_display_name(path);
	if (*display != path) {
		if (file_stdin_hook)
			file_stdin_hook();
		return stdin;
	}
	fp = fopen(path, "rb");
	if (!fp) {
		msg_seterr("%s: %s", path, strerror(errno));
		return NULL;
	}
	/* fopen opens a directory for reading; its first read fails with EISDIR, which the
	 * line reader would report as a corrupt stream */
	{
		struct stat st;

		if (fstat(fileno(fp), &st) == 0 && S_ISDIR(st.st_mode)) {
			fclose(fp);
			msg_seterr("%s: is a directory", path);
			return NULL;
		}
	}
	return fp;
}

int
file_is_gz(const char *path)
{
	size_t n = path ? strlen(path) : 0;

	return n > 3 && strcmp(path + n - 3, ".gz") == 0;
}

/* path's directory part, "." for none, "/" for the root; NULL when out of memory. */
static char *
dir_of(const char *path)
{
	const char *b = strrchr(path, '/');

	return b ? (b == path ? strdup("/") : strndup(path, (size_t)(b - path))) : strdup(".");
}

/* The file path names: stat when follow (an input, a log: read or written through a
 * symbolic link, into the file it names), else lstat (an output replaced by a rename: a
 * link there is replaced, not followed).  A link that names no file yet (a log through it
 * would create its target): the target's name, in *target (malloc'ed), and -1. */
static int
stat_role(const char *path, int follow, struct stat *st, char **target)
{
	char buf[4096];
	ssize_t n;

	*target = NULL;
	if (!follow)
		return lstat(path, st);
	if (stat(path, st) == 0)
		return 0;
	if (lstat(path, st) != 0 || !S_ISLNK(st->st_mode) || (n = readlink(path, buf, sizeof buf - 1)) <= 0)
		return -1;
	buf[n] = '\0';
	if (buf[0] != '/' && strrchr(path, '/')) {	/* relative to the link's directory */
		size_t d = (size_t)(strrchr(path, '/') - path) + 1;

		if (!(*target = malloc(d + (size_t)n + 1)))
			return -1;
		memcpy(*target, path, d);
		memcpy(*target + d, buf, (size_t)n + 1);
	} else
		*target = strdup(buf);
	return -1;
}

/* Whether a (followed when follow_a) and b (when follow_b) are the same file: the same
 * inode when both exist, else the same directory (by inode) and the same last component. */
static int
same_file(const char *a, int follow_a, const char *b, int follow_b)
{
	struct stat sa, sb;
	const char *ba, *bb;
	char *da, *db, *ta, *tb;
	int same, ea, eb;

	if (!a || !b || strcmp(a, "-") == 0 || strcmp(b, "-") == 0)
		return 0;
	if (strcmp(a, b) == 0)
		return 1;
	ea = stat_role(a, follow_a, &sa, &ta);
	eb = stat_role(b, follow_b, &sb, &tb);
	if (ea == 0 && eb == 0)
		return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
	if (ta || tb) {	/* a dangling link: its target's name, once */
		same = same_file(ta ? ta : a, 0, tb ? tb : b, 0);
		free(ta), free(tb);
		return same;
	}
	ba = strrchr(a, '/') ? strrchr(a, '/') + 1 : a;
	bb = strrchr(b, '/') ? strrchr(b, '/') + 1 : b;
	if (strcmp(ba, bb) != 0)
		return 0;
	da = dir_of(a);
	db = dir_of(b);
	same = da && db && stat(da, &sa) == 0 && stat(db, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
	free(da), free(db);
	return same;
}

int
file_same(const char *a, const char *b, int b_output)
{
	return same_file(a, 1, b, !b_output);
}

int
file_is_stdout(const char *path)
{
	struct stat sp, s1;

	if (!path || strcmp(path, "-") == 0)
		return 1;
	if (strcmp(path, "/dev/stdout") == 0 || strcmp(path, "/dev/fd/1") == 0 || strcmp(path, "/proc/self/fd/1") == 0)
		return 1;
	/* standard output redirected to a file, named by its path: written through stdout (a
	 * second stream opened on it would write over the first, or truncate a file opened for
	 * appending) */
	return stat(path, &sp) == 0 && fstat(1, &s1) == 0 && S_ISREG(sp.st_mode) && S_ISREG(s1.st_mode) &&
	    sp.st_dev == s1.st_dev && sp.st_ino == s1.st_ino;
}

/* A path that exists and is neither a regular file nor a directory: a device or a FIFO,
 * which an output writes into. */
static int
is_special(const char *path)
{
	struct stat st;

	return stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

/* An output named by path can be written: 0, or -1 with the slot set. */
static int
output_writable(const char *path, const char *what)
{
	struct stat st;
	char *dir;
	int r = 0;

	if (stat(path, &st) == 0) {
		if (S_ISDIR(st.st_mode)) {
			msg_seterr("%s: '%s' is a directory", what, path);
			return -1;
		}
		if (!S_ISREG(st.st_mode))
			return 0;
	}
	if (!(dir = dir_of(path))) {
		msg_seterr("out of memory");
		return -1;
	}
	if (stat(dir, &st) != 0 || (!S_ISDIR(st.st_mode) && (errno = ENOTDIR)) || access(dir, W_OK | X_OK) != 0) {
		msg_seterr("%s: cannot write in directory '%s': %s", what, dir, strerror(errno));
		r = -1;
	}
	free(dir);
	return r;
}

int
file_roles_check(const struct file_role *r, int n)
{
	int i, j;

	for (i = 0; i < n; i++) {
		if (!r[i].path || r[i].output == FILE_IN)
			continue;
		if (!*r[i].path) {
			msg_seterr("%s: the file name is empty", r[i].what);
			return -1;
		}
		for (j = 0; j < n; j++) {
			const struct file_role *o = &r[j];
			int in = o->output == FILE_IN;

			if (j == i || !o->path || (!in && j < i))
				continue;
			if (!in && file_is_stdout(r[i].path) && file_is_stdout(o->path)) {
				msg_seterr("%s and %s both go to standard output; give one of them a file", o->what, r[i].what);
				return -1;
			}
			if (is_special(r[i].path) || is_special(o->path))
				continue;
			if (same_file(o->path, in || o->output == FILE_LOG, r[i].path, r[i].output == FILE_LOG)) {
				if (in && r[i].output == FILE_UPDATE)
					continue;	/* the pack updated in place: read whole, then renamed over */
				if (!in)
					msg_seterr("%s and %s name the same file '%s': one would replace the other; give each its own",
					    r[i].what, o->what, r[i].path);
				else
					msg_seterr("%s '%s' is %s: write to another file (the input would be %s)", r[i].what,
					    r[i].path, o->what, r[i].output == FILE_LOG ? "lost" : "replaced");
				return -1;
			}
		}
		if (!file_is_stdout(r[i].path) && output_writable(r[i].path, r[i].what))
			return -1;
	}
	return 0;
}

/* A device or a pipe (-o /dev/null, -o /dev/stderr, a FIFO) is written into: the temporary
 * file and rename would replace the device node with a regular file (as root, /dev/null
 * itself).  1: path is one and o is open on it (or -1 on failure); 0: a regular file or none. */
static int
open_special(struct file_out *o, const char *path)
{
	struct stat sb;

	if (stat(path, &sb) != 0 || S_ISREG(sb.st_mode))
		return 0;
	if (S_ISDIR(sb.st_mode)) {
		msg_seterr("%s: is a directory", path);
		return -1;
	}
	o->fp = fopen(path, "w");
	if (!o->fp) {
		msg_seterr("%s: %s", path, strerror(errno));
		return -1;
	}
	o->path = strdup(path);
	if (!o->path) {
		fclose(o->fp);
		o->fp = NULL;
		msg_seterr("out of memory");
		return -1;
	}
	return 1;
}

/* o->path and o->tmp = "DIR/.NAME.XXXXXX" for mkstemp. */
static int
name_tmp(struct file_out *o, const char *path)
{
	const char *slash = strrchr(path, '/');
	size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0;

	if (strlen(path) + 16 >= sizeof tmp_pending[0]) {
		msg_seterr("%s: path too long", path);
		return -1;
	}
	o->path = strdup(path);
	o->tmp = malloc(strlen(path) + 16);
	if (!o->path || !o->tmp) {
		msg_seterr("out of memory");
		return -1;
	}
	memcpy(o->tmp, path, dirlen);
	sprintf(o->tmp + dirlen, ".%s.XXXXXX", path + dirlen);
	return 0;
}

static void
drop_names(struct file_out *o)
{
	free(o->path);
	free(o->tmp);
	o->path = o->tmp = NULL;
}

int
file_out_open(struct file_out *o, const char *path)
{
	mode_t umask_was;
	sigset_t mask;
	int fd, special, e;

	memset(o, 0, sizeof *o);
	if (file_is_stdout(path)) {
		o->fp = stdout;
		return 0;
	}
	if ((special = open_special(o, path)) != 0)
		return special > 0 ? 0 : -1;
	if (name_tmp(o, path)) {
		drop_names(o);
		return -1;
	}
	file_catch_signals();
	/* created and recorded with the signals held: one that comes in between is handled once
	 * the file is recorded, and removes it */
	block_term_signals(&mask);
	fd = mkstemp(o->tmp);
	if (fd < 0) {
		e = errno;
		pthread_sigmask(SIG_SETMASK, &mask, NULL);
		msg_seterr("%s: cannot create temporary file: %s", path, strerror(e));
		drop_names(o);
		return -1;
	}
	if (remember_tmp(o->tmp)) {
		close(fd);
		unlink(o->tmp);
		pthread_sigmask(SIG_SETMASK, &mask, NULL);
		msg_seterr("%s: too many outputs at once", path);
		drop_names(o);
		return -1;
	}
	pthread_sigmask(SIG_SETMASK, &mask, NULL);
	/* mkstemp makes the file 0600; an output gets the usual 0666 less the umask */
	umask_was = umask(0);
	umask(umask_was);
	fchmod(fd, 0666 & ~umask_was);
	o->fp = fdopen(fd, "w");
	if (!o->fp) {
		msg_seterr("%s: %s", path, strerror(errno));
		close(fd);
		file_out_abort(o);
		return -1;
	}
	return 0;
}

int
file_log_open(struct file_out *o, const char *path)
{
	memset(o, 0, sizeof *o);
	if (file_is_stdout(path)) {	/* also /dev/stdout: written through stdout, never reopened */
		o->fp = stdout;
		return 0;
	}
	if (file_is_gz(path)) {
		msg_seterr("%s: a log is written as plain text while the run goes: name it without .gz (and gzip it afterwards)",
		    path);
		return -1;
	}
	if (!(o->path = strdup(path))) {
		msg_seterr("out of memory");
		return -1;
	}
	/* no temporary (o->tmp NULL): the commit only closes it, an abort keeps it */
	if (!(o->fp = fopen(path, "w"))) {
		msg_seterr("%s: %s", path, strerror(errno));
		drop_names(o);
		return -1;
	}
	return 0;
}

/* Compress the finished temporary file of an output named *.gz: the outputs are written as
 * text and gzipped whole at the commit, so that the rename stays the one atomic step.  The
 * compressed temporary TMP.z is remembered before it is created, so that a signal or an
 * exit during the compression removes it too. */
static int
gzip_in_place(const char *tmp)
{
	char buf[1 << 15], *ztmp = malloc(strlen(tmp) + 4);
	FILE *in = fopen(tmp, "rb");
	gzFile z = NULL;
	size_t n;
	int bad = 0;

	if (ztmp)
		sprintf(ztmp, "%s.z", tmp);
	if (!ztmp || !in || remember_tmp(ztmp)) {
		if (in)
			fclose(in);
		free(ztmp);
		return -1;
	}
	if (!(z = gzopen(ztmp, "wb6"))) {
		fclose(in);
		forget_tmp(ztmp);
		free(ztmp);
		return -1;
	}
	while ((n = fread(buf, 1, sizeof buf, in)) > 0)
		if (gzwrite(z, buf, (unsigned)n) != (int)n)
			bad = 1;
	bad |= ferror(in) != 0;
	fclose(in);
	bad |= gzclose(z) != Z_OK;
	if (bad || rename(ztmp, tmp) != 0) {
		unlink(ztmp);
		forget_tmp(ztmp);
		free(ztmp);
		return -1;
	}
	forget_tmp(ztmp);	/* now TMP itself, still remembered */
	free(ztmp);
	return 0;
}

/* Keep the errno of the first failure on o (e, or EIO when a failure left no errno). */
static void
keep_err(struct file_out *o, int e)
{
	if (!o->err)
		o->err = e ? e : EIO;
}

int
file_out_flush(struct file_out *o)
{
	if (!o->fp)
		return -1;
	errno = 0;
	if (fflush(o->fp) != 0)
		keep_err(o, errno);
	else if (ferror(o->fp))	/* a write failed before, and the flush had nothing left */
		keep_err(o, 0);
	return o->err ? -1 : 0;
}

int
file_out_ready(struct file_out *o)
{
	if (o->ready)
		return 0;
	if (!o->fp)
		return -1;
	file_out_flush(o);
	if (o->fp == stdout) {
		o->fp = NULL;
		if (o->err) {
			msg_seterr("<stdout>: write error: %s", strerror(o->err));
			return -1;
		}
		o->ready = 1;
		return 0;
	}
	errno = 0;
	if (fclose(o->fp) != 0)
		keep_err(o, errno);
	o->fp = NULL;
	if (o->err) {
		msg_seterr("%s: write error: %s", o->path, strerror(o->err));
		file_out_abort(o);
		return -1;
	}
	if (o->tmp && file_is_gz(o->path) && gzip_in_place(o->tmp)) {
		msg_seterr("%s: cannot compress: %s", o->path, strerror(errno));
		file_out_abort(o);
		return -1;
	}
	o->ready = 1;
	return 0;
}

/* The rename of an output that is ready. */
static int
file_out_finish(struct file_out *o)
{
	o->ready = 0;
	if (!o->tmp) {	/* stdout, or written straight into a device or pipe */
		free(o->path);
		o->path = NULL;
		return 0;
	}
	if (rename(o->tmp, o->path) != 0) {
		msg_seterr("%s: cannot rename temporary file: %s", o->path, strerror(errno));
		file_out_abort(o);
		return -1;
	}
	forget_tmp(o->tmp);
	free(o->tmp);
	free(o->path);
	o->tmp = o->path = NULL;
	return 0;
}

int
file_out_commit(struct file_out *o)
{
	if (file_out_ready(o))
		return -1;
	return file_out_finish(o);
}

int
file_out_commit_all(struct file_out *const *o, int n)
{
	int k, j, bad = 0;

	for (k = 0; k < n && !bad; k++)
		if (o[k] && file_out_ready(o[k]))
			bad = 1;
	if (bad) {
		for (j = 0; j < n; j++)
			if (o[j])
				file_out_abort(o[j]);
		return -1;
	}
	for (k = 0; k < n; k++)
		if (o[k] && file_out_finish(o[k]))
			bad = 1;
	return bad ? -1 : 0;
}

void
file_out_abort(struct file_out *o)
{
	if (o->fp && o->fp != stdout)
		fclose(o->fp);
	o->fp = NULL;
	o->ready = 0;
	if (o->tmp) {
		unlink(o->tmp);
		forget_tmp(o->tmp);
	}
	free(o->tmp);
	free(o->path);
	o->tmp = o->path = NULL;
}
