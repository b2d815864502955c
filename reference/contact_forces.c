/* contact_forces.c - reference twin of kernels/contact_forces.cl: the same items in one serial loop each (common/contact_forces.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "contact_forces.h"

DEM_REF_LOOP(contact_pairs)
DEM_REF_LOOP(contact_forces)
