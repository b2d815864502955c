/* state.c - the dynamic state of a run, read out and written back, so that a run can be checkpointed and
 * continued bit for bit (dem_state_get / dem_state_set).
 *
 * What continues a run exactly: positions, velocities, angular velocities, the forces and torques of the last step
 * (velocity Verlet's first half kick uses them), the force on each wall, the wall positions, the step index, and the
 * contact memory: which pairs and walls touch, their tangential springs and (MC-strain) their stored normal forces.
 * The per-particle and per-wall part is every buffer the registry marks as saved (common/dem_buffers.h, its
 * checkpoint column), read and written whole by walking it; the pairs are a list of the touching ones. Neighbour rows
 * are not part of it: results do not depend on the rows (any skin or cell size gives the same bits), so restoring
 * rebuilds them from the positions and puts each touching pair's history back into the new rows.
 */
#include "sim.h"
#include <math.h>
#include "dem_layout.h"
#include "sorted_row.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void dem_state_free(dem_state *st)
{
    if (!st)
        return;
    for (int k = 0; k < st->narrays && k < DEM_STATE_MAX_ARRAYS; k++)
        free(st->arrays[k].data);
    free(st->pair_i), free(st->pair_j), free(st->pair_hist), free(st->pair_rec), free(st->pair_mc_disp);
    free(st->pair_law), free(st->pair_rspring);
    free(st->pair_mc_fn);
    free(st->patch_i), free(st->patch_t), free(st->patch_hist), free(st->patch_side);
    memset(st, 0, sizeof *st);
}

/* A whole field as stored (the rows and the pair-sized fields, read together in storage order; host/core/reorder.c) */
void *sim_field_stored(dem_sim *s, dem_field f, size_t *bytes, int *e)
{
    *bytes = sim_stored_bytes(s, f);
    void *p = malloc(*bytes ? *bytes : 1);
    if (!p) {
        *e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
        return NULL;
    }
    if (!*e && *bytes && dem_stage_read_field(s->ops, s->be, f, p, *bytes))
        *e = sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
    return p;
}

/* The saved pairs, named by the callers' ids, in the order of a run never stored anew: ascending i, then j (a
 * reordered run's rows list the owners in storage order) */
typedef struct {
    int i, j, at;
} pair_key;
static int by_owner(const void *a, const void *b)
{
    const pair_key *p = a, *q = b;
    return p->i != q->i ? (p->i > q->i) - (p->i < q->i) : (p->j > q->j) - (p->j < q->j);
}
/* A per-pair array of `item` bytes per pair put in the order of k (tmp holds item * np bytes); NULL: none kept (a
 * law's states in a run of a law without) */
static void pairs_permute(void *arr, size_t item, const pair_key *k, long np, unsigned char *tmp)
{
    if (!arr)
        return;
    for (long p = 0; p < np; p++)
        memcpy(tmp + item * (size_t)p, (unsigned char *)arr + item * (size_t)k[p].at, item);
    memcpy(arr, tmp, item * (size_t)np);
}

static int pairs_to_api(dem_sim *s, dem_state *st)
{
    long np = st->npairs;
    size_t rs = (size_t)st->real_size;
    if (!s->order.count || np == 0)
        return 0;
    pair_key *k = malloc(sizeof *k * (size_t)np);
    size_t widest = (size_t)(st->has_law > PR_STRIDE ? st->has_law : PR_STRIDE); /* a record, or MDR's row */
    unsigned char *tmp = malloc(widest * rs * (size_t)np);
    if (!k || !tmp) {
        free(k), free(tmp);
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    for (long p = 0; p < np; p++)
        k[p] = (pair_key){sim_api(s, st->pair_i[p]), sim_api(s, st->pair_j[p]), (int)p};
    qsort(k, (size_t)np, sizeof *k, by_owner);
    for (long p = 0; p < np; p++)
        st->pair_i[p] = k[p].i, st->pair_j[p] = k[p].j;
    pairs_permute(st->pair_hist, 3 * rs, k, np, tmp);
    pairs_permute(st->pair_mc_fn, rs, k, np, tmp);
    pairs_permute(st->pair_rec, PR_STRIDE * rs, k, np, tmp);
    pairs_permute(st->pair_mc_disp, 2 * rs, k, np, tmp);
    pairs_permute(st->pair_law, (size_t)st->has_law * rs, k, np, tmp); /* has_law reals per pair */
    pairs_permute(st->pair_rspring, 3 * rs, k, np, tmp);
    free(k), free(tmp);
    return 0;
}

/* The touching sphere-patch contacts of the current rows, by the spheres' ids (stable ids), each sphere's in row order
 * (common/patch_contacts.h): the same list in any storage order */
static int patch_contacts_get(dem_sim *s, dem_state *st)
{
    int e = 0, n = s->n, maxp = DEM_CORE(s->be)->maxp, rs = s->setup.real_size;
    if (!(s->setup.effects & DEM_EFFECT_PATCHES) || !s->mesh.npatch)
        return 0;
    int *cnt = sim_buffer_get(s, BUF_PCOUNT, &e), *list = sim_buffer_get(s, BUF_PLIST, &e);
    unsigned char *touch = sim_buffer_get(s, BUF_PTOUCH, &e), *hist = sim_buffer_get(s, BUF_PHIST, &e);
    long np = 0;
    for (int i = 0; !e && i < n; i++)
        for (int k = 0; k < cnt[i]; k++)
            np += touch[i * maxp + k] != 0;
    if (!e) {
        st->patch_i = malloc(sizeof(int) * (size_t)(np ? np : 1));
        st->patch_t = malloc(sizeof(int) * (size_t)(np ? np : 1));
        st->patch_hist = calloc((size_t)(np ? np : 1), 3 * (size_t)rs);
        st->patch_side = malloc(sizeof(int) * (size_t)(np ? np : 1));
        if (!st->patch_i || !st->patch_t || !st->patch_hist || !st->patch_side)
            e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    np = 0;
    for (int q = 0; !e && q < n; q++)
        for (int i = sim_dev(s, q), k = 0; k < cnt[i]; k++) {
            int slot = i * maxp + k;
            if (!touch[slot])
                continue;
            st->patch_i[np] = q, st->patch_t[np] = list[slot];
            st->patch_side[np] = touch[slot] & PATCH_SAVED;
            memcpy((char *)st->patch_hist + (size_t)np * 3 * rs, hist + (size_t)slot * 3 * rs, 3 * (size_t)rs);
            np++;
        }
    st->npatch = np;
    free(cnt), free(list), free(touch), free(hist);
    return e;
}

/* The saved patch contacts into the rows just rebuilt from the saved positions; DEM_ERR_ARG when one is not there */
static int patch_contacts_set(dem_sim *s, const dem_state *st)
{
    int e = 0, n = s->n, rs = s->setup.real_size;
    dem_core *c = DEM_CORE(s->be);
    if (!(s->setup.effects & DEM_EFFECT_PATCHES) || !s->mesh.npatch)
        return st->npatch ? sim_fail(s, DEM_ERR_ARG, "the saved state has %ld patch contacts; this run has no patches",
                                     st->npatch) : 0;
    int maxp = c->maxp;
    int *cnt = sim_buffer_get(s, BUF_PCOUNT, &e), *list = sim_buffer_get(s, BUF_PLIST, &e);
    unsigned char *touch = calloc(c->bytes[BUF_PTOUCH] + 1, 1), *hist = calloc(c->bytes[BUF_PHIST] + 1, 1);
    if (!e && (!touch || !hist))
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (long p = 0; !e && p < st->npatch; p++) {
        int id = st->patch_i[p], t = st->patch_t[p], i = id >= 0 && id < n ? sim_dev(s, id) : -1;
        int k = i >= 0 ? row_find(list + (size_t)i * maxp, cnt[i], t) : -1;
        if (k < 0) {
            e = sim_fail(s, DEM_ERR_ARG, "saved patch contact of particle %d and triangle %d is not a patch candidate "
                         "of the saved positions", id, t);
            break;
        }
        int flags = st->patch_side ? st->patch_side[p] : (int)PATCH_TOUCHED;
        if ((flags & ~(int)PATCH_SAVED) || !flags) {
            e = sim_fail(s, DEM_ERR_ARG, "saved patch contact %ld has flags %d (not a nonzero combination of %u, %u, "
                         "%u and %u)", p, flags, PATCH_TOUCHED, PATCH_BELOW, PATCH_KNOWN, PATCH_CROSSED);
            break;
        }
        touch[(size_t)i * maxp + k] = (unsigned char)flags;
        memcpy(hist + ((size_t)i * maxp + k) * 3 * rs, (const char *)st->patch_hist + (size_t)p * 3 * rs,
               3 * (size_t)rs);
    }
    if (!e && (s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_PTOUCH}, 0, touch, c->bytes[BUF_PTOUCH], 1) ||
               s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_PHIST}, 0, hist, c->bytes[BUF_PHIST], 1)))
        e = sim_fail(s, DEM_ERR_DEVICE, "%s", c->err);
    free(cnt), free(list), free(touch), free(hist);
    return e;
}

/* The row slot of partner j in particle i's row, or -1 (as stored) */
static int find_slot(const int *cnt, const int *list, const int *start, const int *sid, int i, int j)
{
    int k = row_find_sid(list + start[i], cnt[i], sid, sid[j]);
    return k < 0 ? -1 : start[i] + k;
}

/* MC-strain's force of every row slot, as stored (the device keeps it per pair: mc_strain.h); `all` bytes, the
 * field's size (dem_field_bytes), slots past the rows zero. */
int sim_mc_force_slots(dem_sim *s, unsigned char *buf, size_t all)
{
    int n = s->n, rs = s->setup.real_size, e = 0;
    size_t b, pb;
    memset(buf, 0, all);
    int *cnt = sim_field_stored(s, DEM_FIELD_NBR_COUNT, &b, &e), *list = sim_field_stored(s, DEM_FIELD_NBR_LIST, &b, &e);
    int *start = sim_field_stored(s, DEM_FIELD_NBR_START, &b, &e);
    unsigned char *pf = sim_field_stored(s, DEM_FIELD_MC_FORCE, &pb, &e);
    int *own = e ? NULL : sim_own_starts(cnt, list, start, n);
    if (!e && !own)
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (int i = 0; !e && i < n; i++)
        for (int k = 0; k < cnt[i]; k++) {
            size_t slot = (size_t)start[i] + (size_t)k;
            int p = row_pair_of(cnt, list, start, own, s->setup.sid, i, k);
            if (p >= 0 && (size_t)(p + 1) * rs <= pb && (slot + 1) * rs <= all)
                memcpy(buf + slot * rs, pf + (size_t)p * rs, (size_t)rs);
        }
    free(cnt), free(list), free(start), free(pf), free(own);
    return e;
}

/* Where each particle's hosted pairs (partners stored after it) start in the pair numbering (neighbor.h's
 * pair_index: own_start), from the rows */
int *sim_own_starts(const int *cnt, const int *list, const int *start, int n)
{
    int *own = malloc(sizeof(int) * ((size_t)n + 1));
    if (!own)
        return NULL;
    own[0] = 0;
    for (int i = 0; i < n; i++) {
        int hosted = 0;
        for (int k = 0; k < cnt[i]; k++)
            hosted += list[start[i] + k] > i;
        own[i + 1] = own[i] + hosted;
    }
    return own;
}

/* ---- the arrays saved whole: the registry's checkpoint column (common/dem_buffers.h) ---- */

static dem_state_elem state_elem(int elem)
{
    return elem == DEM_ELEM_REAL ? DEM_STATE_REAL : elem == DEM_ELEM_UINT ? DEM_STATE_UINT : DEM_STATE_INT;
}
static size_t state_elem_bytes(dem_state_elem elem, int rs) { return elem == DEM_STATE_REAL ? (size_t)rs : sizeof(int); }

dem_state_array *dem_state_find(const dem_state *st, const char *name)
{
    for (int k = 0; k < st->narrays && k < DEM_STATE_MAX_ARRAYS; k++)
        if (st->arrays[k].name && !strcmp(st->arrays[k].name, name))
            return (dem_state_array *)&st->arrays[k];
    return NULL;
}

int dem_state_arrays(dem_state *st)
{
    const dem_saved_buffer *sb = dem_saved_buffers();
    dem_core c; /* the sizes of st's header: friction and MC-strain as it says; another gate (wall_pf's): full size */
    memset(&c, 0, sizeof c);
    c.n = st->n, c.nwalls = st->nwalls, c.rs = st->real_size;
    unsigned known = DEM_EFFECT_FRICTION | DEM_EFFECT_MC_STRAIN | DEM_LAW_STATE_BITS | DEM_EFFECT_ROLLING_SPRING;
    unsigned law = st->has_law == MDR_PAIR_STRIDE ? DEM_EFFECT_MDR : st->has_law ? DEM_EFFECT_THORNTON_NING : 0u;
    unsigned fx = (st->has_hist ? DEM_EFFECT_FRICTION : 0u) | (st->has_mc ? DEM_EFFECT_MC_STRAIN : 0u) | law |
                  (st->has_rspring ? DEM_EFFECT_ROLLING_SPRING : 0u);
    st->narrays = 0;
    for (int id = 0; id < BUF__COUNT && st->narrays < DEM_STATE_MAX_ARRAYS; id++) {
        if (!sb[id].name)
            continue;
        int told = !(sb[id].gate & ~known); /* whether st's header says if the buffer is there */
        c.fx = told ? fx : sb[id].gate;
        dem_state_elem elem = state_elem(sb[id].elem);
        int wide = id == BUF_WALL_LAW && (law & DEM_EFFECT_MDR);
        st->arrays[st->narrays++] = (dem_state_array){sb[id].name, wide ? NULL : sb[id].unit, elem,
                                                       wide ? MDR_WALL_STRIDE : sb[id].width, sb[id].required && told,
                                                       dem_buffer_bytes(&c, id) / state_elem_bytes(elem, c.rs), NULL};
    }
    return st->narrays;
}

int sim_state_array_layout(const dem_sim *s, const char *name, int *per)
{
    const dem_saved_buffer *sb = dem_saved_buffers();
    for (int id = 0; id < BUF__COUNT; id++)
        if (sb[id].name && name && !strcmp(sb[id].name, name)) {
            size_t item = 0, es = sb[id].elem == DEM_ELEM_REAL ? (size_t)s->setup.real_size : sizeof(int);
            int kind = dem_buffer_move(DEM_CORE(s->be), id, &item);
            *per = (int)(item / es);
            return kind;
        }
    *per = 0;
    return -1;
}

/* Every saved buffer into st, particles in the callers' order */
static int arrays_get(dem_sim *s, dem_state *st)
{
    dem_core *c = DEM_CORE(s->be);
    const dem_saved_buffer *sb = dem_saved_buffers();
    for (int id = 0; id < BUF__COUNT; id++) {
        if (!sb[id].name)
            continue;
        if (st->narrays == DEM_STATE_MAX_ARRAYS)
            return sim_fail(s, DEM_ERR_STATE, "more than %d saved buffers (DEM_STATE_MAX_ARRAYS)", DEM_STATE_MAX_ARRAYS);
        size_t bytes = c->bytes[id];
        dem_state_elem elem = state_elem(sb[id].elem);
        void *p = malloc(bytes ? bytes : 1);
        /* MDR's wall slots are rows of MDR_WALL_STRIDE reals of several units (dem_layout.h MDR_*), written [slots, 13]
         * without a unit; Thornton-Ning's one real per slot is a length */
        int wide = id == BUF_WALL_LAW && (c->fx & DEM_EFFECT_MDR);
        st->arrays[st->narrays++] = (dem_state_array){sb[id].name, wide ? NULL : sb[id].unit, elem,
                                                       wide ? MDR_WALL_STRIDE : sb[id].width, sb[id].required,
                                                       bytes / state_elem_bytes(elem, c->rs), p};
        if (!p)
            return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
        if (bytes && s->ops->read(s->be, (dem_bufref){TABLE_ONE, id}, 0, p, bytes, 1))
            return sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, c->err);
        if (sim_buffer_to_api(s, id, p, bytes))
            return DEM_ERR_NOMEM;
    }
    return 0;
}

/* Whether st's arrays fit this run: each one the registry saves, at the run's size (one a state may lack: missing,
 * or of another size, is zero) */
static int arrays_check(dem_sim *s, const dem_state *st)
{
    dem_core *c = DEM_CORE(s->be);
    const dem_saved_buffer *sb = dem_saved_buffers();
    for (int k = 0; k < st->narrays; k++) {
        const char *name = st->arrays[k].name;
        int id = 0;
        while (id < BUF__COUNT && !(sb[id].name && name && !strcmp(sb[id].name, name)))
            id++;
        if (id == BUF__COUNT || k >= DEM_STATE_MAX_ARRAYS)
            return sim_fail(s, DEM_ERR_ARG, "the saved state has an array '%s' this library does not keep",
                            name ? name : "(unnamed)");
    }
    for (int id = 0; id < BUF__COUNT; id++) {
        const dem_state_array *a = sb[id].name ? dem_state_find(st, sb[id].name) : NULL;
        size_t have = a && a->data ? a->count * state_elem_bytes(a->elem, c->rs) : 0, need = c->bytes[id];
        if (sb[id].name && sb[id].required && have != need)
            return sim_fail(s, DEM_ERR_ARG, "the saved %s has %zu bytes; this run needs %zu", sb[id].name, have, need);
    }
    return 0;
}

/* Every saved buffer from st (particles from the callers' order), zero where st lacks one it may lack */
static int arrays_set(dem_sim *s, const dem_state *st)
{
    dem_core *c = DEM_CORE(s->be);
    const dem_saved_buffer *sb = dem_saved_buffers();
    int e = 0;
    for (int id = 0; !e && id < BUF__COUNT; id++) {
        size_t need = c->bytes[id];
        if (!sb[id].name || !need)
            continue;
        const dem_state_array *a = dem_state_find(st, sb[id].name);
        unsigned char *buf = calloc(need, 1);
        if (!buf)
            return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
        if (a && a->data && a->count * state_elem_bytes(a->elem, c->rs) == need)
            sim_buffer_from_api(s, id, a->data, buf, need);
        if (s->ops->write(s->be, (dem_bufref){TABLE_ONE, id}, 0, buf, need, 1))
            e = sim_fail(s, DEM_ERR_DEVICE, "%s", c->err);
        /* MDR: each particle's apparent radius is its row's (laws/mdr.h), which every contact and the rebuild read
         * from RADIUS (mdr_begin writes it there each step) */
        if (!e && id == BUF_MDR_PART) {
            unsigned char *rad = calloc((size_t)s->n + 1, (size_t)c->rs);
            for (int i = 0; rad && i < s->n; i++)
                memcpy(rad + (size_t)i * c->rs, buf + ((size_t)MDR_P_STRIDE * i + 1) * c->rs, (size_t)c->rs);
            if (!rad)
                e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
            else if (s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_RADIUS}, 0, rad, (size_t)s->n * c->rs, 1))
                e = sim_fail(s, DEM_ERR_DEVICE, "%s", c->err);
            free(rad);
        }
        free(buf);
    }
    return e;
}

/* ---- the contacts: the touching pairs, found in the rows ---- */

/* The touching pairs of the current rows, once each (owner i: the lower stable id), in row order: ascending i, then
 * the partners' stable ids; their history, MC-strain force and displacements, and force records */
static int pairs_get(dem_sim *s, dem_state *st)
{
    int e = 0, n = s->n, rs = s->setup.real_size;
    size_t b, hb, fb;
    unsigned char *mcf = sim_field_stored(s, DEM_FIELD_MC_FORCE, &fb, &e);
    int *cnt = sim_field_stored(s, DEM_FIELD_NBR_COUNT, &b, &e), *list = sim_field_stored(s, DEM_FIELD_NBR_LIST, &b, &e);
    int *start = sim_field_stored(s, DEM_FIELD_NBR_START, &b, &e);
    unsigned char *touch = sim_field_stored(s, DEM_FIELD_TOUCH, &b, &e), *hist = sim_field_stored(s, DEM_FIELD_HIST, &hb, &e);
    unsigned char *rec = sim_field_stored(s, DEM_FIELD_PAIR_RECORDS, &b, &e), *mcd = sim_field_stored(s, DEM_FIELD_MC_DISP, &b, &e);
    int law = (s->setup.effects & DEM_LAW_STATE_BITS) ? DEM_LAW_PAIR_W(s->setup.effects) : 0; /* reals per pair */
    unsigned char *lst = sim_buffer_get(s, BUF_PAIR_LAW, &e);
    int rsp = (s->setup.effects & DEM_EFFECT_ROLLING_SPRING) != 0;
    unsigned char *rsb = sim_buffer_get(s, BUF_PAIR_RSPRING, &e);
    long np = 0;
    const int *sid = s->setup.sid;
    int *own = e ? NULL : sim_own_starts(cnt, list, start, n);
    if (!e && !own)
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (int i = 0; !e && i < n; i++) /* the touching flags are kept per pair, numbered like the history */
        for (int k = 0; k < cnt[i]; k++)
            if (sid[list[start[i] + k]] > sid[i]) {
                int p = row_pair_of(cnt, list, start, own, sid, i, k);
                np += p >= 0 && touch[p];
            }
    if (!e) {
        st->pair_i = malloc(sizeof(int) * (size_t)(np ? np : 1));
        st->pair_j = malloc(sizeof(int) * (size_t)(np ? np : 1));
        st->pair_hist = calloc((size_t)(np ? np : 1), 3 * (size_t)rs);
        st->pair_mc_fn = calloc((size_t)(np ? np : 1), (size_t)rs);
        st->pair_rec = calloc((size_t)(np ? np : 1), PR_STRIDE * (size_t)rs);
        st->pair_mc_disp = calloc((size_t)(np ? np : 1), 2 * (size_t)rs);
        st->pair_law = law ? calloc((size_t)(np ? np : 1), (size_t)law * rs) : NULL;
        st->pair_rspring = rsp ? calloc((size_t)(np ? np : 1), 3 * (size_t)rs) : NULL;
        if (!st->pair_i || !st->pair_j || !st->pair_hist || !st->pair_mc_fn || !st->pair_rec || !st->pair_mc_disp ||
            (law && !st->pair_law) || (rsp && !st->pair_rspring))
            e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    np = 0;
    for (int i = 0; !e && i < n; i++)
        for (int k = 0; k < cnt[i]; k++) {
            int slot = start[i] + k, j = list[slot];
            int pn = sid[j] > sid[i] ? row_pair_of(cnt, list, start, own, sid, i, k) : -1;
            if (pn < 0 || !touch[pn])
                continue;
            st->pair_i[np] = i;
            st->pair_j[np] = j;
            if (hb) /* no tangential history without friction; it is kept per pair (neighbor.h) */
                memcpy((char *)st->pair_hist + (size_t)np * 3 * rs, hist + (size_t)pn * 3 * rs, 3 * (size_t)rs);
            if (fb) /* MC-strain: the force the next step's induced displacements start from (kept per pair) */
                memcpy((char *)st->pair_mc_fn + (size_t)np * rs, mcf + (size_t)pn * rs, (size_t)rs);
            if (law) /* the law's state (laws/law.h), kept per pair like the history */
                memcpy((char *)st->pair_law + (size_t)np * law * rs, lst + (size_t)pn * law * rs, (size_t)law * rs);
            if (rsp) /* the rolling spring (rolling.h), kept per pair like the history */
                memcpy((char *)st->pair_rspring + (size_t)np * 3 * rs, rsb + (size_t)pn * 3 * rs, 3 * (size_t)rs);
            if (fb) { /* the displacements at both ends in the last step: the network's extra (mc_strain.h) */
                int m = find_slot(cnt, list, start, sid, j, i);
                memcpy((char *)st->pair_mc_disp + (size_t)np * 2 * rs, mcd + (size_t)slot * rs, (size_t)rs);
                if (m >= 0)
                    memcpy((char *)st->pair_mc_disp + ((size_t)np * 2 + 1) * rs, mcd + (size_t)m * rs, (size_t)rs);
            }
            /* the force record of the last step: what the contact network reads (the restore runs no force pass) */
            memcpy((char *)st->pair_rec + (size_t)np * PR_STRIDE * rs, rec + (size_t)pn * PR_STRIDE * rs,
                   PR_STRIDE * (size_t)rs);
            np++;
        }
    st->npairs = np;
    st->has_hist = hb > 0;
    st->has_mc = fb > 0;
    st->has_law = law;
    st->has_rspring = rsp;
    free(cnt), free(list), free(start), free(touch), free(hist), free(mcf), free(own), free(rec), free(mcd);
    free(lst), free(rsb);
    return e;
}

int dem_state_get(dem_sim *s, dem_state *st)
{
    memset(st, 0, sizeof *st);
    if (s->split_started)
        return s->split_ops->state_get(s, st);
    if (!s->run.started)
        return sim_need_started(s);
    st->step = s->run.step;
    st->n = s->n;
    st->nwalls = s->nwalls;
    st->real_size = s->setup.real_size;
    st->rebuilds = s->rows.rebuilds;
    st->has_stages = 1;
    for (int k = 0; k < s->nwalls; k++) {
        memcpy(st->wall_pos[k], s->motion.pos[k], sizeof st->wall_pos[k]);
        st->wall_stage[k] = s->motion.stage_cur[k];
        st->wall_stage_first[k] = s->motion.stage_first[k];
        memcpy(st->wall_stage_from[k], s->motion.stage_from[k], sizeof st->wall_stage_from[k]);
    }
    st->mc = s->mc.stats;
    int e = arrays_get(s, st);
    if (!e)
        e = pairs_get(s, st);
    if (!e)
        e = patch_contacts_get(s, st);
    if (!e) /* the pairs named by the callers' ids, like the particle fields (a run stored anew: host/core/reorder.c) */
        e = pairs_to_api(s, st);
    if (e)
        dem_state_free(st);
    return e;
}


static int state_set(dem_sim *s, const dem_state *st, int keep);

/* The rebuilds within keep the storage order (host/core/reorder.c). */
int dem_state_set(dem_sim *s, const dem_state *st)
{
    if (s->split_started)
        return sim_need_started(s);
    int hold = s->order.hold;
    s->order.hold = 1;
    int e = state_set(s, st, 1);
    s->order.hold = hold;
    return e;
}

/* Every check before the first write: a state that does not fit this run changes nothing */
static int state_check(dem_sim *s, const dem_state *st)
{
    int n = s->n, rs = s->setup.real_size;
    if (st->n != n || st->nwalls != s->nwalls || st->real_size != rs)
        return sim_fail(s, DEM_ERR_ARG, "the saved state has %d particles, %d walls, %d-byte reals; this run has %d, "
                        "%d, %d", st->n, st->nwalls, st->real_size, n, s->nwalls, rs);
    unsigned fx = s->setup.effects;
    int fric = (fx & DEM_EFFECT_FRICTION) != 0, mce = (fx & DEM_EFFECT_MC_STRAIN) != 0;
    if (!!st->has_hist != fric)
        return sim_fail(s, DEM_ERR_ARG, "the saved state %s tangential history but this run %s friction",
                        st->has_hist ? "has" : "has no", fric ? "has" : "has no");
    if (!!st->has_mc != mce)
        return sim_fail(s, DEM_ERR_ARG, "the saved state %s MC-strain forces but this run %s mc_strain",
                        st->has_mc ? "has" : "has no", mce ? "has" : "has no");
    int law = (fx & DEM_LAW_STATE_BITS) ? DEM_LAW_PAIR_W(fx) : 0;
    if (st->has_law != law || (law && st->npairs > 0 && !st->pair_law))
        return sim_fail(s, DEM_ERR_ARG, "the saved state has contact law states of %d reals but this run's law keeps "
                        "%d (thornton_ning keeps 1 per contact, mdr %d)", st->has_law, law, MDR_PAIR_STRIDE);
    int rsp = (fx & DEM_EFFECT_ROLLING_SPRING) != 0;
    if (!!st->has_rspring != rsp || (rsp && st->npairs > 0 && !st->pair_rspring))
        return sim_fail(s, DEM_ERR_ARG, "the saved state %s rolling springs but this run %s rolling_spring",
                        st->has_rspring ? "has" : "has no", rsp ? "has" : "has no");
    const dem_state_array *mp = (fx & DEM_EFFECT_MDR) ? dem_state_find(st, "mdr_particle") : NULL;
    for (int i = 0; mp && mp->data && mp->count == (size_t)MDR_P_STRIDE * n && i < n; i++) {
        /* MDR's rows (laws/mdr.h): a radius as created > 0 and an apparent one from it up to M34's cap, 1.5 R_o (the
         * cells hold no more), never shrinking */
        double ro = sim_real_at(mp->data, (size_t)MDR_P_STRIDE * i, rs), r = sim_real_at(mp->data,
                                                                                         (size_t)MDR_P_STRIDE * i + 1, rs);
        if (!(ro > 0) || !(r >= ro) || !(r <= 1.51 * ro))
            return sim_fail(s, DEM_ERR_ARG, "the saved state's MDR row of particle %d has the radius %g m grown from "
                            "%g m (want 0 < R_o <= R <= 1.5 R_o)", i, r, ro);
    }
    if (st->step < 0 || st->npairs < 0 || st->narrays < 0 || st->narrays > DEM_STATE_MAX_ARRAYS)
        return sim_fail(s, DEM_ERR_ARG, "the saved state has step %ld, %ld contacts and %d arrays (at most %d)",
                        st->step, st->npairs, st->narrays, DEM_STATE_MAX_ARRAYS);
    for (int k = 0; st->has_stages && k < s->nwalls; k++) {
        const double *p = st->wall_stage_from[k];
        if (st->wall_stage[k] < 0 || st->wall_stage[k] > s->walls[k].nstages || st->wall_stage_first[k] < 0 ||
            st->wall_stage_first[k] > st->step || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return sim_fail(s, DEM_ERR_ARG, "wall %d: the saved motion stage %d (of %d), begun at step %ld (of %ld), "
                            "does not fit this run", k, st->wall_stage[k], s->walls[k].nstages,
                            st->wall_stage_first[k], st->step);
    }
    for (long p = 0; p < st->npairs; p++) /* saved from its owner, the lower id (neighbor.h) */
        if (!(st->pair_i[p] >= 0 && st->pair_i[p] < st->pair_j[p] && st->pair_j[p] < n))
            return sim_fail(s, DEM_ERR_ARG, "saved contact %ld joins particles %d and %d (want 0 <= i < j < %d)", p,
                            st->pair_i[p], st->pair_j[p], n);
    return arrays_check(s, st);
}

/* The saved contacts into the rows just rebuilt from the saved positions; DEM_ERR_ARG when one is not there */
static int pairs_set(dem_sim *s, const dem_state *st)
{
    int e = 0, n = s->n, rs = s->setup.real_size;
    const int *sid = s->setup.sid;
    size_t b, hb = sim_stored_bytes(s, DEM_FIELD_HIST), fb = sim_stored_bytes(s, DEM_FIELD_MC_FORCE),
              tb = sim_stored_bytes(s, DEM_FIELD_TOUCH), rb = sim_stored_bytes(s, DEM_FIELD_PAIR_RECORDS);
    size_t db = sim_stored_bytes(s, DEM_FIELD_MC_DISP);
    int *cnt = sim_field_stored(s, DEM_FIELD_NBR_COUNT, &b, &e), *list = sim_field_stored(s, DEM_FIELD_NBR_LIST, &b, &e);
    int *start = sim_field_stored(s, DEM_FIELD_NBR_START, &b, &e);
    unsigned char *touch = calloc(tb + 1, 1), *hist = calloc(hb + 1, 1), *mcf = calloc(fb + 1, 1);
    unsigned char *rec = calloc(rb + 1, 1); /* the records too: the restore runs no force pass that would write them */
    unsigned char *disp = calloc(db + 1, 1); /* and MC-strain's displacements */
    size_t lb = DEM_CORE(s->be)->bytes[BUF_PAIR_LAW];
    unsigned char *lst = calloc(lb + 1, 1); /* and the law's states */
    size_t sb = DEM_CORE(s->be)->bytes[BUF_PAIR_RSPRING];
    unsigned char *rsb = calloc(sb + 1, 1); /* and the rolling springs */
    int *own = e ? NULL : sim_own_starts(cnt, list, start, n);
    if (!e && (!touch || !hist || !mcf || !rec || !disp || !lst || !rsb || !own))
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (long p = 0; !e && p < st->npairs; p++) {
        int ci = st->pair_i[p], cj = st->pair_j[p], i = sim_dev(s, ci), j = sim_dev(s, cj); /* ids: checked above */
        int a = find_slot(cnt, list, start, sid, i, j);
        int m = a >= 0 ? find_slot(cnt, list, start, sid, j, i) : -1;
        if (a < 0 || m < 0) {
            e = sim_fail(s, DEM_ERR_ARG, "saved contact %d-%d is not a neighbour pair of the saved positions", ci, cj);
            break;
        }
        size_t pn = (size_t)row_pair_of(cnt, list, start, own, sid, i, a - start[i]); /* >= 0: m was found */
        touch[pn] = 1; /* flag and history are kept per pair (neighbor.h) */
        if (hb && st->has_hist)
            memcpy(hist + pn * 3 * rs, (const char *)st->pair_hist + (size_t)p * 3 * rs, 3 * (size_t)rs);
        if (fb) /* kept per pair, like the history (mc_strain.h) */
            memcpy(mcf + pn * rs, (const char *)st->pair_mc_fn + (size_t)p * rs, (size_t)rs);
        size_t lw = (size_t)st->has_law * rs; /* so is the law's state (state_check: there when the law keeps one) */
        if (lb && (pn + 1) * lw <= lb)
            memcpy(lst + pn * lw, (const char *)st->pair_law + (size_t)p * lw, lw);
        if (sb && (pn + 1) * 3 * rs <= sb) /* and the rolling spring (state_check: there with rolling_spring) */
            memcpy(rsb + pn * 3 * rs, (const char *)st->pair_rspring + (size_t)p * 3 * rs, 3 * (size_t)rs);
        if (fb && st->pair_mc_disp && ((size_t)a + 1) * rs <= db && ((size_t)m + 1) * rs <= db) {
            memcpy(disp + (size_t)a * rs, (const char *)st->pair_mc_disp + (size_t)p * 2 * rs, (size_t)rs);
            memcpy(disp + (size_t)m * rs, (const char *)st->pair_mc_disp + ((size_t)p * 2 + 1) * rs, (size_t)rs);
        }
        if (st->pair_rec && (pn + 1) * PR_STRIDE * rs <= rb)
            memcpy(rec + pn * PR_STRIDE * rs, (const char *)st->pair_rec + (size_t)p * PR_STRIDE * rs,
                   PR_STRIDE * (size_t)rs);
    }
    if (!e)
        e = patch_contacts_set(s, st);
    if (!e && (dem_stage_write_field(s->ops, s->be, DEM_FIELD_TOUCH, touch, tb) ||
               dem_stage_write_field(s->ops, s->be, DEM_FIELD_HIST, hist, hb) ||
               dem_stage_write_field(s->ops, s->be, DEM_FIELD_MC_FORCE, mcf, fb) ||
               dem_stage_write_field(s->ops, s->be, DEM_FIELD_PAIR_RECORDS, rec, rb) ||
               (db && dem_stage_write_field(s->ops, s->be, DEM_FIELD_MC_DISP, disp, db)) ||
               (lb && s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_PAIR_LAW}, 0, lst, lb, 1)) ||
               (sb && s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_PAIR_RSPRING}, 0, rsb, sb, 1))))
        e = sim_fail(s, DEM_ERR_DEVICE, "%s", DEM_CORE(s->be)->err);
    free(cnt), free(list), free(start), free(touch), free(hist), free(mcf), free(own), free(rec), free(disp);
    free(lst), free(rsb);
    return e;
}

/* The run takes st's step, iteration counts, wall positions and stages */
static void state_adopt(dem_sim *s, const dem_state *st)
{
    s->run.step = st->step;
    s->rows.skin_built = s->run.step; /* the rows just built are this step's (rebuild.c skin_choose counts from it) */
    long first_capped = s->mc.stats.first_capped, last_capped = s->mc.stats.last_capped; /* this process's, not the state's */
    s->mc.stats = st->mc;
    s->mc.stats.first_capped = first_capped, s->mc.stats.last_capped = last_capped;
    for (int k = 0; k < s->nwalls; k++)
        memcpy(s->motion.pos[k], st->wall_pos[k], sizeof s->motion.pos[k]);
    if (!st->has_stages) /* a state from before stages could end early: every stage ran its duration */
        sim_stages_from_step(s);
    for (int k = 0; st->has_stages && k < s->nwalls; k++) {
        s->motion.stage_cur[k] = st->wall_stage[k];
        s->motion.stage_first[k] = st->wall_stage_first[k];
        memcpy(s->motion.stage_from[k], st->wall_stage_from[k], sizeof s->motion.stage_from[k]);
    }
    s->motion.stage_log_n = 0; /* dem_stage_ends: the ends from the restored step on */
}

/* keep: the run's own state is saved before the first write and put back when the state turns out not to fit.
 * Whether each saved contact is a neighbour pair needs the rows of the saved positions, so the arrays are written and
 * the rows rebuilt first; when a contact then does not fit, the run's own state goes back and the state changes
 * nothing. Its own state, not only its positions: the rows of the saved positions carry only the contact memory of
 * the pairs they list, so rows rebuilt from the run's positions after them would have lost the rest. The arrays are
 * written again after the rebuild, so that what they hold does not depend on what a rebuild touches. */
static int state_set(dem_sim *s, const dem_state *st, int keep)
{
    if (!s->run.started)
        return sim_need_started(s);
    int e = state_check(s, st);
    dem_state mine;
    memset(&mine, 0, sizeof mine);
    if (e || (keep && (e = dem_state_get(s, &mine))))
        return e;
    if ((e = arrays_set(s, st))) {
        dem_state_free(&mine);
        return e;
    }
    s->rows.skin_now = s->rows.skin_hi; /* how the restored particles move is not known yet: rows of the largest skin */
    s->rows.skin_built = -1;
    if ((e = sim_rebuild(s))) {
        dem_state_free(&mine);
        return e;
    }
    e = pairs_set(s, st);
    if (!e)
        e = arrays_set(s, st);
    if (e == DEM_ERR_ARG && keep) { /* the run's own state back; the message stays the state's */
        char why[sizeof s->report.err];
        snprintf(why, sizeof why, "%s", s->report.err);
        if (state_set(s, &mine, 0))
            e = DEM_ERR_DEVICE;
        snprintf(s->report.err, sizeof s->report.err, "%s", why);
    }
    dem_state_free(&mine);
    if (!e)
        state_adopt(s, st);
    return e;
}
