/* integrate.c - reference twin of kernels/integrate.cl: the same items in one serial loop each (common/integrate.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "integrate.h"

DEM_REF_LOOP(integrate_kick_drift)
DEM_REF_LOOP(integrate_kick)
