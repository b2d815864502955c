/* integrate.c - the flags each step starts from (the half steps themselves are one launch each: integrate_kick_drift,
 * integrate_kick, or the two joined, integrate_kick_kick_drift, of common/integrate.h; host/core/step_loop.c chooses).
 * Written once for every backend. */
#include "backend.h"

/* Non-blocking: the source is static, and the driver's next flag read waits for the queue anyway. */
int dem_stage_reset_flags(const dem_backend_ops *o, dem_backend *b)
{
    static const int init[FLAG_COUNT] = {[FLAG_OUT_OF_DOMAIN] = DEM_NO_PARTICLE, [FLAG_MDR_CAPPED] = DEM_NO_PARTICLE};
    dem_bufref r = {TABLE_ONE, BUF_FLAGS};
    return o->write(b, r, 0, init, sizeof init, 0);
}
