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

/* The whole text of a script file (NUL-terminated; the caller frees it). */
static char *
read_text(const char *path, const char *what)
{
	FILE *fp = fopen(path, "rb");
	char *s = NULL;
	size_t len = 0;
	FILE *m;
	char buf[65536];
	size_t k;

	if (!fp)
		msg_die(EXIT_DATA, "%s: %s (%s: Debian's libjs-three, or %s FILE)", path, strerror(errno), what,
		    strcmp(what, "three.js") == 0 ? "--three" : "--controls");
	if (!(m = open_memstream(&s, &len)))
		msg_die(EXIT_DATA, "out of memory");
	while ((k = fread(buf, 1, sizeof buf, fp)) > 0)
		fwrite(buf, 1, k, m);
	if (ferror(fp))
		msg_die(EXIT_DATA, "%s: read error", path);
	fclose(fp);
	if (fclose(m) != 0)
		msg_die(EXIT_DATA, "out of memory");
	if (strlen(s) != len)
		msg_die(EXIT_DATA, "%s: not a script (a NUL byte)", path);
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
	{
		struct file_role fr[] = {{st.output, "-o", 1}, {st.input, "the input", 0}};
		if (file_roles_check(fr, 2))
			cli_usage_error("%s", msg_geterr());
	}
	cli_usage_done();
	three_path = default_path(three_path, "QUSGM_THREE_JS", THREE_JS);
	controls_path = default_path(controls_path, "QUSGM_ORBIT_JS", CONTROLS_JS);
	three = read_text(three_path, "three.js");
	if (*controls_path)
		controls = read_text(controls_path, "OrbitControls");
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
