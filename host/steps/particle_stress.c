/* particle_stress.c - the stress tensor when DEM_FIELD_STRESS is read, its buffer made then (common/particle_stress.h;
 * the trace each step of MC-stress is one launch, stress_trace). Written once for every backend. */
#include "backend.h"

int dem_stage_stress_tensor(const dem_backend_ops *o, dem_backend *b)
{
    return dem_buffer_ensure(o, b, BUF_STRESS) || dem_launch(o, b, K_stress_tensor);
}
