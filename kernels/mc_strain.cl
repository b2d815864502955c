/* mc_strain.cl - MC-strain: displacements induced at each contact by the particle's other contacts, and one
 * fixed-point update of the contact forces (common/mc_strain.h). Twin: reference/mc_strain.c
 * Arguments: common/dem_kernels.h. */
#include "../common/mc_strain.h"

DEM_KERNEL(mc_strain_disp)
DEM_KERNEL(mc_strain_update)
