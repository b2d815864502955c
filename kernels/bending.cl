/* bending.cl - hinges between pairs of triangles into the contribution channel (common/bending.h).
 * Twin: reference/bending.c. Arguments: common/dem_kernels.h. */
#include "../common/bending.h"

DEM_KERNEL(hinge_forces)
