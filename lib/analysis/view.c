/* SPDX-License-Identifier: GPL-3.0-or-later */
/* view: a pack as one self-contained HTML page (view.h). */
#include "analysis/view.h"
#include "base/msg.h"
#include "base/numfmt.h"
#include "base/quat.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* A JSON string; '<' as \u003c, so that no "</script" ends the data block early. */
static void
put_json_string(FILE *fp, const char *s)
{
	const unsigned char *u = (const unsigned char *)s;

	fputc('"', fp);
	for (; *u; u++) {
		if (*u == '"' || *u == '\\')
			fprintf(fp, "\\%c", *u);
		else if (*u == '\n')
			fputs("\\n", fp);
		else if (*u < 0x20 || *u == '<' || *u == 0x7f)
			fprintf(fp, "\\u%04x", *u);
		else
			fputc(*u, fp);
	}
	fputc('"', fp);
}

static void
put_json_number(FILE *fp, double v)
{
	char b[40];

	if (!isfinite(v)) {
		fputs("null", fp);
		return;
	}
	num_format(b, v);
	fputs(b, fp);
}

/* Base64 (RFC 4648, padded) of n bytes, as a JSON string. */
static void
put_base64(FILE *fp, const unsigned char *b, size_t n)
{
	static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	size_t k;

	fputc('"', fp);
	for (k = 0; k + 2 < n; k += 3) {
		unsigned long v = (unsigned long)b[k] << 16 | (unsigned long)b[k + 1] << 8 | b[k + 2];
		char q[4] = {a[v >> 18], a[v >> 12 & 63], a[v >> 6 & 63], a[v & 63]};
		fwrite(q, 1, 4, fp);
	}
	if (n - k == 1) {
		unsigned long v = (unsigned long)b[k] << 16;
		fprintf(fp, "%c%c==", a[v >> 18], a[v >> 12 & 63]);
	} else if (n - k == 2) {
		unsigned long v = (unsigned long)b[k] << 16 | (unsigned long)b[k + 1] << 8;
		fprintf(fp, "%c%c%c=", a[v >> 18], a[v >> 12 & 63], a[v >> 6 & 63]);
	}
	fputc('"', fp);
}

/* 32-bit words, little-endian as the typed arrays of every browser's machine read them. */
struct words {
	unsigned char *b;
	size_t n;	/* words */
};

static int
words_alloc(struct words *w, size_t n)
{
	w->n = n;
	if (!(w->b = malloc(4 * (n ? n : 1)))) {
		msg_seterr("out of memory");
		return -1;
	}
	return 0;
}

static void
word_set(struct words *w, size_t k, uint32_t u)
{
	unsigned char *b = w->b + 4 * k;

	b[0] = (unsigned char)u, b[1] = (unsigned char)(u >> 8), b[2] = (unsigned char)(u >> 16), b[3] = (unsigned char)(u >> 24);
}

static void
word_set_float(struct words *w, size_t k, double v)
{
	float f = (float)v;
	uint32_t u;

	memcpy(&u, &f, sizeof u);
	word_set(w, k, u);
}

/* "key": base64 of w, then freed. */
static void
put_words(FILE *fp, const char *key, struct words *w)
{
	fprintf(fp, ",\n\"%s\":", key);
	put_base64(fp, w->b, 4 * w->n);
	free(w->b);
	w->b = NULL;
}

/* One field: its key, label, unit and values. */
static void
put_field(FILE *fp, int first, const char *key, const char *label, const char *unit, const char *kind, struct words *w)
{
	fprintf(fp, "%s{\"key\":\"%s\",\"label\":\"%s\",\"unit\":\"%s\",\"kind\":\"%s\",\"data\":", first ? "" : ",\n",
	    key, label, unit, kind);
	put_base64(fp, w->b, 4 * w->n);
	free(w->b);
	w->b = NULL;
	fputc('}', fp);
}

/* The angle of grain i's face normal R(q) e3 from the z axis, 0 to 90 degrees; NaN for a
 * sphere, which has none. */
static double
tilt_degrees(const struct pack *p, size_t i)
{
	double R[9];

	if (!shape_of(pack_grain_shape(p, i))->oriented)
		return NAN;
	quat_to_matrix(p->q + 4 * i, R);
	return acos(fmin(fabs(R[8]), 1.0)) * 180 / M_PI;
}

/* The pack's description: title, counts, box, the scripts' names, history and meta. */
static void
put_header(FILE *fp, const struct pack *p, const struct grain_forces *g, const char *title, const struct view_scripts *s)
{
	size_t i, k, nplates = 0, nhyd = 0, ngg = 0;
	int a;

	for (i = 0; i < p->n; i++) {
		nplates += pack_grain_shape(p, i) != SHAPE_SPHERE;
		nhyd += p->has_phase && p->phase[i] == PHASE_HYDRATE;
	}
	for (k = 0; k < g->nlink; k++)
		ngg += !PACK_IS_WALL(g->link[k].j);
	fputs("{\"title\":", fp);
	put_json_string(fp, title);
	fprintf(fp, ",\n\"n\":%zu,\"plates\":%zu,\"hydrate\":%zu,\"has_phase\":%d,\"has_forces\":%d,\"contacts_gg\":%zu,\"contacts_gw\":%zu,\n\"box\":[",
	    p->n, nplates, nhyd, p->has_phase, g->has_forces, ngg, g->nlink - ngg);
	for (a = 0; a < 6; a++) {
		put_json_number(fp, p->box[a]);
		fputs(a < 5 ? "," : "],\"periodic\":[", fp);
	}
	fprintf(fp, "%d,%d,%d],\n\"scripts\":[", p->periodic[0], p->periodic[1], p->periodic[2]);
	put_json_string(fp, s->three_name ? s->three_name : "");
	fputc(',', fp);
	put_json_string(fp, s->controls && *s->controls && s->controls_name ? s->controls_name : "");
	fputs("],\n\"history\":[", fp);
	for (k = 0; k < p->nhist; k++) {
		if (k)
			fputs(",\n", fp);
		put_json_string(fp, p->history[k]);
	}
	fputs("],\n\"meta\":[", fp);
	for (k = 0; k < p->nmeta; k++) {
		fputs(k ? ",[" : "[", fp);
		put_json_string(fp, p->meta[k].key);
		fputc(',', fp);
		put_json_string(fp, p->meta[k].value);
		fputc(']', fp);
	}
	fputc(']', fp);
}

/* The fields, the default first: the phases where there are hydrate grains. */
static int
put_fields(FILE *fp, const struct pack *p, const struct grain_forces *g, int plates)
{
	struct words w;
	size_t i;

	fputs(",\n\"fields\":[", fp);
	if (p->has_phase) {
		if (words_alloc(&w, p->n))
			return -1;
		for (i = 0; i < p->n; i++)
			word_set_float(&w, i, p->phase[i]);
		put_field(fp, 1, "phase", "phase", "0 mineral, 1 hydrate", "category", &w);
	}
	if (words_alloc(&w, p->n))
		return -1;
	for (i = 0; i < p->n; i++)
		word_set_float(&w, i, g->z[i]);
	put_field(fp, !p->has_phase, "coordination", "coordination", "contacts", "linear", &w);
	if (words_alloc(&w, p->n))
		return -1;
	for (i = 0; i < p->n; i++)
		word_set_float(&w, i, p->r[i]);
	put_field(fp, 0, "radius", plates ? "spheroradius r" : "radius", "m", "linear", &w);
	if (plates) {
		if (words_alloc(&w, p->n))
			return -1;
		for (i = 0; i < p->n; i++)
			word_set_float(&w, i, p->side[i]);
		put_field(fp, 0, "side", "core side L", "m", "linear", &w);
		if (words_alloc(&w, p->n))
			return -1;
		for (i = 0; i < p->n; i++)
			word_set_float(&w, i, tilt_degrees(p, i));
		put_field(fp, 0, "tilt", "face normal from z", "degrees", "linear", &w);
	}
	if (g->has_forces) {
		if (words_alloc(&w, p->n))
			return -1;
		for (i = 0; i < p->n; i++)
			word_set_float(&w, i, g->fmax[i]);
		put_field(fp, 0, "fmax", "largest contact force", "N", "linear", &w);
		if (words_alloc(&w, p->n))
			return -1;
		for (i = 0; i < p->n; i++)
			word_set_float(&w, i, g->residual[i]);
		put_field(fp, 0, "residual", "net force / largest contact force", "1", "log", &w);
	}
	fputc(']', fp);
	return 0;
}

/* The contacts: grain i, grain j or the wall (-1 - w), the normal force. */
static int
put_links(FILE *fp, const struct grain_forces *g)
{
	struct words w;
	size_t k;

	if (words_alloc(&w, g->nlink))
		return -1;
	for (k = 0; k < g->nlink; k++)
		word_set(&w, k, (uint32_t)g->link[k].i);
	put_words(fp, "li", &w);
	if (words_alloc(&w, g->nlink))
		return -1;
	for (k = 0; k < g->nlink; k++)
		word_set(&w, k, (uint32_t)(int32_t)g->link[k].j);
	put_words(fp, "lj", &w);
	if (words_alloc(&w, g->nlink))
		return -1;
	for (k = 0; k < g->nlink; k++)
		word_set_float(&w, k, g->link[k].P);
	put_words(fp, "lp", &w);
	return 0;
}

static int
put_data(FILE *fp, const struct pack *p, const struct grain_forces *g, const char *title, const struct view_scripts *s)
{
	struct words w;
	size_t i;
	double c[3];
	int a, plates = pack_first_plate(p) != (size_t)-1;

	put_header(fp, p, g, title, s);
	for (a = 0; a < 3; a++)
		c[a] = 0.5 * (p->box[a] + p->box[a + 3]);
	if (words_alloc(&w, 3 * p->n))
		return -1;
	for (i = 0; i < 3 * p->n; i++)
		word_set_float(&w, i, p->x[i] - c[i % 3]);
	put_words(fp, "pos", &w);
	if (words_alloc(&w, p->n))
		return -1;
	for (i = 0; i < p->n; i++)
		word_set_float(&w, i, p->r[i]);
	put_words(fp, "rad", &w);
	if (plates) {
		if (words_alloc(&w, p->n))
			return -1;
		for (i = 0; i < p->n; i++)
			word_set_float(&w, i, p->side[i]);
		put_words(fp, "side", &w);
		if (words_alloc(&w, 4 * p->n))
			return -1;
		for (i = 0; i < 4 * p->n; i++)
			word_set_float(&w, i, p->q[i]);
		put_words(fp, "quat", &w);
	}
	if (put_fields(fp, p, g, plates))
		return -1;
	if (put_links(fp, g))
		return -1;
	fputs("}\n", fp);
	return 0;
}

/* A script's text, with any "</script", in any case, written "<\/script" so that it cannot end
 * its element, and any "<!--" written "<\!--" so that it cannot open the HTML spec's escaped
 * script data, in which a "<script" hides the element's end and blanks the page: in a string
 * or a regular expression, where a script has them, the same text to JavaScript. */
static void
put_script(FILE *fp, const char *js)
{
	const char *s = js, *t;

	for (t = s; (t = strchr(t, '<')) != NULL; t++)
		if (strncasecmp(t, "</script", 8) == 0 || strncmp(t, "<!--", 4) == 0) {
			fwrite(s, 1, (size_t)(t - s) + 1, fp);
			fputc('\\', fp);
			s = t + 1;	/* "/script" or "!--" follows as it was, its case kept */
		}
	fputs(s, fp);
}

int
view_write_html(FILE *fp, const struct pack *p, const struct grain_forces *g, const char *title,
    const struct view_scripts *s)
{
	/* the template's places for the three parts, in this order */
	static const char *const mark[3] = {"<!--@THREE@-->", "<!--@CONTROLS@-->", "<!--@DATA@-->"};
	const char *at = view_page_html;
	int k;

	if (p->n > (size_t)INT32_MAX) {
		msg_seterr("%zu grains: more than the page's 32-bit indices hold", p->n);
		return -1;
	}
	for (k = 0; k < 3; k++) {
		const char *m = strstr(at, mark[k]);

		if (!m) {
			msg_seterr("the page template has no %s", mark[k]);
			return -1;
		}
		fwrite(at, 1, (size_t)(m - at), fp);
		at = m + strlen(mark[k]);
		if (k == 0)
			put_script(fp, s->three);
		else if (k == 1)
			put_script(fp, s->controls ? s->controls : "");
		else if (put_data(fp, p, g, title, s))
			return -1;
	}
	fputs(at, fp);
	errno = 0;
	if (fflush(fp) != 0 || ferror(fp)) {
		msg_seterr("write error: %s", strerror(errno ? errno : EIO));
		return -1;
	}
	return 0;
}
