/* particle_stress.c - reference twin of kernels/particle_stress.cl: the same items in one serial loop each (common/particle_stress.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "particle_stress.h"

DEM_REF_LOOP(stress_trace)
DEM_REF_LOOP(stress_tensor)
