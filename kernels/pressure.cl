/* pressure.cl - a pressure on triangles of particles into the contribution channel (common/pressure.h).
 * Twin: reference/pressure.c. Arguments: common/dem_kernels.h. */
#include "../common/pressure.h"

DEM_KERNEL(pressure_forces)
