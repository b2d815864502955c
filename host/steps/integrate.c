/* integrate.c - the velocity Verlet half steps (kernels/integrate.cl), and the flags each step starts from.
 * Written once for every backend. */
#include "backend.h"

int dem_stage_kick_drift(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_integrate_kick_drift); }
int dem_stage_kick(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_integrate_kick); }

/* Non-blocking: the source is static, and the driver's next flag read waits for the queue anyway. */
int dem_stage_reset_flags(const dem_backend_ops *o, dem_backend *b)
{
    static const int init[FLAG_COUNT] = {0, DEM_NO_PARTICLE, 0, 0, 0, 0, 0, 0};
    dem_bufref r = {TABLE_ONE, BUF_FLAGS};
    return o->write(b, r, 0, init, sizeof init, 0);
}
