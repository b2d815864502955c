/* wall_forces.c - the wall-force step (common/wall_forces.h): the tree of exact sums of the force each wall receives
 * (dem_layout.h). Written once for every backend. */
#include "backend.h"

int dem_stage_wall_reduce(const dem_backend_ops *o, dem_backend *b)
{
    return dem_launch(o, b, K_wall_reduce_block) || dem_launch(o, b, K_wall_reduce_mid) ||
           dem_launch(o, b, K_wall_reduce_final);
}

/* New wall positions and velocities (real[W_STRIDE*nwalls]), non-blocking: the driver's next flag read waits. */
int dem_stage_set_walls(const dem_backend_ops *o, dem_backend *b, const void *src)
{
    dem_bufref r = {TABLE_ONE, BUF_WALL_REAL};
    size_t bytes = DEM_CORE(b)->bytes[BUF_WALL_REAL];
    return bytes ? o->write(b, r, 0, src, bytes, 0) : 0;
}
