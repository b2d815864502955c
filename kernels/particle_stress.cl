/* particle_stress.cl - per-particle stress trace (online, MC-stress pass 1) and full stress tensor (output), one work
 * item per particle (common/particle_stress.h). Twin: reference/particle_stress.c. Arguments: common/dem_kernels.h. */
#include "../common/particle_stress.h"

DEM_KERNEL(stress_trace)
DEM_KERNEL(stress_tensor)
