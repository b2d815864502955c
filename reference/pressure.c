/* pressure.c - reference twin of kernels/pressure.cl: the same items in one serial loop (common/pressure.h;
 * arguments: common/dem_kernels.h). */
#include "ref_kernels.h"
#include "pressure.h"

DEM_REF_LOOP(pressure_forces)
