/* patch_contacts.c - the patch rows' build at each neighbour rebuild (common/patch_contacts.h): the current sphere rows
 * become the old ones the history is carried from; capacities and reach as the driver asks (the forces and the
 * vertices' sums are one launch each, patch_forces and patch_gather). Written once for every backend. */
#include "backend.h"

static int patch_alloc(const dem_backend_ops *o, dem_backend *b, int id)
{
    dem_core *c = DEM_CORE(b);
    size_t bytes = dem_buffer_bytes(c, id);
    return bytes != c->bytes[id] ? o->alloc(b, TABLE_ONE, 0, id, bytes, NULL) : 0;
}

int dem_stage_patch_build(const dem_backend_ops *o, dem_backend *b, int first, int maxp, int maxv, double reach)
{
    dem_core *c = DEM_CORE(b);
    static const int rows[4] = {BUF_PCOUNT, BUF_PLIST, BUF_PHIST, BUF_PTOUCH};
    static const int old[4] = {BUF_OLD_PCOUNT, BUF_OLD_PLIST, BUF_OLD_PHIST, BUF_OLD_PTOUCH};
    if (first) { /* the rows in use become the old rows */
        c->maxp_old = c->maxp;
        for (int k = 0; k < 4; k++) {
            dem_bufref from = {TABLE_ONE, rows[k]}, to = {TABLE_ONE, old[k]};
            if (patch_alloc(o, b, old[k]) || (c->bytes[rows[k]] && o->copy(b, from, to, c->bytes[rows[k]])))
                return 1;
        }
    }
    c->maxp = maxp, c->maxv = maxv;
    c->si[SI_MAXP] = maxp, c->si[SI_MAXPO] = c->maxp_old, c->si[SI_MAXV] = maxv;
    c->sr[SR_REACH] = reach;
    static const int grown[5] = {BUF_PLIST, BUF_PHIST, BUF_PTOUCH, BUF_PREC, BUF_VLIST};
    for (int k = 0; k < 5; k++)
        if (patch_alloc(o, b, grown[k]))
            return 1;
    return dem_launch(o, b, K_patch_build);
}
