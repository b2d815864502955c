/* springs.h - damped linear springs between particles (seed 001 Eq. 3-7: the membrane's stretching), and the
 * channel that adds their forces to the particles' sums without atomics.
 *
 * Spring s joins particles a = spring_int[2s] and b = spring_int[2s+1] (stable ids, stored at order[a], order[b]:
 * the tables of springs, triangles, hinges and riders name particles by stable id, so that they stay as they are
 * when the particles are stored anew, host/core/reorder.c). With rho = x_a - x_b, its length |rho| and
 * unit e = rho / |rho|, particle a feels
 *     F_a = -e [k (|rho| - rho0) + c e . (v_a - v_b)],   c = 2 gamma sqrt(k m_eff)  (SP_DAMP, from the host)
 * and b the exact negation. Seed 001 Eq. 6 as printed puts the elastic term with the sign of the force on b and the
 * damping with that on a; the paper calls it "the force of a damped harmonic oscillator", which fixes this reading
 * (a stretched spring pulls its ends together, a separating pair is slowed). At |rho| = 0 the direction is undefined
 * and the force is zero. Only + - * / sqrt.
 *
 * The channel: spring_forces writes each end's force as a record at chan_slot[2s] (end a) and chan_slot[2s+1] (end
 * b); the host laid the slots out so that the records of the particle of stable id p are chan_rec[chan_start[p] ..
 * chan_start[p+1]) in ascending spring index. channel_gather then adds them, in that order, to the particle's force after its contact
 * sums: the same order on every device (contacts.h has the contacts' order; the channel is the pattern for the
 * membrane's hinges, patch contacts and pressure, whose forces land on several vertices).
 */
#ifndef DEM_SPRINGS_H
#define DEM_SPRINGS_H
#include "dem_kernels.h"
#include "vec3.h"
#include "dem_layout.h"

DEM_ITEM(spring_forces)
{
    int a = order[spring_int[2 * i]], b = order[spring_int[2 * i + 1]]; /* stable ids to places */
    vec3 rho = v3_sub(v3_load(x, a), v3_load(x, b));
    real len = dem_sqrt(v3_dot(rho, rho));
    vec3 f = v3_zero();
    if (len > (real)0) {
        vec3 e = v3_scale(rho, (real)1 / len);
        DEM_CONST_GLOBAL real *sp = spring_real + SP_STRIDE * i;
        real rate = v3_dot(e, v3_sub(v3_load(v, a), v3_load(v, b)));
        real mag = sp[SP_K] * (len - sp[SP_REST]) + sp[SP_DAMP] * rate;
        f = v3_scale(e, -mag);
    }
    v3_store(chan_rec, chan_slot[2 * i], f);
    v3_store(chan_rec, chan_slot[2 * i + 1], v3_neg(f)); /* the exact negation */
}

DEM_ITEM(channel_gather)
{
    vec3 f = v3_load(force, i);
    int q = sid[i]; /* the records are laid out by stable id */
    for (int r = chan_start[q]; r < chan_start[q + 1]; r++)
        f = v3_add(f, v3_load(chan_rec, r));
    v3_store(force, i, f);
}
#endif /* DEM_SPRINGS_H */
