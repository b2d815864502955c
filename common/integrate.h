/* integrate.h - velocity Verlet (kick-drift-kick), a second-order symplectic scheme for the conservative part.
 *
 *   kick_drift:  v += dt/2 a(t);  w += dt/2 alpha(t);  x += dt v          (then forces are evaluated at t+dt
 *   kick:        v += dt/2 a(t+dt); w += dt/2 alpha(t+dt)                   with the half-step velocities)
 *
 * a = f/m + g for free particles; inverse mass 0 marks a particle moving at constant velocity (no gravity),
 * inverse inertia 0 a particle that does not rotate. Spheres: I = 2/5 m r^2, so no gyroscopic term.
 * With DEM_EFFECT_CONSTRAINTS a particle's held velocity components (hold[i] bits 0, 1, 2: x, y, z) get no
 * acceleration: a motion prescribed along those axes, free along the others.
 * kick_drift also raises the rebuild flag once a particle has moved more than skin/2 since the last neighbour
 * build (a non-finite position raises it too, so that binning reports it).
 */
#ifndef DEM_INTEGRATE_H
#define DEM_INTEGRATE_H
#include "dem_kernels.h"
#include "vec3.h"
#include "dem_layout.h"
#include "../include/dem_effects.h"
#include "series.h"

DEM_INLINE void integrate_kick_velocity(unsigned fx, int i, real half_dt, vec3 g, DEM_GLOBAL real *v, DEM_GLOBAL real *w,
                                        DEM_CONST_GLOBAL real *force, DEM_CONST_GLOBAL real *torque,
                                        DEM_CONST_GLOBAL real *invmass, DEM_CONST_GLOBAL real *invinertia,
                                        DEM_CONST_GLOBAL unsigned *hold)
{
    real im = invmass[i], ii = invinertia[i];
    if (im > (real)0) {
        vec3 a = v3_scale(v3_load(force, i), im);
        if (fx & DEM_EFFECT_GRAVITY)
            a = v3_add(a, g);
        if (fx & DEM_EFFECT_CONSTRAINTS) { /* held components keep their velocity: v + 0 dt/2 is v */
            unsigned h = hold[i];
            if (h & 1u)
                a.x = (real)0;
            if (h & 2u)
                a.y = (real)0;
            if (h & 4u)
                a.z = (real)0;
        }
        v3_store(v, i, v3_add(v3_load(v, i), v3_scale(a, half_dt)));
    }
    if ((fx & DEM_EFFECT_FRICTION) && ii > (real)0) /* torques come from friction only */
        v3_store(w, i, v3_add(v3_load(w, i), v3_scale(v3_scale(v3_load(torque, i), ii), half_dt)));
}

DEM_INLINE void integrate_drift(int i, real dt, real half_skin2, DEM_GLOBAL real *x, DEM_CONST_GLOBAL real *v,
                                 DEM_CONST_GLOBAL real *x_build, DEM_GLOBAL int *flags)
{
    vec3 xi = v3_add(v3_load(x, i), v3_scale(v3_load(v, i), dt));
    v3_store(x, i, xi);
    vec3 d = v3_sub(xi, v3_load(x_build, i));
    if (!(v3_dot(d, d) <= half_skin2))
        DEM_ATOMIC_MAX(&flags[FLAG_REBUILD], 1);
}

DEM_ITEM(integrate_kick_drift)
{
    vec3 g = v3(gx, gy, gz);
    integrate_kick_velocity(fx, i, (real)0.5 * dt, g, v, w, force, torque, invmass, invinertia, hold);
    integrate_drift(i, dt, half_skin2, x, v, x_build, flags);
}

/* integrate_kick of the step before, then integrate_kick_drift: the same two half kicks, each rounded as it is
 * alone (v + dt/2 a, then that + dt/2 a; not v + dt a), so the bits are those of the two launches. The driver uses
 * it where nothing reads the velocities between the two (host/core/step_loop.c: not after a sampled step or the last
 * step of a call); it saves one pass over the particles' velocities, forces and masses a step. */
DEM_ITEM(integrate_kick_kick_drift)
{
    vec3 g = v3(gx, gy, gz);
    integrate_kick_velocity(fx, i, (real)0.5 * dt, g, v, w, force, torque, invmass, invinertia, hold);
    integrate_kick_velocity(fx, i, (real)0.5 * dt, g, v, w, force, torque, invmass, invinertia, hold);
    integrate_drift(i, dt, half_skin2, x, v, x_build, flags);
}

DEM_ITEM(integrate_kick)
{
    vec3 g = v3(gx, gy, gz);
    integrate_kick_velocity(fx, i, (real)0.5 * dt, g, v, w, force, torque, invmass, invinertia, hold);
    if (sample) { /* a sampled step (series.h): the energies of the motion at its end, and (item 0) the walls'
                     sums of the step */
        series_motion_terms(fx, v3_load(x, i), v3_load(v, i), v3_load(w, i), invmass[i], invinertia[i], g,
                            series_slot(ring, row, n, i));
        if ((fx & DEM_EFFECT_WALLS) && i == 0)
            series_wall_row(nwalls, row, wall_force, wall_nforce, ring_wall);
    }
}
#endif /* DEM_INTEGRATE_H */
