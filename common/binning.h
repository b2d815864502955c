/* binning.h - cell index, counting sort into cells, and the canonical order inside each cell.
 *
 * The binning domain [lo, lo + ncell*cell] is cut into cubes no smaller than the largest interaction range
 * (2 r_max + skin), so every neighbour of a particle lies in its own or one of the 26 adjacent cells.
 * Steps (each a kernel, each with its reference loop):
 *   bin_index:  cell of each particle; counts per cell (integer atomics); a particle outside the domain or with a
 *               non-finite position is reported through FLAG_OUT_OF_DOMAIN (smallest such id) and clamped into
 *               the grid so that no memory outside the arrays is touched; the host then stops with an error.
 *   scan:       exclusive prefix sum of the counts -> cell_start (integer, so any order gives the same result).
 *   bin_scatter: each particle takes a slot in its cell, counting its cell's count back down to zero (the order of
 *               slots depends on thread timing; no second per-cell array) ...
 *   bin_sort:   ... which this step makes canonical: each cell's particles sorted by ascending id.
 */
#ifndef DEM_BINNING_H
#define DEM_BINNING_H
#include "vec3.h"
#include "dem_layout.h"
#include "dem_kernels.h"

DEM_INLINE int bin_axis(real xc, real lo, real inv_cell, int nc, int *outside)
{
    real s = (xc - lo) * inv_cell;
    if (!(s >= (real)0 && s < (real)nc)) { /* also true for NaN */
        *outside = 1;
        return s >= (real)nc ? nc - 1 : 0;
    }
    return (int)s;
}

DEM_ITEM(bin_index)
{
    vec3 lo = v3(lox, loy, loz);
    vec3 xi = v3_load(x, i);
    int outside = 0;
    int cx = bin_axis(xi.x, lo.x, inv_cell, ncx, &outside);
    int cy = bin_axis(xi.y, lo.y, inv_cell, ncy, &outside);
    int cz = bin_axis(xi.z, lo.z, inv_cell, ncz, &outside);
    if (outside)
        DEM_ATOMIC_MIN(&flags[FLAG_OUT_OF_DOMAIN], i);
    int c = (cz * ncy + cy) * ncx + cx;
    cell_of[i] = c;
    DEM_ATOMIC_INC(&cell_count[c]);
}

/* Exclusive scan in fixed blocks of DEM_SCAN_BLOCK items (dem_layout.h): block sums, a scan of the block sums,
 * then each block. Also used for the per-particle pair-record offsets (neighbor.h, contact_forces.h). */
DEM_ITEM(scan_block_sum)
{
    int b = i;
    int s = 0, end = (b + 1) * DEM_SCAN_BLOCK < ncells ? (b + 1) * DEM_SCAN_BLOCK : ncells;
    for (int c = b * DEM_SCAN_BLOCK; c < end; c++)
        s += count[c];
    block_sum[b] = s;
}

DEM_ITEM(scan_block_sums) /* one item */
{
    int s = 0;
    for (int b = 0; b < nblocks; b++) {
        int t = block_sum[b];
        block_sum[b] = s;
        s += t;
    }
}

DEM_ITEM(scan_apply)
{
    int b = i;
    int s = block_sum[b], end = (b + 1) * DEM_SCAN_BLOCK < ncells ? (b + 1) * DEM_SCAN_BLOCK : ncells;
    for (int c = b * DEM_SCAN_BLOCK; c < end; c++) {
        start[c] = s;
        s += count[c];
    }
    if (end == ncells)
        start[ncells] = s;
}

DEM_ITEM(bin_scatter)
{
    int c = cell_of[i];
    cell_particles[start[c] + DEM_ATOMIC_DEC(&cell_count[c]) - 1] = i;
}

DEM_ITEM(bin_sort)
{
    int c = i;
    int s = start[c], e = start[c + 1];
    for (int k = s + 1; k < e; k++) { /* insertion sort: cells hold a handful of particles */
        int id = cell_particles[k], m = k - 1;
        while (m >= s && cell_particles[m] > id) {
            cell_particles[m + 1] = cell_particles[m];
            m--;
        }
        cell_particles[m + 1] = id;
    }
}
#endif /* DEM_BINNING_H */
