/* binning.cl - cell index + counting sort + canonical in-cell order (common/binning.h). Twin: reference/binning.c */
#include "binning.h"

__kernel void bin_index(int n, real lox, real loy, real loz, real inv_cell, int ncx, int ncy, int ncz,
                        __global const real *x, __global int *cell_of, __global int *cell_count, __global int *flags)
{
    int i = get_global_id(0);
    if (i < n)
        bin_index_item(i, v3(lox, loy, loz), inv_cell, ncx, ncy, ncz, x, cell_of, cell_count, flags);
}

__kernel void scan_block_sum(int nblocks, int ncells, __global const int *count, __global int *block_sum)
{
    int b = get_global_id(0);
    if (b < nblocks)
        scan_block_sum_item(b, ncells, count, block_sum);
}

__kernel void scan_block_sums(int nblocks, __global int *block_sum)
{
    if (get_global_id(0) == 0)
        scan_block_sums_item(nblocks, block_sum);
}

__kernel void scan_apply(int nblocks, int ncells, __global const int *count, __global const int *block_sum,
                         __global int *start)
{
    int b = get_global_id(0);
    if (b < nblocks)
        scan_apply_item(b, ncells, count, block_sum, start);
}

__kernel void bin_scatter(int n, __global const int *cell_of, __global const int *start, __global int *fill,
                          __global int *cell_particles)
{
    int i = get_global_id(0);
    if (i < n)
        bin_scatter_item(i, cell_of, start, fill, cell_particles);
}

__kernel void bin_sort(int ncells, __global const int *start, __global int *cell_particles)
{
    int c = get_global_id(0);
    if (c < ncells)
        bin_sort_item(c, start, cell_particles);
}
