/* walls.c - the walls: added (planes, cylinders, boxes) with their motion stages; where each is, and the force it
 * received; the punch-and-die relative density; and, each step, the stage each wall is in (until_* ends), the
 * servos' velocities, and the walls' positions after the drift (sim_walls_move). */
#include "sim.h"
#include "exact_sum.h"
#include "dem_layout.h"
#include <math.h>
#include <string.h>
#include <stdlib.h>

static int check_stages(dem_sim *s, int wall, dem_wall_kind kind, int nstages, const dem_stage *stages)
{
    if (nstages < 0 || nstages > DEM_MAX_STAGES)
        return sim_fail(s, DEM_ERR_ARG, "wall %d: 0..%d motion stages (got %d)", wall, DEM_MAX_STAGES, nstages);
    for (int st = 0; st < nstages; st++) {
        const dem_stage *g = &stages[st];
        if (!(g->duration >= 0) || !sim_finite3(g->velocity))
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: duration >= 0 s and finite velocity", wall, st);
        if (!(g->force >= 0) || !isfinite(g->force))
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: a servo force must be >= 0 N and finite", wall, st);
        if (g->force > 0 && (kind != DEM_WALL_PLANE || !(g->gain > 0) || !isfinite(g->gain) ||
                             !(g->max_speed > 0) || !isfinite(g->max_speed)))
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: a servo stage needs a plane wall, gain > 0 m/(s N) and "
                            "max_speed > 0 m/s (got gain %g, max_speed %g)", wall, st, g->gain, g->max_speed);
        if (!(g->until_force >= 0) || !isfinite(g->until_force) || !(g->until_distance >= 0) ||
            !isfinite(g->until_distance))
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: until_force and until_distance must be >= 0 and finite "
                            "(got %g N, %g m)", wall, st, g->until_force, g->until_distance);
        if (g->until_force > 0 && kind != DEM_WALL_PLANE)
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: until_force needs a plane wall (the force along its "
                            "normal)", wall, st);
        if (!(g->until_density >= 0 && g->until_density <= 1))
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: until_density is a relative density in [0, 1] (got %g)",
                            wall, st, g->until_density);
        if (g->until_density > 0 && kind != DEM_WALL_PLANE)
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: until_density needs a plane wall (a punch)", wall, st);
        if (!(g->ramp >= 0) || !(g->ramp <= g->duration) || (g->ramp > 0 && g->force > 0))
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: a ramp is >= 0 s, at most the stage's duration (%g s), "
                            "and not on a servo stage (got %g s)", wall, st, g->duration, g->ramp);
        if (g->after_wall < 0 || g->after_wall >= DEM_MAX_WALLS || g->after_stage < 0 ||
            g->after_stage > DEM_MAX_STAGES)
            return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d: it waits for wall %d's stage %d, which cannot exist",
                            wall, st, g->after_wall, g->after_stage);
    }
    return 0;
}

double dem_stage_travel(const dem_stage *stages, int st, const double u[3])
{
    double nu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const dem_stage *g = &stages[st], *p = st > 0 && !(stages[st - 1].force > 0) ? &stages[st - 1] : NULL;
    if (g->force > 0 || !(nu > 0))
        return 0;
    double v = (g->velocity[0] * u[0] + g->velocity[1] * u[1] + g->velocity[2] * u[2]) / nu;
    double vp = p ? (p->velocity[0] * u[0] + p->velocity[1] * u[1] + p->velocity[2] * u[2]) / nu : 0;
    return v * g->duration - g->ramp * (v - vp) / 2;
}

int dem_add_wall(dem_sim *s, const dem_wall *w)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    int k = s->nwalls;
    if (k >= DEM_MAX_WALLS)
        return sim_fail(s, DEM_ERR_ARG, "too many walls (at most %d)", DEM_MAX_WALLS);
    if (w->kind != DEM_WALL_PLANE && w->kind != DEM_WALL_CYLINDER)
        return sim_fail(s, DEM_ERR_ARG, "wall %d: unknown kind %d", k, (int)w->kind);
    if (w->material < 0 || w->material >= s->nmat)
        return sim_fail(s, DEM_ERR_ARG, "wall %d: unknown material %d", k, w->material);
    double len = sqrt(w->normal[0] * w->normal[0] + w->normal[1] * w->normal[1] + w->normal[2] * w->normal[2]);
    if (!(len > 0) || !isfinite(len) || !sim_finite3(w->point))
        return sim_fail(s, DEM_ERR_ARG, "wall %d: point must be finite and normal/axis non-zero", k);
    if (w->kind == DEM_WALL_CYLINDER && !(w->radius > 0 && isfinite(w->radius)))
        return sim_fail(s, DEM_ERR_ARG, "wall %d: cylinder radius must be > 0 m (got %g)", k, w->radius);
    if (w->kind == DEM_WALL_CYLINDER && !(w->height >= 0 && isfinite(w->height)))
        return sim_fail(s, DEM_ERR_ARG, "wall %d: cylinder height must be >= 0 m (0: endless; got %g)", k, w->height);
    int flat = w->cup_radius == 0 && w->cup_depth == 0;
    if (!flat && (w->kind != DEM_WALL_PLANE || !(w->cup_depth >= 1e-3 * w->cup_radius) || !(w->cup_radius >= w->cup_depth) ||
                  !isfinite(w->cup_radius) || !(w->cup_depth > 0)))
        return sim_fail(s, DEM_ERR_ARG, "wall %d: a cup is a plane's, with radius / 1000 <= depth <= radius (at most a "
                        "hemisphere; a shallower one is a flat punch; got radius %g m, depth %g m)", k, w->cup_radius,
                        w->cup_depth);
    int e = check_stages(s, k, w->kind, w->nstages, w->stages);
    if (e)
        return e;
    s->walls[k] = *w;
    for (int d = 0; d < 3; d++)
        s->walls[k].normal[d] = w->normal[d] / len;
    return s->nwalls++;
}

int dem_add_box(dem_sim *s, const double lo[3], const double hi[3], int material)
{
    int first = -1;
    for (int k = 0; k < 6; k++) {
        int axis = k / 2, upper = k % 2;
        dem_wall w;
        memset(&w, 0, sizeof w);
        w.kind = DEM_WALL_PLANE;
        w.material = material;
        memcpy(w.point, lo, sizeof w.point);
        w.point[axis] = upper ? hi[axis] : lo[axis];
        w.normal[axis] = upper ? -1 : 1;
        int id = dem_add_wall(s, &w);
        if (id < 0)
            return id;
        if (k == 0)
            first = id;
    }
    return first;
}

int dem_set_wall_motion(dem_sim *s, int wall, int nstages, const dem_stage *stages)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (wall < 0 || wall >= s->nwalls)
        return sim_fail(s, DEM_ERR_ARG, "no wall %d", wall);
    int e = check_stages(s, wall, s->walls[wall].kind, nstages, stages);
    if (e)
        return e;
    s->walls[wall].nstages = nstages;
    memcpy(s->walls[wall].stages, stages, sizeof(dem_stage) * (size_t)nstages);
    return 0;
}

int dem_wall_count(const dem_sim *s) { return s->nwalls; }
int dem_wall_position(const dem_sim *s, int wall, double p[3])
{
    if (wall < 0 || wall >= s->nwalls)
        return DEM_ERR_ARG;
    if (s->split_started) /* a run split by dem_create_mpi: every rank's part moves the walls alike */
        return s->split_ops->part(s) ? dem_wall_position(s->split_ops->part(s), wall, p) : DEM_ERR_STATE;
    memcpy(p, s->run.started ? s->motion.pos[wall] : s->walls[wall].point, sizeof(double) * 3);
    return 0;
}

int dem_wall_get(const dem_sim *s, int wall, dem_wall *w)
{
    if (wall < 0 || wall >= s->nwalls)
        return DEM_ERR_ARG;
    *w = s->walls[wall];
    return 0;
}

int dem_wall_force(dem_sim *s, int wall, double f[3])
{
    if (wall < 0 || wall >= s->nwalls)
        return sim_fail(s, DEM_ERR_ARG, "no wall %d", wall);
    double all[3 * DEM_MAX_WALLS];
    int e = dem_get_field(s, DEM_FIELD_WALL_FORCE, all);
    if (!e)
        memcpy(f, all + 3 * wall, sizeof(double) * 3);
    return e;
}

/* Wall k's sums of the last step that made them (PARTIAL_MID is not saved: after dem_state_set, none until a step
 * makes them), before they are rounded: the merge of the tree's groups (common/wall_forces.h), acc[WP_FX..WP_FN],
 * over the particles the run holds but its ghosts (sim_set_ghosts). The ranks of a split run merge these and round
 * once (host/mpi/mpi_layer.h) to the bits one process would give. */
int sim_wall_sums_exact(dem_sim *s, int wall, exact_acc acc[WP_STRIDE])
{
    if (!s->run.started)
        return sim_need_started(s);
    if (wall < 0 || wall >= s->nwalls)
        return sim_fail(s, DEM_ERR_ARG, "no wall %d", wall);
    int e = 0, nmid = DEM_CORE(s->be)->nmid_red;
    unsigned *mid = sim_buffer_get(s, BUF_PARTIAL_MID, &e);
    for (int q = 0; q < WP_STRIDE; q++) /* as wall_reduce_final merges them */
        exact_sum_stored(&acc[q], mid + ((size_t)wall * nmid * WP_STRIDE + q) * EXACT_WORDS, e ? 0 : nmid,
                         WP_STRIDE * EXACT_WORDS);
    free(mid);
    return e;
}

int sim_wall_sums_set(dem_sim *s, const exact_acc *acc)
{
    if (!s->run.started)
        return sim_need_started(s);
    int nw = s->nwalls, rs = s->setup.real_size;
    unsigned char f[3 * DEM_MAX_WALLS * sizeof(double)], fn[DEM_MAX_WALLS * sizeof(double)];
    for (int k = 0; k < nw; k++)
        for (int q = 0; q < 4; q++) { /* WP_FX, WP_FY, WP_FZ into the force, WP_FN into the normal force */
            const exact_acc *a = &acc[WP_STRIDE * k + (q < 3 ? WP_FX + q : WP_FN)];
            unsigned char *to = q < 3 ? f + (size_t)(3 * k + q) * (size_t)rs : fn + (size_t)k * (size_t)rs;
            if (rs == 8) {
                double v = exact_to_double(a);
                memcpy(to, &v, 8);
            } else {
                float v = exact_to_float(a);
                memcpy(to, &v, 4);
            }
        }
    if (nw && (dem_stage_write_field(s->ops, s->be, DEM_FIELD_WALL_FORCE, f, (size_t)(3 * nw * rs)) ||
               dem_stage_write_field(s->ops, s->be, DEM_FIELD_WALL_NORMAL_FORCE, fn, (size_t)(nw * rs))))
        return sim_be_fail(s);
    return 0;
}

int dem_wall_normal_force(dem_sim *s, int wall, double *fn)
{
    if (wall < 0 || wall >= s->nwalls)
        return sim_fail(s, DEM_ERR_ARG, "no wall %d", wall);
    double all[DEM_MAX_WALLS];
    int e = dem_get_field(s, DEM_FIELD_WALL_NORMAL_FORCE, all);
    if (!e)
        *fn = all[wall];
    return e;
}

int dem_density_walls(const dem_sim *s, int wall, int *die, int *other)
{
    *die = *other = -1;
    if (wall < 0 || wall >= s->nwalls || s->walls[wall].kind != DEM_WALL_PLANE)
        return DEM_ERR_ARG;
    const dem_wall *w = &s->walls[wall];
    double best = INFINITY;
    for (int j = 0; j < s->nwalls; j++) {
        const dem_wall *o = &s->walls[j];
        double c = o->normal[0] * w->normal[0] + o->normal[1] * w->normal[1] + o->normal[2] * w->normal[2];
        double h = (o->point[0] - w->point[0]) * w->normal[0] + (o->point[1] - w->point[1]) * w->normal[1] +
                   (o->point[2] - w->point[2]) * w->normal[2];
        if (o->kind == DEM_WALL_CYLINDER && fabs(c) > 1 - 1e-9 && *die < 0)
            *die = j;
        if (j != wall && o->kind == DEM_WALL_PLANE && c < -(1 - 1e-9) && h > 0 && h < best)
            best = h, *other = j;
    }
    return *die >= 0 && *other >= 0 ? DEM_OK : DEM_ERR_ARG;
}

int dem_cup_in_bore(const dem_sim *s, int wall, int die)
{
    if (wall < 0 || wall >= s->nwalls || die < 0 || die >= s->nwalls)
        return DEM_ERR_ARG;
    const dem_wall *p = &s->walls[wall], *d = &s->walls[die];
    if (!(p->cup_depth > 0))
        return 1;
    double r[3], along = 0, off2 = 0;
    for (int k = 0; k < 3; k++)
        r[k] = p->point[k] - d->point[k], along += r[k] * d->normal[k];
    for (int k = 0; k < 3; k++)
        off2 += (r[k] - along * d->normal[k]) * (r[k] - along * d->normal[k]);
    return sqrt(off2) + p->cup_radius <= d->radius * (1 + 1e-12);
}

/* The volume of a punch's cup (a spherical cap of radius rp at the face and depth c): pi c (3 rp^2 + c^2) / 6 */
static double cup_volume(const dem_wall *w)
{
    return w->cup_depth > 0 ? M_PI * w->cup_depth * (3 * w->cup_radius * w->cup_radius + w->cup_depth * w->cup_depth) / 6
                            : 0;
}

/* The particles' volume vol over the space between punch k at a and the punch `other` facing it at b: die's bore
 * between their lands and their cups; INFINITY once the lands meet. */
static double bore_density(const dem_sim *s, int k, int other, int die, const double a[3], const double b[3],
                           double vol)
{
    const double *n = s->walls[k].normal;
    double h = (b[0] - a[0]) * n[0] + (b[1] - a[1]) * n[1] + (b[2] - a[2]) * n[2], R = s->walls[die].radius;
    return h > 0 ? vol / (M_PI * R * R * h + cup_volume(&s->walls[k]) + cup_volume(&s->walls[other])) : INFINITY;
}

/* The relative density seen by punch k in a run (dem_stage.until_density), from the volume sim_validate summed. */
double sim_relative_density(const dem_sim *s, int k)
{
    return bore_density(s, k, s->motion.density_other[k], s->motion.density_die[k], s->motion.pos[k],
                        s->motion.pos[s->motion.density_other[k]], s->motion.particle_volume);
}

double sim_particle_volume(const dem_sim *s)
{
    if (s->whole_volume > 0) /* a rank's part of a split run: the whole scene's (sim_part_copy) */
        return s->whole_volume;
    exact_acc sum; /* exact and rounded once: the same bits in any order or split of the spheres (exact_sum.h) */
    exact_clear(&sum);
    for (int i = 0; i < s->n; i++)
        exact_add_double(&sum, 4.0 / 3.0 * M_PI * s->radius[i] * s->radius[i] * s->radius[i]);
    return exact_to_double(&sum);
}

int dem_relative_density(const dem_sim *s, int wall, double *rho)
{
    int die, other, e = dem_density_walls(s, wall, &die, &other);
    if (e)
        return e;
    if (dem_cup_in_bore(s, wall, die) != 1 || dem_cup_in_bore(s, other, die) != 1)
        return DEM_ERR_ARG; /* the cup's volume would not be the bore's */
    double a[3], b[3], vol = sim_particle_volume(s);
    dem_wall_position(s, wall, a);
    dem_wall_position(s, other, b);
    *rho = bore_density(s, wall, other, die, a, b, vol);
    return DEM_OK;
}

/* Each wall's stage for the step about to be taken: the next one once the current one has run its duration, or once
 * its end condition held after the step before (dem_stage.until_force, until_distance, until_density); a stage of
 * no steps is passed at once. Decided on the host from the device's wall force and the host's positions: the same
 * step on every backend. */
/* The normal force the particles exerted on plane wall k in the step before (pushing it back along -normal counts
 * positive), from one read of the device's wall forces per step, shared by the stage ends and the servos below. */
typedef struct {
    double f[3 * DEM_MAX_WALLS];
    int read;
} wall_read;

static int wall_normal_before(dem_sim *s, wall_read *wr, int k, double *fn)
{
    if (!wr->read && dem_get_field(s, DEM_FIELD_WALL_FORCE, wr->f))
        return DEM_ERR_DEVICE;
    wr->read = 1;
    const double *n = s->walls[k].normal, *f = wr->f + 3 * k;
    *fn = -(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]);
    return 0;
}

static int stages_advance(dem_sim *s, wall_read *wr)
{
    /* the stages as the last step left them: a stage that waits for another wall (dem_stage.after_wall) sees the same
     * stage of that wall whatever the walls' order */
    int cur[DEM_MAX_WALLS];
    memcpy(cur, s->motion.stage_cur, sizeof(int) * (size_t)s->nwalls);
    for (int k = 0; k < s->nwalls; k++) {
        const dem_wall *w = &s->walls[k];
        while (s->motion.stage_cur[k] < w->nstages) {
            const dem_stage *g = &w->stages[s->motion.stage_cur[k]];
            if (cur[g->after_wall] < g->after_stage) { /* it waits, at rest, and begins when the other wall is there */
                s->motion.stage_first[k] = s->run.step;
                memcpy(s->motion.stage_from[k], s->motion.pos[k], sizeof(double) * 3);
                break;
            }
            long ran = s->run.step - s->motion.stage_first[k];
            int done = ran >= s->motion.stage_steps[k][s->motion.stage_cur[k]];
            int why = DEM_STAGE_END_DURATION;
            double value = 0;
            if (!done && ran > 0 && g->until_distance > 0) {
                const double *p = s->motion.pos[k], *p0 = s->motion.stage_from[k];
                double d = sqrt((p[0] - p0[0]) * (p[0] - p0[0]) + (p[1] - p0[1]) * (p[1] - p0[1]) +
                                (p[2] - p0[2]) * (p[2] - p0[2]));
                done = d >= g->until_distance;
                why = DEM_STAGE_END_DISTANCE, value = d;
            }
            if (!done && ran > 0 && g->until_density > 0) {
                value = sim_relative_density(s, k);
                done = value >= g->until_density;
                why = DEM_STAGE_END_DENSITY;
            }
            if (!done && ran > 0 && g->until_force > 0) { /* the force the particles exerted in the step before */
                double fn;
                if (wall_normal_before(s, wr, k, &fn))
                    return DEM_ERR_DEVICE;
                done = fn >= g->until_force;
                why = DEM_STAGE_END_FORCE, value = fn;
            }
            if (!done)
                break;
            /* the log of stage ends (dem_stage_ends): what the host decided, kept for the caller to report */
            s->motion.stage_log[s->motion.stage_log_n++ % DEM_STAGE_LOG] =
                (dem_stage_end){k, s->motion.stage_cur[k], ran >= s->motion.stage_steps[k][s->motion.stage_cur[k]]
                                ? DEM_STAGE_END_DURATION : why, s->run.step, value};
            s->motion.stage_cur[k]++;
            s->motion.stage_first[k] = s->run.step;
            memcpy(s->motion.stage_from[k], s->motion.pos[k], sizeof(double) * 3);
        }
    }
    return 0;
}

/* Servo stages: each such wall's velocity for this step from the force it received in the last (dem_stage), and
 * the record of how the stage goes (dem_servo_stats) */
static int servo_update(dem_sim *s, wall_read *wr)
{
    for (int k = 0; k < s->nwalls; k++) {
        long first;
        int st = sim_stage_now(s, k, &first);
        const dem_stage *g = st >= 0 ? &s->walls[k].stages[st] : NULL;
        if (!g || !(g->force > 0))
            continue;
        double fn;
        if (wall_normal_before(s, wr, k, &fn))
            return DEM_ERR_DEVICE;
        const double *n = s->walls[k].normal;
        double err = g->force - fn;
        double u = g->gain * err;
        u = u > g->max_speed ? g->max_speed : u < -g->max_speed ? -g->max_speed : u;
        for (int d = 0; d < 3; d++)
            s->motion.servo_v[k][d] = u * n[d];
        dem_servo_stats *r = &s->motion.servo[k];
        if (r->stage != st || r->steps == 0) /* a new stage, or the first step this process runs */
            *r = (dem_servo_stats){st, g->force, 0, 0, NAN, 0}, s->motion.servo_err[k] = s->motion.servo_sum[k] = 0;
        double big = 0.1 * g->force, prev = s->motion.servo_err[k];
        r->chatter += (prev > big && err < -big) || (prev < -big && err > big);
        s->motion.servo_err[k] = err;
        long len = s->motion.stage_steps[k][st];
        if (s->run.step - first >= len - len / 10) /* its last tenth: the force it holds */
            s->motion.servo_sum[k] += fn, r->tail++;
        r->steps++;
    }
    return 0;
}

int dem_servo_stats_get(const dem_sim *s, int wall, dem_servo_stats *st)
{
    if (wall < 0 || wall >= s->nwalls)
        return sim_fail((dem_sim *)s, DEM_ERR_ARG, "wall %d: no such wall (%d)", wall, s->nwalls);
    s = sim_stepped(s); /* a split run's: every rank's part steers its walls alike */
    *st = s->motion.servo[wall];
    if (!st->steps)
        st->stage = -1;
    if (st->tail)
        st->held = s->motion.servo_sum[wall] / (double)st->tail;
    return 0;
}

/* The walls' part of a step (sim_step_once, after the particles' drift): each wall's stage and, under a servo, its
 * velocity; then its position at t + dt, the table the kernels get, and the riders on the walls. */
int sim_walls_move(dem_sim *s)
{
    int e;
    wall_read wr = {.read = 0};
    if ((e = stages_advance(s, &wr)) || (e = servo_update(s, &wr)))
        return e;
    for (int w = 0; w < s->nwalls; w++) {
        double v[3];
        sim_wall_velocity(s, w, v);
        for (int d = 0; d < 3; d++)
            s->motion.pos[w][d] += v[d] * s->dt;
    }
    sim_pack_walls(s);
    if (dem_stage_set_walls(s->ops, s->be, s->motion.table) || (s->mesh.natt && dem_launch(s->ops, s->be, K_rider_place)))
        return sim_be_fail(s);
    return 0;
}
