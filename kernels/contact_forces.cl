/* contact_forces.cl - Hertz-Mindlin particle and wall contacts (with the MC-stress / MC-strain normal law when on)
 * summed per particle (common/contact_forces.h): contact_pairs evaluates each pair once, contact_forces sums them
 * per particle and adds the walls. Twin: reference/contact_forces.c. Arguments: common/dem_kernels.h. */
#include "../common/contact_forces.h"

DEM_KERNEL(contact_pairs)
DEM_KERNEL(contact_forces)
