/* neighbor.h - Verlet neighbour rows from the cell grid, and contact history carried across rebuilds.
 *
 * Row i lists every j != i with |x_i - x_j| < r_i + r_j + skin, sorted by ascending sid[j] (the canonical summation
 * order of contact_forces.h). sid is each particle's stable id (its id at dem_start), so that every sum follows the
 * ids, not the places the particles are stored at (host/core/reorder.c moves them). The test is symmetric in i and j bit
 * for bit (IEEE + and * commute), so j is in row i exactly when i is in row j.
 * The rows are packed (dem_buffers.h DEM_ROWS): a build is a count (nbr_count), a scan of the counts into each row's
 * start (nbr_start[n]: the slots needed; the host grows the list to hold them: host/core/rebuild.c), a fill (nbr_build), which
 * walks the same cells with the same test and so finds exactly the pairs counted (FLAG_ASYMMETRIC 2, a library bug,
 * when it does not), and a sort of each row (nbr_sort). Count and fill each test every pair once, from the particle
 * whose cell comes first in the grid's order (in one cell: the one stored first), so together they cost one walk of
 * the rows in full. Every row is as long as it needs to be: a
 * compact's rows hold 7 to 8 partners on the mean and 20 at the most, and no row is padded to the longest
 * (docs/design.md "Memory in a compact").
 * The pair's touching flag, tangential history and MC-strain force follow in pair_index, once the new pairs are
 * numbered (from the same pair in the old rows, or zero).
 * With DEM_EFFECT_PATCHES the vertices of patch triangles are in no row (they touch spheres as patches); with
 * DEM_EFFECT_SPRINGS two vertices of one membrane are not partners (PM_APART: their spheres may overlap).
 */
#ifndef DEM_NEIGHBOR_H
#define DEM_NEIGHBOR_H
#include "dem_kernels.h"
#include "vec3.h"
#include "dem_layout.h"
#include "../include/dem_effects.h"
#include "sorted_row.h"

/* The pairs of particle i walked from i's side: its own cell's particles stored after it (j > i) and the particles
 * of the 13 neighbouring cells that come after its own in the grid's order (half of the 26: each pair of particles
 * in two cells is walked from the lower cell only). So every pair is walked once, by one particle, with one test
 * for the count and the fill (symmetric in i and j bit for bit): count and fill together cost one walk of the full
 * rows. Count (list 0): each pair adds one to count[j]; returns the pairs found, for i to add to its own count
 * (integers: any order of the additions gives the same counts). Fill: each pair takes the next free slot of both
 * rows (fill[]: the slots taken so far; the order depends on thread timing, nbr_sort makes it canonical), never past
 * a row's count (cap); a row found longer than counted - a bug - raises FLAG_ASYMMETRIC 2. */
DEM_INLINE int nbr_walk(unsigned fx, int i, DEM_GLOBAL int *count, DEM_GLOBAL int *list, DEM_CONST_GLOBAL int *cap,
                        DEM_CONST_GLOBAL int *start, DEM_GLOBAL int *fill, DEM_ARGS_nbr_walk(DEM_P_FIRST, DEM_P_NEXT))
{
    vec3 xi = v3_load(x, i);
    real ri = radius[i];
    int c = cell_of[i];
    int cx = c % ncx, cy = (c / ncx) % ncy, cz = c / (ncx * ncy);
    int cnt = 0;
    (void)n;
    /* a membrane's patch vertex touches no particle as a sphere (patch_contacts.h): its row stays empty, and it is
     * in no other row (vtri_start is indexed by stable id) */
    if ((fx & DEM_EFFECT_PATCHES) && vtri_start[sid[i] + 1] > vtri_start[sid[i]])
        return 0;
    for (int k = 13; k < 27; k++) { /* offsets (dz, dy, dx) from (0, 0, 0) on, in the grid's order */
        int z = cz + k / 9 - 1, y = cy + (k / 3) % 3 - 1, xx = cx + k % 3 - 1;
        if (z < 0 || z >= ncz || y < 0 || y >= ncy || xx < 0 || xx >= ncx)
            continue;
        int cc = (z * ncy + y) * ncx + xx;
        for (int s = cell_start[cc]; s < cell_start[cc + 1]; s++) {
            int j = cell_particles[s];
            if (k == 13 && j <= i)
                continue; /* i's own cell: the pair is walked by the one stored first */
            if ((fx & DEM_EFFECT_PATCHES) && vtri_start[sid[j] + 1] > vtri_start[sid[j]])
                continue;
            if ((fx & DEM_EFFECT_SPRINGS) && pairmat[PM_STRIDE * (mat[i] * nmat + mat[j]) + PM_APART] != (real)0)
                continue; /* two vertices of one membrane */
            vec3 d = v3_sub(xi, v3_load(x, j));
            real cut = ri + radius[j] + skin;
            if (!(v3_dot(d, d) < cut * cut))
                continue;
            cnt++;
            if (!list) {
                DEM_ATOMIC_INC(&count[j]);
                continue;
            }
            int a = DEM_ATOMIC_INC(&fill[i]), b = DEM_ATOMIC_INC(&fill[j]);
            if (a < cap[i] && b < cap[j]) {
                list[start[i] + a] = j;
                list[start[j] + b] = i;
            } else
                DEM_ATOMIC_MAX(&flags[FLAG_ASYMMETRIC], 2);
        }
    }
    return cnt;
}

/* Pass 1 of a build: the length of each row (nbr_count zeroed before) */
DEM_ITEM(nbr_count)
{
    int cnt = nbr_walk(fx, i, nbr_count, 0, 0, 0, 0, DEM_ARGS_nbr_walk(DEM_N_FIRST, DEM_N_NEXT));
    if (cnt)
        DEM_ATOMIC_ADD(&nbr_count[i], cnt);
}

/* Pass 2: each pair into both rows, at nbr_start[i] on (nbr_fill zeroed before) */
DEM_ITEM(nbr_build)
{
    nbr_walk(fx, i, 0, nbr_list, nbr_count, nbr_start, nbr_fill, DEM_ARGS_nbr_walk(DEM_N_FIRST, DEM_N_NEXT));
}

/* Pass 3: row i sorted by stable id (the canonical order); the split of the row for the sums (nbr_lower) and the
 * counts of the pairs i hosts and is a guest in, which the commit scans (host/steps/neighbor.c) */
DEM_ITEM(nbr_sort)
{
    int cap = nbr_count[i];
    DEM_GLOBAL int *row = nbr_list + nbr_start[i];
    if (nbr_fill[i] != cap) { /* filled short of its count: a bug; the host stops before anything reads the rows */
        DEM_ATOMIC_MAX(&flags[FLAG_ASYMMETRIC], 2);
        return;
    }
    DEM_ATOMIC_MAX(&flags[FLAG_NBR_WIDEST], cap);
    for (int k = 1; k < cap; k++) { /* insertion sort: rows hold a handful of partners */
        int j = row[k], sj = sid[j], m = k - 1;
        while (m >= 0 && sid[row[m]] > sj) {
            row[m + 1] = row[m];
            m--;
        }
        row[m + 1] = j;
    }
    int lower = 0, guests = 0, si = sid[i];
    for (int k = 0; k < cap; k++) {
        lower += sid[row[k]] < si; /* partners of lower stable id: the row's front (the sums' split) */
        guests += row[k] < i;      /* partners stored before i: their pairs are numbered by them */
    }
    int alike = guests == lower; /* the partners stored before i are the row's front: contact_forces reads no row */
    for (int k = 0; alike && k < lower; k++)
        alike = row[k] < i;
    nbr_lower[i] = alike ? lower : ~lower; /* contacts.h's row_lower */
    in_count[i] = guests;
    own_count[i] = cap - guests;
}

/* The number of pair (a, b) in the old rows' pair list, or -1 when it was not listed. A pair is numbered by its host,
 * the one of its particles stored first (old_slot: where each particle was stored when the old rows were numbered;
 * host reorder.c, the identity unless the particles were stored anew since): the host's first pair,
 * old_own_start[host], plus the partners the host hosted before this one in its row. The old rows' partners and
 * old_own_start are already in the current places. */
DEM_INLINE int old_pair_number(int a, int b, DEM_CONST_GLOBAL int *old_count, DEM_CONST_GLOBAL int *old_list,
                               DEM_CONST_GLOBAL int *old_start, DEM_CONST_GLOBAL int *old_own_start,
                               DEM_CONST_GLOBAL int *old_slot, DEM_CONST_GLOBAL int *sid)
{
    int h = old_slot[a] < old_slot[b] ? a : b, g = h == a ? b : a, oh = old_slot[h];
    DEM_CONST_GLOBAL int *row = old_list + old_start[h];
    int found = row_find_sid(row, old_count[h], sid, sid[g]);
    if (found < 0)
        return -1;
    int p = old_own_start[h];
    for (int k = 0; k < found; k++)
        p += old_slot[row[k]] > oh;
    return p;
}

/* The flat pair list of the committed rows (contact_forces.h). A pair is numbered by its host, the one of its two
 * particles stored first (whichever has the lower stable id evaluates it: contact_pairs), so that the pairs follow
 * the storage order: pair p = own_start[i] + h is the h-th partner j > i (stored after i) in particle i's row;
 * pair_host[p] = i (as ~i, negative, when j has the lower stable id: contact_pairs then evaluates the pair for j
 * without reading the stable ids each step) and pair_guest[p] = j. The partner j's slot of the same pair (the slot
 * of i in row j, found by binary search; it is the g-th of j's partners stored before j) gets
 * in_pair[in_start[j] + g] = p. With MC-strain, pair_slot[p] names i's row slot of the pair and pair_mirror[p] j's. Each entry has one writer: p's host writes them all. A pair whose partner row lacks
 * it (rows are symmetric: a bug) raises FLAG_ASYMMETRIC. The touching flag (touch[p]), tangential history
 * (hist[3 p], in the orientation of the lower stable id), MC-strain force (mc_fn[p]) and the law's state
 * (law_st[p], a law with memory: laws/law.h) and rolling spring (rspring[3 p], rolling.h) are kept per pair: a pair
 * takes them from its number in the old rows (old_pair_number), a new one starts untouched, from zero. Per pair, not per row slot, they are dense
 * arrays read in order by contact_pairs. */
DEM_ITEM(pair_index)
{
    int cnt = nbr_count[i], p = own_start[i], row0 = nbr_start[i];
    DEM_CONST_GLOBAL int *row = nbr_list + row0;
    for (int c = 0; c < cnt; c++) {
        int j = row[c];
        if (j < i)
            continue; /* hosted by j */
        DEM_CONST_GLOBAL int *rj = nbr_list + nbr_start[j];
        int m = row_find_sid(rj, nbr_count[j], sid, sid[i]);
        pair_host[p] = sid[i] < sid[j] ? i : ~i;
        pair_guest[p] = j;
        if (fx & DEM_EFFECT_MC_STRAIN) {
            pair_slot[p] = row0 + c;
            pair_mirror[p] = m >= 0 ? nbr_start[j] + m : -1;
        }
        if (m >= 0) {
            int g = 0; /* i's place among j's partners stored before j */
            for (int k = 0; k < m; k++)
                g += rj[k] < j;
            in_pair[in_start[j] + g] = p;
        } else
            DEM_ATOMIC_MAX(&flags[FLAG_ASYMMETRIC], 1);
        int q = old_pair_number(i, j, old_count, old_list, old_start, old_own_start, old_slot, sid); /* -1: new */
        int t = q >= 0 ? old_touch[q] : 0;
        touch[p] = (unsigned char)t;
        if (fx & DEM_EFFECT_FRICTION) /* no history exists without friction */
            v3_store(hist, p, t ? v3_load(old_hist, q) : v3_zero());
        if (fx & DEM_EFFECT_MC_STRAIN) /* the lagged MC-strain force of the same contact (mc_strain.h) */
            mc_fn[p] = t ? old_mc_fn[q] : (real)0;
        for (int k = 0; (fx & DEM_LAW_STATE_BITS) && k < DEM_LAW_PAIR_W(fx); k++) /* the law's state of the same
                                                                                     contact (laws/law.h) */
            law_st[p * DEM_LAW_PAIR_W(fx) + k] = t ? old_law_st[q * DEM_LAW_PAIR_W(fx) + k] : (real)0;
        if (fx & DEM_EFFECT_ROLLING_SPRING) /* its rolling spring (rolling.h) */
            v3_store(rspring, p, t ? v3_load(old_rspring, q) : v3_zero());
        p++;
    }
}
#endif /* DEM_NEIGHBOR_H */
