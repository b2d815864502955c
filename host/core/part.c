/* part.c - a run of part of a scene's particles, for a run split over MPI ranks (host/mpi/, app/run_mpi.c): the
 * particles a rank does not hold dropped before dem_start, and its ghosts (copies of other ranks' particles) marked,
 * so that the walls' sums count its own particles only (common/wall_forces.h) and so do the series rows' sums
 * (host/physics/energy.c). Nothing here changes a run that does not call it. */
#include "sim.h"
#include <stdlib.h>
#include <string.h>

/* Keeps the particles i with keep[i] != 0, in their order (so that ids keep the order of the whole scene's),
 * dropping the others. Before dem_start; refused for a scene with membranes or riders (their tables name particles
 * by index). Returns the particles kept, or a dem_status. */
int sim_keep_particles(dem_sim *s, const unsigned char *keep)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (s->mesh.nsprings || s->mesh.ntri || s->mesh.nhinges || s->mesh.npatch || s->mesh.natt)
        return sim_fail(s, DEM_ERR_ARG, "a scene with membranes or riders cannot be split over ranks yet");
    if (!(s->whole_volume > 0)) /* until_density's volume: the whole scene's spheres, not the part's */
        s->whole_volume = sim_particle_volume(s);
    int m = 0;
    for (int i = 0; i < s->n; i++) {
        if (!keep[i])
            continue;
        memmove(s->x + 3 * m, s->x + 3 * i, sizeof(double) * 3);
        memmove(s->v + 3 * m, s->v + 3 * i, sizeof(double) * 3);
        memmove(s->w + 3 * m, s->w + 3 * i, sizeof(double) * 3);
        memmove(s->body + 2 * m, s->body + 2 * i, sizeof(double) * 2);
        s->radius[m] = s->radius[i];
        s->mat[m] = s->mat[i];
        s->pflags[m] = s->pflags[i];
        if (s->order.source && i < s->order.source_n)
            s->order.source[m] = s->order.source[i];
        m++;
    }
    if (s->order.source && s->order.source_n > m)
        s->order.source_n = m;
    s->n = m;
    free(s->ghost);
    s->ghost = NULL;
    return m;
}

/* Marks particle i a ghost where ghost[i] != 0 (NULL: none). Before dem_start. */
int sim_set_ghosts(dem_sim *s, const unsigned char *ghost)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    free(s->ghost);
    s->ghost = NULL;
    if (!ghost)
        return 0;
    if (!(s->ghost = malloc(s->n ? (size_t)s->n : 1)))
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    memcpy(s->ghost, ghost, (size_t)s->n);
    return 0;
}

void sim_wall_record_get(const dem_sim *s, sim_wall_record *r)
{
    memcpy(r->servo, s->motion.servo, sizeof r->servo);
    memcpy(r->servo_sum, s->motion.servo_sum, sizeof r->servo_sum);
    memcpy(r->servo_err, s->motion.servo_err, sizeof r->servo_err);
    memcpy(r->log, s->motion.stage_log, sizeof r->log);
    r->log_n = s->motion.stage_log_n;
}

void sim_wall_record_set(dem_sim *s, const sim_wall_record *r)
{
    memcpy(s->motion.servo, r->servo, sizeof r->servo);
    memcpy(s->motion.servo_sum, r->servo_sum, sizeof r->servo_sum);
    memcpy(s->motion.servo_err, r->servo_err, sizeof r->servo_err);
    memcpy(s->motion.stage_log, r->log, sizeof r->log);
    s->motion.stage_log_n = r->log_n;
}
