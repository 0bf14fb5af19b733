/* SPDX-License-Identifier: GPL-3.0-or-later */
/* law: the table of the contact laws (see law.h); each law is its own file (hertz.c,
 * linear.c). */
#include "contact/law.h"
#include "base/msg.h"

#include <stdio.h>
#include <string.h>

#define CONTACT_LAW_ROW(id) &contact_law_##id,
const struct contact_law *const contact_laws[] = {CONTACT_LAWS(CONTACT_LAW_ROW) NULL};
#undef CONTACT_LAW_ROW

const struct contact_law *
contact_law_find(const char *name)
{
	const struct contact_law *const *l;

	for (l = contact_laws; *l; l++)
		if (!strcmp(name, (*l)->name) || ((*l)->pack_key && !strcmp(name, (*l)->pack_key)))
			return *l;
	return NULL;
}

const struct contact_law *
contact_law_of_pack(const struct pack *p)
{
	const char *key = pack_get_meta(p, "contact-law");
	const struct contact_law *law;

	if (!key)
		return contact_laws[0];
	if (!(law = contact_law_find(key))) {
		char names[256];

		contact_law_names(names, sizeof names);
		msg_seterr("meta contact-law '%s': no such contact law (the laws: %s)", key, names);
	}
	return law;
}

void
contact_law_names(char *buf, size_t size)
{
	const struct contact_law *const *l;
	size_t at = 0;

	if (size == 0)
		return;
	buf[0] = 0;
	for (l = contact_laws; *l && at < size; l++) {
		int k = (*l)->pack_key && strcmp((*l)->pack_key, (*l)->name) ?
		    snprintf(buf + at, size - at, "%s%s (%s)", at ? ", " : "", (*l)->name, (*l)->pack_key) :
		    snprintf(buf + at, size - at, "%s%s", at ? ", " : "", (*l)->name);

		if (k < 0)
			break;
		at += (size_t)k;
	}
}

const struct contact_law *
contact_law_choose(const struct pack *p, const char *name)
{
	const struct contact_law *law;
	char names[256];

	if (!name)
		return contact_law_of_pack(p);
	if (!(law = contact_law_find(name))) {
		contact_law_names(names, sizeof names);
		msg_seterr("no such contact law '%s' (the laws: %s)", name, names);
	}
	return law;
}

int
contact_law_claim(struct pack *p, const struct contact_law *law)
{
	const char *key = pack_get_meta(p, "contact-law");

	if ((key ? contact_law_find(key) : contact_laws[0]) == law)
		return 0;
	return pack_set_meta(p, "contact-law", law->pack_key ? law->pack_key : law->name);
}
