/* riders.cl - particles riding on walls, placed at their walls (common/riders.h).
 * Twin: reference/riders.c. Arguments: common/dem_kernels.h. */
#include "../common/riders.h"

DEM_KERNEL(rider_place)
