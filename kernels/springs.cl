/* springs.cl - damped linear springs and the channel that adds their forces per particle (common/springs.h).
 * Twin: reference/springs.c. Arguments: common/dem_kernels.h. */
#include "../common/springs.h"

DEM_KERNEL(spring_forces)
DEM_KERNEL(channel_gather)
