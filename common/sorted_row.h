/* sorted_row.h - binary search in a row of ids in ascending order (patch rows), or in a neighbour row, whose partners
 * are in ascending order of their stable ids (row_find_sid), integers only, so that the kernels (neighbor.h) and the
 * host (host/state.c, restoring a checkpoint) use the same code. */
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

/* The number of the pair in row slot k of a row of count partners, whose owned pairs (partners above the row's own
 * stable id: the back of the row) are numbered from own_first to own_end - 1 (neighbor.h's pair_index; host/state.c). */
DEM_INLINE int row_pair_number(int own_first, int own_end, int count, int k)
{
    return own_first + k - (count - (own_end - own_first));
}
#endif /* DEM_SORTED_ROW_H */
