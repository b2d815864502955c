/* riders.c - reference twin of kernels/riders.cl: the same items in one serial loop (common/riders.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "riders.h"

DEM_REF_LOOP(rider_place)
