/* wall_forces.cl - the canonical per-wall force sum (common/wall_forces.h); the wall contacts themselves are
 * applied per particle inside kernels/contact_forces.cl (and evaluated again here when their forces are not kept).
 * Twin: reference/wall_forces.c
 * Arguments: common/dem_kernels.h. */
#include "../common/wall_forces.h"

DEM_KERNEL(wall_reduce_block)
DEM_KERNEL(wall_reduce_final)
