/* integrate.cl - velocity Verlet half steps (common/integrate.h). Twin: reference/integrate.c
 * Arguments: common/dem_kernels.h. */
#include "../common/integrate.h"

DEM_KERNEL(integrate_kick_drift)
DEM_KERNEL(integrate_kick)
