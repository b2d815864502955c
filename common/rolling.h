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
 * of the order mu_r r f_n dt / I each step (the elastic-plastic spring-dashpot model, which keeps a spring per
 * contact, is the cure; not here yet).
 */
#ifndef DEM_ROLLING_H
#define DEM_ROLLING_H
#include "vec3.h"
#include "dem_layout.h"

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
#endif /* DEM_ROLLING_H */
