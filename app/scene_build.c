/* scene_build.c - checks a loaded scene and builds the simulation it describes.
 * Every rejection names file, line and field (scene_locate.c) and says why; nothing is half-built. */
/* The most steps a scene may ask for (1e12: weeks of run time even for two spheres). */
#ifndef DEM_SCENE_MAX_STEPS
#define DEM_SCENE_MAX_STEPS 1e12
#endif
#include "scene.h"
#include "scene_particles.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "file:line: path: reason" */
int scene_fail(const scene *sc, char *err, size_t errlen, const char *path, const char *fmt, ...)
{
    char why[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    int line = scene_line(sc->loc, path);
    char parent[512];
    snprintf(parent, sizeof parent, "%s", path);
    while (!line && parent[0]) { /* an absent key: point at the innermost part that exists */
        char *cut = strrchr(parent, '.'), *br = strrchr(parent, '[');
        if (br > cut)
            cut = br;
        if (!cut)
            break;
        *cut = 0;
        line = scene_line(sc->loc, parent);
    }
    snprintf(err, errlen, "%s:%d: %s: %s", sc->path, line, path, why);
    return 1;
}

/* For an unknown effect name near a known one (the names dem_effect_name gives that a scene may list, and
 * "membrane"): "unknown effect 'x' (known: ...) (did you mean 'y'?)" in buf, and 1; else 0. */
/* "unknown effect 'e' (known: <the names a scene may list>)", and the nearest name when one is near */
static void effect_unknown(const char *e, char *buf, size_t len)
{
    const char *known[DEM_EFFECT_COUNT + 1];
    int n = 0;
    unsigned unnamed = DEM_EFFECT_CHANNEL | DEM_EFFECT_PATCHES | DEM_EFFECT_RIDERS | DEM_EFFECT_CONSTRAINTS;
    for (int b = 0; b < DEM_EFFECT_COUNT; b++)
        if (dem_effect_name(b) && (DEM_EFFECT_ALL & ~unnamed & (1u << b)))
            known[n++] = dem_effect_name(b);
    known[n++] = "membrane";
    char hint[300], list[400] = "";
    scene_did_you_mean(e, known, n, hint, sizeof hint);
    for (int k = 0; k < n; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", known[k]);
    snprintf(buf, len, "unknown effect '%s' (known: %s)%s", e, list, hint);
}

static int finite3(const double *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }
static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }


/* One rule for the scene's effects and for --model: a multi-contact law needs a material whose prefactor makes it do
 * something (MC-stress: beta nu != 0, seed 000's "nu = 0 de-activates the model"; MC-strain: gamma > 0), or it would
 * run as classical DEM in disguise. NULL when the law can act, else the reason. */
static const char *mc_prefactor_missing(const scene *sc, unsigned law)
{
    for (unsigned q = 0; q < sc->f->materials_count; q++) {
        const scene_material *m = &sc->f->materials[q];
        if (law == DEM_EFFECT_MC_STRESS ? m->beta > 0 && m->poisson != 0 : m->gamma > 0)
            return NULL;
    }
    return law == DEM_EFFECT_MC_STRESS ? "no material has beta > 0 and a non-zero poisson (beta nu = 0 is classical DEM)"
                                       : "no material has gamma > 0 (gamma = 0 is classical DEM)";
}

/* mc_stress_convention: each sub-key picks one branch of common/particle_stress.h; absent ones keep the default. */
static int parse_mcs_convention(const scene *sc, scene_run *run, char *err, size_t errlen)
{
    const scene_mcs_convention *c = sc->f->mc_stress_convention;
    run->mcs_conv = DEM_MCS_DEFAULT;
    if (!c)
        return 0;
    int beta = 0;
    for (unsigned q = 0; q < sc->f->materials_count; q++)
        beta |= sc->f->materials[q].beta > 0;
    if (!(run->effects & DEM_EFFECT_MC_STRESS) && !beta)
        return scene_fail(sc, err, errlen, "mc_stress_convention",
                          "an MC-stress convention is given but mc_stress is off and no material has beta > 0");
    static const struct {
        const char *key, *names[3];
        unsigned bits[3];
        unsigned clear;
    } opt[3] = {
        {"own_contact", {"in", "out", NULL}, {DEM_MCS_OWN_IN, 0, 0}, DEM_MCS_OWN_IN},
        {"lever", {"centres", "contact_point", NULL}, {DEM_MCS_LEVER_CENTRES, 0, 0}, DEM_MCS_LEVER_CENTRES},
        {"scale", {"mean_trace", "text", "mean_pressure"}, {DEM_MCS_SCALE_TRACE, DEM_MCS_SCALE_TEXT, 0},
         DEM_MCS_SCALE_TRACE | DEM_MCS_SCALE_TEXT},
    };
    const char *given[3] = {c->own_contact, c->lever, c->scale};
    for (int k = 0; k < 3; k++) {
        if (!given[k])
            continue;
        int q = 0;
        while (q < 3 && !(opt[k].names[q] && !strcmp(given[k], opt[k].names[q])))
            q++;
        char p[64];
        snprintf(p, sizeof p, "mc_stress_convention.%s", opt[k].key);
        if (q == 3)
            return scene_fail(sc, err, errlen, p, "unknown value '%s' (%s%s%s%s%s)", given[k], opt[k].names[0],
                              ", ", opt[k].names[1], opt[k].names[2] ? ", " : "",
                              opt[k].names[2] ? opt[k].names[2] : "");
        run->mcs_conv = (run->mcs_conv & ~opt[k].clear) | opt[k].bits[q];
    }
    return 0;
}

/* thornton_ning needs a material that yields (else every contact is Hertz's and the law's name would mislead) */
static const char *yield_missing(const scene *sc)
{
    for (unsigned k = 0; k < sc->f->materials_count; k++)
        if (sc->f->materials[k].yield_stress > 0)
            return NULL;
    return "no material has a yield_stress > 0 (the limiting contact pressure p_y [Pa] at which it yields)";
}

/* adhesion is thornton_ning's (mdr has its own) and needs a surface that adheres; the library checks the pairs */
static const char *adhesion_missing(const scene *sc, unsigned effects)
{
    if (!(effects & DEM_EFFECT_THORNTON_NING))
        return "thornton_ning is not (adhesion is that law's JKR adhesion; mdr adheres by surface_energy alone)";
    for (unsigned k = 0; k < sc->f->materials_count; k++)
        if (sc->f->materials[k].surface_energy > 0)
            return NULL;
    for (unsigned k = 0; k < sc->f->material_pairs_count; k++) { /* a pair's own, where the scene gives it */
        char key[96];
        snprintf(key, sizeof key, "material_pairs[%u].surface_energy", k);
        if (scene_has(sc->loc, key) && sc->f->material_pairs[k].surface_energy > 0)
            return NULL;
    }
    return "no material or material pair has a surface_energy > 0 (the work of adhesion w [J/m^2] of JKR)";
}

/* mdr needs its parameters on every material particles use: a yield stress, and psi_b said (0.5 in Zunker et al.'s
 * MCC, 0 turns the bulk response off: no default hides that choice); the library checks that they are one material */
static const char *mdr_missing(const scene *sc)
{
    static char why[256];
    const scene_file *f = sc->f;
    for (unsigned k = 0; k < f->materials_count; k++) {
        const scene_material *m = &f->materials[k];
        int used = 0;
        for (unsigned g = 0; g < f->particles_count && !used; g++)
            used = f->particles[g].material && !strcmp(f->particles[g].material, m->name);
        char key[64];
        snprintf(key, sizeof key, "materials[%u].bulk_fraction", k);
        if (used && !(m->yield_stress > 0)) {
            snprintf(why, sizeof why, "material '%s' (used by particles) has no yield_stress > 0 (MDR's yield stress Y "
                     "[Pa])", m->name);
            return why;
        }
        if (used && !scene_has(sc->loc, key)) {
            snprintf(why, sizeof why, "material '%s' (used by particles) gives no bulk_fraction (MDR's psi_b: 0.5 in "
                     "Zunker et al.'s MCC; 0 turns the bulk response off)", m->name);
            return why;
        }
    }
    return NULL;
}

/* material_pairs: each names two defined materials (in dem_add_material's order, the scene's) once, and gives a
 * friction or a restitution or both, which replace the mean of the two materials' for that pair */
static int parse_material_pairs(const scene *sc, dem_sim *s, char *err, size_t errlen)
{
    const scene_file *f = sc->f;
    for (unsigned k = 0; k < f->material_pairs_count; k++) {
        const scene_material_pair *mp = &f->material_pairs[k];
        char p[96];
        int id[2];
        for (int q = 0; q < 2; q++) {
            id[q] = -1;
            for (unsigned m = 0; m < f->materials_count; m++)
                if (!strcmp(f->materials[m].name, mp->materials[q]))
                    id[q] = (int)m;
            if (id[q] < 0) {
                snprintf(p, sizeof p, "material_pairs[%u].materials[%d]", k, q);
                return scene_fail(sc, err, errlen, p, "no material is called '%s'", mp->materials[q]);
            }
        }
        for (unsigned j = 0; j < k; j++) {
            const scene_material_pair *o = &f->material_pairs[j];
            if ((!strcmp(o->materials[0], mp->materials[0]) && !strcmp(o->materials[1], mp->materials[1])) ||
                (!strcmp(o->materials[0], mp->materials[1]) && !strcmp(o->materials[1], mp->materials[0]))) {
                snprintf(p, sizeof p, "material_pairs[%u].materials", k);
                return scene_fail(sc, err, errlen, p, "the pair %s-%s is given twice (also material_pairs[%u])",
                                  mp->materials[0], mp->materials[1], j);
            }
        }
        /* each value the scene gives replaces the rule's (NAN: keep it) */
        dem_material_pair dp = {NAN, NAN, NAN, NAN, NAN};
        const struct {
            const char *key;
            double given, *to;
        } keys[] = {{"friction", mp->friction, &dp.friction},
                    {"restitution", mp->restitution, &dp.restitution},
                    {"rolling_friction", mp->rolling_friction, &dp.rolling_friction},
                    {"bond_strength", mp->bond_strength, &dp.bond_strength},
                    {"surface_energy", mp->surface_energy, &dp.surface_energy}};
        int any = 0;
        for (unsigned q = 0; q < sizeof keys / sizeof keys[0]; q++) {
            snprintf(p, sizeof p, "material_pairs[%u].%s", k, keys[q].key);
            if (scene_has(sc->loc, p)) {
                *keys[q].to = keys[q].given;
                any = 1;
            }
        }
        snprintf(p, sizeof p, "material_pairs[%u]", k);
        if (!any)
            return scene_fail(sc, err, errlen, p,
                              "give the pair's friction, restitution, rolling_friction, bond_strength or "
                              "surface_energy");
        if (dem_set_material_pair(s, id[0], id[1], &dp))
            return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
    }
    return 0;
}

static int parse_effects(const scene *sc, scene_run *run, char *err, size_t errlen)
{
    const scene_file *f = sc->f;
    run->effects = 0;
    for (unsigned k = 0; k < f->effects_count; k++) {
        char path[64];
        snprintf(path, sizeof path, "effects[%u]", k);
        const char *e = f->effects[k];
        int bit = dem_effect_bit(e);
        if (!strcmp(e, "membrane")) { /* springs, pressure, bending, patches as the membranes need (scene_membranes.c) */
            for (unsigned j = 0; j < k; j++)
                if (!strcmp(f->effects[j], e))
                    return scene_fail(sc, err, errlen, path, "effect '%s' is listed twice", e);
            continue;
        }
        if (bit < 0) { /* the names from the library's list, and the nearest one to a misspelt name */
            effect_unknown(e, err, errlen);
            return scene_fail(sc, err, errlen, path, "%s", err);
        }
        if (run->effects & (1u << bit))
            return scene_fail(sc, err, errlen, path, "effect '%s' is listed twice", e);
        if ((1u << bit) & (DEM_EFFECT_CHANNEL | DEM_EFFECT_PATCHES | DEM_EFFECT_RIDERS | DEM_EFFECT_CONSTRAINTS))
            return scene_fail(sc, err, errlen, path, "effect '%s' is not listed by name: %s", e,
                              (1u << bit) == DEM_EFFECT_CONSTRAINTS
                                  ? "a particle group's 'hold' turns it on"
                                  : "it is part of the effect 'membrane': list that, and the scene's membranes turn on "
                                    "what they need");
        run->effects |= 1u << bit;
    }
    if (!(run->effects & DEM_EFFECT_HERTZ))
        return scene_fail(sc, err, errlen, "effects", "'hertz' (the contact law) must be listed");
    if ((run->effects & DEM_EFFECT_MC_STRESS) && (run->effects & DEM_EFFECT_MC_STRAIN))
        return scene_fail(sc, err, errlen, "effects", "mc_stress and mc_strain are alternative normal laws: list one");
    if ((run->effects & DEM_EFFECT_THORNTON_NING) && (run->effects & (DEM_EFFECT_MC_STRESS | DEM_EFFECT_MC_STRAIN)))
        return scene_fail(sc, err, errlen, "effects",
                          "thornton_ning and the multi-contact laws are alternative normal laws: list one");
    if ((run->effects & DEM_EFFECT_MDR) &&
        (run->effects & (DEM_EFFECT_MC_STRESS | DEM_EFFECT_MC_STRAIN | DEM_EFFECT_THORNTON_NING)))
        return scene_fail(sc, err, errlen, "effects",
                          "mdr, thornton_ning and the multi-contact laws are alternative normal laws: list one");
    for (unsigned k = 0; k < f->effects_count; k++) {
        int bit = dem_effect_bit(f->effects[k]);
        if (bit < 0) /* membrane */
            continue;
        unsigned law = 1u << bit;
        const char *why = (law == DEM_EFFECT_MC_STRESS || law == DEM_EFFECT_MC_STRAIN) ? mc_prefactor_missing(sc, law)
                          : law == DEM_EFFECT_THORNTON_NING ? yield_missing(sc)
                          : law == DEM_EFFECT_MDR           ? mdr_missing(sc)
                          : law == DEM_EFFECT_ADHESION      ? adhesion_missing(sc, run->effects)
                                                            : NULL;
        if (why) {
            char path[64];
            snprintf(path, sizeof path, "effects[%u]", k);
            return scene_fail(sc, err, errlen, path, "%s is listed but %s", f->effects[k], why);
        }
    }
    if (f->mc_iterations < 0 || f->mc_iterations > 10000)
        return scene_fail(sc, err, errlen, "mc_iterations", "must be in 0..10000 (0: the lagged scheme)");
    if (scene_has(sc->loc, "mc_tolerance") && !(f->mc_tolerance > 0 && isfinite(f->mc_tolerance)))
        return scene_fail(sc, err, errlen, "mc_tolerance", "must be > 0");
    if ((scene_has(sc->loc, "mc_iterations") || scene_has(sc->loc, "mc_tolerance")) && !(run->effects & DEM_EFFECT_MC_STRAIN))
        return scene_fail(sc, err, errlen, scene_has(sc->loc, "mc_iterations") ? "mc_iterations" : "mc_tolerance",
                          "MC-strain settings are given but the effect 'mc_strain' is off");
    if (scene_has(sc->loc, "mc_contact_distance")) {
        if (!(f->mc_contact_distance >= 1 && f->mc_contact_distance <= 2))
            return scene_fail(sc, err, errlen, "mc_contact_distance",
                              "must be in [1, 2] (a factor on r_i + r_j; 1: only overlapping spheres are contacts)");
        if (!(run->effects & DEM_EFFECT_MC_STRAIN) && mc_prefactor_missing(sc, DEM_EFFECT_MC_STRAIN))
            return scene_fail(sc, err, errlen, "mc_contact_distance",
                              "an MC-strain setting is given but mc_strain is off and no material has gamma > 0");
    }
    return parse_mcs_convention(sc, run, err, errlen);
}

/* Mass scaling (time.mass_scale S): every particle and membrane vertex is S times heavier than its density says and
 * gravity is S times weaker, so weights and every force law stay real and only inertia grows. Time scales (Rayleigh,
 * Hertz, the stability bound) grow by sqrt(S), so a step of dt_rayleigh covers sqrt(S) times more simulated time;
 * the price is that inertial effects are S times too strong: fine where they are small (a slow, dense press), wrong
 * for impacts, pours and flows. docs/scenes.md "Mass scaling"; on a press: docs/tableting.md "Mass scaling". */
double scene_mass_scale(const scene *sc)
{
    return scene_has(sc->loc, "time.mass_scale") ? sc->f->time.mass_scale : 1.0;
}

const char *scene_particle_order(const scene *sc)
{
    if (!sc->f) /* no scene file (a program's own packing written through checkpoint_write): as added */
        return "input";
    return sc->f->particle_order ? sc->f->particle_order : sc->order_default ? sc->order_default : "spatial";
}

int scene_keeps_acceleration(const scene *sc)
{
    const char *k = sc->f->time.mass_scale_keeps;
    return k && !strcmp(k, "acceleration");
}

static int parse_materials(const scene *sc, dem_sim *s, char *err, size_t errlen)
{
    const scene_file *f = sc->f;
    const double scale = scene_mass_scale(sc);
    if (!(scale >= 1 && scale <= 1e12))
        return scene_fail(sc, err, errlen, "time.mass_scale", "must be in [1, 1e12] (every mass is multiplied by it "
                          "to allow a longer time step; 1 is the real mass), got %g", scale);
    for (unsigned k = 0; k < f->materials_count; k++) {
        const scene_material *m = &f->materials[k];
        char p[128];
#define MCHECK(field, cond, why)                                                                                     \
    do {                                                                                                             \
        if (!(cond)) {                                                                                               \
            snprintf(p, sizeof p, "materials[%u].%s", k, field);                                                    \
            return scene_fail(sc, err, errlen, p, why);                                                              \
        }                                                                                                            \
    } while (0)
        int used = 0; /* by a particle group: only then is a density needed (a wall's material has no mass) */
        for (unsigned g = 0; g < f->particles_count && !used; g++)
            used = f->particles[g].material && !strcmp(f->particles[g].material, m->name);
        MCHECK("density", !used || (m->density > 0 && isfinite(m->density)),
               "density must be > 0 kg/m^3 (a material that particles use needs one)");
        MCHECK("density", m->density >= 0 && isfinite(m->density), "density must be >= 0 kg/m^3");
        MCHECK("young", m->young > 0 && isfinite(m->young), "Young's modulus must be > 0 Pa");
        MCHECK("poisson", m->poisson > -1 && m->poisson <= 0.5, "Poisson's ratio must be in (-1, 0.5]");
        MCHECK("restitution", m->restitution > 0 && m->restitution <= 1, "restitution must be in (0, 1]");
        MCHECK("friction", m->friction >= 0 && isfinite(m->friction), "friction must be >= 0");
        MCHECK("beta", m->beta >= 0 && isfinite(m->beta), "the MC-stress prefactor beta must be >= 0");
        MCHECK("gamma", m->gamma >= 0 && isfinite(m->gamma), "the MC-strain prefactor gamma must be >= 0");
        MCHECK("yield_stress", m->yield_stress >= 0 && isfinite(m->yield_stress),
               "the yield stress must be >= 0 Pa (0: the material does not yield)");
        MCHECK("rolling_friction", m->rolling_friction >= 0 && isfinite(m->rolling_friction),
               "the rolling friction must be >= 0");
        MCHECK("bond_strength", m->bond_strength >= 0 && isfinite(m->bond_strength),
               "the bond strength must be >= 0 Pa (0: the material does not bond)");
        MCHECK("rolling_damping", m->rolling_damping >= 0 && isfinite(m->rolling_damping),
               "the rolling damping ratio must be >= 0");
        MCHECK("surface_energy", m->surface_energy >= 0 && isfinite(m->surface_energy),
               "the surface energy must be >= 0 J/m^2 (0: no adhesion)");
        MCHECK("bulk_fraction", m->bulk_fraction >= 0 && m->bulk_fraction < 1,
               "the bulk fraction psi_b must be in [0, 1) (0: no bulk response while psi >= 0)");
        MCHECK("mdr_damping", m->mdr_damping >= 0 && isfinite(m->mdr_damping), "the MDR damping must be >= 0");
#undef MCHECK
        for (unsigned j = 0; j < k; j++)
            if (!strcmp(f->materials[j].name, m->name)) {
                snprintf(p, sizeof p, "materials[%u].name", k);
                return scene_fail(sc, err, errlen, p, "material '%s' is defined twice", m->name);
            }
        /* a wall-only material without a density gets a placeholder the library accepts; no mass is made from it */
        dem_material dm = {used || m->density > 0 ? m->density * scale : 1.0, m->young, m->poisson, m->restitution,
                           m->friction, m->beta, m->gamma, m->yield_stress, m->rolling_friction,
                           m->bond_strength, m->rolling_damping, m->surface_energy, m->bulk_fraction,
                           m->mdr_damping};
        if (dem_add_material(s, &dm) < 0) {
            snprintf(p, sizeof p, "materials[%u]", k);
            return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
        }
    }
    return parse_material_pairs(sc, s, err, errlen);
}

int scene_apply_model(const scene *sc, dem_sim *s, scene_run *run, const char *model, char *err, size_t errlen)
{
    static const char *const names[] = {"classical", "mc_stress", "mc_strain", "mc_strain_iterated", "thornton_ning",
                                        "mdr"};
    int k = 0;
    while (k < 6 && strcmp(model, names[k]))
        k++;
    if (k == 6) {
        snprintf(err, errlen, "unknown model '%s' (classical, mc_stress, mc_strain, mc_strain_iterated, thornton_ning, "
                 "mdr)", model);
        return 1;
    }
    /* adhesion goes with thornton_ning: another model drops it (mdr adheres by surface_energy alone) */
    unsigned fx = run->effects & ~(unsigned)(DEM_EFFECT_MC_STRESS | DEM_EFFECT_MC_STRAIN | DEM_EFFECT_THORNTON_NING |
                                             DEM_EFFECT_MDR | (k == 4 ? 0u : DEM_EFFECT_ADHESION));
    fx |= k == 1 ? DEM_EFFECT_MC_STRESS : k == 4 ? DEM_EFFECT_THORNTON_NING : k == 5 ? DEM_EFFECT_MDR
          : k >= 2 ? DEM_EFFECT_MC_STRAIN : 0;
    const char *why = k == 0 ? NULL
                      : k == 4 ? yield_missing(sc)
                      : k == 5 ? mdr_missing(sc)
                               : mc_prefactor_missing(sc, k == 1 ? DEM_EFFECT_MC_STRESS : DEM_EFFECT_MC_STRAIN);
    if (why) {
        snprintf(err, errlen, "model %s: %s", model, why);
        return 1;
    }
    int iters = k == 3 ? (sc->f->mc_iterations > 0 ? sc->f->mc_iterations : 20) : 0;
    double tol = scene_has(sc->loc, "mc_tolerance") ? sc->f->mc_tolerance : 1e-6;
    run->mc_cap = iters;
    run->mc_tol = tol;
    if (dem_set_effects(s, fx) || dem_set_mc_strain(s, iters, tol)) {
        snprintf(err, errlen, "model %s: %s", model, dem_error(s));
        return 1;
    }
    run->effects = fx;
    snprintf(run->model, sizeof run->model, "%s", model);
    return 0;
}

int scene_material_id(const scene *sc, const char *name)
{
    for (unsigned j = 0; j < sc->f->materials_count; j++)
        if (!strcmp(sc->f->materials[j].name, name))
            return (int)j;
    return -1;
}

static int lookup_material(const scene *sc, const char *name, const char *path, int *id, char *err, size_t errlen)
{
    *id = scene_material_id(sc, name);
    if (*id < 0) {
        char hint[300];
        return scene_fail(sc, err, errlen, path, "unknown material '%s'%s", name,
                          scene_material_hint(sc, name, hint, sizeof hint));
    }
    return 0;
}

/* Motion stages of wall k, after an optional settling pause. */
/* A servo stage (dem_stage.force): `force` [N], or `stress` [Pa] x `area` [m^2], with `gain` and `max_speed`, for a
 * duration; the wall then moves along its normal to receive that force (plane walls: checked by the library) */
static int servo_stage(const scene *sc, const char *base, const scene_stage *g, int has_v, int has_d, dem_stage *st,
                       char *err, size_t errlen)
{
    char p[160];
    int has[5];
    static const char *const keys[5] = {"force", "stress", "area", "gain", "max_speed"};
    for (int q = 0; q < 5; q++) {
        snprintf(p, sizeof p, "%s.%s", base, keys[q]);
        has[q] = scene_has(sc->loc, p);
    }
    if (!has[0] && !has[1]) {
        snprintf(p, sizeof p, "%s.until_stress", base);
        int until_area = scene_has(sc->loc, p); /* the area an until_stress acts on (until_stage) */
        for (int q = 2; q < 5; q++)
            if (has[q] && !(q == 2 && until_area)) {
                snprintf(p, sizeof p, "%s.%s", base, keys[q]);
                return scene_fail(sc, err, errlen, p, "belongs to a servo stage (force or stress)");
            }
        return 0;
    }
    if (has[0] && has[1])
        return scene_fail(sc, err, errlen, base, "give force [N] or stress [Pa] x area [m^2], not both");
    if (has_v || has_d != 0)
        return scene_fail(sc, err, errlen, base, "a servo stage has a duration and no velocity");
    if (has[1] && !(has[2] && g->area > 0 && isfinite(g->area)))
        return scene_fail(sc, err, errlen, base, "a stress needs the area > 0 m^2 it acts on");
    st->force = has[0] ? g->force : g->stress * g->area;
    st->gain = g->gain, st->max_speed = g->max_speed;
    if (!(st->force > 0) || !isfinite(st->force)) {
        snprintf(p, sizeof p, "%s.%s", base, has[0] ? "force" : "stress");
        return scene_fail(sc, err, errlen, p, "must be > 0 and finite");
    }
    for (int q = 3; q < 5; q++)
        if (!has[q] || !(q == 3 ? g->gain > 0 && isfinite(g->gain) : g->max_speed > 0 && isfinite(g->max_speed))) {
            snprintf(p, sizeof p, "%s.%s", base, keys[q]);
            return scene_fail(sc, err, errlen, p, "a servo stage needs %s > 0 (%s)", keys[q],
                              q == 3 ? "m/s per N" : "m/s");
        }
    return 0;
}

/* A stage's early end (dem_stage.until_force, until_distance, until_density): `until_force` [N] or `until_stress`
 * [Pa] x `area` [m^2], and/or `until_distance` [m], and/or `until_density` (relative density in the die, (0, 1]);
 * its duration (or distance, strain) stays its longest. */
static int until_stage(const scene *sc, const char *base, const scene_stage *g, dem_stage *st, char *err, size_t errlen)
{
    char p[160];
    int has[5];
    static const char *const keys[5] = {"until_force", "until_stress", "until_distance", "area", "until_density"};
    const double v[3] = {g->until_force, g->until_stress, g->until_distance};
    for (int q = 0; q < 5; q++) {
        snprintf(p, sizeof p, "%s.%s", base, keys[q]);
        has[q] = scene_has(sc->loc, p);
    }
    if (has[0] && has[1])
        return scene_fail(sc, err, errlen, base, "give until_force [N] or until_stress [Pa] x area [m^2], not both");
    for (int q = 0; q < 3; q++) {
        snprintf(p, sizeof p, "%s.%s", base, keys[q]);
        if (has[q] && (!(v[q] > 0) || !isfinite(v[q])))
            return scene_fail(sc, err, errlen, p, "must be > 0 and finite");
    }
    if (has[1] && !(has[3] && g->area > 0 && isfinite(g->area)))
        return scene_fail(sc, err, errlen, base, "until_stress needs the area > 0 m^2 it acts on");
    if (has[4] && !(g->until_density > 0 && g->until_density <= 1)) {
        snprintf(p, sizeof p, "%s.until_density", base);
        return scene_fail(sc, err, errlen, p, "a relative density in (0, 1]: the spheres' volume over the die's "
                                              "bore between the punches");
    }
    st->until_density = has[4] ? g->until_density : 0;
    st->until_force = has[0] ? g->until_force : has[1] ? g->until_stress * g->area : 0;
    st->until_distance = has[2] ? g->until_distance : 0;
    return 0;
}

/* A stage's `after`: the wall it names (after_wall, its id in the library) and that wall's number of stages
 * (after_stage: the stage waits until the other has run them all). first_wall, nst_of: NULL in the first pass (the
 * walls not all added yet: no wait), the walls' ids and stage counts in the second. */
static int stage_after(const scene *sc, const char *base, const scene_stage *g, int k, const int *first_wall,
                       const int *nst_of, dem_stage *st, char *err, size_t errlen)
{
    if (!g->after || !first_wall)
        return 0;
    const scene_file *f = sc->f;
    char p[160];
    snprintf(p, sizeof p, "%s.after", base);
    for (unsigned q = 0; q < f->walls_count; q++)
        if (f->walls[q].name && !strcmp(f->walls[q].name, g->after)) {
            if ((int)q == k)
                return scene_fail(sc, err, errlen, p, "a wall's stage cannot wait for its own wall");
            if (!nst_of[q])
                return scene_fail(sc, err, errlen, p, "wall '%s' has no motion to wait for", g->after);
            st->after_wall = first_wall[q];
            st->after_stage = nst_of[q];
            return 0;
        }
    return scene_fail(sc, err, errlen, p, "no wall is named '%s'", g->after);
}

static int parse_motion(const scene *sc, int k, double settle, dem_stage *st, int *nst, const int *first_wall,
                        const int *nst_of, char *err, size_t errlen)
{
    const scene_wall *w = &sc->f->walls[k];
    int n = 0;
    if (settle > 0)
        st[n++] = (dem_stage){settle, {0, 0, 0}};
    for (unsigned j = 0; j < w->motion_count; j++) {
        const scene_stage *g = &w->motion[j];
        char base[96], p[128];
        snprintf(base, sizeof base, "walls[%d].motion[%u]", k, j);
        int has_d = 0, cnt = 0;
        const char *keys[] = {"duration", "distance", "strain"};
        for (int q = 0; q < 3; q++) {
            snprintf(p, sizeof p, "%s.%s", base, keys[q]);
            if (scene_has(sc->loc, p)) {
                cnt++;
                has_d = q;
            }
        }
        if (cnt != 1)
            return scene_fail(sc, err, errlen, base, "give exactly one of duration, distance or strain (got %d)", cnt);
        snprintf(p, sizeof p, "%s.velocity", base);
        int has_v = scene_has(sc->loc, p);
        if (has_v && !finite3(g->velocity))
            return scene_fail(sc, err, errlen, p, "velocity must be finite");
        double speed = has_v ? norm3(g->velocity) : 0, dur = g->duration;
        if (has_d == 0) {
            snprintf(p, sizeof p, "%s.duration", base);
            if (!(g->duration >= 0) || !isfinite(g->duration))
                return scene_fail(sc, err, errlen, p, "duration must be >= 0 s");
        } else {
            double dist = g->distance;
            snprintf(p, sizeof p, "%s.%s", base, keys[has_d]);
            if (has_d == 2) {
                char lp[160];
                snprintf(lp, sizeof lp, "%s.length", base);
                if (!scene_has(sc->loc, lp) || !(g->length > 0))
                    return scene_fail(sc, err, errlen, lp, "a strain stage needs the sample length > 0 m");
                dist = g->strain * g->length;
            }
            if (!(dist >= 0) || !isfinite(dist))
                return scene_fail(sc, err, errlen, p, "must be >= 0");
            if (!(speed > 0))
                return scene_fail(sc, err, errlen, base, "a stage given by distance or strain needs a non-zero velocity");
            dur = dist / speed;
            /* with a ramp the wall covers ramp (v_prev + v) / 2 in it (dem_stage.ramp): the duration holds the distance
             * along v (v_prev the previous stage's velocity as the library takes it: 0 after a servo stage) */
            if (g->ramp > 0) {
                const dem_stage *pv = n > 0 && !(st[n - 1].force > 0) ? &st[n - 1] : NULL;
                double along = 0;
                for (int d = 0; pv && d < 3; d++)
                    along += pv->velocity[d] * g->velocity[d] / speed;
                dur = (dist - g->ramp * (along + speed) / 2) / speed + g->ramp;
            }
        }
        snprintf(p, sizeof p, "%s.ramp", base);
        if (scene_has(sc->loc, p) && !(g->ramp >= 0 && g->ramp <= dur && isfinite(g->ramp)))
            return scene_fail(sc, err, errlen, p, "a ramp is >= 0 s and at most the stage's duration (%g s)", dur);
        if (n >= DEM_MAX_STAGES)
            return scene_fail(sc, err, errlen, base, "at most %d motion stages", DEM_MAX_STAGES - 1);
        memset(&st[n], 0, sizeof st[n]);
        st[n].duration = dur;
        for (int d = 0; d < 3; d++)
            st[n].velocity[d] = has_v ? g->velocity[d] : 0;
        st[n].ramp = g->ramp;
        if (servo_stage(sc, base, g, has_v, has_d, &st[n], err, errlen) || until_stage(sc, base, g, &st[n], err, errlen) ||
            stage_after(sc, base, g, k, first_wall, nst_of, &st[n], err, errlen))
            return 1;
        if (g->ramp > 0 && st[n].force > 0)
            return scene_fail(sc, err, errlen, p, "a servo stage has no ramp");
        n++;
    }
    /* repeat: N plays the list N times (load-unload cycles), each stage rounded to steps on its own as if written
     * out */
    char rp[96];
    snprintf(rp, sizeof rp, "walls[%d].repeat", k);
    if (scene_has(sc->loc, rp)) {
        int first = settle > 0, len = n - first;
        if (w->repeat < 1 || len < 1)
            return scene_fail(sc, err, errlen, rp, "repeat needs a motion list and a count >= 1");
        if ((double)first + (double)len * w->repeat > DEM_MAX_STAGES)
            return scene_fail(sc, err, errlen, rp, "%u x %d stages%s make %.0f; at most %d", w->repeat, len,
                              first ? " (+ the settling pause)" : "", (double)first + (double)len * w->repeat,
                              DEM_MAX_STAGES);
        for (unsigned r = 1; r < w->repeat; r++)
            for (int j = 0; j < len; j++)
                st[n++] = st[first + j];
    }
    *nst = n;
    return 0;
}

static int parse_walls(const scene *sc, dem_sim *s, const scene_run *run, int *first_wall, char *err, size_t errlen)
{
    const scene_file *f = sc->f;
    if (f->walls_count && !(run->effects & DEM_EFFECT_WALLS))
        return scene_fail(sc, err, errlen, "walls", "walls are defined but the effect 'walls' is not listed");
    int rigid_of[64]; /* the rigid copy of each scene material, made when a rigid wall first needs it */
    for (int k = 0; k < 64; k++)
        rigid_of[k] = -1;
    int nst_of[DEM_MAX_WALLS] = {0}; /* each scene wall's number of stages (a stage's `after`) */
    for (unsigned k = 0; k < f->walls_count; k++) {
        const scene_wall *w = &f->walls[k];
        char base[64], p[128];
        snprintf(base, sizeof base, "walls[%u]", k);
        int mat;
        snprintf(p, sizeof p, "%s.material", base);
        if (lookup_material(sc, w->material, p, &mat, err, errlen))
            return 1;
        if (w->rigid) { /* a copy of its material, infinitely stiff (same friction and restitution), one per material */
            if (rigid_of[mat] < 0) {
                const scene_material *m = &f->materials[mat];
                dem_material dm = {0, INFINITY, m->poisson, m->restitution, m->friction, m->beta, m->gamma};
                rigid_of[mat] = dem_add_material(s, &dm);
            }
            if (rigid_of[mat] < 0) {
                snprintf(p, sizeof p, "%s.rigid", base);
                return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
            }
            mat = rigid_of[mat];
        }
        dem_stage st[DEM_MAX_STAGES];
        int nst = 0;
        if (parse_motion(sc, (int)k, f->time.settle, st, &nst, NULL, NULL, err, errlen))
            return 1;
        nst_of[k] = nst;
        const char *need[4] = {0};
        dem_wall dw;
        memset(&dw, 0, sizeof dw);
        dw.material = mat;
        if (!strcmp(w->type, "plane")) {
            need[0] = "point", need[1] = "normal";
            dw.kind = DEM_WALL_PLANE;
        } else if (!strcmp(w->type, "cylinder")) {
            need[0] = "point", need[1] = "axis", need[2] = "radius";
            dw.kind = DEM_WALL_CYLINDER;
        } else if (!strcmp(w->type, "box")) {
            need[0] = "lo", need[1] = "hi";
        } else {
            snprintf(p, sizeof p, "%s.type", base);
            return scene_fail(sc, err, errlen, p, "unknown wall type '%s' (plane, cylinder or box)", w->type);
        }
        if (w->cup && strcmp(w->type, "plane")) {
            snprintf(p, sizeof p, "%s.cup", base);
            return scene_fail(sc, err, errlen, p, "only a plane wall (a punch) has a cup");
        }
        for (int q = 0; need[q]; q++) {
            snprintf(p, sizeof p, "%s.%s", base, need[q]);
            if (!scene_has(sc->loc, p))
                return scene_fail(sc, err, errlen, p, "a %s wall needs '%s'", w->type, need[q]);
        }
        snprintf(p, sizeof p, "%s.height", base);
        if (scene_has(sc->loc, p) && (strcmp(w->type, "cylinder") || !(w->height > 0) || !isfinite(w->height)))
            return scene_fail(sc, err, errlen, p, !strcmp(w->type, "cylinder") ? "cylinder height must be > 0 m (leave "
                                                                               "it out for an endless cylinder)"
                                                                             : "only a cylinder has a height");
        if (!strcmp(w->type, "box")) {
            for (int d = 0; d < 3; d++)
                if (!(w->hi[d] > w->lo[d]) || !isfinite(w->lo[d]) || !isfinite(w->hi[d])) {
                    snprintf(p, sizeof p, "%s.hi", base);
                    return scene_fail(sc, err, errlen, p, "box needs finite lo < hi on every axis");
                }
            int id = dem_add_box(s, w->lo, w->hi, mat);
            if (id < 0)
                return scene_fail(sc, err, errlen, base, "%s", dem_error(s));
            first_wall[k] = id;
            if (nst) /* a moving box moves as a whole */
                for (int q = 0; q < 6; q++)
                    dem_set_wall_motion(s, id + q, nst, st);
            continue;
        }
        memcpy(dw.point, w->point, sizeof dw.point);
        memcpy(dw.normal, dw.kind == DEM_WALL_PLANE ? w->normal : w->axis, sizeof dw.normal);
        dw.radius = w->radius;
        if (!finite3(dw.point)) {
            snprintf(p, sizeof p, "%s.point", base);
            return scene_fail(sc, err, errlen, p, "must be finite");
        }
        if (!(norm3(dw.normal) > 0) || !finite3(dw.normal)) {
            snprintf(p, sizeof p, "%s.%s", base, dw.kind == DEM_WALL_PLANE ? "normal" : "axis");
            return scene_fail(sc, err, errlen, p, "must be a finite non-zero vector");
        }
        if (dw.kind == DEM_WALL_CYLINDER && !(dw.radius > 0 && isfinite(dw.radius))) {
            snprintf(p, sizeof p, "%s.radius", base);
            return scene_fail(sc, err, errlen, p, "cylinder radius must be > 0 m");
        }
        dw.height = dw.kind == DEM_WALL_CYLINDER ? w->height : 0;
        if (w->cup) {
            snprintf(p, sizeof p, "%s.cup.radius", base);
            if (!(w->cup->radius > 0) || !isfinite(w->cup->radius))
                return scene_fail(sc, err, errlen, p, "must be > 0 m and finite");
            snprintf(p, sizeof p, "%s.cup.depth", base);
            if (!(w->cup->depth >= 1e-3 * w->cup->radius) || !(w->cup->radius >= w->cup->depth))
                return scene_fail(sc, err, errlen, p, "a cup needs radius / 1000 <= depth <= radius (at most a "
                                  "hemisphere; a shallower one is a flat punch; got radius %g m, depth %g m)",
                                  w->cup->radius, w->cup->depth);
            dw.cup_radius = w->cup->radius;
            dw.cup_depth = w->cup->depth;
        }
        dw.nstages = nst;
        memcpy(dw.stages, st, sizeof(dem_stage) * (size_t)nst);
        int id = dem_add_wall(s, &dw);
        if (id < 0)
            return scene_fail(sc, err, errlen, base, "%s", dem_error(s));
        first_wall[k] = id;
    }
    /* the stages that wait for another wall (`after`), now that every wall has its id */
    for (unsigned k = 0; k < f->walls_count; k++) {
        int waits = 0;
        for (unsigned j = 0; j < f->walls[k].motion_count; j++)
            waits |= f->walls[k].motion[j].after != NULL;
        if (!waits)
            continue;
        dem_stage st[DEM_MAX_STAGES];
        int nst = 0, box = !strcmp(f->walls[k].type, "box");
        if (parse_motion(sc, (int)k, f->time.settle, st, &nst, first_wall, nst_of, err, errlen))
            return 1;
        for (int q = 0; q < (box ? 6 : 1); q++)
            if (dem_set_wall_motion(s, first_wall[k] + q, nst, st)) {
                char p[64];
                snprintf(p, sizeof p, "walls[%u].motion", k);
                return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
            }
    }
    return 0;
}

static int parse_output(const scene *sc, scene_run *run, char *err, size_t errlen)
{
    const scene_output *o = &sc->f->output;
    static const char *names[] = {"position", "velocity", "angular_velocity", "radius", "force", "torque", "material",
                                  "stress", "contacts"};
    run->fields = 0;
    if (!o->fields_count)
        run->fields = OUT_POSITION | OUT_VELOCITY | OUT_RADIUS;
    for (unsigned k = 0; k < o->fields_count; k++) {
        unsigned bit = 0;
        for (int q = 0; q < 9; q++)
            if (!strcmp(o->fields[k], names[q]))
                bit = 1u << q;
        char p[64];
        snprintf(p, sizeof p, "output.fields[%u]", k);
        if (!bit)
            return scene_fail(sc, err, errlen, p,
                              "unknown field '%s' (position, velocity, angular_velocity, radius, force, torque, "
                              "material, stress, contacts)", o->fields[k]);
        run->fields |= bit;
    }
    const double dt = run->dt, T = sc->f->time.duration;
    struct {
        const char *key;
        double value, dflt;
        long *steps;
    } iv[3] = {{"output.frame_every", o->frame_every, T / 50, &run->frame_every},
               {"output.series_every", o->series_every, T / 500, &run->series_every},
               {"output.checkpoint_every", o->checkpoint_every, 0, &run->checkpoint_every}};
    for (int q = 0; q < 3; q++) {
        double v = scene_has(sc->loc, iv[q].key) ? iv[q].value : iv[q].dflt;
        if (!(v >= 0) || !isfinite(v))
            return scene_fail(sc, err, errlen, iv[q].key, "must be >= 0 s");
        /* in steps, computed in double and capped at the run's length before it becomes an integer: an interval longer
         * than the run means the first and last frames only (in integers, 1e300 s would overflow into "every step") */
        double r = v / dt;
        long st = r >= (double)run->steps ? run->steps : (long)llround(r);
        *iv[q].steps = st < 1 ? (q == 2 && v == 0 ? 0 : 1) : st;
    }
    /* series_average N: a row is the mean of the N steps that end at it (LIGGGHTS' fix ave/time), so N cannot
     * exceed the steps between rows */
    run->series_average = 1;
    if (scene_has(sc->loc, "output.series_average")) {
        if (o->series_average < 1 || (long)o->series_average > run->series_every)
            return scene_fail(sc, err, errlen, "output.series_average",
                              "must be 1 .. %ld (steps between series rows: series_every / dt), got %u",
                              run->series_every, o->series_average);
        run->series_average = o->series_average;
    }
    return 0;
}

static int parse_time(const scene *sc, dem_sim *s, scene_run *run, char *err, size_t errlen)
{
    const scene_time *t = &sc->f->time;
    int has_dt = scene_has(sc->loc, "time.dt"), has_fr = scene_has(sc->loc, "time.dt_rayleigh");
    if (has_dt == has_fr)
        return scene_fail(sc, err, errlen, "time", "give exactly one of dt [s] or dt_rayleigh (fraction of the "
                                                   "Rayleigh time)");
    /* every particle's mass and its inverse must be ordinary numbers: a denormal density or radius would make the
     * time scales 0 and be blamed on the time step */
    for (int i = 0; i < dem_count(s); i++) {
        int m = dem_particle_material(s, i);
        double r = dem_particle_radius(s, i), mass = dem_particle_mass(s, i);
        if (!isnormal(mass) || !isfinite(1 / mass)) {
            char p[64];
            if (m < (int)sc->f->materials_count)
                snprintf(p, sizeof p, "materials[%d].density", m);
            else
                snprintf(p, sizeof p, "membranes"); /* a vertex: its membrane's density x thickness x area */
            return scene_fail(sc, err, errlen, p, "particle %d (radius %g m) would weigh %g kg, too small to integrate "
                              "(its inverse overflows); check the density [kg/m^3] and the radii [m]", i, r, mass);
        }
    }
    run->particles = dem_count(s);
    dem_time_scales_get(s, 0, &run->ts);
    if (!(run->ts.rayleigh_time > 0) || !isfinite(run->ts.rayleigh_time))
        return scene_fail(sc, err, errlen, "materials", "the Rayleigh time of these materials and radii is %g s: check "
                          "young, poisson and density", run->ts.rayleigh_time);
    if (has_fr) {
        if (!(t->dt_rayleigh > 0) || !isfinite(t->dt_rayleigh))
            return scene_fail(sc, err, errlen, "time.dt_rayleigh", "must be > 0");
        run->dt = t->dt_rayleigh * run->ts.rayleigh_time;
    } else {
        if (!(t->dt > 0) || !isfinite(t->dt))
            return scene_fail(sc, err, errlen, "time.dt", "time step must be > 0 s");
        run->dt = t->dt;
    }
    if (run->dt > run->ts.max_dt) {
        char why[160];
        dem_time_scales_limit(&run->ts, why, sizeof why);
        return scene_fail(sc, err, errlen, has_dt ? "time.dt" : "time.dt_rayleigh",
                          "time step %.6g s exceeds the stability bound %.6g s (%s; recommended %.6g s)", run->dt,
                          run->ts.max_dt, why, run->ts.recommended_dt);
    }
    if (!(t->duration > 0) || !isfinite(t->duration))
        return scene_fail(sc, err, errlen, "time.duration", "duration must be > 0 s");
    if (!(t->settle >= 0) || !(t->settle < t->duration))
        return scene_fail(sc, err, errlen, "time.settle", "settling time must be in [0, duration)");
    double ns = t->duration / run->dt; /* in double first: in integers 1e-300 s would overflow into "1 steps" */
    if (!(ns <= DEM_SCENE_MAX_STEPS))
        return scene_fail(sc, err, errlen, has_dt ? "time.dt" : "time.dt_rayleigh",
                          "duration %g s / time step %g s = %.3g steps, more than %.0e: use a larger time step or a "
                          "shorter duration", t->duration, run->dt, ns, (double)DEM_SCENE_MAX_STEPS);
    run->steps = (long)llround(ns);
    if (run->steps < 1)
        run->steps = 1;
    dem_set_dt(s, run->dt);
    return 0;
}

static int parse_run_options(const scene *sc, dem_sim *s, scene_run *run, char *err, size_t errlen)
{
    const scene_file *f = sc->f;
    dem_config_default(&run->cfg);
    if (f->precision) {
        if (!strcmp(f->precision, "fp32"))
            run->cfg.precision = DEM_FP32;
        else if (strcmp(f->precision, "fp64"))
            return scene_fail(sc, err, errlen, "precision", "precision must be fp32 or fp64 (got '%s')", f->precision);
    }
    if (f->backend) {
        if (!strcmp(f->backend, "reference"))
            run->cfg.backend = DEM_BACKEND_REFERENCE;
        else if (strcmp(f->backend, "opencl"))
            return scene_fail(sc, err, errlen, "backend", "backend must be opencl or reference (got '%s')",
                              f->backend);
    }
    if (scene_has(sc->loc, "device")) {
        if (f->device < 0)
            return scene_fail(sc, err, errlen, "device", "device index must be >= 0");
        run->cfg.device = f->device;
    }
    if (!finite3(f->gravity))
        return scene_fail(sc, err, errlen, "gravity", "must be finite");
    if (norm3(f->gravity) > 0 && !(run->effects & DEM_EFFECT_GRAVITY))
        return scene_fail(sc, err, errlen, "gravity", "gravity is set but the effect 'gravity' is not listed");
    /* under mass scaling the weights stay real (gravity / S), or the fall does (time.mass_scale_keeps: acceleration,
     * for a pour: docs/scenes.md "Mass scaling") */
    const char *keeps = f->time.mass_scale_keeps;
    if (keeps && strcmp(keeps, "weight") && strcmp(keeps, "acceleration"))
        return scene_fail(sc, err, errlen, "time.mass_scale_keeps", "'%s': give weight (gravity / mass_scale, the "
                          "default: weights real) or acceleration (gravity as given: a pour falls at the real rate)",
                          keeps);
    if (keeps && !scene_has(sc->loc, "time.mass_scale"))
        return scene_fail(sc, err, errlen, "time.mass_scale_keeps", "means something only with time.mass_scale");
    const double scale = scene_keeps_acceleration(sc) ? 1.0 : scene_mass_scale(sc);
    const double g[3] = {f->gravity[0] / scale, f->gravity[1] / scale, f->gravity[2] / scale};
    dem_set_gravity(s, g);
    if (scene_has(sc->loc, "domain") && dem_set_domain(s, f->domain_lo, f->domain_hi))
        return scene_fail(sc, err, errlen, "domain", "%s", dem_error(s));
    if (dem_set_effects(s, run->effects))
        return scene_fail(sc, err, errlen, "effects", "%s", dem_error(s));
    if (dem_set_mc_stress_convention(s, run->mcs_conv))
        return scene_fail(sc, err, errlen, "mc_stress_convention", "%s", dem_error(s));
    if (scene_has(sc->loc, "mc_contact_distance") && dem_set_mc_strain_reach(s, f->mc_contact_distance))
        return scene_fail(sc, err, errlen, "mc_contact_distance", "%s", dem_error(s));
    run->mc_cap = f->mc_iterations;
    run->mc_tol = scene_has(sc->loc, "mc_tolerance") ? f->mc_tolerance : 1e-6;
    if (f->mc_iterations > 0 && dem_set_mc_strain(s, f->mc_iterations, run->mc_tol))
        return scene_fail(sc, err, errlen, "mc_iterations", "%s", dem_error(s));
    return 0;
}

/* The sample a piston compresses: its height and cross-section, for strain and stress. */
static int parse_sample(const scene *sc, dem_sim *s, scene_run *run, const int *first_wall,
                        const scene_origin *origin, int nspheres, char *err, size_t errlen)
{
    const scene_file *f = sc->f;
    run->piston = -1;
    if (!f->sample)
        return 0;
    int k = -1;
    for (unsigned q = 0; q < f->walls_count; q++)
        if (f->walls[q].name && !strcmp(f->walls[q].name, f->sample->piston) && !strcmp(f->walls[q].type, "plane"))
            k = (int)q;
    if (k < 0) {
        char hint[300];
        return scene_fail(sc, err, errlen, "sample.piston", "no plane wall named '%s'%s", f->sample->piston,
                          scene_wall_hint(sc, f->sample->piston, 1, hint, sizeof hint));
    }
    run->piston = first_wall[k];
    const double *p = f->walls[k].point, *nr = f->walls[k].normal;
    double nn = norm3(nr), n[3] = {nr[0] / nn, nr[1] / nn, nr[2] / nn};
    memcpy(run->piston_point, p, sizeof run->piston_point);
    memcpy(run->piston_normal, n, sizeof run->piston_normal);
    run->sample_height = f->sample->height;
    run->contact_travel = f->sample->contact_travel;
    if (!(run->contact_travel >= 0) || !isfinite(run->contact_travel))
        return scene_fail(sc, err, errlen, "sample.contact_travel", "must be >= 0 m");
    if (!(run->sample_height > 0)) { /* piston to the lowest particle bottom along the normal */
        double far = 0;
        for (int i = 0; i < nspheres; i++) { /* the spheres (origin holds no membrane vertex) */
            const double *x = origin[i].x;
            double dd = (x[0] - p[0]) * n[0] + (x[1] - p[1]) * n[1] + (x[2] - p[2]) * n[2] + origin[i].r;
            if (dd > far)
                far = dd;
        }
        run->sample_height = far;
    }
    run->sample_area = f->sample->area;
    for (unsigned q = 0; q < f->walls_count && !(run->sample_area > 0); q++) {
        const scene_wall *w = &f->walls[q];
        if (!strcmp(w->type, "cylinder")) {
            double an = norm3(w->axis), c = fabs(w->axis[0] * n[0] + w->axis[1] * n[1] + w->axis[2] * n[2]) / an;
            if (c > 0.999)
                run->sample_area = M_PI * w->radius * w->radius;
        } else if (!strcmp(w->type, "box")) {
            int ax = fabs(n[0]) > 0.999 ? 0 : fabs(n[1]) > 0.999 ? 1 : fabs(n[2]) > 0.999 ? 2 : -1;
            if (ax >= 0)
                run->sample_area = (w->hi[(ax + 1) % 3] - w->lo[(ax + 1) % 3]) * (w->hi[(ax + 2) % 3] - w->lo[(ax + 2) % 3]);
        }
    }
    if (!(run->sample_area > 0) || !isfinite(run->sample_area))
        return scene_fail(sc, err, errlen, "sample.area", "give the cross-section (no box or cylinder along the "
                                                           "piston normal to take it from)");
    if (!(run->sample_height > 0) || !isfinite(run->sample_height))
        return scene_fail(sc, err, errlen, "sample.height", "sample height must be > 0 m");
    return 0;
}

/* A punch stage that ends at a relative density needs a die and a facing punch (dem_density_walls): refused here,
 * at the stage's line, rather than by dem_start with the library's wall numbers. */
static int check_density_walls(const scene *sc, dem_sim *s, const int *first_wall, char *err, size_t errlen)
{
    for (unsigned k = 0; k < sc->f->walls_count; k++)
        for (unsigned q = 0; q < sc->f->walls[k].motion_count; q++) {
            char p[128];
            snprintf(p, sizeof p, "walls[%u].motion[%u].until_density", k, q);
            int die, other;
            if (!scene_has(sc->loc, p))
                continue;
            if (dem_density_walls(s, first_wall[k], &die, &other))
                return scene_fail(sc, err, errlen, p, "needs the die (a cylinder wall along this punch's normal) and a "
                                  "punch facing it on the particles' side: %s", die < 0 ? "no such cylinder"
                                                                                       : "no facing plane wall");
            dem_wall d, w;
            dem_wall_get(s, die, &d);
            for (int e = 0; e < 2; e++) { /* the cups' volumes count as the bore's (dem_relative_density) */
                dem_wall_get(s, e ? other : first_wall[k], &w);
                int in = dem_cup_in_bore(s, e ? other : first_wall[k], die); /* 1, 0, or a negative DEM_ERR_* */
                if (in < 0)
                    return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
                if (!in)
                    return scene_fail(sc, err, errlen, p, "the %s punch's cup (radius %g m) does not lie within the "
                                      "die's bore (radius %g m)", e ? "facing" : "moving", w.cup_radius, d.radius);
            }
        }
    return 0;
}

dem_sim *scene_build(const scene *sc, scene_run *run, char *err, size_t errlen)
{
    memset(run, 0, sizeof *run);
    dem_sim *s = dem_create();
    int first_wall[DEM_MAX_WALLS], nspheres = 0;
    scene_origin *origin = NULL;
    if (!s) {
        snprintf(err, errlen, "%s: out of memory", sc->path);
        return NULL;
    }
    if (!sc->f->particles_count && !sc->f->membranes_count) { /* a membrane alone is a scene: its vertices move */
        snprintf(err, errlen, "%s:1: particles: a scene needs particles, or a membrane (whose vertices are "
                 "particles)", sc->path); /* line 1, as libcyaml names a missing key */
        dem_destroy(s);
        return NULL;
    }
    if (parse_effects(sc, run, err, errlen) || parse_materials(sc, s, err, errlen) ||
        scene_add_particles(sc, s, &origin, run->fill, sizeof run->fill, err, errlen) || (nspheres = dem_count(s), 0) ||
        parse_walls(sc, s, run, first_wall, err, errlen) || check_density_walls(sc, s, first_wall, err, errlen) ||
        scene_add_membranes(sc, s, run, first_wall, err, errlen) ||
        (run->effects |= dem_effects(s) & DEM_EFFECT_CONSTRAINTS, 0) ||
        parse_run_options(sc, s, run, err, errlen) || parse_time(sc, s, run, err, errlen) ||
        parse_output(sc, run, err, errlen) ||
        scene_check_overlaps(sc, s, origin, nspheres, err, errlen) ||
        parse_sample(sc, s, run, first_wall, origin, nspheres, err, errlen)) {
        free(origin);
        dem_destroy(s);
        return NULL;
    }
    free(origin);
    run->cfg.contacts = (run->fields & OUT_CONTACTS) != 0; /* frames carry the contact network: keep wall forces */
    /* particle_order: spatial (the default) sorts the particles at load (scene_particles.c) and stores them anew every
     * DEM_REORDER_PERIOD rebuilds as they move (host/core/reorder.c: the same bits and ids) */
    run->cfg.reorder = !strcmp(scene_particle_order(sc), "spatial") ? DEM_REORDER_PERIOD : 0;
    run->cfg.sample_every = run->series_average > 1 ? 1 : run->series_every; /* steps between the series' samples */
    if (!(run->effects & DEM_EFFECT_FRICTION))
        for (unsigned k = 0; k < sc->f->materials_count; k++)
            if (sc->f->materials[k].friction > 0) {
                snprintf(run->note, sizeof run->note,
                         "friction coefficients are given but the effect 'friction' is off: they are not used");
                break;
            }
    return s;
}
