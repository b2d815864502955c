/* neighbor.c - reference twin of kernels/neighbor.cl: the same items in one serial loop each (common/neighbor.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "neighbor.h"

DEM_REF_LOOP(nbr_count)
DEM_REF_LOOP(nbr_build)
DEM_REF_LOOP(nbr_sort)
DEM_REF_LOOP(pair_index)
