/* riders.h - particles that ride on walls (dem_attach_to_wall; host/mesh/attach.c): each step, after the walls have
 * moved, rider i is put at its wall's point plus its offset from it at the start and given its wall's velocity of the
 * step. Placed, not integrated: in fp32 an integrated rider drifted from its wall by half an ulp per step (1.6e-9 m
 * per step at z = 0.08 m); placed, it is one rounding away from the wall's double position, whatever the step. */
#ifndef DEM_RIDERS_H
#define DEM_RIDERS_H
#include "dem_kernels.h"
#include "vec3.h"
#include "dem_layout.h"

DEM_ITEM(rider_place)
{
    int p = order[rider_int[2 * i]], w = rider_int[2 * i + 1]; /* the particle's stable id to its place */
    DEM_CONST_GLOBAL real *wr = wall_real + W_STRIDE * w;
    vec3 point = v3(wr[W_PX], wr[W_PY], wr[W_PZ]), vel = v3(wr[W_VX], wr[W_VY], wr[W_VZ]);
    v3_store(x, p, v3_add(point, v3_load(rider_off, i)));
    v3_store(v, p, vel);
}
#endif /* DEM_RIDERS_H */
