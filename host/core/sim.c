/* sim.c - the simulation object: created, set up (materials, particles and their masses, flags and spins, gravity,
 * the domain, the time step) and destroyed. The other parts of a simulation are added in their own files:
 * mesh_elements.c (springs, triangles, patches, hinges, pressure), walls.c, effects.c (which physics). The run itself:
 * step_loop.c (dem_start, dem_step), rebuild.c (the neighbour rows), fields.c (reading the device's fields),
 * diagnostics.c (errors, the kernels' trace, memory); sim_setup.c validates and packs the set-up at dem_start. */
#include "sim.h"
#include "dem_layout.h"
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

dem_sim *dem_create(void)
{
    dem_sim *s = calloc(1, sizeof(dem_sim));
    if (s) {
        s->effects = DEM_EFFECT_CLASSICAL;
        s->mc.stress_conv = DEM_MCS_DEFAULT;
        s->mc.tol = 1e-6;
        s->mc.reach = 1;
        s->run.sample_row = -1; /* no step is sampled until dem_step_sampled says so */
        s->mc.stats.first_capped = s->mc.stats.last_capped = -1;
        s->report.err_particle = -1;
        s->report.mdr_capped_step = s->report.mdr_capped_particle = -1;
    }
    return s;
}

void dem_destroy(dem_sim *s)
{
    if (!s)
        return;
    if (s->split_ops)
        s->split_ops->destroy(s);
    if (s->be)
        s->ops->destroy(s->be);
    sim_setup_free(s);
    free(s->setup_mem);
    free(s->motion.table);
    free(s->scratch.buf);
    free(s->x);
    free(s->v);
    free(s->w);
    free(s->radius);
    free(s->mat);
    free(s->pflags);
    free(s->ghost);
    free(s->body);
    free(s->order.source);
    free(s->mesh.spring_ij);
    free(s->mesh.spring_kr);
    free(s->mesh.tri);
    free(s->mesh.patch);
    free(s->mesh.hinge);
    free(s->mesh.att);
    free(s->mesh.hinge_k);
    free(s);
}

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
    const char *one = getenv("DEM_ONE_PASS"); /* the same bits: lets every scene and test run in one pass unchanged */
    c->one_pass = one && !strcmp(one, "1");
}

int sim_not_started(dem_sim *s)
{
    return s->run.started || s->split_started
               ? sim_fail(s, DEM_ERR_STATE, "the simulation has started: the set-up is fixed")
               : 0;
}

int sim_need_started(dem_sim *s)
{
    if (s->split_started)
        return sim_fail(s, DEM_ERR_STATE, "not on a run split over MPI ranks (dem_create_mpi), whose particles are "
                        "the ranks' parts: dem_step, dem_step_sampled, dem_sample_get, dem_get_field and dem_state_get "
                        "(the whole state, on every rank) work on it");
    return sim_fail(s, DEM_ERR_STATE, "dem_start first");
}

const dem_sim *sim_stepped(const dem_sim *s)
{
    const dem_sim *p = s->split_started ? s->split_ops->part(s) : NULL;
    return p ? p : s;
}

int dem_add_material(dem_sim *s, const dem_material *m)
{
    if (sim_not_started(s))
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
    if (!(m->rolling_friction >= 0) || !isfinite(m->rolling_friction))
        return sim_fail(s, DEM_ERR_ARG, "material %d: rolling friction must be >= 0 (got %g)", s->nmat,
                        m->rolling_friction);
    if (!(m->rolling_damping >= 0) || !isfinite(m->rolling_damping))
        return sim_fail(s, DEM_ERR_ARG, "material %d: rolling damping must be >= 0 (got %g)", s->nmat,
                        m->rolling_damping);
    if (!(m->yield_stress >= 0) || !isfinite(m->yield_stress))
        return sim_fail(s, DEM_ERR_ARG, "material %d: yield stress must be >= 0 Pa, 0 for a material that does not "
                        "yield (got %g)", s->nmat, m->yield_stress);
    if (!(m->surface_energy >= 0) || !isfinite(m->surface_energy))
        return sim_fail(s, DEM_ERR_ARG, "material %d: surface energy must be >= 0 J/m^2 (got %g)", s->nmat,
                        m->surface_energy);
    if (!(m->bulk_fraction >= 0 && m->bulk_fraction < 1))
        return sim_fail(s, DEM_ERR_ARG, "material %d: bulk fraction (MDR's psi_b) must be in [0, 1) (got %g)", s->nmat,
                        m->bulk_fraction);
    if (!(m->mdr_damping >= 0) || !isfinite(m->mdr_damping))
        return sim_fail(s, DEM_ERR_ARG, "material %d: MDR damping must be >= 0 (got %g)", s->nmat, m->mdr_damping);
    if (!(m->bond_strength >= 0) || !isfinite(m->bond_strength))
        return sim_fail(s, DEM_ERR_ARG, "material %d: bond strength must be >= 0 Pa, 0 for a material that does not "
                        "bond (got %g)", s->nmat, m->bond_strength);
    s->mats[s->nmat] = *m;
    return s->nmat++;
}

int dem_set_material_pair(dem_sim *s, int a, int b, const dem_material_pair *p)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (a < 0 || a >= s->nmat || b < 0 || b >= s->nmat || !p)
        return sim_fail(s, DEM_ERR_ARG, "material pair %d-%d: no such material (%d defined)", a, b, s->nmat);
    if (!isnan(p->friction) && !(p->friction >= 0 && isfinite(p->friction)))
        return sim_fail(s, DEM_ERR_ARG, "material pair %d-%d: friction must be >= 0 (got %g)", a, b, p->friction);
    if (!isnan(p->rolling_friction) && !(p->rolling_friction >= 0 && isfinite(p->rolling_friction)))
        return sim_fail(s, DEM_ERR_ARG, "material pair %d-%d: rolling friction must be >= 0 (got %g)", a, b,
                        p->rolling_friction);
    if (!isnan(p->bond_strength) && !(p->bond_strength >= 0 && isfinite(p->bond_strength)))
        return sim_fail(s, DEM_ERR_ARG, "material pair %d-%d: bond strength must be >= 0 Pa (got %g)", a, b,
                        p->bond_strength);
    if (!isnan(p->surface_energy) && !(p->surface_energy >= 0 && isfinite(p->surface_energy)))
        return sim_fail(s, DEM_ERR_ARG, "material pair %d-%d: the work of adhesion (surface_energy) must be >= 0 J/m^2 "
                        "(got %g)", a, b, p->surface_energy);
    if (!isnan(p->restitution) && !(p->restitution > 0 && p->restitution <= 1))
        return sim_fail(s, DEM_ERR_ARG, "material pair %d-%d: restitution must be in (0, 1] (got %g)", a, b,
                        p->restitution);
    s->pair_props[a][b] = s->pair_props[b][a] = *p;
    s->pair_set[a][b] = s->pair_set[b][a] = 1;
    return 0;
}

int dem_add_particle(dem_sim *s, const double x[3], const double v[3], double radius, int material)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (!(radius > 0) || !isfinite(radius))
        return sim_fail(s, DEM_ERR_ARG, "particle %d: radius must be > 0 m (got %g)", s->n, radius);
    if (material < 0 || material >= s->nmat)
        return sim_fail(s, DEM_ERR_ARG, "particle %d: unknown material %d", s->n, material);
    if (s->mats[material].young == INFINITY)
        return sim_fail(s, DEM_ERR_ARG, "particle %d: material %d is rigid (Young's modulus infinite): for walls only",
                        s->n, material);
    if (!sim_finite3(x) || (v && !sim_finite3(v)))
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
    if (sim_not_started(s))
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
    if (sim_not_started(s))
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
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (id < 0 || id >= s->n || !sim_finite3(w))
        return sim_fail(s, DEM_ERR_ARG, "particle %d: no such particle or non-finite angular velocity", id);
    memcpy(s->w + 3 * id, w, sizeof(double) * 3);
    return 0;
}

int dem_set_gravity(dem_sim *s, const double g[3])
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (!sim_finite3(g))
        return sim_fail(s, DEM_ERR_ARG, "gravity must be finite");
    memcpy(s->gravity, g, sizeof s->gravity);
    return 0;
}

int dem_set_domain(dem_sim *s, const double lo[3], const double hi[3])
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    for (int d = 0; d < 3; d++)
        if (!(hi[d] > lo[d]) || !isfinite(lo[d]) || !isfinite(hi[d]))
            return sim_fail(s, DEM_ERR_ARG, "domain: need finite lo < hi on every axis (axis %d: %g, %g)", d, lo[d],
                            hi[d]);
    memcpy(s->domain.lo, lo, sizeof s->domain.lo);
    memcpy(s->domain.hi, hi, sizeof s->domain.hi);
    s->domain.given = 1;
    return 0;
}

int dem_set_dt(dem_sim *s, double dt)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (!(dt > 0) || !isfinite(dt))
        return sim_fail(s, DEM_ERR_ARG, "time step must be > 0 s (got %g)", dt);
    s->dt = dt;
    return 0;
}

int dem_count(const dem_sim *s) { return s->n; }
double dem_particle_radius(const dem_sim *s, int i) { return i >= 0 && i < s->n ? s->radius[sim_dev(s, i)] : NAN; }
int dem_particle_material(const dem_sim *s, int i) { return i >= 0 && i < s->n ? s->mat[sim_dev(s, i)] : DEM_ERR_ARG; }
double dem_particle_mass(const dem_sim *s, int i) { return i >= 0 && i < s->n ? sim_mass(s, sim_dev(s, i)) : NAN; }
double dem_dt(const dem_sim *s) { return s->dt; }
