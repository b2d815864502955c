/* sim.c - the driver: builds a simulation, starts a backend and steps it. Every decision (when to rebuild the
 * neighbour rows, how large they are, where the walls are) is taken here, the same way for every backend. */
#include "sim.h"
#include "dem_layout.h"
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

dem_sim *dem_create(void)
{
    dem_sim *s = calloc(1, sizeof(dem_sim));
    if (s) {
        s->effects = DEM_EFFECT_CLASSICAL;
        s->mcs_conv = DEM_MCS_DEFAULT;
        s->mc_tol = 1e-6;
        s->mc_reach = 1;
        s->sample_row = -1; /* no step is sampled until dem_step_sampled says so */
        s->mc.first_capped = s->mc.last_capped = -1;
        s->err_particle = -1;
    }
    return s;
}

void dem_destroy(dem_sim *s)
{
    if (!s)
        return;
    if (s->be)
        s->ops->destroy(s->be);
    sim_setup_free(s);
    free(s->setup_mem);
    free(s->wall_real);
    free(s->scratch);
    free(s->x);
    free(s->v);
    free(s->w);
    free(s->radius);
    free(s->mat);
    free(s->pflags);
    free(s->body);
    free(s->source);
    free(s->spring_ij);
    free(s->spring_kr);
    free(s->tri);
    free(s->patch);
    free(s->hinge);
    free(s->att);
    free(s->hinge_k);
    free(s);
}

const char *dem_error(const dem_sim *s) { return s ? s->err : "no simulation (out of memory?)"; }
int dem_error_particle(const dem_sim *s) { return s ? s->err_particle : -1; }

void dem_config_default(dem_config *c)
{
    memset(c, 0, sizeof *c);
    c->backend = DEM_BACKEND_OPENCL;
    c->precision = DEM_FP64;
    c->local_size = 128; /* PoCL's own choice (groups of n/31) ran contact_forces 1.5-2x slower at n = 1e5 */
    const char *dev = getenv("DEM_DEVICE"); /* lets the demo and the tests run on another device unchanged */
    if (dev && *dev) { /* a whole index in 0..65535; anything else is device -1, which dem_start refuses by name */
        char *end;
        errno = 0;
        long v = strtol(dev, &end, 10);
        c->device = (*dev < '0' || *dev > '9' || *end || errno || v > 65535) ? -1 : (int)v;
    }
}

static int not_started(dem_sim *s)
{
    return s->started ? sim_fail(s, DEM_ERR_STATE, "the simulation has started: the set-up is fixed") : 0;
}

int dem_add_material(dem_sim *s, const dem_material *m)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (s->nmat >= (int)(sizeof s->mats / sizeof s->mats[0]))
        return sim_fail(s, DEM_ERR_ARG, "too many materials (at most 64)");
    /* young = +inf: a rigid material, for walls only (E* and G* of a contact then come from the particle alone,
     * exactly: (1 - nu^2) / inf = 0); its density is never used and may be 0 */
    int rigid = m->young == INFINITY;
    if (!rigid && (!(m->density > 0) || !isfinite(m->density)))
        return sim_fail(s, DEM_ERR_ARG, "material %d: density must be > 0 kg/m^3 (got %g)", s->nmat, m->density);
    if (!(m->young > 0) || !(isfinite(m->young) || rigid))
        return sim_fail(s, DEM_ERR_ARG, "material %d: Young's modulus must be > 0 Pa, or infinite for a rigid wall "
                        "material (got %g)", s->nmat, m->young);
    if (!(m->poisson > -1 && m->poisson <= 0.5))
        return sim_fail(s, DEM_ERR_ARG, "material %d: Poisson's ratio must be in (-1, 0.5] (got %g)", s->nmat,
                        m->poisson);
    if (!(m->restitution > 0 && m->restitution <= 1))
        return sim_fail(s, DEM_ERR_ARG, "material %d: restitution must be in (0, 1] (got %g)", s->nmat,
                        m->restitution);
    if (!(m->friction >= 0) || !isfinite(m->friction))
        return sim_fail(s, DEM_ERR_ARG, "material %d: friction must be >= 0 (got %g)", s->nmat, m->friction);
    if (!(m->mc_beta >= 0) || !isfinite(m->mc_beta) || !(m->mc_gamma >= 0) || !isfinite(m->mc_gamma))
        return sim_fail(s, DEM_ERR_ARG, "material %d: multi-contact prefactors beta and gamma must be >= 0 (got %g, %g)",
                        s->nmat, m->mc_beta, m->mc_gamma);
    s->mats[s->nmat] = *m;
    return s->nmat++;
}

static int finite3(const double *a) { return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]); }

int dem_add_particle(dem_sim *s, const double x[3], const double v[3], double radius, int material)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (!(radius > 0) || !isfinite(radius))
        return sim_fail(s, DEM_ERR_ARG, "particle %d: radius must be > 0 m (got %g)", s->n, radius);
    if (material < 0 || material >= s->nmat)
        return sim_fail(s, DEM_ERR_ARG, "particle %d: unknown material %d", s->n, material);
    if (s->mats[material].young == INFINITY)
        return sim_fail(s, DEM_ERR_ARG, "particle %d: material %d is rigid (Young's modulus infinite): for walls only",
                        s->n, material);
    if (!finite3(x) || (v && !finite3(v)))
        return sim_fail(s, DEM_ERR_ARG, "particle %d: position and velocity must be finite", s->n);
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 1024;
        double *nx = realloc(s->x, sizeof(double) * 3 * cap);
        if (nx) s->x = nx;
        double *nv = realloc(s->v, sizeof(double) * 3 * cap);
        if (nv) s->v = nv;
        double *nw = realloc(s->w, sizeof(double) * 3 * cap);
        if (nw) s->w = nw;
        double *nr = realloc(s->radius, sizeof(double) * cap);
        if (nr) s->radius = nr;
        int *nm = realloc(s->mat, sizeof(int) * cap);
        if (nm) s->mat = nm;
        unsigned *nf = realloc(s->pflags, sizeof(unsigned) * cap);
        if (nf) s->pflags = nf;
        double *nb = realloc(s->body, sizeof(double) * 2 * cap);
        if (nb) s->body = nb;
        if (!nx || !nv || !nw || !nr || !nm || !nf || !nb)
            return sim_fail(s, DEM_ERR_NOMEM, "out of host memory at %d particles", s->n);
        s->cap = cap;
    }
    int i = s->n++;
    for (int d = 0; d < 3; d++) {
        s->x[3 * i + d] = x[d];
        s->v[3 * i + d] = v ? v[d] : 0;
        s->w[3 * i + d] = 0;
    }
    s->radius[i] = radius;
    s->mat[i] = material;
    s->pflags[i] = 0;
    s->body[2 * i] = s->body[2 * i + 1] = 0; /* mass and inertia from the material's density and the radius */
    return i;
}

int dem_set_particle_mass(dem_sim *s, int id, double mass, double inertia)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (id < 0 || id >= s->n)
        return sim_fail(s, DEM_ERR_ARG, "no particle %d", id);
    if (!(mass > 0) || !isfinite(mass) || !(inertia >= 0) || !isfinite(inertia) ||
        !isnormal(1 / mass) || (inertia > 0 && !isnormal(1 / inertia)))
        return sim_fail(s, DEM_ERR_ARG, "particle %d: mass must be > 0 kg and inertia >= 0 kg m^2, both with a finite "
                        "normal inverse (got %g, %g)", id, mass, inertia);
    s->body[2 * id] = mass;
    s->body[2 * id + 1] = inertia;
    return 0;
}

/* Room for one more row of a table of `count` rows (ni ints and nr doubles each; reals may be NULL), doubling its
 * capacity; 0, or DEM_ERR_NOMEM with the table's name. */
int sim_grow(dem_sim *s, int count, int *cap, int **ints, int ni, double **reals, int nr, const char *what)
{
    if (count < *cap)
        return 0;
    int c = *cap ? 2 * *cap : 256;
    int *a = realloc(*ints, sizeof(int) * (size_t)ni * (size_t)c);
    if (a)
        *ints = a;
    double *r = reals ? realloc(*reals, sizeof(double) * (size_t)nr * (size_t)c) : NULL;
    if (r)
        *reals = r;
    if (!a || (reals && !r))
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory at %d %s", count, what);
    *cap = c;
    return 0;
}

void *sim_buffer_get(dem_sim *s, int id, int *e)
{
    size_t bytes = DEM_CORE(s->be)->bytes[id];
    void *p = malloc(bytes ? bytes : 1);
    if (!p) {
        if (!*e)
            *e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
        return NULL;
    }
    if (!*e && bytes && s->ops->read(s->be, (dem_bufref){TABLE_ONE, id}, 0, p, bytes, 1))
        *e = sim_fail(s, DEM_ERR_DEVICE, "%s", DEM_CORE(s->be)->err);
    return p;
}

int dem_add_spring(dem_sim *s, int i, int j, double k, double rest, double gamma)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (i < 0 || i >= s->n || j < 0 || j >= s->n || i == j)
        return sim_fail(s, DEM_ERR_ARG, "spring %d: particles %d and %d (two different particles of 0..%d)",
                        s->nsprings, i, j, s->n - 1);
    if (!(k > 0) || !isfinite(k) || !isfinite(rest) || !(gamma >= 0) || !isfinite(gamma))
        return sim_fail(s, DEM_ERR_ARG, "spring %d: k must be > 0 N/m, rest finite, gamma >= 0 (got %g, %g, %g)",
                        s->nsprings, k, rest, gamma);
    if (sim_grow(s, s->nsprings, &s->spring_cap, &s->spring_ij, 2, &s->spring_kr, 3, "springs"))
        return DEM_ERR_NOMEM;
    int id = s->nsprings++;
    s->spring_ij[2 * id] = i, s->spring_ij[2 * id + 1] = j;
    s->spring_kr[3 * id] = k, s->spring_kr[3 * id + 1] = rest, s->spring_kr[3 * id + 2] = gamma;
    s->effects |= DEM_EFFECT_SPRINGS;
    return id;
}

int dem_spring_count(const dem_sim *s) { return s->nsprings; }

int dem_add_triangle(dem_sim *s, int a, int b, int c)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (a < 0 || a >= s->n || b < 0 || b >= s->n || c < 0 || c >= s->n || a == b || b == c || a == c)
        return sim_fail(s, DEM_ERR_ARG, "triangle %d: particles %d, %d, %d (three different particles of 0..%d)",
                        s->ntri, a, b, c, s->n - 1);
    if (sim_grow(s, s->ntri, &s->tri_cap, &s->tri, 3, NULL, 0, "triangles"))
        return DEM_ERR_NOMEM;
    int id = s->ntri++;
    s->tri[3 * id] = a, s->tri[3 * id + 1] = b, s->tri[3 * id + 2] = c;
    return id;
}

int dem_triangle_count(const dem_sim *s) { return s->ntri; }
void dem_triangles_get(const dem_sim *s, int *tri) { memcpy(tri, s->tri, sizeof(int) * 3 * (size_t)s->ntri); }

int dem_add_patches(dem_sim *s, int first, int count)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (first < 0 || count < 1 || first > s->ntri - count)
        return sim_fail(s, DEM_ERR_ARG, "patches: triangles %d..%d (of 0..%d)", first, first + count - 1, s->ntri - 1);
    for (int k = 0; k < s->npatch; k++)
        if (s->patch[k] >= first && s->patch[k] < first + count)
            return sim_fail(s, DEM_ERR_ARG, "patches: triangle %d is a patch already", s->patch[k]);
    for (int t = first; t < first + count; t++) {
        if (sim_grow(s, s->npatch, &s->patch_cap, &s->patch, 1, NULL, 0, "patches"))
            return DEM_ERR_NOMEM;
        s->patch[s->npatch++] = t;
    }
    s->effects |= DEM_EFFECT_PATCHES;
    return 0;
}

int dem_add_hinge(dem_sim *s, int p1, int p2, int p3, int p4, double kel, double kdiss, double theta0)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    int p[4] = {p1, p2, p3, p4};
    for (int a = 0; a < 4; a++) {
        if (p[a] < 0 || p[a] >= s->n)
            return sim_fail(s, DEM_ERR_ARG, "hinge %d: no particle %d", s->nhinges, p[a]);
        for (int b = 0; b < a; b++)
            if (p[a] == p[b])
                return sim_fail(s, DEM_ERR_ARG, "hinge %d: particle %d twice", s->nhinges, p[a]);
    }
    if (!(kel >= 0) || !isfinite(kel) || !(kdiss >= 0) || !isfinite(kdiss) || isinf(theta0))
        return sim_fail(s, DEM_ERR_ARG, "hinge %d: kel and kdiss must be >= 0, theta0 finite or NAN (got %g, %g, %g)",
                        s->nhinges, kel, kdiss, theta0);
    if (sim_grow(s, s->nhinges, &s->hinge_cap, &s->hinge, 4, &s->hinge_k, 3, "hinges"))
        return DEM_ERR_NOMEM;
    int id = s->nhinges++;
    memcpy(s->hinge + 4 * id, p, sizeof p);
    s->hinge_k[3 * id] = kel, s->hinge_k[3 * id + 1] = kdiss, s->hinge_k[3 * id + 2] = theta0;
    s->effects |= DEM_EFFECT_BENDING;
    return id;
}

int dem_hinge_count(const dem_sim *s) { return s->nhinges; }

int dem_set_pressure_stages(dem_sim *s, int nstages, const dem_pressure_stage *st)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (nstages < 0 || nstages > DEM_MAX_STAGES || (nstages > 0 && !st))
        return sim_fail(s, DEM_ERR_ARG, "pressure stages: 0 to %d stages (got %d)", DEM_MAX_STAGES, nstages);
    for (int k = 0; k < nstages; k++)
        if (!(st[k].duration >= 0) || !isfinite(st[k].duration) || !isfinite(st[k].pressure))
            return sim_fail(s, DEM_ERR_ARG, "pressure stage %d: duration must be >= 0 and finite, pressure finite (got "
                            "%g s, %g Pa)", k, st[k].duration, st[k].pressure);
    memcpy(s->pstages, st, sizeof *st * (size_t)nstages);
    s->npstages = nstages;
    s->effects |= DEM_EFFECT_PRESSURE;
    return 0;
}

/* The scheduled pressure at time t [s] (dem_set_pressure_stages) */
static double pressure_at(const dem_sim *s, double t)
{
    double from = s->pressure, t0 = 0;
    for (int k = 0; k < s->npstages; k++) {
        const dem_pressure_stage *g = &s->pstages[k];
        if (t < t0 + g->duration)
            return from + (g->pressure - from) * ((t - t0) / g->duration);
        from = g->pressure, t0 += g->duration;
    }
    return from;
}

double dem_pressure(const dem_sim *s) { return s->started ? s->pressure_now : 0; }

int dem_set_pressure(dem_sim *s, double sigma)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (!isfinite(sigma))
        return sim_fail(s, DEM_ERR_ARG, "pressure must be finite (got %g Pa)", sigma);
    s->pressure = sigma;
    s->effects |= DEM_EFFECT_PRESSURE;
    return 0;
}

double sim_mass(const dem_sim *s, int i)
{
    double r = s->radius[i];
    return s->body[2 * i] > 0 ? s->body[2 * i] : s->mats[s->mat[i]].density * 4.0 / 3.0 * M_PI * r * r * r;
}

double sim_inertia(const dem_sim *s, int i)
{
    double r = s->radius[i];
    return s->body[2 * i + 1] > 0 ? s->body[2 * i + 1] : 0.4 * sim_mass(s, i) * r * r;
}

int dem_set_particle_flags(dem_sim *s, int id, unsigned flags)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (id < 0 || id >= s->n)
        return sim_fail(s, DEM_ERR_ARG, "no particle %d", id);
    s->pflags[id] = flags;
    if (flags & DEM_PARTICLE_HOLD_V)
        s->effects |= DEM_EFFECT_CONSTRAINTS;
    return 0;
}

int dem_set_particle_omega(dem_sim *s, int id, const double w[3])
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (id < 0 || id >= s->n || !finite3(w))
        return sim_fail(s, DEM_ERR_ARG, "particle %d: no such particle or non-finite angular velocity", id);
    memcpy(s->w + 3 * id, w, sizeof(double) * 3);
    return 0;
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
    return bore_density(s, k, s->density_other[k], s->density_die[k], s->wall_pos[k],
                        s->wall_pos[s->density_other[k]], s->particle_volume);
}

int dem_relative_density(const dem_sim *s, int wall, double *rho)
{
    int die, other, e = dem_density_walls(s, wall, &die, &other);
    if (e)
        return e;
    if (dem_cup_in_bore(s, wall, die) != 1 || dem_cup_in_bore(s, other, die) != 1)
        return DEM_ERR_ARG; /* the cup's volume would not be the bore's */
    double vol = 0, a[3], b[3];
    for (int i = 0; i < s->n; i++)
        vol += 4.0 / 3.0 * M_PI * s->radius[i] * s->radius[i] * s->radius[i];
    dem_wall_position(s, wall, a);
    dem_wall_position(s, other, b);
    *rho = bore_density(s, wall, other, die, a, b, vol);
    return DEM_OK;
}

static int check_stages(dem_sim *s, int wall, dem_wall_kind kind, int nstages, const dem_stage *stages)
{
    if (nstages < 0 || nstages > DEM_MAX_STAGES)
        return sim_fail(s, DEM_ERR_ARG, "wall %d: 0..%d motion stages (got %d)", wall, DEM_MAX_STAGES, nstages);
    for (int st = 0; st < nstages; st++) {
        const dem_stage *g = &stages[st];
        if (!(g->duration >= 0) || !finite3(g->velocity))
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
    }
    return 0;
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
    for (int k = 0; k < s->nwalls; k++) {
        const dem_wall *w = &s->walls[k];
        while (s->stage_cur[k] < w->nstages) {
            const dem_stage *g = &w->stages[s->stage_cur[k]];
            long ran = s->step - s->stage_first[k];
            int done = ran >= s->wall_stage_steps[k][s->stage_cur[k]];
            if (!done && ran > 0 && g->until_distance > 0) {
                const double *p = s->wall_pos[k], *p0 = s->stage_from[k];
                double d = sqrt((p[0] - p0[0]) * (p[0] - p0[0]) + (p[1] - p0[1]) * (p[1] - p0[1]) +
                                (p[2] - p0[2]) * (p[2] - p0[2]));
                done = d >= g->until_distance;
            }
            if (!done && ran > 0 && g->until_density > 0)
                done = sim_relative_density(s, k) >= g->until_density;
            if (!done && ran > 0 && g->until_force > 0) { /* the force the particles exerted in the step before */
                double fn;
                if (wall_normal_before(s, wr, k, &fn))
                    return DEM_ERR_DEVICE;
                done = fn >= g->until_force;
            }
            if (!done)
                break;
            s->stage_cur[k]++;
            s->stage_first[k] = s->step;
            memcpy(s->stage_from[k], s->wall_pos[k], sizeof(double) * 3);
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
            s->servo_v[k][d] = u * n[d];
        dem_servo_stats *r = &s->servo[k];
        if (r->stage != st || r->steps == 0) /* a new stage, or the first step this process runs */
            *r = (dem_servo_stats){st, g->force, 0, 0, NAN, 0}, s->servo_err[k] = s->servo_sum[k] = 0;
        double big = 0.1 * g->force, prev = s->servo_err[k];
        r->chatter += (prev > big && err < -big) || (prev < -big && err > big);
        s->servo_err[k] = err;
        long len = s->wall_stage_steps[k][st];
        if (s->step - first >= len - len / 10) /* its last tenth: the force it holds */
            s->servo_sum[k] += fn, r->tail++;
        r->steps++;
    }
    return 0;
}

int dem_servo_stats_get(const dem_sim *s, int wall, dem_servo_stats *st)
{
    if (wall < 0 || wall >= s->nwalls)
        return sim_fail((dem_sim *)s, DEM_ERR_ARG, "wall %d: no such wall (%d)", wall, s->nwalls);
    *st = s->servo[wall];
    if (!st->steps)
        st->stage = -1;
    if (st->tail)
        st->held = s->servo_sum[wall] / (double)st->tail;
    return 0;
}

int dem_add_wall(dem_sim *s, const dem_wall *w)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    int k = s->nwalls;
    if (k >= DEM_MAX_WALLS)
        return sim_fail(s, DEM_ERR_ARG, "too many walls (at most %d)", DEM_MAX_WALLS);
    if (w->kind != DEM_WALL_PLANE && w->kind != DEM_WALL_CYLINDER)
        return sim_fail(s, DEM_ERR_ARG, "wall %d: unknown kind %d", k, (int)w->kind);
    if (w->material < 0 || w->material >= s->nmat)
        return sim_fail(s, DEM_ERR_ARG, "wall %d: unknown material %d", k, w->material);
    double len = sqrt(w->normal[0] * w->normal[0] + w->normal[1] * w->normal[1] + w->normal[2] * w->normal[2]);
    if (!(len > 0) || !isfinite(len) || !finite3(w->point))
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
    if (not_started(s))
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

int dem_set_gravity(dem_sim *s, const double g[3])
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (!finite3(g))
        return sim_fail(s, DEM_ERR_ARG, "gravity must be finite");
    memcpy(s->gravity, g, sizeof s->gravity);
    return 0;
}

int dem_set_domain(dem_sim *s, const double lo[3], const double hi[3])
{
    if (not_started(s))
        return DEM_ERR_STATE;
    for (int d = 0; d < 3; d++)
        if (!(hi[d] > lo[d]) || !isfinite(lo[d]) || !isfinite(hi[d]))
            return sim_fail(s, DEM_ERR_ARG, "domain: need finite lo < hi on every axis (axis %d: %g, %g)", d, lo[d],
                            hi[d]);
    memcpy(s->lo, lo, sizeof s->lo);
    memcpy(s->hi, hi, sizeof s->hi);
    s->have_domain = 1;
    return 0;
}

int dem_set_dt(dem_sim *s, double dt)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (!(dt > 0) || !isfinite(dt))
        return sim_fail(s, DEM_ERR_ARG, "time step must be > 0 s (got %g)", dt);
    s->dt = dt;
    return 0;
}

int dem_set_effects(dem_sim *s, unsigned effects)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (effects & ~(unsigned)(DEM_EFFECT_ALL | DEM_EFFECT_TEST_LAWS))
        return sim_fail(s, DEM_ERR_ARG, "effect mask 0x%x has bits of effects this version does not have", effects);
    if ((effects & DEM_EFFECT_MC_STRESS) && (effects & DEM_EFFECT_MC_STRAIN))
        return sim_fail(s, DEM_ERR_ARG, "mc_stress and mc_strain are two alternative normal laws: choose one");
    if (!(effects & DEM_EFFECT_HERTZ))
        return sim_fail(s, DEM_ERR_ARG, "the effect mask must contain DEM_EFFECT_HERTZ (the contact law itself)");
    s->effects = effects;
    return 0;
}

unsigned dem_effects(const dem_sim *s) { return s->effects; }

int dem_set_mc_stress_convention(dem_sim *s, unsigned convention)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (convention & ~(unsigned)DEM_MCS_MASK)
        return sim_fail(s, DEM_ERR_ARG, "MC-stress convention 0x%x has bits other than DEM_MCS_*", convention);
    if ((convention & DEM_MCS_SCALE_TEXT) && (convention & DEM_MCS_SCALE_TRACE))
        return sim_fail(s, DEM_ERR_ARG, "MC-stress convention: choose one scale (text or trace), not both");
    s->mcs_conv = convention;
    return 0;
}

unsigned dem_mc_stress_convention(const dem_sim *s) { return s->mcs_conv; }

void dem_mc_stress_convention_string(unsigned c, char *buf, size_t len)
{
    snprintf(buf, len, "own_contact %s, lever %s, scale %s", (c & DEM_MCS_OWN_IN) ? "in" : "out",
             (c & DEM_MCS_LEVER_CENTRES) ? "centres" : "contact_point",
             (c & DEM_MCS_SCALE_TRACE) ? "mean_trace" : (c & DEM_MCS_SCALE_TEXT) ? "text" : "mean_pressure");
}

int dem_set_mc_strain(dem_sim *s, int max_iterations, double tolerance)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (max_iterations < 0 || max_iterations > 10000 || !(tolerance > 0) || !isfinite(tolerance))
        return sim_fail(s, DEM_ERR_ARG, "MC-strain: iterations in 0..10000 (0 = lagged) and tolerance > 0 (got %d, %g)",
                        max_iterations, tolerance);
    s->mc_max_iter = max_iterations;
    s->mc_tol = tolerance;
    return 0;
}

int dem_set_mc_strain_reach(dem_sim *s, double factor)
{
    if (not_started(s))
        return DEM_ERR_STATE;
    if (!(factor >= 1 && factor <= 2))
        return sim_fail(s, DEM_ERR_ARG, "MC-strain contact distance factor must be in [1, 2] (got %g)", factor);
    s->mc_reach = factor;
    return 0;
}

void dem_mc_stats_get(const dem_sim *s, dem_mc_stats *st) { *st = s->mc; }

/* by bit position; the convention bits (7..11, dem_effects.h) have no name */
static const char *const effect_names[DEM_EFFECT_COUNT] = {"hertz", "damping", "friction", "gravity", "walls",
                                                           "mc_stress", "mc_strain", NULL, NULL, NULL, NULL, NULL,
                                                           "springs", "pressure", "bending", "patches", "riders", "constraints"};

const char *dem_effect_name(int bit) { return bit >= 0 && bit < DEM_EFFECT_COUNT ? effect_names[bit] : NULL; }

void dem_effects_string(unsigned effects, char *buf, size_t len)
{
    size_t at = 0;
    buf[0] = 0;
    for (int k = 0; k < DEM_EFFECT_COUNT && at < len; k++)
        if (effect_names[k] && (effects & (1u << k)))
            at += (size_t)snprintf(buf + at, len - at, "%s%s", at ? "+" : "", effect_names[k]);
}

int dem_effect_bit(const char *name)
{
    for (int k = 0; k < DEM_EFFECT_COUNT; k++)
        if (effect_names[k] && !strcmp(name, effect_names[k]))
            return k;
    return DEM_ERR_ARG;
}

/* ---- stepping ---- */

static int sim_rebuild_traced(dem_sim *s);

static int be_fail(dem_sim *s)
{
    return sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
}

static int read_flags(dem_sim *s, int *flags)
{
    return dem_stage_read_field(s->ops, s->be, DEM_FIELD_FLAGS, flags, sizeof(int) * FLAG_COUNT) ? be_fail(s) : 0;
}

static int report_out_of_domain(dem_sim *s, int slot)
{
    int id = sim_api(s, slot); /* the caller's id of the particle stored there (host/core/reorder.c) */
    int rs = s->setup.real_size;
    double p[3] = {NAN, NAN, NAN};
    unsigned char *buf = malloc((size_t)3 * s->n * rs);
    if (buf && dem_stage_read_field(s->ops, s->be, DEM_FIELD_X, buf, (size_t)3 * s->n * rs) == 0)
        for (int d = 0; d < 3; d++)
            p[d] = rs == 8 ? ((double *)buf)[3 * slot + d] : ((float *)buf)[3 * slot + d];
    free(buf);
    s->err_particle = id;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) /* a value that overflowed or was never a number */
        return sim_fail(s, DEM_ERR_DOMAIN,
                        "step %ld: particle %d: its position became non-finite (%g, %g, %g): a velocity or force "
                        "overflowed or was not a number (check the time step, overlaps and parameters)",
                        s->step, id, p[0], p[1], p[2]);
    return sim_fail(s, DEM_ERR_DOMAIN,
                    "step %ld: particle %d at (%g, %g, %g) m is outside the binning domain [%g,%g]x[%g,%g]x[%g,%g] "
                    "(the domain rounded up to whole cells of %g m) or not finite; enlarge the domain or check the "
                    "set-up (time step, overlaps)",
                    s->step, id, p[0], p[1], p[2], s->lo[0], s->grid_hi[0], s->lo[1], s->grid_hi[1], s->lo[2],
                    s->grid_hi[2], s->grid_cell);
}

/* Copies launches [a, z) of the core's trace after the n already in dst. */
static int copy_trace(const dem_core *c, int a, int z, unsigned char *dst, int n)
{
    for (int k = a; k < z && k < DEM_TRACE_MAX && n < DEM_TRACE_MAX; k++)
        dst[n++] = c->trace[k];
    return n;
}

int sim_rebuild(dem_sim *s)
{
    int e = sim_rebuild_traced(s);
    if (!e) {
        const dem_core *c = DEM_CORE(s->be);
        s->nseq_rebuild = copy_trace(c, s->rebuild_at, c->ntrace, s->seq_rebuild, 0);
        s->rebuild_len = c->ntrace - s->rebuild_at;
    }
    return e;
}

/* The patch rows (common/patch_contacts.h), built again with wider rows or a wider reach until nothing overflowed */
static int patch_rows(dem_sim *s)
{
    for (int first = 1;; first = 0) {
        int flags[FLAG_COUNT];
        if (dem_stage_patch_build(s->ops, s->be, first, s->maxp, s->maxv, s->reach))
            return be_fail(s);
        if (read_flags(s, flags))
            return DEM_ERR_DEVICE;
        if (flags[FLAG_PATCH_NEEDED] <= s->maxp && flags[FLAG_VROW_NEEDED] <= s->maxv && !flags[FLAG_PATCH_REACH])
            return 0;
        while (s->maxp < flags[FLAG_PATCH_NEEDED])
            s->maxp *= 2;
        while (s->maxv < flags[FLAG_VROW_NEEDED])
            s->maxv *= 2;
        if (flags[FLAG_PATCH_REACH])
            s->reach *= 1.5;
        flags[FLAG_PATCH_NEEDED] = flags[FLAG_VROW_NEEDED] = flags[FLAG_PATCH_REACH] = 0;
        if (dem_stage_write_field(s->ops, s->be, DEM_FIELD_FLAGS, flags, sizeof flags))
            return be_fail(s);
    }
}

/* The skin of the rows about to be built. Fixed by dem_config.skin, or chosen (docs/design.md "The neighbour skin"):
 * a rebuild costs about as much as R steps, and each r_min of skin adds B of a step's cost (R / B =
 * DEM_SKIN_COST_RATIO, measured); the particles moved up to s/2 in the n steps since the last rebuild (its trigger,
 * or less when a probe rebuilds), so about u = s / (2 n) per step, and 1 + B s / r_min + R 2 u / s is least at
 * s = sqrt(R / B r_min s_old / n). Any skin gives the same bits (rows list every pair within reach; one that does
 * not touch adds nothing): this only moves the time between the steps and the rebuilds. */
static void skin_choose(dem_sim *s)
{
    if (s->skin_lo < s->skin_hi && s->skin_built >= 0 && s->step > s->skin_built) {
        double best = sqrt(DEM_SKIN_COST_RATIO * s->rmin * s->skin_now / (double)(s->step - s->skin_built));
        s->skin_now = best < s->skin_lo ? s->skin_lo : best > s->skin_hi ? s->skin_hi : best;
    }
    s->skin_built = s->step;
    dem_core *c = DEM_CORE(s->be);
    c->sr[SR_SKIN] = s->skin_now + s->skin_extra;
    c->sr[SR_HALF_SKIN2] = 0.25 * s->skin_now * s->skin_now;
}

/* An automatic skin above its lower end is tried smaller once the rows have lasted DEM_SKIN_PROBE steps. */
static int skin_probe_due(const dem_sim *s)
{
    return s->skin_now > s->skin_lo && s->skin_built >= 0 && s->step - s->skin_built >= DEM_SKIN_PROBE;
}

/* The slots of a row set for a build whose rows need `need` together: 1/8 to spare, so that a packing that
 * tightens grows them at one rebuild in several, not at each. The rows are packed (dem_buffers.h DEM_ROWS): each
 * slot is an int (MC-strain's displacements per slot are held for the current set only: MAXC). Until
 * 2026-12-03 every row had the longest row's capacity: a compact in the press lists 17-23 partners in its longest row
 * and about 8 in its mean one (docs/design.md "Memory in a compact"). */
static int row_capacity(int need)
{
    return need + need / 8 + 16;
}

static int sim_rebuild_traced(dem_sim *s)
{
    int flags[FLAG_COUNT], e;
    if (sim_reorder_due(s) && (e = sim_reorder(s)))
        return e;
    skin_choose(s);
    s->rebuild_at = DEM_CORE(s->be)->ntrace;
    if (dem_stage_bin_bounds(s->ops, s->be))
        return be_fail(s);
    if (read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if (flags[FLAG_OUT_OF_DOMAIN] != DEM_NO_PARTICLE)
        return report_out_of_domain(s, flags[FLAG_OUT_OF_DOMAIN]);
    if (dem_stage_bin_cells(s->ops, s->be, flags) || dem_stage_bin(s->ops, s->be))
        return be_fail(s);
    /* s->maxn is the current rows' slots: it changes only once new rows are committed */
    int maxn = s->maxn, need = 0;
    if (dem_stage_nbr_count(s->ops, s->be, &need))
        return be_fail(s);
    if (need < 0 || need > INT_MAX / 9 * 8 - 16)
        return sim_fail(s, DEM_ERR_NOMEM, "step %ld: the neighbour rows need %d slots, more than an int counts",
                        s->step, need);
    if (need > maxn)
        maxn = row_capacity(need);
    if (dem_stage_nbr_reserve(s->ops, s->be, maxn) || dem_stage_nbr_build(s->ops, s->be))
        return be_fail(s);
    /* checked before the commit reads the rows: a row filled short of its count would hand it stale partners */
    if (read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if (flags[FLAG_ASYMMETRIC])
        return sim_fail(s, DEM_ERR_STATE, "step %ld: neighbour rows are not as counted (a library bug; please report)",
                        s->step);
    if (dem_stage_nbr_commit(s->ops, s->be))
        return be_fail(s);
    s->maxn = maxn;
    if (read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if (flags[FLAG_ASYMMETRIC])
        return sim_fail(s, DEM_ERR_STATE, "step %ld: neighbour rows are not symmetric (a library bug; please report)",
                        s->step);
    if ((s->effects & DEM_EFFECT_PATCHES) && s->npatch && (e = patch_rows(s)))
        return e;
    if (s->reordered) { /* the rows are numbered in the new places: where the particles were no longer matters */
        dem_bufref r = {TABLE_ONE, BUF_OLD_SLOT};
        if (s->ops->write(s->be, r, 0, s->setup.identity, sizeof(int) * (size_t)s->n, 1))
            return be_fail(s);
        s->reordered = 0;
    }
    s->rebuilds++;
    return 0;
}

/* MC-strain before the contact pass: displacements from the stored forces (lagged), or iterated to the tolerance. */
static int mc_strain(dem_sim *s)
{
    long it = 0;
    int converged = 0;
    if (dem_launch(s->ops, s->be, K_mc_strain_disp))
        return be_fail(s);
    while (it < s->mc_max_iter) {
        int flags[FLAG_COUNT];
        if (read_flags(s, flags))
            return DEM_ERR_DEVICE;
        flags[FLAG_MC_PENDING] = 0;
        if (dem_stage_write_field(s->ops, s->be, DEM_FIELD_FLAGS, flags, sizeof flags) || dem_stage_mc_strain_update(s->ops, s->be, s->mc_tol) ||
            dem_launch(s->ops, s->be, K_mc_strain_disp))
            return be_fail(s);
        it++;
        if (read_flags(s, flags))
            return DEM_ERR_DEVICE;
        if (!flags[FLAG_MC_PENDING]) {
            converged = 1;
            break;
        }
    }
    s->mc.last = it;
    if (s->force_step == s->step) /* dem_start's forces, before any step: no step to count (a cap hit there made
                                   * the count one more than the steps, "6001 of 6000") */
        return 0;
    if (s->mc_max_iter && !converged) {
        s->mc.unconverged++;
        if (s->mc.first_capped < 0)
            s->mc.first_capped = s->force_step;
        s->mc.last_capped = s->force_step;
    }
    s->mc.total += it;
    if (it > s->mc.max)
        s->mc.max = it;
    return 0;
}

/* The force stages of a step, in order, each run only when the run has its effect (0: always) and, for the walls'
 * sum, walls. A stage returns 0 or a dem_status (a backend failure already reported through be_fail). */
static int stage_stress_trace(dem_sim *s) { return dem_launch(s->ops, s->be, K_stress_trace) ? be_fail(s) : 0; }
/* The force each wall received is summed only where someone can read it: the last step of every dem_step call (so
 * dem_get_field and the output see it after any call) and every step while a servo stage may read it. Unless the
 * run keeps each particle's wall forces (DEM_KEEP_WALL_FORCES: a servo, the contact network), the sum evaluates
 * the wall contacts itself, between the pair pass and the per-particle sums, which then apply exactly those forces
 * (common/wall_forces.h); otherwise it adds the kept forces after the per-particle sums. The bits are the same. */
static int stage_contacts(dem_sim *s)
{
    /* A sampled step's row (common/series.h) keeps the blocks' partial sums: integrate_kick takes them from the kept
     * forces, or else they are computed here; the final sum runs only when due. */
    int walls = (s->effects & DEM_EFFECT_WALLS) && s->nwalls, fin = walls && s->wall_sums_due;
    int kept = (s->setup.effects & DEM_KEEP_WALL_FORCES) != 0; /* then the sums read what contact_forces kept */
    int blocks = fin || (walls && s->sample_row >= 0 && !kept);
    return dem_launch(s->ops, s->be, K_contact_pairs) ||
                   (blocks && !kept && dem_stage_wall_reduce(s->ops, s->be, fin)) ||
                   dem_launch(s->ops, s->be, K_contact_forces) ||
                   (blocks && kept && dem_stage_wall_reduce(s->ops, s->be, fin))
               ? be_fail(s)
               : 0;
}
static int stage_springs(dem_sim *s)
{
    return s->nsprings && dem_launch(s->ops, s->be, K_spring_forces) ? be_fail(s) : 0;
}
static int stage_pressure(dem_sim *s)
{
    s->pressure_now = pressure_at(s, (double)s->force_step * s->dt);
    DEM_CORE(s->be)->sr[SR_PRESSURE] = s->pressure_now;
    return s->ntri && dem_launch(s->ops, s->be, K_pressure_forces) ? be_fail(s) : 0;
}
static int stage_bending(dem_sim *s)
{
    return s->nhinges && dem_launch(s->ops, s->be, K_hinge_forces) ? be_fail(s) : 0;
}
static int stage_gather(dem_sim *s)
{
    return (s->nsprings || s->ntri || s->nhinges) && dem_launch(s->ops, s->be, K_channel_gather) ? be_fail(s) : 0;
}
static int stage_patches(dem_sim *s)
{
    return s->npatch && (dem_launch(s->ops, s->be, K_patch_forces) || dem_launch(s->ops, s->be, K_patch_gather))
               ? be_fail(s)
               : 0;
}
static const struct {
    unsigned gate;
    int (*run)(dem_sim *s);
} force_stages[] = {
    {DEM_EFFECT_MC_STRESS, stage_stress_trace}, /* pass 1 of MC-stress: the traces the contacts read */
    {DEM_EFFECT_MC_STRAIN, mc_strain},          /* induced displacements (lagged or iterated forces) */
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
            int e = force_stages[k].run(s);
            if (e)
                return e;
        }
    return 0;
}

int dem_start(dem_sim *s, const dem_config *c)
{
    if (not_started(s))
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
    s->started = 1;
    if (dem_stage_reset_flags(s->ops, s->be))
        return be_fail(s);
    s->force_step = s->step;
    s->wall_sums_due = 1;
    s->servo_walls = sim_has_servo(s);
    if ((e = sim_rebuild(s)) || (e = forces(s)))
        return e;
    return 0;
}

int dem_step(dem_sim *s, long nsteps)
{
    if (!s->started)
        return sim_fail(s, DEM_ERR_STATE, "dem_start first");
    for (long k = 0; k < nsteps; k++) {
        int e = sim_step_once(s, k == nsteps - 1, -1);
        if (e)
            return e;
    }
    return 0;
}

int sim_step_once(dem_sim *s, int wall_sums, int sample_row)
{
    int flags[FLAG_COUNT], e;
    dem_core *c = DEM_CORE(s->be);
    c->ntrace = 0;
    s->rebuild_at = s->rebuild_len = 0;
    if (dem_stage_reset_flags(s->ops, s->be) || dem_launch(s->ops, s->be, K_integrate_kick_drift))
        return be_fail(s);
    /* walls move with the particles' drift: positions at t + dt, velocity of this step */
    wall_read wr = {.read = 0};
    if (s->nwalls && ((e = stages_advance(s, &wr)) || (e = servo_update(s, &wr))))
        return e;
    if (s->nwalls) {
        for (int w = 0; w < s->nwalls; w++) {
            double v[3];
            sim_wall_velocity(s, w, v);
            for (int d = 0; d < 3; d++)
                s->wall_pos[w][d] += v[d] * s->dt;
        }
        sim_pack_walls(s);
        if (dem_stage_set_walls(s->ops, s->be, s->wall_real) || (s->natt && dem_launch(s->ops, s->be, K_rider_place)))
            return be_fail(s);
    }
    if (read_flags(s, flags))
        return DEM_ERR_DEVICE;
    if ((flags[FLAG_REBUILD] || skin_probe_due(s)) && (e = sim_rebuild(s)))
        return e;
    s->force_step = s->step + 1; /* the drifted positions are those of t + dt */
    s->wall_sums_due = wall_sums || s->servo_walls;
    s->sample_row = sample_row;
    if (sample_row >= 0 && dem_stage_series_arm(s->ops, s->be, 1, sample_row))
        return be_fail(s);
    if ((e = forces(s))) {
        s->sample_row = -1; /* a later step is not sampled into this row */
        dem_stage_series_arm(s->ops, s->be, 0, 0);
        return e;
    }
    if (dem_launch(s->ops, s->be, K_integrate_kick) || (sample_row >= 0 && dem_stage_series_arm(s->ops, s->be, 0, 0)))
        return be_fail(s);
    s->sample_row = -1;
    s->nseq_step = copy_trace(c, 0, s->rebuild_len ? s->rebuild_at : c->ntrace, s->seq_step, 0);
    if (s->rebuild_len)
        s->nseq_step = copy_trace(c, s->rebuild_at + s->rebuild_len, c->ntrace, s->seq_step, s->nseq_step);
    s->step++;
    return 0;
}

/* ---- queries ---- */

int dem_count(const dem_sim *s) { return s->n; }
double dem_particle_radius(const dem_sim *s, int i) { return i >= 0 && i < s->n ? s->radius[sim_dev(s, i)] : NAN; }
int dem_particle_material(const dem_sim *s, int i) { return i >= 0 && i < s->n ? s->mat[sim_dev(s, i)] : DEM_ERR_ARG; }
double dem_particle_mass(const dem_sim *s, int i) { return i >= 0 && i < s->n ? sim_mass(s, sim_dev(s, i)) : NAN; }
int dem_wall_count(const dem_sim *s) { return s->nwalls; }
long dem_step_index(const dem_sim *s) { return s->step; }
double dem_time(const dem_sim *s) { return (double)s->step * s->dt; }
double dem_dt(const dem_sim *s) { return s->dt; }
int dem_neighbor_capacity(const dem_sim *s) { return s->maxn; }
double dem_neighbor_skin(const dem_sim *s) { return s->skin_now; }
long dem_rebuild_count(const dem_sim *s) { return s->rebuilds; }
long dem_reorder_count(const dem_sim *s) { return s->reorders; }
int dem_cell_count(const dem_sim *s)
{
    return s->be ? DEM_CORE(s->be)->ncells : s->setup.cells[0] * s->setup.cells[1] * s->setup.cells[2];
}
int dem_grid_cells(const dem_sim *s, int first[3], int count[3])
{
    if (!s->started)
        return DEM_ERR_STATE;
    const int *si = DEM_CORE(s->be)->si;
    first[0] = si[SI_CX0], first[1] = si[SI_CY0], first[2] = si[SI_CZ0];
    count[0] = si[SI_NCX], count[1] = si[SI_NCY], count[2] = si[SI_NCZ];
    return 0;
}
int dem_grid_get(const dem_sim *s, double lo[3], double *inv_cell, int ncell[3])
{
    if (!s->started)
        return DEM_ERR_STATE;
    memcpy(lo, s->setup.lo, sizeof(double) * 3);
    memcpy(ncell, s->setup.ncell, sizeof(int) * 3);
    *inv_cell = s->setup.inv_cell;
    return 0;
}
const char *dem_describe(dem_sim *s)
{
    if (!s->be)
        return "not started";
    char fx[128];
    dem_effects_string(s->effects, fx, sizeof fx);
    snprintf(s->desc, sizeof s->desc, "%s, effects %s", s->ops->describe(s->be), fx);
    return s->desc;
}

size_t sim_stored_bytes(const dem_sim *s, dem_field f)
{
    dem_bufref r;
    size_t bytes;
    return s->be && !dem_field_ref(DEM_CORE(s->be), f, &r, &bytes) ? bytes : 0;
}

size_t dem_field_bytes(const dem_sim *s, dem_field f)
{
    if (f == DEM_FIELD_MC_FORCE) /* kept per pair, handed out per row slot (dem_get_raw) */
        return (s->setup.effects & DEM_EFFECT_MC_STRAIN)
                   ? (size_t)s->setup.real_size * (size_t)(s->be ? DEM_CORE(s->be)->maxn[DEM_CORE(s->be)->cur] : s->maxn)
                   : 0;
    if (s->started) /* the run's own sizes: the pair-sized fields follow the pairs allocated */
        return sim_stored_bytes(s, f);
    return dem_field_size(f, s->setup.effects, (size_t)s->n, (size_t)s->maxn, (size_t)s->nwalls, (size_t)dem_cell_count(s),
                          (size_t)s->setup.real_size);
}

int dem_get_raw(dem_sim *s, dem_field f, void *dst, size_t bytes)
{
    if (!s->started)
        return sim_fail(s, DEM_ERR_STATE, "dem_start first");
    if (f == DEM_FIELD_STRESS && dem_stage_stress_tensor(s->ops, s->be)) /* computed from the current positions when asked */
        return be_fail(s);
    int slots = f == DEM_FIELD_MC_FORCE; /* kept per pair, handed out per row slot */
    if (!bytes || (!slots && !s->reorders))
        return dem_stage_read_field(s->ops, s->be, f, dst, bytes) ? be_fail(s) : 0;
    /* stored anew (dem_config.reorder): the whole field read, then put in the callers' order */
    size_t all = dem_field_bytes(s, f);
    if (bytes > all)
        return sim_fail(s, DEM_ERR_ARG, "field %d holds %zu bytes, %zu asked", (int)f, all, bytes);
    unsigned char *buf = malloc(all ? all : 1);
    if (!buf)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    int e = slots ? sim_mc_force_slots(s, buf, all)
                  : dem_stage_read_field(s->ops, s->be, f, buf, all) ? be_fail(s) : 0;
    if (!e && s->reorders)
        e = sim_field_to_api(s, f, buf, all);
    if (!e)
        memcpy(dst, buf, bytes);
    free(buf);
    return e;
}

int dem_get_field(dem_sim *s, dem_field f, double *dst)
{
    if (f == DEM_FIELD_NBR_COUNT || f == DEM_FIELD_NBR_LIST || f == DEM_FIELD_NBR_START || f == DEM_FIELD_CELL_START ||
        f == DEM_FIELD_CELL_PARTICLES ||
        f == DEM_FIELD_FLAGS || f == DEM_FIELD_TOUCH || f == DEM_FIELD_WALL_MASK || f == DEM_FIELD_IN_START ||
        f == DEM_FIELD_IN_PAIR)
        return sim_fail(s, DEM_ERR_ARG, "field %d holds integers: use dem_get_raw", (int)f);
    size_t bytes = dem_field_bytes(s, f), cnt = bytes / (size_t)s->setup.real_size;
    void *buf = malloc(bytes ? bytes : 1);
    if (!buf)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    int e = dem_get_raw(s, f, buf, bytes);
    for (size_t k = 0; !e && k < cnt; k++)
        dst[k] = s->setup.real_size == 8 ? ((double *)buf)[k] : (double)((float *)buf)[k];
    free(buf);
    return e;
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

int dem_wall_position(const dem_sim *s, int wall, double p[3])
{
    if (wall < 0 || wall >= s->nwalls)
        return DEM_ERR_ARG;
    memcpy(p, s->started ? s->wall_pos[wall] : s->walls[wall].point, sizeof(double) * 3);
    return 0;
}

int dem_wall_get(const dem_sim *s, int wall, dem_wall *w)
{
    if (wall < 0 || wall >= s->nwalls)
        return DEM_ERR_ARG;
    *w = s->walls[wall];
    return 0;
}

int dem_kernel_times(dem_sim *s, const char ***names, const double **seconds, int *count)
{
    *count = 0;
    if (!s->be)
        return 0;
    if (s->ops->finish(s->be))
        return be_fail(s);
    *names = (const char **)dem_kernel_names;
    *seconds = DEM_CORE(s->be)->ktime;
    *count = DEM_CORE(s->be)->timed ? K__COUNT : 0;
    return 0;
}


double dem_kernel_bytes(const dem_sim *s, int k)
{
    return s->be && k >= 0 && k < K__COUNT ? (double)dem_kernel_bound_bytes(DEM_CORE(s->be), (dem_kernel_id)k) : 0;
}

int dem_kernel_sequence(const dem_sim *s, int rebuild, char *buf, size_t len)
{
    const unsigned char *q = rebuild ? s->seq_rebuild : s->seq_step;
    int n = rebuild ? s->nseq_rebuild : s->nseq_step;
    size_t o = 0;
    if (len)
        buf[0] = 0;
    for (int k = 0; k < n && o < len;) {
        /* a repeated pair of launches (an iteration) is written once with its count */
        int rep = 1;
        while (k + 2 * rep + 1 < n && q[k + 2 * rep] == q[k] && q[k + 2 * rep + 1] == q[k + 1])
            rep++;
        if (rep > 1) {
            o += (size_t)snprintf(buf + o, len - o, "%s%d x (%s, %s)", o ? ", " : "", rep, dem_kernel_names[q[k]],
                                  dem_kernel_names[q[k + 1]]);
            k += 2 * rep;
        } else {
            o += (size_t)snprintf(buf + o, len - o, "%s%s", o ? ", " : "", dem_kernel_names[q[k]]);
            k++;
        }
    }
    return n;
}

size_t dem_device_bytes(const dem_sim *s)
{
    if (!s->be)
        return 0;
    const dem_core *c = DEM_CORE(s->be);
    size_t sum = 0;
    for (int id = 0; id < BUF__COUNT; id++)
        sum += c->bytes[id];
    for (int set = 0; set < 2; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            sum += c->row_bytes[set][id];
    return sum;
}

size_t dem_device_bytes_part(const dem_sim *s, dem_memory_part part)
{
    if (!s->be)
        return 0;
    const dem_core *c = DEM_CORE(s->be);
    size_t sum = 0;
    for (int id = 0; id < BUF__COUNT; id++)
        if (dem_buffer_part(id) == (int)part)
            sum += c->bytes[id];
    for (int set = 0; set < 2 && part == DEM_MEM_ROWS; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            sum += c->row_bytes[set][id];
    return sum;
}

const char *dem_memory_part_name(dem_memory_part part)
{
    static const char *const names[DEM_MEM__COUNT] = {"particles", "pairs", "neighbour rows", "walls",
                                                      "cells",     "output", "membranes and riders"};
    return (int)part >= 0 && part < DEM_MEM__COUNT ? names[part] : "?";
}

int dem_memory_estimate(dem_sim *s, const dem_config *c, size_t *bytes)
{
    *bytes = 0;
    if (s->started)
        return sim_fail(s, DEM_ERR_STATE, "dem_memory_estimate is for a run not started (dem_device_bytes after)");
    s->cfg = *c;
    int e = sim_validate(s);
    if (e || (e = sim_pack(s)))
        return e;
    dem_core core;
    dem_core_init(&core, &s->setup);
    core.pair_cap = (size_t)DEM_ESTIMATE_PAIRS_PER_PARTICLE * (size_t)s->n;
    for (int id = 0; id < BUF__COUNT; id++)
        *bytes += dem_buffer_bytes(&core, id);
    for (int set = 0; set < 2; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            *bytes += dem_row_bytes(&core, id, core.maxn[set]);
    return 0;
}

#ifndef DEM_BUILD_FLAGS
#define DEM_BUILD_FLAGS "unknown"
#endif
#if defined(__clang__)
#define DEM_COMPILER "clang " __clang_version__
#elif defined(__GNUC__)
#define DEM_COMPILER "gcc " __VERSION__
#else
#define DEM_COMPILER "unknown"
#endif

const char *dem_build_info(dem_sim *s)
{
    snprintf(s->build, sizeof s->build, "libdem %s; host code compiled by %s with %s; kernels: %s", DEM_VERSION,
             DEM_COMPILER, DEM_BUILD_FLAGS, s->be ? DEM_CORE(s->be)->build : "not started");
    return s->build;
}
