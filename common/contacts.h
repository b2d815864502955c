/* contacts.h - the contacts of one particle in the one canonical order every per-particle sum uses.
 *
 * Particle i's possible contacts are numbered c = 0 .. contact_count(cnt, nw) - 1:
 *   c <  cnt:  its neighbour row's slot c, partners in ascending stable id (neighbor.h): MIRRORED in the row's first
 *              `lower` slots (nbr_lower[i]: the partners of lower stable id; i reads the pair's record), OWNED after
 *              them (the pair is evaluated by i: contact_pairs);
 *   c >= cnt:  wall c - cnt, in index order (nw: the walls when the walls effect is on, else none).
 * The stress sums (particle_stress.h) and MC-strain (mc_strain.h) run over every c; the force sum takes the OWNED
 * ones in pass 1 and the MIRRORED ones, then the walls, in pass 2 (contact_forces.h). A contact_ref also names where
 * its per-contact values live: a row slot (start[i] + c: dem_buffers.h DEM_ROWS) or a wall slot (i * nwalls + w), so that arrays kept per
 * row slot and per wall slot (MC-strain's displacements) are written through one helper; a value kept per pair is
 * found by row_pair.
 * The membrane's patch contacts are not a range here: they have rows of their own (patch_contacts.h), are summed
 * after everything above, and enter neither the stress sums nor MC-strain.
 */
#ifndef DEM_CONTACTS_H
#define DEM_CONTACTS_H
#include "dem_real.h"

enum { CONTACT_OWNED = 0, CONTACT_MIRRORED = 1, CONTACT_WALL = 2 };

typedef struct {
    int kind;    /* CONTACT_* */
    int partner; /* the partner particle's id, or the wall's index */
    int slot;    /* start[i] + c for a pair, i * nwalls + wall for a wall */
} contact_ref;

DEM_INLINE int contact_count(int cnt, int nw) { return cnt + nw; }

/* The row's count of partners of lower stable id from nbr_lower[i], which holds ~count (negative) when the partners
 * stored before i are not exactly those (the particles were stored anew: neighbor.h, contact_forces.h) */
DEM_INLINE int row_lower(int v) { return v < 0 ? ~v : v; }

/* Contact number c of particle i (cnt = nbr_count[i], lower = nbr_lower[i], row0 = nbr_start[i]). */
DEM_INLINE contact_ref contact_at(int i, int c, int cnt, int lower, int row0, int nwalls,
                                  DEM_CONST_GLOBAL int *nbr_list)
{
    contact_ref r;
    if (c < cnt) {
        r.slot = row0 + c;
        r.partner = nbr_list[r.slot];
        r.kind = c >= lower ? CONTACT_OWNED : CONTACT_MIRRORED;
    } else {
        r.kind = CONTACT_WALL;
        r.partner = c - cnt;
        r.slot = i * nwalls + r.partner;
    }
    return r;
}

/* The pair number (neighbor.h pair_index: the pair records' and the per-pair arrays' index) of row slot c of
 * particle i, partner j, given h: how many of the row's slots before c hold a partner stored after i. A partner
 * stored after i makes the pair i's own, own + h (own = own_start[i]); one stored before makes it the partner's,
 * listed at in_pair[in + c - h] (in = in_start[i]). A reader that walks the row in order counts h as it goes. */
DEM_INLINE int row_pair(int i, int j, int c, int h, int own, int in, DEM_CONST_GLOBAL int *in_pair)
{
    return j > i ? own + h : in_pair[in + c - h];
}

/* A per-contact value kept per row slot (row) and per wall slot (wall). */
DEM_INLINE void contact_set(contact_ref r, DEM_GLOBAL real *row, DEM_GLOBAL real *wall, real v)
{
    if (r.kind == CONTACT_WALL)
        wall[r.slot] = v;
    else
        row[r.slot] = v;
}
#endif /* DEM_CONTACTS_H */
