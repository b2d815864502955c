/* binning.c - host driver of kernels/binning.cl: cell index and counts, scan, scatter, canonical in-cell order. */
#include "cl_backend.h"

int clb_scan(dem_backend *b, cl_mem count, cl_mem start, int items, cl_mem block_sum)
{
    int nblocks = (items + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK;
    cl_kernel k = b->k[K_SCAN_BLOCK_SUM];
    if (clb_arg_int(b, k, 0, nblocks) || clb_arg_int(b, k, 1, items) || clb_arg_mem(b, k, 2, count) ||
        clb_arg_mem(b, k, 3, block_sum) || clb_launch(b, K_SCAN_BLOCK_SUM, (size_t)nblocks))
        return 1;
    k = b->k[K_SCAN_BLOCK_SUMS];
    if (clb_arg_int(b, k, 0, nblocks) || clb_arg_mem(b, k, 1, block_sum) || clb_launch(b, K_SCAN_BLOCK_SUMS, 1))
        return 1;
    k = b->k[K_SCAN_APPLY];
    return clb_arg_int(b, k, 0, nblocks) || clb_arg_int(b, k, 1, items) || clb_arg_mem(b, k, 2, count) ||
           clb_arg_mem(b, k, 3, block_sum) || clb_arg_mem(b, k, 4, start) ||
           clb_launch(b, K_SCAN_APPLY, (size_t)nblocks);
}

int clb_bin(dem_backend *b)
{
    cl_kernel k;
    if (clb_fill_int(b, b->cell_count, 0, (size_t)b->ncells) || clb_fill_int(b, b->cell_fill, 0, (size_t)b->ncells))
        return 1;
    k = b->k[K_BIN_INDEX];
    if (clb_arg_int(b, k, 0, b->n) || clb_arg_real(b, k, 1, b->lo[0]) || clb_arg_real(b, k, 2, b->lo[1]) ||
        clb_arg_real(b, k, 3, b->lo[2]) || clb_arg_real(b, k, 4, b->inv_cell) || clb_arg_int(b, k, 5, b->ncx) ||
        clb_arg_int(b, k, 6, b->ncy) || clb_arg_int(b, k, 7, b->ncz) || clb_arg_mem(b, k, 8, b->x) ||
        clb_arg_mem(b, k, 9, b->cell_of) || clb_arg_mem(b, k, 10, b->cell_count) || clb_arg_mem(b, k, 11, b->flags) ||
        clb_launch(b, K_BIN_INDEX, (size_t)b->n))
        return 1;
    if (clb_scan(b, b->cell_count, b->cell_start, b->ncells, b->block_sum))
        return 1;
    k = b->k[K_BIN_SCATTER];
    if (clb_arg_int(b, k, 0, b->n) || clb_arg_mem(b, k, 1, b->cell_of) || clb_arg_mem(b, k, 2, b->cell_start) ||
        clb_arg_mem(b, k, 3, b->cell_fill) || clb_arg_mem(b, k, 4, b->cell_particles) ||
        clb_launch(b, K_BIN_SCATTER, (size_t)b->n))
        return 1;
    k = b->k[K_BIN_SORT];
    return clb_arg_int(b, k, 0, b->ncells) || clb_arg_mem(b, k, 1, b->cell_start) ||
           clb_arg_mem(b, k, 2, b->cell_particles) || clb_launch(b, K_BIN_SORT, (size_t)b->ncells);
}
