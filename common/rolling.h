/* rolling.h - rolling resistance of constant torque (DEM_EFFECT_ROLLING): model A of Ai, Chen, Rotter and Ooi,
 * "Assessment of rolling resistance models in discrete element simulations", Powder Technology 206 (2011) 269, as
 * LIGGGHTS' `rolling_friction cdt`. A contact resists the relative rolling of its two bodies with a torque of fixed
 * size, against the direction of their relative spin in the tangent plane:
 *   M_a = -mu_r r* f_n w_t / |w_t|,   w_t = w - (w . n) n,   w = w_a - w_b (a wall's spin: 0)
 * on body a, and -M_a on body b (a wall receives nothing: its spin is prescribed). The spin about the normal (twist)
 * is not resisted. f_n the contact's normal force (>= 0), r* its effective radius (a wall: the sphere's), mu_r the
 * pair table's PM_MU_ROLL (the mean of the two materials', or the pair's own: dem_set_material_pair).
 * Only + - * / sqrt. A sphere rolling on a plane slows at 5/7 mu_r g (tests/test_rolling.c). The model's known limit:
 * the torque does not fall as the relative spin does, so a rolling sphere that comes to rest rocks about it by a spin
 * of the order mu_r r f_n dt / I each step.
 *
 * The cure, with DEM_EFFECT_ROLLING_SPRING: model C of the same paper, the elastic-plastic spring-dashpot (EPSD), as
 * LIGGGHTS' `rolling_friction epsd` has it. Each contact keeps a rolling spring M (a torque, in its tangent plane),
 * which the relative rotation winds up and the full mobilisation torque caps:
 *   M <- R[M] - k_r w_t dt,   k_r = 2.25 k_n mu_r^2 r*^2,   |M| <= M_m = mu_r r* f_n,
 * R rotating the stored spring into the current tangent plane keeping its length (as the tangential history:
 * hm_rotate_history), k_n = 4/3 E* sqrt(r* delta) Hertz's force over overlap at the geometric overlap (LIGGGHTS'
 * Hertz kn, so that a calibration made there carries over; Ai et al.'s springs were linear, where k_n is the one
 * stiffness; 2.25 is their 3D factor, after Iwashita and Oda), 0 where the overlap is not positive (a bond or an
 * induced displacement holding a contact across a gap: its spring then only slides to the cap); f_n the contact's
 * normal force with its damping, as model A takes it (0: no cap, the spring slides to zero); below the cap a dashpot
 * acts too,
 *   M_d = -eta_r 2 sqrt(I_r k_r) w_t,   1/I_r = 1/(I_a + m_a r_a^2) + 1/(I_b + m_b r_b^2)   (a wall: its term 0),
 * and none once the spring is at the cap (f = 0 in Ai et al.; LIGGGHTS does the same). The torque on a is M + M_d,
 * -(M + M_d) on b. At full mobilisation the spring's torque is model A's, so a rolling sphere slows as before; once
 * the rolling stops the spring holds the sphere still instead of rocking it (tests/test_rolling.c: both, and the
 * rocking period 2 pi sqrt((I + m arm^2) / k_r) of a resting sphere). The spring's elastic energy is not in the
 * series' energy rows. PAIR_RSPRING and WALL_RSPRING keep it, carried across rebuilds and checkpointed like the
 * tangential history.
 */
#ifndef DEM_ROLLING_H
#define DEM_ROLLING_H
#include "vec3.h"
#include "dem_layout.h"
#include "laws/hertz_mindlin.h" /* hm_rotate_history */

/* The rolling torque on body a of a contact with normal n (from b to a), normal force fn, relative spin w = w_a -
 * w_b, effective radius rstar, pair-table row pm */
DEM_INLINE vec3 rolling_torque(vec3 n, real fn, vec3 w, real rstar, DEM_CONST_GLOBAL real *pm)
{
    vec3 wt = v3_sub(w, v3_scale(n, v3_dot(w, n)));
    real w2 = v3_dot(wt, wt);
    if (!(w2 > (real)0) || !(fn > (real)0))
        return v3_zero();
    return v3_scale(wt, -(pm[PM_MU_ROLL] * rstar * fn) / dem_sqrt(w2));
}

/* The rolling spring model (DEM_EFFECT_ROLLING_SPRING): the torque on body a (*torque) and the new spring to keep,
 * from the stored one (spring, zero for a new contact), for the contact's normal n (from b to a), overlap delta,
 * normal force fn, relative spin w = w_a - w_b, effective radius rstar, 1/I_r = the bodies' 1/(I + m r^2) summed
 * (ia_ib; ROLL_INERTIA holds each particle's, host/core/sim_setup.c; a wall's is 0), dt, and the pair-table row pm */
DEM_INLINE vec3 rolling_spring_torque(vec3 n, real delta, real fn, vec3 w, vec3 spring, real rstar, real ia_ib, real dt,
                                      DEM_CONST_GLOBAL real *pm, vec3 *torque)
{
    vec3 wt = v3_sub(w, v3_scale(n, v3_dot(w, n)));
    real mu = pm[PM_MU_ROLL];
    real dk = delta > (real)0 ? delta : (real)0;
    real kr = (real)9 / (real)4 * ((real)4 / (real)3 * pm[PM_ESTAR] * dem_sqrt(rstar * dk)) * mu * mu * rstar * rstar;
    vec3 m = v3_sub(hm_rotate_history(spring, n), v3_scale(wt, kr * dt));
    real mmax = fn > (real)0 ? mu * rstar * fn : (real)0, m2 = v3_dot(m, m);
    if (m2 > mmax * mmax) { /* full mobilisation: the spring slides at the cap, no dashpot */
        m = m2 > (real)0 ? v3_scale(m, mmax / dem_sqrt(m2)) : m;
        *torque = m;
        return m;
    }
    *torque = m;
    if (pm[PM_ROLL_DAMP] > (real)0 && ia_ib > (real)0)
        *torque = v3_sub(m, v3_scale(wt, pm[PM_ROLL_DAMP] * (real)2 * dem_sqrt(kr / ia_ib)));
    return m;
}
#endif /* DEM_ROLLING_H */
