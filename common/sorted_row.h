/* sorted_row.h - binary search in a row of ids in ascending order (patch rows), or in a neighbour row, whose partners
 * are in ascending order of their stable ids (row_find_sid), and a pair's number; integers only, so that the kernels
 * (neighbor.h) and the host (host/core/state.c, restoring a checkpoint) use the same code. */
#ifndef DEM_SORTED_ROW_H
#define DEM_SORTED_ROW_H
#ifndef DEM_INLINE /* host code that does not include dem_real.h: the same definitions as its C branch */
#define DEM_INLINE static inline
#define DEM_CONST_GLOBAL const
#endif

/* Position of key in row[0..count), or -1. */
DEM_INLINE int row_find(DEM_CONST_GLOBAL int *row, int count, int key)
{
    int a = 0, z = count - 1;
    while (a <= z) {
        int m = (a + z) / 2;
        if (row[m] < key)
            a = m + 1;
        else if (row[m] > key)
            z = m - 1;
        else
            return m;
    }
    return -1;
}

/* Position of the partner whose stable id is key in a neighbour row (partners ordered by sid, their stable ids),
 * or -1. */
DEM_INLINE int row_find_sid(DEM_CONST_GLOBAL int *row, int count, DEM_CONST_GLOBAL int *sid, int key)
{
    int a = 0, z = count - 1;
    while (a <= z) {
        int m = (a + z) / 2, at = sid[row[m]];
        if (at < key)
            a = m + 1;
        else if (at > key)
            z = m - 1;
        else
            return m;
    }
    return -1;
}

/* The number of the pair in row slot k of particle a (partner b = list[start[a] + k]) in the pair list of the rows
 * (neighbor.h's pair_index): numbered by its host, the one stored first, from own[host] in the host's row order.
 * -1 when the partner's row lacks the pair (host/core/state.c, host/physics/contacts.c). */
DEM_INLINE int row_pair_of(DEM_CONST_GLOBAL int *count, DEM_CONST_GLOBAL int *list, DEM_CONST_GLOBAL int *start,
                           DEM_CONST_GLOBAL int *own, DEM_CONST_GLOBAL int *sid, int a, int k)
{
    int b = list[start[a] + k], h = a < b ? a : b, c = k;
    if (h == b && (c = row_find_sid(list + start[b], count[b], sid, sid[a])) < 0)
        return -1;
    int p = own[h];
    for (int q = 0; q < c; q++)
        p += list[start[h] + q] > h;
    return p;
}
#endif /* DEM_SORTED_ROW_H */
