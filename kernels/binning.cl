/* binning.cl - cell index + counting sort + canonical in-cell order (common/binning.h). Twin: reference/binning.c
 * Arguments: common/dem_kernels.h. */
#include "../common/binning.h"

DEM_KERNEL(bin_bounds)
DEM_KERNEL(bin_index)
DEM_KERNEL(scan_block_sum)
DEM_KERNEL(scan_block_sums)
DEM_KERNEL(scan_apply)
DEM_KERNEL(bin_scatter)
DEM_KERNEL(bin_sort)
