/* binning.c - the binning step (kernels/binning.cl): cell index and counts, scan, scatter, canonical in-cell order;
 * and the scan alone, which also makes the pair-record offsets (neighbor.c). Written once for every backend. */
#include "backend.h"

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
