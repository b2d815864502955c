/* binning.c - reference twin of kernels/binning.cl (serial loops over common/binning.h). */
#include "ref_kernels.h"
#include "binning.h"

void REF(ref_bin_index)(int n, vec3 lo, real inv_cell, int ncx, int ncy, int ncz, const real *x, int *cell_of,
                        int *cell_count, int *flags)
{
    for (int i = 0; i < n; i++)
        bin_index_item(i, lo, inv_cell, ncx, ncy, ncz, x, cell_of, cell_count, flags);
}

void REF(ref_scan)(int ncells, const int *count, int *block_sum, int *start)
{
    int nblocks = (ncells + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK;
    for (int b = 0; b < nblocks; b++)
        scan_block_sum_item(b, ncells, count, block_sum);
    scan_block_sums_item(nblocks, block_sum);
    for (int b = 0; b < nblocks; b++)
        scan_apply_item(b, ncells, count, block_sum, start);
}

void REF(ref_bin_scatter)(int n, const int *cell_of, const int *start, int *fill, int *cell_particles)
{
    for (int i = 0; i < n; i++)
        bin_scatter_item(i, cell_of, start, fill, cell_particles);
}

void REF(ref_bin_sort)(int ncells, const int *start, int *cell_particles)
{
    for (int c = 0; c < ncells; c++)
        bin_sort_item(c, start, cell_particles);
}
