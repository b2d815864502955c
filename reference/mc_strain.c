/* mc_strain.c - reference twin of kernels/mc_strain.cl: the same items in one serial loop each (common/mc_strain.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "mc_strain.h"

DEM_REF_LOOP(mc_strain_disp)
DEM_REF_LOOP(mc_strain_update)
