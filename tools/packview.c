/* SPDX-License-Identifier: GPL-3.0-or-later */
/* packview: a pack as one self-contained HTML page with a 3D view (three.js inlined). */
#include "analysis/measure.h"
#include "analysis/view.h"
#include "base/cli.h"
#include "base/fileio.h"
#include "base/msg.h"
#include "pack/packio.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Debian's libjs-three: three.js and its OrbitControls as classic scripts.  The page inlines
 * them when packview runs, so that it follows the installed package (its security updates)
 * and the build needs no JavaScript. */
#define THREE_JS "/usr/share/javascript/three/three.min.js"
#define CONTROLS_JS "/usr/share/javascript/three/examples/js/controls/OrbitControls.js"

static const char *three_path, *controls_path;

static struct cli_opt opts[] = {
	{"three", 0, CLI_STRING, &three_path, "FILE", "three.js to inline (default: $QUSGM_THREE_JS, else " THREE_JS ")", NULL},
	{"controls", 0, CLI_STRING, &controls_path, "FILE",
	    "OrbitControls to inline (default: $QUSGM_ORBIT_JS, else libjs-three's; '' for the page's own orbit control)", NULL},
	{NULL, 0, CLI_END, NULL, NULL, NULL, NULL},
};

static const struct cli_tool tool = {
	"packview", "[--three FILE] [--controls FILE] [-o FILE] [FILE]",
	"Write one self-contained HTML page that shows a pack in 3D in any browser, offline: grains coloured by a field, force chains, slabs.",
	opts, 1,
};

/* A script file is at most this large: three.min.js is 0.6 MB, three.module.js 1.2 MB. */
#define SCRIPT_MAX (16L << 20)

/* The whole text of a script file (NUL-terminated; the caller frees it): a regular file of
 * 1 byte to SCRIPT_MAX, no NUL, holding the word it must (three.js names THREE and its
 * REVISION, OrbitControls itself).  An empty file, /dev/null, /dev/zero, a FIFO, or a text
 * that is no such script would make a page that shows nothing, or never be read to its end. */
static char *
read_text(const char *path, const char *what, const char *const words[2])
{
	FILE *fp = fopen(path, "rb");
	const char *opt = strcmp(what, "three.js") == 0 ? "--three" : "--controls";
	struct stat sb;
	char *s;
	size_t len;

	if (!fp)
		msg_die(EXIT_DATA, "%s: %s (%s: Debian's libjs-three, or %s FILE)", path, strerror(errno), what, opt);
	if (fstat(fileno(fp), &sb) != 0 || !S_ISREG(sb.st_mode))
		msg_die(EXIT_DATA, "%s: not a regular file (%s %s: a script file, read whole)", path, opt, what);
	if (sb.st_size == 0)
		msg_die(EXIT_DATA, "%s: empty, not %s (%s)", path, what, opt);
	if (sb.st_size > SCRIPT_MAX)
		msg_die(EXIT_DATA, "%s: %lld bytes, more than the %ld MiB a script may have (%s %s)", path,
		    (long long)sb.st_size, SCRIPT_MAX >> 20, opt, what);
	/* its size, and one byte more to see that it grew meanwhile */
	if (!(s = malloc((size_t)sb.st_size + 2)))
		msg_die(EXIT_DATA, "out of memory");
	len = fread(s, 1, (size_t)sb.st_size + 1, fp);
	s[len] = 0;
	if (ferror(fp) || len != (size_t)sb.st_size || strlen(s) != len ||
	    (!strstr(s, words[0]) && !(words[1] && strstr(s, words[1])))) {
		int e = ferror(fp), nul = strlen(s) != len;
		fclose(fp);
		free(s);
		if (e)
			msg_die(EXIT_DATA, "%s: read error", path);
		if (len != (size_t)sb.st_size)
			msg_die(EXIT_DATA, "%s: changed while read (%s %s)", path, opt, what);
		if (nul)
			msg_die(EXIT_DATA, "%s: not a script (a NUL byte)", path);
		msg_die(EXIT_DATA, "%s: not %s (no '%s'%s%s%s in it; %s FILE)", path, what, words[0],
		    words[1] ? " or '" : "", words[1] ? words[1] : "", words[1] ? "'" : "", opt);
	}
	fclose(fp);
	return s;
}

static const char *
default_path(const char *given, const char *env, const char *fallback)
{
	const char *e;

	if (given)
		return given;
	e = getenv(env);
	return e && *e ? e : fallback;
}

int
main(int argc, char **argv)
{
	struct cli_state st;
	struct pack p;
	struct grain_forces g;
	struct view_scripts s;
	struct file_out out;
	const char *name;
	char *page = NULL, *three, *controls = NULL;
	size_t len = 0;
	FILE *m;

	msg_init(argv[0]);
	cli_parse(&tool, argc, argv, &st);
	three_path = default_path(three_path, "QUSGM_THREE_JS", THREE_JS);
	controls_path = default_path(controls_path, "QUSGM_ORBIT_JS", CONTROLS_JS);
	{
		/* -o is none of the inputs, the scripts included (same device and inode) */
		struct file_role fr[] = {{st.output, "-o", 1}, {st.input, "the input", 0},
		    {three_path, "the --three file", 0}, {*controls_path ? controls_path : NULL, "the --controls file", 0}};
		if (file_roles_check(fr, 4))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
	{
		static const char *const three_words[2] = {"THREE", "REVISION"}, *const orbit_words[2] = {"OrbitControls", NULL};
		three = read_text(three_path, "three.js", three_words);
		if (*controls_path)
			controls = read_text(controls_path, "OrbitControls", orbit_words);
	}
	s = (struct view_scripts){three, three_path, controls, controls_path};

	if (pack_read_path(st.input, &p))
		msg_die_err(EXIT_DATA);
	name = file_display_name(st.input);
	if (measure_grain_forces(&p, &g))
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	/* the page in memory first: nothing half-written reaches stdout either */
	if (!(m = open_memstream(&page, &len)))
		msg_die(EXIT_DATA, "out of memory");
	if (view_write_html(m, &p, &g, name, &s))
		msg_die(EXIT_DATA, "%s: %s", name, msg_geterr());
	if (fclose(m) != 0)
		msg_die(EXIT_DATA, "out of memory");
	if (file_out_open(&out, st.output))
		msg_die_err(EXIT_DATA);
	errno = 0;
	if (fwrite(page, 1, len, out.fp) != len) {
		int e = errno ? errno : EIO;
		file_out_abort(&out);
		msg_die(EXIT_DATA, "%s: write error: %s", st.output ? st.output : "<stdout>", strerror(e));
	}
	if (file_out_commit(&out))
		msg_die_err(EXIT_DATA);
	free(page);
	free(three);
	free(controls);
	grain_forces_free(&g);
	pack_free(&p);
	return 0;
}
