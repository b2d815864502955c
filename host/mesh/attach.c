/* attach.c - particles that ride on a wall (dem_attach_to_wall): a membrane's end rings on the platens of a triaxial
 * cell (seed 001 section 3.1). A rider is a fixed particle (DEM_PARTICLE_FIXED: infinite mass) that the device puts
 * at its wall's place and velocity every step after the walls move (common/riders.h, kernel rider_place); here it
 * gets its wall's velocity of the first step on the host, for the forces at the start. Placed rather than
 * integrated: integrated in fp32, a rider drifted from its wall by half an ulp per step (1.6e-9 m per step of 1e-6
 * m at z = 0.08 m, 0.3 mm over 2e5 steps); placed, it stays one rounding from the wall's double position. */
#include "sim.h"

int dem_attach_to_wall(dem_sim *s, int particle, int wall)
{
    if (s->run.started || s->split_started)
        return sim_fail(s, DEM_ERR_STATE, "dem_attach_to_wall after dem_start");
    if (particle < 0 || particle >= s->n || wall < 0 || wall >= s->nwalls)
        return sim_fail(s, DEM_ERR_ARG, "attach: no particle %d or no wall %d (particles 0..%d, walls 0..%d)",
                        particle, wall, s->n - 1, s->nwalls - 1);
    for (int k = 0; k < s->mesh.natt; k++)
        if (s->mesh.att[2 * k] == particle)
            return sim_fail(s, DEM_ERR_ARG, "attach: particle %d already rides on wall %d", particle,
                            s->mesh.att[2 * k + 1]);
    if (sim_grow(s, s->mesh.natt, &s->mesh.att_cap, &s->mesh.att, 2, NULL, 0, "riders"))
        return DEM_ERR_NOMEM;
    s->mesh.att[2 * s->mesh.natt] = particle, s->mesh.att[2 * s->mesh.natt + 1] = wall, s->mesh.natt++;
    s->pflags[particle] |= DEM_PARTICLE_FIXED;
    s->effects |= DEM_EFFECT_RIDERS; /* and it does not touch that wall (contact_geometry.h, wall_met) */
    return 0;
}

void sim_attach_start(dem_sim *s)
{
    for (int k = 0; k < s->mesh.natt; k++) {
        int i = s->mesh.att[2 * k], w = s->mesh.att[2 * k + 1];
        sim_wall_velocity(s, w, s->v + 3 * i);
    }
}
