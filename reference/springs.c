/* springs.c - reference twin of kernels/springs.cl: the same items in one serial loop each (common/springs.h;
 * arguments: common/dem_kernels.h). */
#include "ref_kernels.h"
#include "springs.h"

DEM_REF_LOOP(spring_forces)
DEM_REF_LOOP(channel_gather)
