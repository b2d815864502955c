/* pressure.h - a pressure on triangles of particles (seed 001 Eq. 18: the membrane's confining stress).
 *
 * Triangle t = (a, b, c) under the pressure sigma carries F = sigma A n_hat with its current area A and unit normal
 * n_hat along (x_b - x_a) x (x_c - x_a), i.e. F = sigma (x_b - x_a) x (x_c - x_a) / 2; each vertex gets F / 3,
 * written as a record of the contribution channel (springs.h) at chan_slot[2 nsprings + 3 t + k], so that a
 * particle's records are its springs in order and then its triangles in order. The reading (current area and
 * normal: a follower load) is taken; seed 001 section 3 also says "using the initial areas of the triangles", which
 * would be a dead load - the current one is the pressure of a fluid on the deformed membrane. Only + - * /.
 */
#ifndef DEM_PRESSURE_H
#define DEM_PRESSURE_H
#include "dem_kernels.h"
#include "vec3.h"

DEM_ITEM(pressure_forces)
{
    int a = order[tri[3 * i]], b = order[tri[3 * i + 1]], c = order[tri[3 * i + 2]]; /* stable ids to places */
    vec3 xa = v3_load(x, a);
    vec3 cr = v3_cross(v3_sub(v3_load(x, b), xa), v3_sub(v3_load(x, c), xa));
    vec3 f3 = v3_scale(cr, pressure * (real)0.5 / (real)3); /* sigma A n_hat / 3 */
    int base = 2 * nsprings + 3 * i;
    for (int k = 0; k < 3; k++)
        v3_store(chan_rec, chan_slot[base + k], f3);
}
#endif /* DEM_PRESSURE_H */
