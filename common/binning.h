/* binning.h - cell index, counting sort into cells, and the canonical order inside each cell.
 *
 * The binning domain [lo, lo + ncell*cell] is cut into cubes no smaller than the largest interaction range
 * (2 r_max + skin), so every neighbour of a particle lies in its own or one of the 26 adjacent cells. The cells a
 * build uses are only those of the particles' bounding box in that grid (its first cell c0 and its cells per axis
 * nc): a domain with room for a pour, a punch's travel or an ejection costs no memory until particles fill it
 * (docs/design.md "Cells over the particles").
 * Steps (each a kernel, each with its reference loop):
 *   bin_bounds: the lowest and highest cell of the domain's grid holding a particle, per axis (integer atomics:
 *               a minimum and a maximum, the same in any order); a particle outside the domain or with a
 *               non-finite position is reported through FLAG_OUT_OF_DOMAIN (smallest such id) instead, and the
 *               host stops with an error before the cells are used.
 *   bin_index:  cell of each particle among the cells in use (clamped into them, so that no memory outside the
 *               arrays is touched whatever the positions); counts per cell (integer atomics).
 *   scan:       exclusive prefix sum of the counts -> cell_start (integer, so any order gives the same result).
 *   bin_scatter: each particle takes a slot in its cell, counting its cell's count back down to zero (the order of
 *               slots depends on thread timing; no second per-cell array) ...
 *   bin_sort:   ... which this step makes canonical: each cell's particles sorted by ascending id.
 * Which cells a build uses changes no bit of a result: the rows are sorted by stable id (neighbor.h).
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

/* The bound k (FLAG_CELL_LO + axis) lowered to c and bound k + 3 raised to c. Each is read first and updated only when
 * c lies beyond it, so that most particles make no atomic operation; a stale read costs one more atomic, never a
 * wrong bound (the bounds only move outwards, and the atomics decide). */
DEM_INLINE void bin_widen(DEM_GLOBAL int *flags, int k, int c)
{
    if (c < flags[k])
        DEM_ATOMIC_MIN(&flags[k], c);
    if (c > flags[k + 3])
        DEM_ATOMIC_MAX(&flags[k + 3], c);
}

DEM_ITEM(bin_bounds)
{
    vec3 xi = v3_load(x, i);
    int outside = 0;
    int cx = bin_axis(xi.x, lox, inv_cell, dcx, &outside);
    int cy = bin_axis(xi.y, loy, inv_cell, dcy, &outside);
    int cz = bin_axis(xi.z, loz, inv_cell, dcz, &outside);
    if (outside) {
        DEM_ATOMIC_MIN(&flags[FLAG_OUT_OF_DOMAIN], i);
        return;
    }
    bin_widen(flags, FLAG_CELL_LO, cx);
    bin_widen(flags, FLAG_CELL_LO + 1, cy);
    bin_widen(flags, FLAG_CELL_LO + 2, cz);
}

/* Cell c of the domain's grid along one axis, as a cell in use: c - c0, clamped into [0, nc) */
DEM_INLINE int bin_in_use(int c, int c0, int nc)
{
    c -= c0;
    return c < 0 ? 0 : c >= nc ? nc - 1 : c;
}

DEM_ITEM(bin_index)
{
    vec3 xi = v3_load(x, i);
    int outside = 0; /* reported by bin_bounds */
    int cx = bin_in_use(bin_axis(xi.x, lox, inv_cell, dcx, &outside), cx0, ncx);
    int cy = bin_in_use(bin_axis(xi.y, loy, inv_cell, dcy, &outside), cy0, ncy);
    int cz = bin_in_use(bin_axis(xi.z, loz, inv_cell, dcz, &outside), cz0, ncz);
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
