/* binning.c - reference twin of kernels/binning.cl: the same items in one serial loop each (common/binning.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "binning.h"

DEM_REF_LOOP(bin_bounds)
DEM_REF_LOOP(bin_index)
DEM_REF_LOOP(scan_block_sum)
DEM_REF_LOOP(scan_block_sums)
DEM_REF_LOOP(scan_apply)
DEM_REF_LOOP(bin_scatter)
DEM_REF_LOOP(bin_sort)
