/* contacts: the geometric contact network of a pack, from grain positions alone.
 *
 * A contact is a grain pair (or grain and wall) with overlap h > 0 (physics.md §2-3): its
 * unit normal n pointing from j (or out of the wall) to i, centre distance d, Hertz normal
 * force P and, where the pack carries history for the pair, the index of that history line.
 * Found with the cell grid in O(N). */
#ifndef QUSGM_CONTACTS_H
#define QUSGM_CONTACTS_H

#include <stddef.h>
#include "pack/pack.h"

struct geo_contact {
	size_t i;
	long j;		/* grain index or PACK_WALL(w) */
	double h;	/* overlap (m) */
	double d;	/* centre distance; for a wall, distance centre-wall */
	double n[3];	/* unit normal, on i, from j to i */
	double P;	/* Hertz normal force (N) */
	long hist;	/* index into pack.c[] or -1 */
};

struct geo_contacts {
	size_t n, cap;
	struct geo_contact *c;
};

void contacts_init(struct geo_contacts *gc);
void contacts_free(struct geo_contacts *gc);
/* All contacts with h > 0, grain-grain first (i < j), then grain-wall; 0 or -1. */
int contacts_find(const struct pack *p, struct geo_contacts *gc);
/* Replace p->c by a line per touching contact with P0 from Hertz at the current positions;
 * Q0 and M0 are carried over from the line of the same pair when keep_history is set (lines
 * of pairs that no longer touch are dropped), zero otherwise.  0 or -1. */
int contacts_store(struct pack *p, int keep_history);
/* The E* and R* of contact c. */
void contacts_moduli(const struct pack *p, const struct geo_contact *c, double *Es, double *Rs);
/* Inward normal of wall w and the coordinate of its plane. */
void contacts_wall_plane(const struct pack *p, int w, double n[3], double *pos);

#endif
