/* attach.c - particles that ride on a wall (dem_attach_to_wall): a membrane's end rings on the platens of a triaxial
 * cell (seed 001 section 3.1). A rider is a fixed particle (DEM_PARTICLE_FIXED: infinite mass, moves at its
 * velocity) whose velocity is its wall's at every step: set on the host before the run is packed, and written to the
 * device for the riders of a wall whenever that wall's velocity changes (at its stage boundaries), before the
 * step's drift. Its position therefore advances by the same v dt as the wall's, but in the run's precision, while the
 * wall's is kept in double on the host: in fp64 they agree exactly (tests/test_membrane.c, test_riders); in fp32 each
 * step's addition rounds to half an ulp of the coordinate, the same way every step, so a rider drifts from its wall
 * (measured: 3.2e-7 m after 200 steps of 1e-6 m at z = 0.08 m, 1.6e-9 m per step; 0.3 mm over 2e5 steps). Use fp64
 * for long runs with riders; the remedy is a small kernel that places riders at their start plus the wall's
 * displacement (a device-side table), not yet written. */
#include "sim.h"
#include <string.h>

int dem_attach_to_wall(dem_sim *s, int particle, int wall)
{
    if (s->started)
        return sim_fail(s, DEM_ERR_STATE, "dem_attach_to_wall after dem_start");
    if (particle < 0 || particle >= s->n || wall < 0 || wall >= s->nwalls)
        return sim_fail(s, DEM_ERR_ARG, "attach: no particle %d or no wall %d (particles 0..%d, walls 0..%d)",
                        particle, wall, s->n - 1, s->nwalls - 1);
    for (int k = 0; k < s->natt; k++)
        if (s->att[2 * k] == particle)
            return sim_fail(s, DEM_ERR_ARG, "attach: particle %d already rides on wall %d", particle,
                            s->att[2 * k + 1]);
    if (sim_grow(s, s->natt, &s->att_cap, &s->att, 2, NULL, 0, "riders"))
        return DEM_ERR_NOMEM;
    s->att[2 * s->natt] = particle, s->att[2 * s->natt + 1] = wall, s->natt++;
    s->pflags[particle] |= DEM_PARTICLE_FIXED;
    return 0;
}

void sim_attach_start(dem_sim *s)
{
    for (int k = 0; k < s->natt; k++) {
        int i = s->att[2 * k], w = s->att[2 * k + 1];
        s->pflags[i] |= DEM_PARTICLE_FIXED;
        sim_wall_velocity(s, w, s->step, s->v + 3 * i);
    }
    for (int w = 0; w < s->nwalls; w++)
        sim_wall_velocity(s, w, s->step, s->att_v[w]);
    s->att_valid = 1;
}

int sim_attach_step(dem_sim *s)
{
    int rs = s->setup.real_size;
    for (int w = 0; w < s->nwalls; w++) {
        double v[3];
        sim_wall_velocity(s, w, s->step, v);
        if (s->att_valid && !memcmp(v, s->att_v[w], sizeof v))
            continue;
        memcpy(s->att_v[w], v, sizeof v);
        float vf[3] = {(float)v[0], (float)v[1], (float)v[2]};
        for (int k = 0; k < s->natt; k++) {
            int i = s->att[2 * k];
            if (s->att[2 * k + 1] == w &&
                dem_stage_write_field_at(s->ops, s->be, DEM_FIELD_V, (size_t)rs * 3 * (size_t)i,
                                         rs == 8 ? (const void *)v : (const void *)vf, (size_t)rs * 3))
                return 1;
        }
    }
    s->att_valid = 1;
    return 0;
}
