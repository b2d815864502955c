/* loops.c - the reference twin of kernels/program.cl: every kernel of DEM_KERNEL_LIST (common/dem_kernels.h) as one
 * serial loop over its items in ascending order, REF(ref_<name>) (declared in ref_kernels.h), from the families'
 * DEM_ITEM bodies (common/dem_families.h). Compiled once per precision. */
#include "ref_kernels.h"
#include "dem_families.h"

DEM_KERNEL_LIST(DEM_REF_LOOP)
