/* particle_stress.c - the stress steps (kernels/particle_stress.cl): the trace each step (MC-stress) and the tensor
 * when DEM_FIELD_STRESS is read (its buffer made then). Written once for every backend. */
#include "backend.h"

int dem_stage_stress_trace(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_stress_trace); }

int dem_stage_stress_tensor(const dem_backend_ops *o, dem_backend *b)
{
    return dem_buffer_ensure(o, b, BUF_STRESS) || dem_launch(o, b, K_stress_tensor);
}
