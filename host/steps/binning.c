/* binning.c - the binning step (common/binning.h): the cells in use, cell index and counts, scan, scatter, canonical
 * in-cell order; and the scan alone, which also makes the pair-record offsets (neighbor.c). Written once for every
 * backend. */
#include "backend.h"
#include <limits.h>

int dem_stage_scan(const dem_backend_ops *o, dem_backend *b, dem_bufref count, dem_bufref start, dem_bufref block_sum,
                   int items)
{
    dem_core *c = DEM_CORE(b);
    c->alias[ALIAS_SCAN_COUNT] = count;
    c->alias[ALIAS_SCAN_START] = start;
    c->alias[ALIAS_SCAN_BLOCK_SUM] = block_sum;
    c->si[SI_SCAN_ITEMS] = items;
    c->si[SI_SCAN_NBLOCKS] = (items + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK;
    return dem_launch(o, b, K_scan_block_sum) || dem_launch(o, b, K_scan_block_sums) || dem_launch(o, b, K_scan_apply);
}

int dem_stage_bin_bounds(const dem_backend_ops *o, dem_backend *b)
{
    static const int none[6] = {INT_MAX, INT_MAX, INT_MAX, -1, -1, -1}; /* FLAG_CELL_LO .. FLAG_CELL_HI + 2 */
    dem_bufref flags = {TABLE_ONE, BUF_FLAGS};
    return o->write(b, flags, sizeof(int) * FLAG_CELL_LO, none, sizeof none, 0) || dem_launch(o, b, K_bin_bounds);
}

/* The cell buffers grow with 1/4 to spare (a bounding box that creeps outwards by a layer of cells costs one
 * allocation in several builds), never beyond the domain's cells, and never shrink: what a run holds is what its
 * widest build needed. */
static int cells_reserve(const dem_backend_ops *o, dem_backend *b, int cells, int domain_cells)
{
    dem_core *c = DEM_CORE(b);
    if (cells <= c->cell_cap)
        return 0;
    long cap = (long)cells + cells / 4 + 64;
    c->cell_cap = cap > domain_cells ? domain_cells : (int)cap;
    static const int grown[] = {BUF_CELL_COUNT, BUF_CELL_START, BUF_BLOCK_SUM}; /* written before read at each build */
    for (size_t k = 0; k < sizeof grown / sizeof grown[0]; k++)
        if (o->alloc(b, TABLE_ONE, 0, grown[k], dem_buffer_bytes(c, grown[k]), NULL))
            return 1;
    return 0;
}

int dem_stage_bin_cells(const dem_backend_ops *o, dem_backend *b, const int *flags)
{
    dem_core *c = DEM_CORE(b);
    int first[3], count[3], domain = 1, cells = 1;
    for (int d = 0; d < 3; d++) {
        int lo = flags[FLAG_CELL_LO + d], hi = flags[FLAG_CELL_HI + d];
        first[d] = hi < lo ? 0 : lo; /* no particles: one cell */
        count[d] = hi < lo ? 1 : hi - lo + 1;
        cells *= count[d];                /* at most the domain's cells, which fit an int (host/core/sim_setup.c) */
        domain *= c->si[SI_DCX + d];
    }
    if (cells_reserve(o, b, cells, domain))
        return 1;
    c->ncells = c->si[SI_NCELLS] = cells;
    c->si[SI_NCX] = count[0], c->si[SI_NCY] = count[1], c->si[SI_NCZ] = count[2];
    c->si[SI_CX0] = first[0], c->si[SI_CY0] = first[1], c->si[SI_CZ0] = first[2];
    return 0;
}

int dem_stage_bin(const dem_backend_ops *o, dem_backend *b)
{
    dem_core *c = DEM_CORE(b);
    dem_bufref count = {TABLE_ONE, BUF_CELL_COUNT}; /* bin_scatter leaves it zero again; zeroed here all the same */
    return o->fill_int(b, count, 0, (size_t)c->ncells) ||
           dem_launch(o, b, K_bin_index) ||
           dem_stage_scan(o, b, count, (dem_bufref){TABLE_ONE, BUF_CELL_START}, (dem_bufref){TABLE_ONE, BUF_BLOCK_SUM},
                          c->ncells) ||
           dem_launch(o, b, K_bin_scatter) || dem_launch(o, b, K_bin_sort);
}
