/* SPDX-License-Identifier: GPL-3.0-or-later */
/* law: the table of the contact laws (see law.h); each law is its own file (hertz.c,
 * linear.c). */
#include "contact/law.h"
#include "base/msg.h"

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
	if (!(law = contact_law_find(key)))
		msg_seterr("meta contact-law '%s': no such contact law", key);
	return law;
}
