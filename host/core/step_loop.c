/* step_loop.c - the run: dem_start, and each step (dem_step, sim_step_once): kick and drift, the walls' move, a
 * rebuild when due (rebuild.c), the force stages in order (the pressure schedule, MC-strain's iteration), and the
 * second kick (inside a call, joined to the next step's first). Every decision is taken here the same way for every
 * backend. */
#include "sim.h"
#include "dem_layout.h"
#include <math.h>
#include <stdlib.h>

int sim_read_flags(dem_sim *s, int *flags)
{
    return dem_stage_read_field(s->ops, s->be, DEM_FIELD_FLAGS, flags, sizeof(int) * FLAG_COUNT) ? sim_be_fail(s) : 0;
}

/* The scheduled pressure at time t [s] (dem_set_pressure_stages) */
static double pressure_at(const dem_sim *s, double t)
{
    double from = s->mesh.pressure, t0 = 0;
    for (int k = 0; k < s->mesh.npstages; k++) {
        const dem_pressure_stage *g = &s->mesh.pstages[k];
        if (t < t0 + g->duration)
            return from + (g->pressure - from) * ((t - t0) / g->duration);
        from = g->pressure, t0 += g->duration;
    }
    return from;
}

/* a run split over ranks (dem_sim.halo_hook): the ghosts' values, or a decision, made the run's */
static int halo(dem_sim *s, int event, int *value)
{
    int e = s->halo_hook ? s->halo_hook(s, s->halo_ctx, event, value) : 0;
    if (e) /* agreed: every rank fails the step here */
        s->run.halo_agreed = 1;
    return e;
}

/* MC-strain before the contact pass: displacements from the stored forces (lagged), or iterated to the tolerance. */
static int mc_strain(dem_sim *s)
{
    long it = 0;
    int converged = 0, e;
    if (dem_launch(s->ops, s->be, K_mc_strain_disp))
        return sim_be_fail(s);
    if ((e = halo(s, SIM_HOOK_MC_DISP, NULL)))
        return e;
    while (it < s->mc.max_iter) {
        int flags[FLAG_COUNT];
        if (sim_read_flags(s, flags))
            return DEM_ERR_DEVICE;
        flags[FLAG_MC_PENDING] = 0;
        if (dem_stage_write_field(s->ops, s->be, DEM_FIELD_FLAGS, flags, sizeof flags) || dem_stage_mc_strain_update(s->ops, s->be, s->mc.tol) ||
            dem_launch(s->ops, s->be, K_mc_strain_disp))
            return sim_be_fail(s);
        if ((e = halo(s, SIM_HOOK_MC_DISP, NULL)))
            return e;
        it++;
        if (sim_read_flags(s, flags))
            return DEM_ERR_DEVICE;
        if ((e = halo(s, SIM_HOOK_MC_PENDING, &flags[FLAG_MC_PENDING])))
            return e;
        if (!flags[FLAG_MC_PENDING]) {
            converged = 1;
            break;
        }
    }
    s->mc.stats.last = it;
    if (s->run.force_step == s->run.step) /* dem_start's forces, before any step: no step to count (a cap hit there made
                                   * the count one more than the steps, "6001 of 6000") */
        return 0;
    if (s->mc.max_iter && !converged) {
        s->mc.stats.unconverged++;
        if (s->mc.stats.first_capped < 0)
            s->mc.stats.first_capped = s->run.force_step;
        s->mc.stats.last_capped = s->run.force_step;
    }
    s->mc.stats.total += it;
    if (it > s->mc.stats.max)
        s->mc.stats.max = it;
    return 0;
}

/* The force stages of a step, in order, each run only when the run has its effect (0: always) and, for the walls'
 * sum, walls. A stage returns 0 or a dem_status (a backend failure already reported through sim_be_fail). */
static int stage_stress_trace(dem_sim *s) { return dem_launch(s->ops, s->be, K_stress_trace) ? sim_be_fail(s) : 0; }
/* The force each wall received is summed only where someone can read it: the last step of every dem_step call (so
 * dem_get_field and the output see it after any call), a sampled step (its row, common/series.h) and every step while
 * a servo stage may read it. Unless the
 * run keeps each particle's wall forces (DEM_KEEP_WALL_FORCES: a servo, the contact network), the sum evaluates
 * the wall contacts itself, between the pair pass and the per-particle sums, which then apply exactly those forces
 * (common/wall_forces.h); otherwise it adds the kept forces after the per-particle sums. The bits are the same. */
static int stage_contacts(dem_sim *s)
{
    int walls = (s->effects & DEM_EFFECT_WALLS) && s->nwalls;
    int sums = walls && (s->run.wall_sums_due || s->run.sample_row >= 0);
    int kept = (s->setup.effects & DEM_KEEP_WALL_FORCES) != 0; /* then the sums read what contact_forces kept */
    int one = s->run.one_pass; /* contact_rows for both passes (the walls' sums read no pair record) */
    if ((!one && dem_launch(s->ops, s->be, K_contact_pairs)) ||
        (sums && !kept && dem_stage_wall_reduce(s->ops, s->be)) ||
        dem_launch(s->ops, s->be, one ? K_contact_rows : K_contact_forces))
        return sim_be_fail(s);
    if (one) { /* its next touching flags and histories become the current ones */
        s->ops->swap(s->be, BUF_TOUCH, BUF_TOUCH_NEXT);
        if (s->setup.effects & DEM_ONE_PASS_HIST)
            s->ops->swap(s->be, BUF_PAIR_HIST, BUF_PAIR_HIST_NEXT);
    }
    return sums && kept && dem_stage_wall_reduce(s->ops, s->be) ? sim_be_fail(s) : 0;
}
static int stage_mdr_surface(dem_sim *s)
{
    return dem_launch(s->ops, s->be, K_mdr_surface) ? sim_be_fail(s) : 0;
}
static int stage_springs(dem_sim *s)
{
    return s->mesh.nsprings && dem_launch(s->ops, s->be, K_spring_forces) ? sim_be_fail(s) : 0;
}
static int stage_pressure(dem_sim *s)
{
    s->mesh.pressure_now = pressure_at(s, (double)s->run.force_step * s->dt);
    DEM_CORE(s->be)->sr[SR_PRESSURE] = s->mesh.pressure_now;
    return s->mesh.ntri && dem_launch(s->ops, s->be, K_pressure_forces) ? sim_be_fail(s) : 0;
}
static int stage_bending(dem_sim *s)
{
    return s->mesh.nhinges && dem_launch(s->ops, s->be, K_hinge_forces) ? sim_be_fail(s) : 0;
}
static int stage_gather(dem_sim *s)
{
    return (s->mesh.nsprings || s->mesh.ntri || s->mesh.nhinges) && dem_launch(s->ops, s->be, K_channel_gather) ? sim_be_fail(s) : 0;
}
static int stage_patches(dem_sim *s)
{
    return s->mesh.npatch && (dem_launch(s->ops, s->be, K_patch_forces) || dem_launch(s->ops, s->be, K_patch_gather))
               ? sim_be_fail(s)
               : 0;
}
static const struct {
    unsigned gate;
    int (*run)(dem_sim *s);
} force_stages[] = {
    {DEM_EFFECT_MC_STRESS, stage_stress_trace}, /* pass 1 of MC-stress: the traces the contacts read */
    {DEM_EFFECT_MC_STRAIN, mc_strain},          /* induced displacements (lagged or iterated forces) */
    {DEM_EFFECT_MDR, stage_mdr_surface},        /* MDR's mean surface displacements (mdr_particle.h) */
    {0, stage_contacts},                        /* pairs once, [the walls' sums,] per-particle sums with the walls */
    {DEM_EFFECT_SPRINGS, stage_springs},        /* spring forces into the contribution channel (springs.h) */
    {DEM_EFFECT_PRESSURE, stage_pressure},      /* triangle loads into it (pressure.h) */
    {DEM_EFFECT_BENDING, stage_bending},        /* hinge forces into it (bending.h) */
    {DEM_EFFECT_CHANNEL, stage_gather},         /* each particle's records added in order */
    {DEM_EFFECT_PATCHES, stage_patches},        /* spheres on patches, then the vertices' sums (patch_contacts.h) */
};

static int forces(dem_sim *s)
{
    for (size_t k = 0; k < sizeof force_stages / sizeof force_stages[0]; k++)
        if (!force_stages[k].gate || (s->effects & force_stages[k].gate)) {
            int e = force_stages[k].run(s), gate = (int)force_stages[k].gate;
            if (!e && gate) /* split over ranks: the ghosts' values their owners' */
                e = halo(s, SIM_HOOK_STAGE, &gate);
            if (e)
                return e;
        }
    return 0;
}

int dem_start(dem_sim *s, const dem_config *c)
{
    if (s->split_ops) /* a run split over MPI ranks (dem_create_mpi): the split's start, collective */
        return s->split_ops->start(s, c);
    int e = sim_start_deferred(s, c);
    return e ? e : sim_start_forces(s);
}

int sim_start_deferred(dem_sim *s, const dem_config *c)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    s->cfg = *c;
    int e = sim_validate(s);
    if (e || (e = sim_pack(s)))
        return e;
    if (c->backend == DEM_BACKEND_REFERENCE)
        s->ops = c->precision == DEM_FP64 ? &dem_reference_ops_f64 : &dem_reference_ops_f32;
    else if (c->backend == DEM_BACKEND_OPENCL)
        s->ops = &dem_opencl_ops;
    else
        return sim_fail(s, DEM_ERR_ARG, "unknown backend %d", (int)c->backend);
    char err[4096];
    if (s->ops->create(&s->be, &s->setup, err, sizeof err)) {
        s->be = NULL;
        return sim_fail(s, DEM_ERR_DEVICE, "%s", err);
    }
    s->run.started = 1;
    if (dem_stage_reset_flags(s->ops, s->be))
        return sim_be_fail(s);
    s->run.force_step = s->run.step;
    s->run.wall_sums_due = 1;
    s->motion.servo_walls = sim_has_servo(s);
    if ((e = sim_rebuild(s)))
        return e;
    s->run.forces_due = 1;
    return 0;
}

int sim_start_forces(dem_sim *s)
{
    if (!s->run.started || !s->run.forces_due)
        return sim_fail(s, DEM_ERR_STATE, "sim_start_forces: after sim_start_deferred, once");
    s->run.forces_due = 0;
    s->run.halo_agreed = s->run.halo_learned = 0;
    int e = forces(s);
    if (!s->halo_hook)
        return e;
    if (e && !s->run.halo_agreed) { /* as a step's failure (sim_step_once): the other ranks meet it */
        int v = e;
        s->halo_hook(s, s->halo_ctx, SIM_HOOK_FAILED, &v);
        return e;
    }
    return e ? e : halo(s, SIM_HOOK_STEP_END, NULL);
}

int dem_step(dem_sim *s, long nsteps)
{
    if (s->split_started)
        return s->split_ops->step(s, nsteps, NULL, NULL);
    if (!s->run.started)
        return sim_need_started(s);
    for (long k = 0; k < nsteps; k++) {
        int e = sim_step_once(s, k == nsteps - 1, -1);
        if (e)
            return e;
    }
    return 0;
}

static int step_body(dem_sim *s, int wall_sums, int sample_row);

/* One step; in a part of a split run (halo_hook), with the ranks' meetings: a failure of this rank's own is told to
 * the others at their next meeting, and the step ends with one, so that no rank goes on when another has failed */
int sim_step_once(dem_sim *s, int wall_sums, int sample_row)
{
    if (s->run.forces_due)
        return sim_fail(s, DEM_ERR_STATE, "sim_start_forces first");
    s->run.halo_agreed = s->run.halo_learned = 0;
    int e = step_body(s, wall_sums, sample_row);
    if (!s->halo_hook)
        return e;
    if (e && !s->run.halo_agreed) {
        int v = e;
        s->halo_hook(s, s->halo_ctx, SIM_HOOK_FAILED, &v);
        return e;
    }
    return e ? e : halo(s, SIM_HOOK_STEP_END, NULL);
}

static int step_body(dem_sim *s, int wall_sums, int sample_row)
{
    int flags[FLAG_COUNT], e;
    dem_core *c = DEM_CORE(s->be);
    c->ntrace = 0;
    s->trace.rebuild_at = s->trace.rebuild_len = 0;
    dem_kernel_id first = s->run.kick_pending ? K_integrate_kick_kick_drift : K_integrate_kick_drift;
    if (dem_stage_reset_flags(s->ops, s->be) || dem_launch(s->ops, s->be, first))
        return sim_be_fail(s); /* a kick still pending stays so: a step tried again still carries it */
    s->run.kick_pending = 0;
    if ((s->effects & DEM_EFFECT_MDR) && dem_launch(s->ops, s->be, K_mdr_begin)) /* MDR's radii: before the rebuild
                                                                                   test (mdr_particle.h) */
        return sim_be_fail(s);
    /* walls move with the particles' drift: positions at t + dt, velocity of this step */
    if (s->nwalls && (e = sim_walls_move(s)))
        return e;
    if (sim_read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if (flags[FLAG_MDR_CAPPED] != DEM_NO_PARTICLE && s->report.mdr_capped_step < 0) { /* before a rebuild reorders */
        long id = sim_api(s, flags[FLAG_MDR_CAPPED]);
        s->report.mdr_capped_step = s->run.step + 1;
        s->report.mdr_capped_particle = s->said_ids ? (long)s->said_ids[id] : id; /* a split run's part: the run's id */
    }
    if ((flags[FLAG_REBUILD] || sim_skin_probe_due(s)) && (e = sim_rebuild(s)))
        return e;
    s->run.force_step = s->run.step + 1; /* the drifted positions are those of t + dt */
    s->run.wall_sums_due = wall_sums || s->motion.servo_walls;
    s->run.sample_row = sample_row;
    /* One pass over the rows (dem_config.one_pass) where nothing reads this step's pair records: not the last step
     * of a call (the getters and output read them after it), not a sampled step (its energies are summed from
     * them), not a part of a split run (its every step is the last of a call) - the steps whose second kick is left
     * pending below. A servo's walls' sums every step read no record and stay. */
    s->run.one_pass = (s->setup.effects & DEM_ONE_PASS) && !wall_sums && sample_row < 0 && !s->halo_hook &&
                      !s->said_ids;
    if (sample_row >= 0 && dem_stage_series_arm(s->ops, s->be, 1, sample_row))
        return sim_be_fail(s);
    e = forces(s);
    s->run.one_pass = 0; /* dem_start's forces and a failed step's retry take the two passes */
    if (e) {
        s->run.sample_row = -1; /* a later step is not sampled into this row */
        dem_stage_series_arm(s->ops, s->be, 0, 0);
        return e;
    }
    /* The second kick. Where nothing reads the velocities before the next step's first kick - a step that is not the
     * last of its call (wall_sums: dem_step, dem_step_sampled; a host-sampled step is one) and not sampled on the
     * device, in a run that is not a rank's part of a split run (whose halo exchanges read them; its parts step one
     * step a call anyway) - it is left to that kick's launch (integrate_kick_kick_drift: the same bits, one pass
     * over the particles fewer). */
    if (!wall_sums && sample_row < 0 && !s->halo_hook && !s->said_ids)
        s->run.kick_pending = 1;
    else if (dem_launch(s->ops, s->be, K_integrate_kick) ||
             (sample_row >= 0 && dem_stage_series_arm(s->ops, s->be, 0, 0)))
        return sim_be_fail(s);
    s->run.sample_row = -1;
    s->trace.nstep = sim_copy_trace(c, 0, s->trace.rebuild_len ? s->trace.rebuild_at : c->ntrace, s->trace.step, 0);
    if (s->trace.rebuild_len)
        s->trace.nstep = sim_copy_trace(c, s->trace.rebuild_at + s->trace.rebuild_len, c->ntrace, s->trace.step, s->trace.nstep);
    s->run.step++;
    return 0;
}

long dem_step_index(const dem_sim *s) { return s->split_started ? s->split_ops->step_index(s) : s->run.step; }
double dem_time(const dem_sim *s) { return (double)dem_step_index(s) * s->dt; }
