/* wall_forces.c - reference twin of kernels/wall_forces.cl: the same items in one serial loop each (common/wall_forces.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "wall_forces.h"

DEM_REF_LOOP(wall_reduce_block)
DEM_REF_LOOP(wall_reduce_final)
