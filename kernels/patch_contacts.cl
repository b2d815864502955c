/* patch_contacts.cl - spheres touching a membrane's triangular patches: rows, forces, the vertices' sums
 * (common/patch_contacts.h). Twin: reference/patch_contacts.c. Arguments: common/dem_kernels.h. */
#include "../common/patch_contacts.h"

DEM_KERNEL(patch_build)
DEM_KERNEL(patch_forces)
DEM_KERNEL(patch_gather)
