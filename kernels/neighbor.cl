/* neighbor.cl - Verlet rows from cells, history carried across rebuilds (common/neighbor.h). Twin: reference/neighbor.c
 * Arguments: common/dem_kernels.h. */
#include "../common/neighbor.h"

DEM_KERNEL(nbr_count)
DEM_KERNEL(nbr_build)
DEM_KERNEL(nbr_sort)
DEM_KERNEL(pair_index)
