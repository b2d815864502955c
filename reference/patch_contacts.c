/* patch_contacts.c - reference twin of kernels/patch_contacts.cl: the same items in one serial loop each
 * (common/patch_contacts.h; arguments: common/dem_kernels.h). */
#include "ref_kernels.h"
#include "patch_contacts.h"

DEM_REF_LOOP(patch_build)
DEM_REF_LOOP(patch_forces)
DEM_REF_LOOP(patch_gather)
