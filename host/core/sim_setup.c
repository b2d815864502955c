/* sim_setup.c - parameter validation, time scales, the material-pair table, and packing into the run precision. */
#include "sim.h"
#include "dem_layout.h"
#include "ref_kernels.h" /* the hinges' rest angle, period and damping rate */
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(DEM_MAX_WALLS <= DEM_WALL_MASK_BITS, "a particle's wall mask (common/dem_layout.h) holds every wall");

int sim_fail(dem_sim *s, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->report.err, sizeof s->report.err, fmt, ap);
    va_end(ap);
    return code;
}

static double shear_modulus(const dem_material *m) { return m->young / (2 * (1 + m->poisson)); }

/* seed 000 Eq. 3: 1/E* = (1-nu_i^2)/E_i + (1-nu_j^2)/E_j  (the paper's (1-nu)/2G form is the same) */
static double estar(const dem_material *a, const dem_material *b)
{
    return 1 / ((1 - a->poisson * a->poisson) / a->young + (1 - b->poisson * b->poisson) / b->young);
}
/* seed 000 Eq. 5: 1/G* = (2-nu_i)/G_i + (2-nu_j)/G_j */
static double gstar(const dem_material *a, const dem_material *b)
{
    return 1 / ((2 - a->poisson) / shear_modulus(a) + (2 - b->poisson) / shear_modulus(b));
}

/* Hertz's head-on impact without damping: t_c = HERTZ_TC (m*^2 / (r* E*^2 v))^(1/5), with
 * HERTZ_TC = 2 (15/16)^(2/5) Int_0^1 dx / sqrt(1 - x^(5/2)) = 2.868 (Johnson, Contact Mechanics, 1985, Sec. 11.4). */
#define HERTZ_TC 2.868

double dem_hertz_contact_time(double mstar, double rstar, double es, double v)
{
    return HERTZ_TC * pow(mstar * mstar / (rstar * es * es * v), 0.2);
}

double dem_hertz_max_overlap(double mstar, double rstar, double es, double v)
{
    return pow(15 * mstar * v * v / (16 * es * sqrt(rstar)), 0.4);
}

void dem_time_scales_limit(const dem_time_scales *ts, char *buf, size_t len)
{
    double b = ts->max_dt;
    if (b == ts->hinge_damping_time)
        snprintf(buf, len, "the membrane hinges' damping time %.6g s: 1 / the largest decay rate of their k_diss terms, "
                           "lambda dt <= 1", ts->hinge_damping_time);
    else if (b == ts->spring_period / 10)
        snprintf(buf, len, "a tenth of the shortest spring period, %.6g s", ts->spring_period);
    else if (b == ts->hinge_period / 10)
        snprintf(buf, len, "a tenth of the shortest hinge period, %.6g s", ts->hinge_period);
    else
        snprintf(buf, len, "0.5 x Rayleigh time %.6g s", ts->rayleigh_time);
}

/* 1 / mass, 0 for a fixed particle (it does not move: no share in a spring's or hinge's oscillation) */
static double inverse_mass(const dem_sim *s, int i) { return (s->pflags[i] & DEM_PARTICLE_FIXED) ? 0 : 1 / sim_mass(s, i); }

int dem_time_scales_get(dem_sim *s, double v, dem_time_scales *ts)
{
    memset(ts, 0, sizeof *ts);
    if (s->n == 0)
        return sim_fail(s, DEM_ERR_ARG, "time scales need particles");
    double tr = INFINITY, tc = INFINITY;
    for (int i = 0; i < s->n; i++) {
        const dem_material *m = &s->mats[s->mat[i]];
        double r = s->radius[i], nu = m->poisson, mass = sim_mass(s, i);
        /* Rayleigh wave time across a particle: pi r sqrt(rho/G) / (0.1631 nu + 0.8766), rho the body's own
         * (mass / volume: the material's density unless the body's mass is set apart, dem_set_particle_mass) */
        double rho = s->body[2 * i] > 0 ? mass / (4.0 / 3.0 * M_PI * r * r * r) : m->density;
        double t = M_PI * r * sqrt(rho / shear_modulus(m)) / (0.1631 * nu + 0.8766);
        if (t < tr)
            tr = t;
        if (v > 0) {
            double c = dem_hertz_contact_time(mass / 2, r / 2, estar(m, m), v);
            if (c < tc)
                tc = c;
        }
    }
    ts->rayleigh_time = tr;
    ts->recommended_dt = 0.2 * tr;
    ts->max_dt = 0.5 * tr;
    /* springs and hinges: velocity Verlet is stable for omega dt < 2 (dt < T / pi) and misses the period by (omega dt)^2 / 24:
     * 10 steps per period (1.6 %) bound it, 50 (0.07 %) are recommended */
    ts->spring_period = INFINITY;
    /* the tables name particles by id; the per-particle arrays are in storage order (host/core/reorder.c) */
    int *hg = s->order.count && s->mesh.nhinges ? malloc(sizeof(int) * 4 * (size_t)s->mesh.nhinges) : s->mesh.hinge;
    if (s->mesh.nhinges && !hg)
        return sim_fail(s, DEM_ERR_NOMEM, "out of memory for the hinges' time scales");
    for (int k = 0; hg != s->mesh.hinge && k < 4 * s->mesh.nhinges; k++)
        hg[k] = sim_dev(s, s->mesh.hinge[k]);
    for (int k = 0; k < s->mesh.nsprings; k++) { /* a fixed end has no inverse mass; two fixed ends, no period */
        double ia = inverse_mass(s, sim_dev(s, s->mesh.spring_ij[2 * k]));
        double ib = inverse_mass(s, sim_dev(s, s->mesh.spring_ij[2 * k + 1]));
        if (ia + ib > 0)
            ts->spring_period = fmin(ts->spring_period, 2 * M_PI * sqrt(1 / (ia + ib) / s->mesh.spring_kr[3 * k]));
    }
    ts->hinge_period = ts->hinge_damping_time = INFINITY;
    for (int h = 0; h < s->mesh.nhinges; h++) {
        double m4[4];
        for (int k = 0; k < 4; k++) /* a fixed vertex: an infinite mass, no share in the fold's motion */
            m4[k] = inverse_mass(s, hg[4 * h + k]) > 0 ? sim_mass(s, hg[4 * h + k]) : INFINITY;
        ts->hinge_period = fmin(ts->hinge_period, dem_hinge_period(s->x, hg + 4 * h, s->mesh.hinge_k[3 * h], m4));
    }
    if (s->mesh.nhinges) {
        double *sqrt_im = malloc(sizeof(double) * (size_t)s->n), rate = -1;
        for (int i = 0; sqrt_im && i < s->n; i++)
            sqrt_im[i] = sqrt(inverse_mass(s, i));
        if (sqrt_im)
            rate = dem_hinge_damping_rate(s->x, hg, s->mesh.hinge_k, s->mesh.nhinges, sqrt_im, s->n);
        free(sqrt_im);
        if (rate < 0) {
            if (hg != s->mesh.hinge)
                free(hg);
            return sim_fail(s, DEM_ERR_NOMEM, "out of memory for the hinges' damping rate");
        }
        if (rate > 0)
            ts->hinge_damping_time = 1 / rate;
    }
    if (hg != s->mesh.hinge)
        free(hg);
    double t_osc = fmin(ts->spring_period, ts->hinge_period);
    ts->recommended_dt = fmin(ts->recommended_dt, t_osc / 50);
    ts->max_dt = fmin(ts->max_dt, t_osc / 10);
    /* the hinges' dissipative term: lambda dt < 2 is the explicit limit; the bound keeps lambda dt <= 1 (each step then
     * removes at most all of a mode's speed, never reverses it), and 0.5 is recommended */
    ts->recommended_dt = fmin(ts->recommended_dt, 0.5 * ts->hinge_damping_time);
    ts->max_dt = fmin(ts->max_dt, ts->hinge_damping_time);
    ts->hertz_time = v > 0 ? tc : 0;
    return 0;
}

/* The fastest a wall's stages bring it onto the particles: a plane's speed along its normal towards them, in the stages
 * that reach the particles as placed (its travel along the normal, ramps counted, at least the gap to the nearest
 * sphere by the stage's end) or that press them (a servo: its max_speed); a fast approach that stops short, or a
 * stage that moves the plane away or along itself, brings no impact. A cylinder: its fastest stage, whatever it
 * does. */
static double wall_approach_speed(const dem_sim *s, int w)
{
    const dem_wall *wl = &s->walls[w];
    double ws = 0, nn = sqrt(wl->normal[0] * wl->normal[0] + wl->normal[1] * wl->normal[1] +
                             wl->normal[2] * wl->normal[2]);
    if (wl->kind != DEM_WALL_PLANE || !(nn > 0)) {
        for (int st = 0; st < wl->nstages; st++) {
            const double *u = wl->stages[st].velocity;
            ws = fmax(ws, wl->stages[st].force > 0 ? wl->stages[st].max_speed : sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
        }
        return ws;
    }
    double gap = INFINITY, travel = 0;
    for (int i = 0; i < s->n; i++) {
        const double *x = s->x + 3 * i;
        double h = ((x[0] - wl->point[0]) * wl->normal[0] + (x[1] - wl->point[1]) * wl->normal[1] +
                    (x[2] - wl->point[2]) * wl->normal[2]) / nn - s->radius[i];
        gap = fmin(gap, h);
    }
    for (int st = 0; st < wl->nstages; st++) {
        const dem_stage *g = &wl->stages[st];
        if (g->force > 0) { /* a servo presses whatever is there, at up to its max_speed */
            ws = fmax(ws, g->max_speed);
            continue;
        }
        double vn = (g->velocity[0] * wl->normal[0] + g->velocity[1] * wl->normal[1] + g->velocity[2] * wl->normal[2]) / nn;
        travel += dem_stage_travel(wl->stages, st, wl->normal); /* ramps counted */
        if (vn > 0 && travel >= gap)
            ws = fmax(ws, vn);
    }
    return ws;
}

int dem_contact_advice_get(dem_sim *s, dem_contact_advice *a)
{
    memset(a, 0, sizeof *a);
    a->pair_time = a->wall_time = a->contact_time = INFINITY;
    a->wall = -1;
    if (s->n == 0)
        return sim_fail(s, DEM_ERR_ARG, "contact times need particles");
    /* the fastest particle (gravity is left out: a settled bed is not falling, and a pour's impact speed is
     * sqrt(2 g h) of its own drop height, which the user knows better than a bound would) */
    double vmax = 0, fall = 0;
    for (int i = 0; i < s->n; i++) {
        const double *v = s->v + 3 * i;
        vmax = fmax(vmax, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
    a->pair_speed = 2 * vmax + fall;
    double stage_max = 0, ws_of[DEM_MAX_WALLS]; /* each wall's approach speed, once: it scans every particle */
    for (int w = 0; (s->effects & DEM_EFFECT_WALLS) && w < s->nwalls; w++)
        stage_max = fmax(stage_max, ws_of[w] = wall_approach_speed(s, w));
    for (int i = 0; i < s->n; i++) {
        const dem_material *m = &s->mats[s->mat[i]];
        double r = s->radius[i], mass = sim_mass(s, i);
        if (a->pair_speed > 0)
            a->pair_time = fmin(a->pair_time, dem_hertz_contact_time(mass / 2, r / 2, estar(m, m), a->pair_speed));
        if (!(s->effects & DEM_EFFECT_WALLS))
            continue;
        for (int w = 0; w < s->nwalls; w++) {
            double v = vmax + ws_of[w] + fall;
            if (!(v > 0))
                continue;
            double t = dem_hertz_contact_time(mass, r, estar(m, &s->mats[s->walls[w].material]), v);
            if (t < a->wall_time)
                a->wall_time = t, a->wall = w;
        }
    }
    a->wall_speed = s->nwalls && (s->effects & DEM_EFFECT_WALLS) ? vmax + stage_max + fall : 0;
    a->contact_time = fmin(a->pair_time, a->wall_time);
    a->steps = s->dt > 0 && isfinite(a->contact_time) ? a->contact_time / s->dt : 0;
    return 0;
}

/* MDR (common/laws/mdr.h): every particle's material yields, and all of them are one MDR material (the law presses each
 * sphere of a pair on a flat with its own modulus and averages: a mixed pair is not specified, docs/laws/mdr.md (M1)) */
/* Whether two materials are the same MDR material (what the mdr law reads of them) */
static int same_mdr_material(const dem_material *m, const dem_material *f)
{
    return m->young == f->young && m->poisson == f->poisson && m->yield_stress == f->yield_stress &&
           m->surface_energy == f->surface_energy && m->bulk_fraction == f->bulk_fraction &&
           m->mdr_damping == f->mdr_damping;
}

static int validate_mdr(dem_sim *s)
{
    if (!(s->effects & DEM_EFFECT_MDR))
        return 0;
    for (int a = 0; a < s->nmat; a++)
        for (int b = a; b < s->nmat; b++)
            if (s->pair_set[a][b] && !isnan(s->pair_props[a][b].surface_energy))
                return sim_fail(s, DEM_ERR_ARG, "materials %d and %d: a pair's own surface_energy is thornton_ning's "
                                "adhesion; the mdr law takes its materials' (a wall's own at a wall)", a, b);
    int first = -1;
    for (int i = 0; i < s->n; i++) {
        int k = s->mat[i];
        const dem_material *m = &s->mats[k], *f = first >= 0 ? &s->mats[first] : m;
        if (!(m->yield_stress > 0) || !(m->poisson < 0.5) || !isfinite(m->young))
            return sim_fail(s, DEM_ERR_ARG, "particle %d: the mdr law needs its material %d to yield (yield_stress > 0, "
                            "got %g Pa), to be compressible (poisson < 0.5, got %g) and not rigid", i, k,
                            m->yield_stress, m->poisson);
        if (!same_mdr_material(m, f))
            return sim_fail(s, DEM_ERR_ARG, "particle %d: the mdr law has one particle material (young, poisson, "
                            "yield_stress, surface_energy, bulk_fraction, mdr_damping alike), and materials %d and %d "
                            "differ", i, first, k);
        first = k;
    }
    /* a wall of a material that yields would give the sphere's surface energy instead of its own (pack_pairs): only
     * the particles' own MDR material may yield among the walls' */
    for (int w = 0; first >= 0 && w < s->nwalls; w++) {
        const dem_material *m = &s->mats[s->walls[w].material], *f = &s->mats[first];
        if (m->yield_stress > 0 && !same_mdr_material(m, f))
            return sim_fail(s, DEM_ERR_ARG, "wall %d: under the mdr law a wall's material does not yield (yield_stress "
                            "0: it gives the wall's surface energy; the sphere's properties act at the wall) or is the "
                            "particles' own MDR material; material %d is neither", w, s->walls[w].material);
    }
    return 0;
}

/* The work of adhesion of materials a and b (DEM_EFFECT_ADHESION): the pair's own (dem_set_material_pair), else the
 * geometric mean of their surface energies (Berthelot's rule for dispersion forces; a tool's steel left at 0 adheres
 * to nothing) */
static double pair_adhesion(const dem_sim *s, int a, int b)
{
    const dem_material_pair *pp = s->pair_set[a][b] ? &s->pair_props[a][b] : NULL;
    if (pp && !isnan(pp->surface_energy))
        return pp->surface_energy;
    return sqrt(s->mats[a].surface_energy * s->mats[b].surface_energy);
}

/* The bond strength of materials a and b: the pair's own (dem_set_material_pair), else the weaker of the two (a tool's
 * steel, 0, bonds to nothing) */
static double pair_bond(const dem_sim *s, int a, int b)
{
    const dem_material_pair *pp = s->pair_set[a][b] ? &s->pair_props[a][b] : NULL;
    return pp && !isnan(pp->bond_strength) ? pp->bond_strength : fmin(s->mats[a].bond_strength, s->mats[b].bond_strength);
}

/* Thornton-Ning's JKR adhesion (DEM_EFFECT_ADHESION): some pair of materials adheres (both give a surface_energy and
 * one yields), and no pair both adheres and bonds: a bond is that law's other adhesion, over the yielded area, and
 * the two are not combined (thornton_ning.h) */
static int validate_adhesion(dem_sim *s)
{
    if (!(s->effects & DEM_EFFECT_ADHESION))
        return 0;
    int any = 0;
    for (int a = 0; a < s->nmat; a++)
        for (int b = a; b < s->nmat; b++) {
            const dem_material *ma = &s->mats[a], *mb = &s->mats[b];
            if (!(pair_adhesion(s, a, b) > 0) || !(ma->yield_stress > 0 || mb->yield_stress > 0))
                continue;
            any = 1;
            double sb = pair_bond(s, a, b);
            if (sb > 0)
                return sim_fail(s, DEM_ERR_ARG, "materials %d and %d both adhere (surface_energy, the effect adhesion) "
                                "and bond (bond_strength %g Pa): thornton_ning takes one adhesion per pair", a, b, sb);
        }
    if (!any)
        return sim_fail(s, DEM_ERR_ARG, "the effect adhesion is on but no pair of materials adheres: it needs two "
                        "surfaces with surface_energy > 0 (or a pair's own), one of which yields (yield_stress > 0)");
    return 0;
}

int sim_validate(dem_sim *s)
{
    int e;
    if (s->n == 0)
        return sim_fail(s, DEM_ERR_ARG, "no particles");
    if (!(s->dt > 0) || !isfinite(s->dt))
        return sim_fail(s, DEM_ERR_ARG, "time step not set (dem_set_dt)");
    for (int k = 0; k < s->nwalls; k++) /* a stage waits for a wall and a stage that exist (dem_stage.after_wall) */
        for (int st = 0; st < s->walls[k].nstages; st++) {
            const dem_stage *g = &s->walls[k].stages[st];
            if ((g->after_wall || g->after_stage) &&
                (g->after_wall >= s->nwalls || g->after_wall == k || g->after_stage > s->walls[g->after_wall].nstages))
                return sim_fail(s, DEM_ERR_ARG, "wall %d stage %d waits for wall %d's stage %d: no such %s", k, st,
                                g->after_wall, g->after_stage, g->after_wall == k ? "other wall" : "wall or stage");
        }
    s->rmin = INFINITY;
    s->rmax = 0;
    for (int i = 0; i < s->n; i++) {
        if (s->radius[i] < s->rmin)
            s->rmin = s->radius[i];
        if (s->radius[i] > s->rmax)
            s->rmax = s->radius[i];
    }
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    if (s->dt > ts.max_dt && !s->cfg.force_dt) {
        char why[160];
        dem_time_scales_limit(&ts, why, sizeof why);
        return sim_fail(s, DEM_ERR_DT, "time step %.6g s exceeds the stability bound %.6g s (%s; recommended %.6g s); "
                        "set force_dt to run anyway", s->dt, ts.max_dt, why, ts.recommended_dt);
    }
    for (int k = 0; k < s->nwalls; k++) {
        const dem_wall *w = &s->walls[k];
        if (w->kind == DEM_WALL_CYLINDER)
            for (int i = 0; i < s->n; i++)
                if (s->radius[i] >= w->radius)
                    return sim_fail(s, DEM_ERR_ARG, "particle %d (radius %g m) does not fit in cylinder wall %d "
                                    "(radius %g m)", i, s->radius[i], k, w->radius);
    }
    if (s->nwalls && !(s->effects & DEM_EFFECT_WALLS))
        return sim_fail(s, DEM_ERR_ARG, "%d walls are defined but the effect 'walls' is off", s->nwalls);
    if ((e = validate_mdr(s)) || (e = validate_adhesion(s)))
        return e;
    s->motion.particle_volume = sim_particle_volume(s); /* until_density's: the same bits as dem_relative_density's */
    for (int k = 0; k < s->nwalls; k++) { /* until_density: the die and the punch facing this one */
        const dem_wall *w = &s->walls[k];
        int wants = 0;
        for (int st = 0; st < w->nstages; st++)
            wants |= w->stages[st].until_density > 0;
        s->motion.density_die[k] = s->motion.density_other[k] = -1;
        if (wants && dem_density_walls(s, k, &s->motion.density_die[k], &s->motion.density_other[k]))
            return sim_fail(s, DEM_ERR_ARG, "wall %d: a stage ends at a relative density (until_density), which needs "
                            "a die (a cylinder wall along its normal) and a punch facing it on the particles' side: "
                            "found %s", k, s->motion.density_die[k] < 0 ? "no such cylinder" : "no facing plane wall");
        for (int q = 0; wants && q < 2; q++) { /* the cups' volumes count as the bore's (dem_relative_density) */
            int p = q ? s->motion.density_other[k] : k;
            if (!dem_cup_in_bore(s, p, s->motion.density_die[k]))
                return sim_fail(s, DEM_ERR_ARG, "wall %d: a stage ends at a relative density, and punch %d's cup "
                                "(radius %g m) does not lie within the die's bore (radius %g m)", k, p,
                                s->walls[p].cup_radius, s->walls[s->motion.density_die[k]].radius);
        }
    }
    if (s->mesh.nsprings && !(s->effects & DEM_EFFECT_SPRINGS))
        return sim_fail(s, DEM_ERR_ARG, "%d springs are defined but the effect 'springs' is off", s->mesh.nsprings);
    if (s->mesh.nhinges && !(s->effects & DEM_EFFECT_BENDING))
        return sim_fail(s, DEM_ERR_ARG, "%d hinges are defined but the effect 'bending' is off", s->mesh.nhinges);
    if (s->cfg.skin < 0 || !isfinite(s->cfg.skin))
        return sim_fail(s, DEM_ERR_ARG, "skin must be >= 0 (got %g)", s->cfg.skin);
    if (s->cfg.reorder < 0)
        return sim_fail(s, DEM_ERR_ARG, "reorder must be >= 0 rebuilds (got %d)", s->cfg.reorder);
    if (!(s->cfg.reorder_gain >= 0) || !isfinite(s->cfg.reorder_gain))
        return sim_fail(s, DEM_ERR_ARG, "reorder_gain must be >= 0 (got %g)", s->cfg.reorder_gain);
    if (s->cfg.precision != DEM_FP32 && s->cfg.precision != DEM_FP64)
        return sim_fail(s, DEM_ERR_ARG, "precision must be DEM_FP32 or DEM_FP64");
    return 0;
}

/* Converts n doubles into the run precision. */
static void *pack_real(const double *src, size_t n, int rs)
{
    void *p = calloc(n ? n : 1, (size_t)rs);
    if (!p)
        return NULL;
    for (size_t k = 0; k < n; k++) {
        if (rs == 8)
            ((double *)p)[k] = src[k];
        else
            ((float *)p)[k] = (float)src[k];
    }
    return p;
}

/* The setup's host arrays (what create uploads; a few the host reads by place after the start: ride, sid, order)
 * are owned by the simulation, listed here to be freed when packed again or destroyed. keep(s, p) lists p and returns
 * it; NULL (out of memory) sets the simulation's error and stays NULL. */
static void *keep(dem_sim *s, void *p)
{
    void **grown = p && s->nsetup_mem == s->setup_mem_cap
                       ? realloc(s->setup_mem, sizeof(void *) * (size_t)(s->setup_mem_cap * 2 + 16))
                       : NULL;
    if (grown)
        s->setup_mem = grown, s->setup_mem_cap = s->setup_mem_cap * 2 + 16;
    if (p && s->nsetup_mem < s->setup_mem_cap) {
        s->setup_mem[s->nsetup_mem++] = p;
        return p;
    }
    free(p);
    sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    return NULL;
}

void sim_setup_free(dem_sim *s)
{
    for (int k = 0; k < s->nsetup_mem; k++)
        free(s->setup_mem[k]);
    s->nsetup_mem = 0;
}

int sim_stage_now(const dem_sim *s, int k, long *first)
{
    int st = s->motion.stage_cur[k];
    *first = s->motion.stage_first[k];
    return st < s->walls[k].nstages ? st : -1;
}

void sim_stages_from_step(dem_sim *s)
{
    s->motion.stage_log_n = 0; /* the ends logged are those from here on */
    for (int k = 0; k < s->nwalls; k++) {
        long start = 0;
        int st = 0;
        while (st < s->walls[k].nstages && s->run.step >= start + s->motion.stage_steps[k][st])
            start += s->motion.stage_steps[k][st++];
        s->motion.stage_cur[k] = st;
        s->motion.stage_first[k] = start;
        memcpy(s->motion.stage_from[k], s->motion.pos[k], sizeof(double) * 3); /* only a distance-ended stage reads it */
    }
}

/* Whether wall k's stage st waits for another wall (dem_stage.after_wall) at this step: the wall rests */
static int stage_waits(const dem_sim *s, int k, int st)
{
    const dem_stage *g = &s->walls[k].stages[st];
    return s->motion.stage_cur[g->after_wall] < g->after_stage;
}

void sim_wall_velocity(const dem_sim *s, int k, double v[3])
{
    long first;
    int st = sim_stage_now(s, k, &first);
    v[0] = v[1] = v[2] = 0;
    if (st < 0 || stage_waits(s, k, st))
        return;
    const dem_stage *g = &s->walls[k].stages[st];
    /* a servo stage: the velocity dem_step worked out (walls.c) */
    memcpy(v, g->force > 0 ? s->motion.servo_v[k] : g->velocity, sizeof(double) * 3);
    long ran = s->run.step - first, nr = lround(g->ramp / s->dt);
    if (g->force > 0 || ran >= nr) /* nr = 0: no ramp */
        return;
    /* the ramp: from the previous stage's velocity (0 after a servo stage or for the first) to this one's, at the
     * midpoint of each step */
    const dem_stage *prev = st > 0 ? &s->walls[k].stages[st - 1] : NULL;
    double f = ((double)ran + 0.5) / (double)nr;
    for (int d = 0; d < 3; d++) {
        double v0 = prev && !(prev->force > 0) ? prev->velocity[d] : 0;
        v[d] = v0 + (v[d] - v0) * f;
    }
}

void sim_pack_walls(dem_sim *s)
{
    double tab[W_STRIDE * DEM_MAX_WALLS];
    for (int k = 0; k < s->nwalls; k++) {
        const dem_wall *w = &s->walls[k];
        double *t = tab + k * W_STRIDE, v[3];
        /* velocity of the step being taken (step index s->run.step, moving the wall from t to t + dt) */
        sim_wall_velocity(s, k, v);
        for (int d = 0; d < 3; d++) {
            t[W_PX + d] = s->motion.pos[k][d];
            t[W_NX + d] = w->normal[d];
            t[W_VX + d] = v[d];
        }
        sim_wall_table(w, &t[W_RADIUS], &t[W_HEIGHT]);
    }
    int rs = s->setup.real_size;
    for (int k = 0; k < W_STRIDE * s->nwalls; k++) {
        if (rs == 8)
            ((double *)s->motion.table)[k] = tab[k];
        else
            ((float *)s->motion.table)[k] = (float)tab[k];
    }
}

/* sim_pack in phases: what the kernels are compiled with, the bodies, the material pairs, the packing into the run's
 * precision with the walls, and the binning grid. */

/* whether any wall has a servo stage (walls are fixed once started: dem_start asks once) */
int sim_has_servo(const dem_sim *s)
{
    for (int k = 0; k < s->nwalls; k++)
        for (int st = 0; st < s->walls[k].nstages; st++)
            if (s->walls[k].stages[st].force > 0 || s->walls[k].stages[st].until_force > 0)
                return 1;
    return 0;
}

/* Effects and the convention bits compiled in with them. */
static void pack_effects(dem_sim *s, dem_setup *u)
{
    /* the MC-stress convention is compiled in with the effects (only when MC-stress is on: other runs' kernels and
     * their cached binaries stay as they were) */
    u->effects = s->effects | ((s->effects & DEM_EFFECT_MC_STRESS) ? s->mc.stress_conv : 0u);
    int reach = (s->effects & DEM_EFFECT_MC_STRAIN) && s->mc.reach > 1; /* compiled in only when it can act */
    if (reach)
        u->effects |= DEM_MC_REACH;
    /* the force from each wall on each particle is kept where it is read: by the contact network, and by the
     * walls' sums when they are due every step (a servo): evaluating the wall contacts again for the sums costs
     * about 7 % of such a step (1e5 spheres, 5 walls), while a sum over kept forces costs 2 %; and by the sums of
     * frequent samples (a series row every few steps) for the same reason */
    int sampled = s->cfg.sample_every > 0 && s->cfg.sample_every <= DEM_SAMPLE_KEEP;
    if ((s->cfg.contacts || sampled || sim_has_servo(s)) && s->nwalls > 0 && (s->effects & DEM_EFFECT_WALLS))
        u->effects |= DEM_KEEP_WALL_FORCES;
    /* a law with memory keeps its pairs' energies, computed where the contact's state is at hand (series.h) */
    if (sampled || (s->effects & DEM_LAW_STATE_BITS))
        u->effects |= DEM_KEEP_PAIR_ENERGY;
    /* one pass over the rows (common/contact_rows.h) where the law keeps nothing per pair but the history */
    if (s->cfg.one_pass && !(s->effects & DEM_ONE_PASS_REFUSED) && !s->ghost)
        u->effects |= DEM_ONE_PASS | ((s->effects & DEM_EFFECT_FRICTION) ? DEM_ONE_PASS_HIST : 0u);
    if (s->ghost) /* a rank's part of a split run: its ghosts left out of the walls' sums */
        u->effects |= DEM_HAS_GHOSTS;
    u->n = s->n;
    u->nmat = s->nmat;
    u->nwalls = s->nwalls;
}

/* Per particle: inverse mass, inverse moment of inertia, inverse volume (double). */
static void pack_bodies(const dem_sim *s, double *invm, double *invi, double *invv)
{
    for (int i = 0; i < s->n; i++) {
        double r = s->radius[i], mass = sim_mass(s, i);
        invm[i] = (s->pflags[i] & DEM_PARTICLE_FIXED) ? 0 : 1 / mass;
        invi[i] = (s->pflags[i] & (DEM_PARTICLE_FIXED | DEM_PARTICLE_NO_ROTATION)) ? 0 : 1 / sim_inertia(s, i);
        invv[i] = 1 / (4.0 / 3.0 * M_PI * r * r * r);
    }
}

/* The material-pair table (dem_layout.h PM_*), double; damp: scratch of nmat^2. */
static void pack_pairs(const dem_sim *s, double *pm, double *damp)
{
    /* pair table: restitution and friction of a pair are the means of the two materials' values, unless the pair is
     * set apart (dem_set_material_pair) */
    for (int a = 0; a < s->nmat; a++)
        for (int b = 0; b < s->nmat; b++) {
            const dem_material *ma = &s->mats[a], *mb = &s->mats[b];
            double *row = pm + PM_STRIDE * (a * s->nmat + b);
            row[PM_ESTAR] = estar(ma, mb);
            row[PM_GSTAR] = gstar(ma, mb);
            /* a pair set apart (dem_set_material_pair) takes its own values where given */
            const dem_material_pair *pp = s->pair_set[a][b] ? &s->pair_props[a][b] : NULL;
            row[PM_MU] = pp && !isnan(pp->friction) ? pp->friction : 0.5 * (ma->friction + mb->friction);
            double e = pp && !isnan(pp->restitution) ? pp->restitution : 0.5 * (ma->restitution + mb->restitution);
            double c = (a <= b) ? dem_damping_for_restitution(e) : damp[b * s->nmat + a];
            damp[a * s->nmat + b] = c;
            row[PM_DAMP_N] = c * sqrt(2 * row[PM_ESTAR]);
            row[PM_DAMP_T] = c * sqrt(8 * row[PM_GSTAR]);
            /* multi-contact (seed 000 Eq. 7, 10): the pair's pi beta nu is the mean of the two materials'; the
             * MC-strain constants are those of material a (read on the diagonal only, see dem_layout.h) */
            row[PM_MC_STRESS] = M_PI * 0.5 * (ma->mc_beta * ma->poisson + mb->mc_beta * mb->poisson);
            row[PM_MCS_K] = ma->mc_gamma * (1 + ma->poisson) / (2 * M_PI * ma->young);
            row[PM_MCS_C1] = 3 - 4 * ma->poisson;
            row[PM_MCS_C2] = 1 - 2 * ma->poisson;
            row[PM_MC_REACH] = s->mc.reach;
            row[PM_APART] = a == b && s->mat_apart[a];
            /* Thornton-Ning: the pair yields at the smaller limiting pressure of its materials that yield */
            double py = ma->yield_stress > 0 && (mb->yield_stress <= 0 || ma->yield_stress < mb->yield_stress)
                            ? ma->yield_stress
                            : mb->yield_stress;
            double ky = M_PI * py / (2 * row[PM_ESTAR]);
            row[PM_TN_PIPY] = M_PI * py;
            row[PM_TN_DY] = ky * ky;
            row[PM_TN_FY] = 4.0 / 3.0 * row[PM_ESTAR] * ky * ky * ky;
            row[PM_MU_ROLL] = pp && !isnan(pp->rolling_friction) ? pp->rolling_friction
                                                                : 0.5 * (ma->rolling_friction + mb->rolling_friction);
            row[PM_ROLL_DAMP] = 0.5 * (ma->rolling_damping + mb->rolling_damping);
            double sb = pair_bond(s, a, b);
            row[PM_TN_SIGB] = py > 0 ? M_PI * sb : 0;
            /* JKR adhesion (DEM_EFFECT_ADHESION) */
            double wad = pair_adhesion(s, a, b);
            row[PM_TN_K] = (s->effects & DEM_EFFECT_ADHESION) && py > 0 && wad > 0 ? sqrt(2 * M_PI * wad / row[PM_ESTAR]) : 0;
            /* MDR: the sphere's material is the one that yields (sim_validate: an MDR run has one such); at a wall
             * (a material that does not yield) the wall's surface energy, as in LAMMPS */
            const dem_material *sp = mb->yield_stress > 0 && !(ma->yield_stress > 0) ? mb : ma;
            const dem_material *tool = sp == ma ? mb : ma;
            double E = sp->young, nu = sp->poisson;
            row[PM_MDR + 0] = E / (1 - nu * nu);
            row[PM_MDR + 1] = E / (2 * (1 + nu));
            row[PM_MDR + 2] = nu < 0.5 ? E / (3 * (1 - 2 * nu)) : 0;
            row[PM_MDR + 3] = nu;
            row[PM_MDR + 4] = sp->yield_stress;
            row[PM_MDR + 5] = tool->yield_stress > 0 ? sp->surface_energy : tool->surface_energy;
            row[PM_MDR + 6] = sp->bulk_fraction;
            row[PM_MDR + 7] = sp->mdr_damping;
        }
}

/* The springs' and triangles' tables and their contribution channel (common/springs.h), naming particles by stable id
 * (packed at dem_start, where each particle is stored at its id; they stay so when it is stored anew, reorder.c):
 * particle p's records at chan_start[p] .. chan_start[p+1] - its spring ends in ascending spring index, then its triangle vertices in
 * ascending triangle index - so that every device adds them in one order. chan_slot: 2 per spring, then 3 per
 * triangle. A rest length < 0 is the distance of the initial positions; the damping constant 2 gamma
 * sqrt(k m_eff) is computed here in double. */
static int pack_channel(dem_sim *s, dem_setup *u, int rs)
{
    int ns = s->mesh.nsprings, nt = s->mesh.ntri, nh = s->mesh.nhinges, n = s->n;
    int *ij = calloc(2 * (size_t)ns + 1, sizeof(int));
    int *slot = calloc(2 * (size_t)ns + 3 * (size_t)nt + 4 * (size_t)nh + 1, sizeof(int));
    int *start = calloc((size_t)n + 1, sizeof(int)), *fill = calloc((size_t)n + 1, sizeof(int));
    int *tri = calloc(3 * (size_t)nt + 1, sizeof(int)), *hg = calloc(4 * (size_t)nh + 1, sizeof(int));
    double *kr = calloc(SP_STRIDE * (size_t)ns + 1, sizeof(double)), *hk = calloc(HG_STRIDE * (size_t)nh + 1,
                                                                                   sizeof(double));
    if (!ij || !slot || !start || !fill || !tri || !kr || !hg || !hk) {
        free(ij), free(slot), free(start), free(fill), free(tri), free(kr), free(hg), free(hk);
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    for (int k = 0; k < ns; k++)
        start[s->mesh.spring_ij[2 * k] + 1]++, start[s->mesh.spring_ij[2 * k + 1] + 1]++;
    for (int t = 0; t < 3 * nt; t++)
        start[s->mesh.tri[t] + 1]++;
    for (int t = 0; t < 4 * nh; t++)
        start[s->mesh.hinge[t] + 1]++;
    for (int p = 0; p < n; p++)
        start[p + 1] += start[p];
    for (int k = 0; k < ns; k++) {
        int a = s->mesh.spring_ij[2 * k], b = s->mesh.spring_ij[2 * k + 1];
        ij[2 * k] = a, ij[2 * k + 1] = b;
        slot[2 * k] = start[a] + fill[a]++;
        slot[2 * k + 1] = start[b] + fill[b]++;
        double kk = s->mesh.spring_kr[3 * k], rest = s->mesh.spring_kr[3 * k + 1], gamma = s->mesh.spring_kr[3 * k + 2];
        if (rest < 0) {
            const double *xa = s->x + 3 * a, *xb = s->x + 3 * b;
            rest = sqrt((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]) +
                        (xa[2] - xb[2]) * (xa[2] - xb[2]));
        }
        double ma = sim_mass(s, a), mb = sim_mass(s, b);
        kr[SP_STRIDE * k + SP_K] = kk;
        kr[SP_STRIDE * k + SP_REST] = rest;
        kr[SP_STRIDE * k + SP_DAMP] = 2 * gamma * sqrt(kk * ma * mb / (ma + mb));
    }
    for (int t = 0; t < 3 * nt; t++) { /* after every spring: a particle's triangles follow its springs */
        tri[t] = s->mesh.tri[t];
        slot[2 * ns + t] = start[tri[t]] + fill[tri[t]]++;
    }
    for (int h = 0; h < nh; h++) { /* then its hinges; the rest angle as s(theta0) = sin(theta0 / 2) (bending.h) */
        for (int k = 0; k < 4; k++) {
            hg[4 * h + k] = s->mesh.hinge[4 * h + k];
            slot[2 * ns + 3 * nt + 4 * h + k] = start[hg[4 * h + k]] + fill[hg[4 * h + k]]++;
        }
        double th0 = s->mesh.hinge_k[3 * h + 2];
        hk[HG_STRIDE * h + HG_KEL] = s->mesh.hinge_k[3 * h];
        hk[HG_STRIDE * h + HG_KDISS] = s->mesh.hinge_k[3 * h + 1];
        hk[HG_STRIDE * h + HG_SIN0] = isnan(th0) ? dem_hinge_rest_shalf(s->x, hg + 4 * h) : sin(0.5 * th0);
    }
    u->nsprings = ns, u->spring_int = keep(s, ij), u->chan_slot = keep(s, slot), u->chan_start = keep(s, start);
    u->spring_real = keep(s, pack_real(kr, SP_STRIDE * (size_t)ns, rs));
    u->ntriangles = nt, u->tri = keep(s, tri), u->pressure = s->mesh.pressure;
    u->nhinges = nh, u->hinge_int = keep(s, hg), u->hinge_real = keep(s, pack_real(hk, HG_STRIDE * (size_t)nh, rs));
    free(fill), free(kr), free(hk);
    return u->spring_int && u->chan_slot && u->chan_start && u->spring_real && u->tri && u->hinge_int && u->hinge_real
               ? 0 : DEM_ERR_NOMEM;
}

/* The riders' table (common/riders.h): particle and wall, and the particle's offset from the wall's point at the
 * start (after pack_walls) */
static int pack_riders(dem_sim *s, dem_setup *u, int rs)
{
    int nr = s->mesh.natt;
    int *ri = malloc(sizeof(int) * 2 * (size_t)(nr ? nr : 1));
    double *off = malloc(sizeof(double) * 3 * (size_t)(nr ? nr : 1));
    if (!ri || !off)
        return free(ri), free(off), sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (int k = 0; k < nr; k++) {
        int p = s->mesh.att[2 * k], w = s->mesh.att[2 * k + 1];
        ri[2 * k] = p, ri[2 * k + 1] = w;
        for (int d = 0; d < 3; d++)
            off[3 * k + d] = s->x[3 * p + d] - s->motion.pos[w][d];
    }
    unsigned *ride = calloc((size_t)s->n, sizeof(unsigned));
    for (int k = 0; ride && k < nr; k++)
        ride[ri[2 * k]] |= 1u << ri[2 * k + 1];
    u->nriders = nr, u->rider_int = keep(s, ri), u->rider_off = keep(s, pack_real(off, 3 * (size_t)nr, rs));
    u->ride = keep(s, ride);
    free(off);
    return u->rider_int && u->rider_off && u->ride ? 0 : DEM_ERR_NOMEM;
}

/* The walls' integer table and start positions, and the real table of step 0. */
static void pack_walls(dem_sim *s, int *wint)
{
    for (int k = 0; k < s->nwalls; k++) {
        double rad, hgt;
        wint[k * WI_STRIDE + WI_TYPE] = sim_wall_table(&s->walls[k], &rad, &hgt);
        wint[k * WI_STRIDE + WI_MATERIAL] = s->walls[k].material;
        memcpy(s->motion.pos[k], s->walls[k].point, sizeof(double) * 3);
    }
    sim_pack_walls(s);
}

/* The binning domain before it is cut into cells: the given one, or the particles' bounding box padded by half its
 * extent, 4 r_max and the deepest punch cup on each side (a fill settles into a concave punch's cup, below its land);
 * the bounding box into pmin, pmax. */
void sim_domain_bounds(const dem_sim *s, double rmax, double lo[3], double hi[3], double pmin[3], double pmax[3])
{
    for (int d = 0; d < 3; d++)
        pmin[d] = INFINITY, pmax[d] = -INFINITY;
    for (int i = 0; i < s->n; i++) /* the particles' bounding box */
        for (int d = 0; d < 3; d++) {
            pmin[d] = fmin(pmin[d], s->x[3 * i + d]);
            pmax[d] = fmax(pmax[d], s->x[3 * i + d]);
        }
    if (s->domain.given) {
        memcpy(lo, s->domain.lo, sizeof(double) * 3);
        memcpy(hi, s->domain.hi, sizeof(double) * 3);
        return;
    }
    double cup = 0;
    for (int k = 0; k < s->nwalls; k++)
        cup = fmax(cup, s->walls[k].cup_depth);
    for (int d = 0; d < 3; d++) {
        double pad = 0.5 * (pmax[d] - pmin[d]) + 4 * rmax + cup;
        lo[d] = pmin[d] - pad;
        hi[d] = pmax[d] + pad;
    }
}

/* The binning grid: the domain (given, or the particles' padded bounding box) cut into cubic cells. Returns the
 * skin actually used; the cell size goes to u->inv_cell. */
static double pack_grid(dem_sim *s, dem_setup *u)
{
    int n = s->n;
    /* binning grid: cubic cells no smaller than 1.01 x the largest interaction range; the 1 % margin keeps a
     * rounding of (x - lo)/cell in fp32 from ever placing a neighbour two cells away */
    double skin = s->cfg.skin > 0 ? s->cfg.skin : DEM_SKIN_AUTO_HI * s->rmin;
    /* rows are built to the interaction range plus the skin: with the MC-strain contact distance the range is
     * F (r_i + r_j) <= r_i + r_j + 2 (F - 1) r_max; the rebuild trigger stays at half the skin itself */
    /* MDR's radii grow to 1.5 R_o (M34; mdr_particle.h): the cells hold the grown pairs, the rows the radii of their
     * build (a growth counts against the skin) */
    double reach_extra = ((u->effects & DEM_MC_REACH) ? 2 * (s->mc.reach - 1) * s->rmax : 0) +
                         ((u->effects & DEM_EFFECT_MDR) ? 1.01 * s->rmax : 0);
    double cell = 1.01 * (2 * s->rmax + skin + reach_extra);
    if (s->cfg.cell_size > cell)
        cell = s->cfg.cell_size;
    double lo[3], hi[3], pmin[3], pmax[3];
    sim_domain_bounds(s, s->rmax, lo, hi, pmin, pmax);
    for (;;) {
        double total = 1;
        for (int d = 0; d < 3; d++) {
            u->ncell[d] = (int)ceil((hi[d] - lo[d]) / cell);
            if (u->ncell[d] < 1)
                u->ncell[d] = 1;
            total *= u->ncell[d];
        }
        if (total <= (double)(1 << 24) && total <= 64.0 * n + 4096)
            break;
        cell *= 1.25; /* a sparse domain: fewer, larger cells */
    }
    for (int d = 0; d < 3; d++) {
        u->lo[d] = lo[d];
        s->domain.lo[d] = lo[d];
        s->domain.hi[d] = hi[d];
        s->domain.grid_hi[d] = lo[d] + u->ncell[d] * cell; /* what the binning checks: whole cells, past hi by < 1 cell */
    }
    s->domain.grid_cell = cell;
    u->inv_cell = 1 / cell;
    /* the cells of the particles' bounding box now (binning.h bin_bounds finds them on the device at each build, in
     * the run's precision; a cell more or less here only moves when the buffers grow) */
    for (int d = 0; d < 3; d++) {
        int c[2];
        for (int e = 0; e < 2; e++) {
            double t = ((e ? pmax[d] : pmin[d]) - lo[d]) * u->inv_cell;
            c[e] = t >= 0 ? (t < u->ncell[d] ? (int)t : u->ncell[d] - 1) : 0; /* none, or NaN: 0 */
        }
        u->cell0[d] = c[0] <= c[1] ? c[0] : 0;
        u->cells[d] = c[0] <= c[1] ? c[1] - c[0] + 1 : 1;
    }
    return skin;
}

/* The patch triangles of each particle by stable id (common/patch_contacts.h): vtri_start / vtri_list in ascending
 * triangle id; the
 * search reach (1.5 x the longest patch edge: the device widens it when an edge reaches it) and the largest radius of
 * the particles that are not patch vertices. */
static int pack_patches(dem_sim *s, dem_setup *u)
{
    int n = s->n, nt = s->mesh.ntri;
    int *start = calloc((size_t)n + 1, sizeof(int)), *list = calloc(3 * (size_t)(nt ? nt : 1), sizeof(int));
    int *fill = calloc((size_t)n + 1, sizeof(int));
    unsigned char *mark = calloc((size_t)(nt ? nt : 1), 1);
    if (!start || !list || !mark || !fill)
        return free(start), free(list), free(mark), free(fill), sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (int k = 0; k < s->mesh.npatch; k++)
        mark[s->mesh.patch[k]] = 1;
    double longest = 0;
    for (int t = 0; t < nt; t++)
        for (int c = 0; mark[t] && c < 3; c++) {
            start[s->mesh.tri[3 * t + c] + 1]++;
            const double *a = s->x + 3 * s->mesh.tri[3 * t + c], *b = s->x + 3 * s->mesh.tri[3 * t + (c + 1) % 3];
            longest = fmax(longest, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                         (a[2] - b[2]) * (a[2] - b[2])));
        }
    for (int p = 0; p < n; p++)
        start[p + 1] += start[p];
    for (int t = 0; t < nt; t++)
        for (int c = 0; mark[t] && c < 3; c++) {
            int p = s->mesh.tri[3 * t + c];
            list[start[p] + fill[p]++] = t;
        }
    u->rmax = 0;
    for (int p = 0; p < n; p++)
        if (start[p + 1] == start[p] && s->radius[p] > u->rmax)
            u->rmax = s->radius[p];
    free(fill), free(mark);
    u->vtri_start = keep(s, start), u->vtri_list = keep(s, list);
    if (!u->vtri_start || !u->vtri_list)
        return DEM_ERR_NOMEM;
    s->rows.reach = u->reach = longest > 0 ? 1.5 * longest : s->rmax;
    s->rows.maxp = u->maxp = 16;
    s->rows.maxv = u->maxv = 32;
    return 0;
}

/* Per particle, in the run's precision: the state of the start, the bodies, the held axes, and the stable ids every
 * sum follows (neighbor.h): the particles' ids at the start, so that the bits do not depend on where the particles
 * are stored later (host/core/reorder.c). (Their places in the input instead, which would make a sorted packing
 * (dem_sort_particles) run the bits of the unsorted one, cost that sorted run a third of its speed: docs/design.md
 * "Every sum follows the particle ids".) */
/* Each particle's MDR row as laws/mdr_core.h mdr_particle_new makes it, in the run's precision with the same
 * operations (its volumes (4/3) pi r^3 rounded as the kernels round them) */
static void *pack_mdr_part(const dem_sim *s, int rs)
{
    size_t n = (size_t)s->n;
    void *p = calloc(MDR_P_STRIDE * (n ? n : 1), (size_t)rs);
    for (size_t i = 0; p && i < n; i++) {
        if (rs == 8) {
            double r = s->radius[i], *q = (double *)p + MDR_P_STRIDE * i;
            double v = 4.0 / 3.0 * 0x1.921fb54442d18p+1 * r * r * r;
            q[0] = q[1] = r, q[10] = 1, q[11] = q[12] = v;
        } else {
            float r = (float)s->radius[i], *q = (float *)p + MDR_P_STRIDE * i;
            float v = 4.0f / 3.0f * (float)0x1.921fb54442d18p+1 * r * r * r;
            q[0] = q[1] = r, q[10] = 1, q[11] = q[12] = v;
        }
    }
    return p;
}

static int pack_particles(dem_sim *s, dem_setup *u, int rs)
{
    size_t n = (size_t)s->n;
    double *invm = malloc(sizeof(double) * n), *invi = malloc(sizeof(double) * n), *invv = malloc(sizeof(double) * n);
    double *iroll = malloc(sizeof(double) * (n ? n : 1));
    unsigned *hold = calloc(n, sizeof(unsigned)); /* DEM_PARTICLE_HOLD_V{X,Y,Z} as bits 0, 1, 2 */
    int *sid = malloc(sizeof(int) * (n ? n : 1)), *order = malloc(sizeof(int) * (n ? n : 1));
    int *identity = malloc(sizeof(int) * (n ? n : 1));
    if (invm && invi && invv)
        pack_bodies(s, invm, invi, invv);
    for (size_t i = 0; invm && invi && iroll && i < n; i++) { /* 1 / (I + m r^2) in double (rolling.h) */
        double d = invm[i] + s->radius[i] * s->radius[i] * invi[i];
        iroll[i] = d > 0 ? invm[i] * invi[i] / d : 0;
    }
    for (size_t i = 0; hold && i < n; i++)
        hold[i] = (s->pflags[i] & DEM_PARTICLE_HOLD_V) / DEM_PARTICLE_HOLD_VX;
    for (size_t i = 0; sid && order && identity && i < n; i++)
        sid[i] = order[i] = identity[i] = (int)i;
    unsigned *ghost = NULL;
    if (s->ghost && (ghost = malloc(sizeof(unsigned) * n)))
        for (size_t i = 0; i < n; i++)
            ghost[i] = s->ghost[i] != 0;
    u->ghost = s->ghost ? keep(s, ghost) : NULL;
    u->hold = keep(s, hold), u->sid = keep(s, sid), u->order = keep(s, order), u->identity = keep(s, identity);
    u->x = keep(s, pack_real(s->x, 3 * n, rs));
    u->v = keep(s, pack_real(s->v, 3 * n, rs));
    u->w = keep(s, pack_real(s->w, 3 * n, rs));
    u->radius = keep(s, pack_real(s->radius, n, rs));
    u->invmass = invm ? keep(s, pack_real(invm, n, rs)) : NULL;
    u->invinertia = invi ? keep(s, pack_real(invi, n, rs)) : NULL;
    u->invvol = invv ? keep(s, pack_real(invv, n, rs)) : NULL;
    u->roll_inertia = iroll ? keep(s, pack_real(iroll, n, rs)) : NULL;
    u->mat = s->mat;
    u->mdr_part = (s->effects & DEM_EFFECT_MDR) ? keep(s, pack_mdr_part(s, rs)) : NULL;
    free(invm), free(invi), free(invv), free(iroll);
    return (u->ghost || !s->ghost) && u->hold && u->sid && u->order && u->identity && u->x && u->v && u->w && u->radius && u->invmass &&
                   u->invinertia && u->invvol && u->roll_inertia && (u->mdr_part || !(s->effects & DEM_EFFECT_MDR))
               ? 0 : sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
}

int sim_pack(dem_sim *s)
{
    dem_setup *u = &s->setup;
    int e, rs = (int)s->cfg.precision;
    sim_setup_free(s); /* packed again (dem_memory_estimate, then dem_start): the last packing holds */
    free(s->motion.table);
    s->motion.table = NULL;
    memset(u, 0, sizeof *u);
    u->real_size = rs;
    pack_effects(s, u);
    double *pm = malloc(sizeof(double) * PM_STRIDE * s->nmat * s->nmat);
    double *damp = malloc(sizeof(double) * s->nmat * s->nmat);
    if (pm && damp)
        pack_pairs(s, pm, damp);
    u->pairmat = pm && damp ? keep(s, pack_real(pm, (size_t)PM_STRIDE * s->nmat * s->nmat, rs)) : NULL;
    free(pm), free(damp);
    for (int k = 0; k < s->nwalls; k++) /* the walls' stage lengths in steps, then the riders' velocities of step 0 */
        for (int st = 0; st < s->walls[k].nstages; st++)
            s->motion.stage_steps[k][st] = lround(s->walls[k].stages[st].duration / s->dt);
    for (int k = 0; k < s->nwalls; k++) /* where the walls start (pack_walls packs them), and the stages of step 0 */
        memcpy(s->motion.pos[k], s->walls[k].point, sizeof(double) * 3);
    sim_stages_from_step(s);
    sim_attach_start(s);
    int *wint = keep(s, calloc((size_t)WI_STRIDE * (s->nwalls ? s->nwalls : 1), sizeof(int)));
    s->motion.table = calloc((size_t)W_STRIDE * (s->nwalls ? s->nwalls : 1), (size_t)rs);
    if (!u->pairmat || !wint || !s->motion.table)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    if ((e = pack_particles(s, u, rs)))
        return e;
    pack_walls(s, wint);
    if ((e = pack_channel(s, u, rs)) || (e = pack_riders(s, u, rs)) || (e = pack_patches(s, u)))
        return e;
    u->wall_int = wint;
    u->wall_real = s->motion.table;
    double skin = pack_grid(s, u);
    double reach_extra = (u->effects & DEM_MC_REACH) ? 2 * (s->mc.reach - 1) * s->rmax : 0;
    u->dt = s->dt;
    memcpy(u->gravity, s->gravity, sizeof u->gravity);
    u->skin = skin + reach_extra;
    u->half_skin2 = 0.25 * skin * skin;
    s->rows.skin_hi = s->rows.skin_now = skin; /* the cells fit the largest skin: rebuild.c's skin_choose stays below it */
    s->rows.skin_lo = s->cfg.skin > 0 ? skin : DEM_SKIN_AUTO_LO * s->rmin;
    s->rows.skin_extra = reach_extra;
    s->rows.skin_built = -1;
    u->maxn = s->n > INT_MAX / DEM_INITIAL_ROW_CAPACITY ? INT_MAX : DEM_INITIAL_ROW_CAPACITY * s->n;
    u->device = s->cfg.device;
    u->local_size = s->cfg.local_size;
    u->source_dir = s->cfg.source_dir;
    if (!u->source_dir)
        u->source_dir = getenv("DEM_SOURCE_DIR");
#ifdef DEM_DEFAULT_SOURCE_DIR
    if (!u->source_dir)
        u->source_dir = DEM_DEFAULT_SOURCE_DIR;
#endif
    if (!u->source_dir)
        u->source_dir = ".";
    s->rows.maxn = u->maxn;
    return 0;
}
