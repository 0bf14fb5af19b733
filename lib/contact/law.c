/* SPDX-License-Identifier: GPL-3.0-or-later */
/* law: the table of the contact laws (see law.h), and the policy the spring laws share; each
 * law is its own file (hertz.c, linear.c, harmonic.c). */
#include "contact/law.h"
#include "base/vec3.h"
#include "base/msg.h"

#include <math.h>
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

	if (size == 0)
		return;
	buf[0] = 0;
	for (l = contact_laws; *l; l++)
		if ((*l)->pack_key && strcmp((*l)->pack_key, (*l)->name))
			msg_list_add(buf, size, "%s (%s)", (*l)->name, (*l)->pack_key);
		else
			msg_list_add(buf, size, "%s", (*l)->name);
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

const struct contact_law *const contact_laws_qs_friction[] = {&contact_law_hertz_mindlin, NULL};

int
contact_law_in(const struct contact_law *law, const struct contact_law *const *laws)
{
	for (; *laws; laws++)
		if (*laws == law)
			return 1;
	return 0;
}

const struct contact_law *
contact_law_require(const struct pack *p, const char *who, const struct contact_law *const *laws)
{
	const struct contact_law *law = contact_law_of_pack(p), *const *l;
	char names[256];

	if (!law || contact_law_in(law, laws))
		return law;
	names[0] = 0;
	for (l = laws; *l; l++)
		msg_list_add(names, sizeof names, "%s", (*l)->name);
	msg_seterr("the pack's contact law is %s (meta contact-law); %s runs %s", law->name, who, names);
	return NULL;
}

int
contact_law_claim(struct pack *p, const struct contact_law *law)
{
	const char *key = pack_get_meta(p, "contact-law");

	if ((key ? contact_law_find(key) : contact_laws[0]) == law)
		return 0;
	return pack_set_meta(p, "contact-law", law->pack_key ? law->pack_key : law->name);
}

double
law_pack_kn(const struct contact_law *law, const struct pack *p)
{
	double kn;

	return pack_get_meta_double(p, "kn", &kn) == 0 && kn > 0 && isfinite(kn) ? kn : law->kn;
}

void
law_pack_bind(const struct contact_law *law, const struct pack *p, struct law_pack *lk)
{
	lk->p = p;
	lk->kn = law->stiffness == LAW_SPRING ? law_pack_kn(law, p) : law->kn;
}

int
law_pack_knows_stiffness(const struct contact_law *law, const struct pack *p)
{
	double kn;

	return law->stiffness == LAW_MODULI || (pack_get_meta_double(p, "kn", &kn) == 0 && kn > 0 && isfinite(kn));
}

double
law_mean_radius(const struct pack *p)
{
	double r0 = 0;
	size_t i, n = p->n;

	for (i = 0; i < n; i++)
		r0 += p->r[i] / n;
	return r0;
}

double
law_spring_dem_units(const struct contact_law *law, const struct pack *p, double r0, double kn, struct law_pair *g,
    struct law_pair *w)
{
	(void)law, (void)p, (void)r0;
	g->kn = w->kn = 1;
	g->Es = w->Es = 1;
	return kn;
}

double
law_spring_overlap(const struct contact_law *law, const struct law_pair *lp, double P)
{
	(void)law;
	return P > 0 ? P / lp->kn : 0.0;
}

void
law_contact_limits(const struct contact_law *law, const struct law_pair *lp, double P, double *qmax, double *mmax)
{
	struct law_tangent t;

	law->tangent(law, lp, law->overlap(law, lp, P), P, &t);
	if (qmax)
		*qmax = t.qmax;
	if (mmax)
		*mmax = t.mmax;
}

int
law_line_at_limit(const struct contact_law *law, const struct law_pair *lp, const struct pack_contact *c)
{
	double qlim = law->coulomb(law, lp, c->P0);

	return qlim > 0 && vec3_norm(c->Q0) >= qlim * (1 - 1e-9);
}

int
law_contact_at_limit(const struct contact_law *law, const struct law_pack *lk, const struct pack_contact *c)
{
	struct law_pair lp;

	law->pair(law, lk, c->i, c->j, &lp);
	return law_line_at_limit(law, &lp, c);
}

double
law_coulomb_mu(const struct contact_law *law, const struct law_pair *lp, double P)
{
	(void)law;
	return law_coulomb_limit(lp->mu, P);
}

double
law_coulomb_none(const struct contact_law *law, const struct law_pair *lp, double P)
{
	(void)law, (void)lp, (void)P;
	return 0;
}

double
law_spring_stiffest(const struct contact_law *law, const struct law_pair *w, double r, double h)
{
	(void)law, (void)r, (void)h;
	return w->kn;
}

double
law_spring_kappa(const struct contact_law *law, const struct pack *p, double kn, double sigma)
{
	(void)law;
	return kn / (sigma * law_mean_radius(p));
}

double
law_spring_kappa_stress(const struct contact_law *law, const struct pack *p, double kn, double kappa)
{
	(void)law;
	return kn / (kappa * law_mean_radius(p));
}

int
law_spring_stress_in_range(const struct contact_law *law, const struct pack *p, double stress)
{
	double kn = law_pack_kn(law, p), kappa = law_spring_kappa(law, p, kn, stress);

	if (p->n && !(kappa >= LAW_SPRING_KAPPA_MIN)) {
		msg_seterr("%g Pa is beyond the small-strain range of the %s law at k_n %g N/m (stiffness number %g, below %g)",
		    stress, law->name, kn, kappa, LAW_SPRING_KAPPA_MIN);
		return -1;
	}
	return 0;
}

void
law_history_none(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double *hist, double Q[3])
{
	(void)law, (void)lp, (void)in, (void)hist;
	Q[0] = Q[1] = Q[2] = 0;
}

void
law_history_set_none(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double Q[3], double *hist)
{
	(void)law, (void)lp, (void)in, (void)Q, (void)hist;
}

void
law_history_force_kept(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double *hist, double Q[3])
{
	int a;

	(void)law, (void)lp, (void)in;
	for (a = 0; a < 3; a++)
		Q[a] = -hist[a];
}

void
law_history_set_force_kept(const struct contact_law *law, const struct law_pair *lp, const struct law_dem_elems *in,
    const double Q[3], double *hist)
{
	int a;

	(void)law, (void)lp, (void)in;
	for (a = 0; a < 3; a++)
		hist[a] = -Q[a];
}

void
contact_law_option_help(char *buf, size_t size)
{
	char names[256];

	contact_law_names(names, sizeof names);
	snprintf(buf, size, "contact law: %s (default: the pack's meta contact-law; none: %s)", names, contact_laws[0]->name);
}
