/* scene_membranes.c - the scene's `membranes:` (seed 001): each a generated mesh made a membrane of its material and
 * model, the confining pressure (one for all membranes: the library loads every triangle with it), and the vertices
 * near a plane wall riding on it. Keys in docs/scenes.md; the library calls in include/dem_membrane.h (dem_mesh_make,
 * dem_add_membrane, dem_set_pressure_stages, dem_attach_to_wall). */
#include "scene.h"
#include "scene_particles.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef DEM_SCENE_MAX_GENERATED /* as scene_particles.c */
#define DEM_SCENE_MAX_GENERATED 5000000
#endif

/* A generated mesh's spec (0), a file mesh (-1: read_mesh reads it), or a refusal (1) */
static int mesh_spec(const scene *sc, unsigned k, const scene_mesh *ms, dem_mesh_spec *sp, char *err, size_t errlen)
{
    static const struct {
        const char *kind;
        dem_mesh_kind id;
        const char *need[3];
    } kinds[] = {{"tube", DEM_MESH_TUBE, {"radius", "height", "edge"}},
                 {"sheet", DEM_MESH_SHEET, {"size", "edge", NULL}},
                 {"sphere", DEM_MESH_SPHERE, {"radius", "edge", NULL}}};
    static const char *const generated_only[] = {"center", "radius", "height", "size", "edge"};
    static const char *const file_only[] = {"path", "scale", "translate", "flip"};
    char p[128];
    int q = 0, file = !strcmp(ms->kind, "file");
    while (q < 3 && strcmp(ms->kind, kinds[q].kind))
        q++;
    if (q == 3 && !file) {
        snprintf(p, sizeof p, "membranes[%u].mesh.kind", k);
        return scene_fail(sc, err, errlen, p, "unknown mesh kind '%s' (tube, sheet, sphere or file)", ms->kind);
    }
    for (int j = 0; j < (file ? 5 : 4); j++) { /* keys of the other family are refused, not ignored */
        snprintf(p, sizeof p, "membranes[%u].mesh.%s", k, file ? generated_only[j] : file_only[j]);
        if (scene_has(sc->loc, p))
            return scene_fail(sc, err, errlen, p, "not a key of a %s mesh", ms->kind);
    }
    if (file) {
        snprintf(p, sizeof p, "membranes[%u].mesh.path", k);
        if (!ms->path)
            return scene_fail(sc, err, errlen, p, "a file mesh needs 'path' (.obj or .stl)");
        return -1; /* a file: the caller reads it */
    }
    for (int j = 0; j < 3 && kinds[q].need[j]; j++) {
        snprintf(p, sizeof p, "membranes[%u].mesh.%s", k, kinds[q].need[j]);
        if (!scene_has(sc->loc, p))
            return scene_fail(sc, err, errlen, p, "a %s mesh needs '%s'", ms->kind, kinds[q].need[j]);
    }
    if (!(ms->edge > 0) || !isfinite(ms->edge)) {
        snprintf(p, sizeof p, "membranes[%u].mesh.edge", k);
        return scene_fail(sc, err, errlen, p, "must be > 0 m and finite");
    }
    memset(sp, 0, sizeof *sp);
    sp->kind = kinds[q].id;
    memcpy(sp->center, ms->center, sizeof sp->center);
    sp->a = q == 1 ? ms->size[0] : ms->radius;
    sp->b = q == 1 ? ms->size[1] : ms->height;
    sp->edge = ms->edge;
    const char *bad = NULL; /* the centre and the sizes, refused at their own keys */
    for (int j = 0; j < 3; j++)
        bad = !isfinite(sp->center[j]) ? "center" : bad;
    if (!bad && !(sp->a > 0 && isfinite(sp->a)))
        bad = q == 1 ? "size" : "radius";
    if (!bad && q != 2 && !(sp->b > 0 && isfinite(sp->b)))
        bad = q == 1 ? "size" : "height";
    if (bad) {
        snprintf(p, sizeof p, "membranes[%u].mesh.%s", k, bad);
        return scene_fail(sc, err, errlen, p, strcmp(bad, "center") ? "must be > 0 m and finite" : "must be finite [m]");
    }
    /* the vertices it will have, counted exactly (dem_mesh_vertices) before anything is made: the cap of generated
     * particle groups (scene_particles.c) holds for meshes too */
    double nv = dem_mesh_vertices(sp);
    if (!(nv <= DEM_SCENE_MAX_GENERATED)) {
        snprintf(p, sizeof p, "membranes[%u].mesh.edge", k);
        return scene_fail(sc, err, errlen, p, "edges of %g m make %.3g vertices (at most %d): use longer edges",
                          ms->edge, nv, DEM_SCENE_MAX_GENERATED);
    }
    return 0;
}

/* A generated mesh whose springs would make the time step fail, refused before it is made (a tube of 1.9e6 vertices
 * took 17.6 s and 1.35 GB in dem check to be refused by parse_time once made). Only a sure refusal, with margins: the
 * stability bound parse_time will compute is at most a tenth of the shortest spring period, 2 pi sqrt(mu / k) with
 * k = sqrt(3)/2 E t and mu at most the mass of the spring's free end; no vertex of a generated sheet or tube weighs
 * more than an inner one, density x thickness x the area of its six triangles / 3 = rho t dx dy (dx the spacing along
 * a row or ring, dy between rows), taken 1.5 times for the triangles' slant. A time.dt above that bound: refused.
 * With dt_rayleigh, dt = f x the smallest Rayleigh time of all particles, pi sqrt(3 m / (4 pi r G)) / (0.1631 nu +
 * 0.8766) for a vertex of mass m and radius r (host/core/sim_setup.c): at least the lightest vertex's - a tube's rims
 * weigh half an inner vertex, a sheet's corners a twelfth (taken a third and a sixteenth) - with r at most a quarter
 * of one edge (the default vertex_radius is a quarter of the shortest), and the spheres' own; only the scene's one
 * membrane, so that no other adds vertices of unknown weight. Spheres (irregular vertex areas) and fixed membranes
 * (no spring period) are left to parse_time, which checks every scene exactly once the mesh exists. */
static int mesh_dt_check(const scene *sc, dem_sim *s, unsigned k, const dem_mesh_spec *sp, char *err, size_t errlen)
{
    const scene_membrane *m = &sc->f->membranes[k];
    const scene_membrane_material *mt = &m->material;
    const scene_time *t = &sc->f->time;
    int has_dt = scene_has(sc->loc, "time.dt"), has_fr = scene_has(sc->loc, "time.dt_rayleigh");
    if (m->fixed || has_dt == has_fr || sp->kind == DEM_MESH_SPHERE || !(mt->poisson > -1) || !(mt->poisson <= 0.5))
        return 0; /* nothing sure to say: parse_time decides (and names what is wrong) */
    int tube = sp->kind == DEM_MESH_TUBE;
    double n1, n2, dx, dy; /* the grid the generator will make */
    dem_mesh_grid(sp, &n1, &n2, &dx, &dy);
    double inner = mt->density * scene_mass_scale(sc) * mt->thickness * dx * dy, E = mt->young;
    double kspring = sqrt(3.0) / 2 * E * mt->thickness;
    double bound = 2 * M_PI * sqrt(1.5 * inner / kspring) / 10; /* at least parse_time's stability bound */
    if (!(bound > 0) || !isfinite(bound))
        return 0;
    double dt = t->dt;
    char p[128], given[128];
    snprintf(given, sizeof given, "time.dt gives %.3g s", dt);
    if (has_fr) {
        snprintf(p, sizeof p, "membranes[%u].material.vertex_radius", k);
        double r = scene_has(sc->loc, p) ? mt->vertex_radius : 0.25 * dx;
        double G = E / (2 * (1 + mt->poisson)), c = 0.1631 * mt->poisson + 0.8766, light = (tube ? 1.0 / 3 : 1.0 / 16);
        double vertex = M_PI * sqrt(3 * light * inner / (4 * M_PI * r * G)) / c, spheres = INFINITY;
        dem_time_scales ts; /* the particles so far: spheres only (one membrane), so no spring or hinge to weigh */
        if (sc->f->membranes_count != 1 || !(t->dt_rayleigh > 0) || !(r > 0) || !isfinite(vertex) ||
            (dem_count(s) > 0 && dem_time_scales_get(s, 0, &ts)))
            return 0;
        if (dem_count(s) > 0)
            spheres = ts.rayleigh_time;
        dt = t->dt_rayleigh * fmin(spheres, vertex); /* at most what parse_time will take */
        snprintf(given, sizeof given, "time.dt_rayleigh %g gives at least %.3g s (its lightest vertex's Rayleigh "
                                      "time %.3g s)", t->dt_rayleigh, dt, vertex);
    }
    if (!(dt > bound))
        return 0;
    snprintf(p, sizeof p, "membranes[%u].mesh.edge", k);
    return scene_fail(sc, err, errlen, p, "edges of %g m make %.0f vertices of at most %.3g kg, whose springs (%.3g "
                      "N/m) need a time step below %.3g s (a tenth of their shortest period); the scene's %s: refused "
                      "before the mesh is made. Use longer edges, a smaller time step, or mass scaling", sp->edge,
                      dem_mesh_vertices(sp), 1.5 * inner, kspring, bound, given);
}

static int find_wall(const scene *sc, const char *name, const int *first_wall)
{
    for (unsigned w = 0; w < sc->f->walls_count; w++)
        if (sc->f->walls[w].name && !strcmp(sc->f->walls[w].name, name))
            return (int)w;
    (void)first_wall;
    return -1;
}

/* Vertices (particles first .. first + nv - 1 at x) within `within` of plane wall k ride on it */
static int attach(const scene *sc, dem_sim *s, unsigned k, unsigned a, const double *x, int first, int nv,
                  const int *first_wall, char *err, size_t errlen)
{
    const scene_attach *at = &sc->f->membranes[k].attach[a];
    char p[128];
    snprintf(p, sizeof p, "membranes[%u].attach[%u].wall", k, a);
    int w = find_wall(sc, at->wall, first_wall);
    if (w < 0) {
        char hint[300];
        return scene_fail(sc, err, errlen, p, "no wall named '%s'%s", at->wall,
                          scene_wall_hint(sc, at->wall, 0, hint, sizeof hint));
    }
    const scene_wall *sw = &sc->f->walls[w];
    if (strcmp(sw->type, "plane"))
        return scene_fail(sc, err, errlen, p, "wall '%s' is a %s: vertices ride on plane walls only", at->wall,
                          sw->type);
    snprintf(p, sizeof p, "membranes[%u].attach[%u].within", k, a);
    if (!(at->within >= 0) || !isfinite(at->within))
        return scene_fail(sc, err, errlen, p, "must be >= 0 m and finite");
    double n = sqrt(sw->normal[0] * sw->normal[0] + sw->normal[1] * sw->normal[1] + sw->normal[2] * sw->normal[2]);
    int count = 0;
    for (int i = 0; i < nv; i++) {
        double d = 0;
        for (int c = 0; c < 3; c++)
            d += (x[3 * i + c] - sw->point[c]) * sw->normal[c] / n;
        if (fabs(d) <= at->within) {
            if (dem_attach_to_wall(s, first + i, first_wall[w]))
                return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
            count++;
        }
    }
    if (!count)
        return scene_fail(sc, err, errlen, p, "no vertex of the membrane is within %g m of wall '%s'", at->within,
                          at->wall);
    return 0;
}

/* The confining pressure: the first membrane that gives one sets it; every other must give the same */
static int pressure(const scene *sc, dem_sim *s, unsigned k, int *set_by, char *err, size_t errlen)
{
    const scene_membrane *m = &sc->f->membranes[k];
    char p[128], ps[128];
    snprintf(p, sizeof p, "membranes[%u].pressure", k);
    snprintf(ps, sizeof ps, "membranes[%u].pressure_stages", k);
    int has_p = scene_has(sc->loc, p), has_st = m->pressure_stages_count > 0;
    if (!has_p && !has_st)
        return 0;
    if (!isfinite(m->pressure))
        return scene_fail(sc, err, errlen, p, "must be finite [Pa]");
    for (unsigned j = 0; j < m->pressure_stages_count; j++)
        if (!(m->pressure_stages[j].duration >= 0) || !isfinite(m->pressure_stages[j].duration) ||
            !isfinite(m->pressure_stages[j].pressure)) {
            snprintf(ps, sizeof ps, "membranes[%u].pressure_stages[%u]", k, j);
            return scene_fail(sc, err, errlen, ps, "duration must be >= 0 s and pressure finite");
        }
    if (*set_by >= 0) { /* the same as the first, or refused */
        const scene_membrane *f = &sc->f->membranes[*set_by];
        int same = f->pressure == m->pressure && f->pressure_stages_count == m->pressure_stages_count;
        for (unsigned j = 0; same && j < m->pressure_stages_count; j++)
            same = f->pressure_stages[j].duration == m->pressure_stages[j].duration &&
                   f->pressure_stages[j].pressure == m->pressure_stages[j].pressure;
        if (!same)
            return scene_fail(sc, err, errlen, has_p ? p : ps, "differs from membranes[%d]'s: libdem %s loads every "
                              "triangle with one confining pressure", *set_by, DEM_VERSION);
        return 0;
    }
    *set_by = (int)k;
    if (dem_set_pressure(s, m->pressure))
        return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
    if (has_st) {
        dem_pressure_stage st[DEM_MAX_STAGES];
        for (unsigned j = 0; j < m->pressure_stages_count; j++)
            st[j].duration = m->pressure_stages[j].duration, st[j].pressure = m->pressure_stages[j].pressure;
        if (dem_set_pressure_stages(s, (int)m->pressure_stages_count, st))
            return scene_fail(sc, err, errlen, ps, "%s", dem_error(s));
    }
    return 0;
}

/* A mesh file (relative to the scene's folder), scaled, moved and, if asked, turned over */
static int read_mesh(const scene *sc, unsigned k, dem_mesh *mesh, char *err, size_t errlen)
{
    const scene_mesh *ms = &sc->f->membranes[k].mesh;
    char file[4200], why[4600], p[128];
    scene_file_path(sc, ms->path, file, sizeof file);
    snprintf(p, sizeof p, "membranes[%u].mesh.path", k);
    if (dem_mesh_read(file, mesh, why, sizeof why))
        return scene_fail(sc, err, errlen, p, "%s", why);
    snprintf(p, sizeof p, "membranes[%u].mesh.scale", k);
    double scale = scene_has(sc->loc, p) ? ms->scale : 1;
    if (!(scale > 0) || !isfinite(scale)) {
        dem_mesh_free(mesh);
        return scene_fail(sc, err, errlen, p, "must be > 0 and finite [m per unit of the file]");
    }
    snprintf(p, sizeof p, "membranes[%u].mesh.translate", k);
    if (!isfinite(ms->translate[0]) || !isfinite(ms->translate[1]) || !isfinite(ms->translate[2])) {
        dem_mesh_free(mesh);
        return scene_fail(sc, err, errlen, p, "must be finite [m]");
    }
    for (int i = 0; i < mesh->nv; i++)
        for (int d = 0; d < 3; d++)
            mesh->x[3 * i + d] = mesh->x[3 * i + d] * scale + ms->translate[d];
    for (int t = 0; ms->flip && t < mesh->nt; t++) {
        int a = mesh->tri[3 * t + 1];
        mesh->tri[3 * t + 1] = mesh->tri[3 * t + 2], mesh->tri[3 * t + 2] = a;
    }
    return 0;
}

static double shortest_edge(const dem_mesh *m)
{
    double s = INFINITY;
    for (int t = 0; t < m->nt; t++)
        for (int c = 0; c < 3; c++) {
            const double *a = m->x + 3 * m->tri[3 * t + c], *b = m->x + 3 * m->tri[3 * t + (c + 1) % 3];
            s = fmin(s, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
        }
    return s;
}

int scene_add_membranes(const scene *sc, dem_sim *s, scene_run *run, const int *first_wall, char *err, size_t errlen)
{
    const scene_file *f = sc->f;
    int listed = -1;
    for (unsigned k = 0; k < f->effects_count; k++)
        if (!strcmp(f->effects[k], "membrane"))
            listed = (int)k;
    if (f->membranes_count && listed < 0)
        return scene_fail(sc, err, errlen, "membranes", "membranes are defined but the effect 'membrane' is not listed");
    if (!f->membranes_count && listed >= 0) {
        char p[64];
        snprintf(p, sizeof p, "effects[%d]", listed);
        return scene_fail(sc, err, errlen, p, "effect 'membrane' is listed but the scene has no membranes");
    }
    int set_by = -1;
    for (unsigned k = 0; k < f->membranes_count; k++) {
        const scene_membrane *m = &f->membranes[k];
        const scene_membrane_material *mt = &m->material;
        char p[128];
        dem_mesh_spec sp;
        int e = mesh_spec(sc, k, &m->mesh, &sp, err, errlen);
        if (e > 0)
            return 1;
        dem_mesh mesh;
        char why[4600];
        snprintf(p, sizeof p, "membranes[%u].mesh", k);
        if (e == 0 && mesh_dt_check(sc, s, k, &sp, err, errlen))
            return 1;
        if (e == 0 && dem_mesh_make(&sp, &mesh, why, sizeof why))
            return scene_fail(sc, err, errlen, p, "%s", why);
        if (e < 0 && read_mesh(sc, k, &mesh, err, errlen))
            return 1;

        int model = DEM_MEMBRANE_PATCH;
        if (m->model && !strcmp(m->model, "particle"))
            model = DEM_MEMBRANE_PARTICLE;
        else if (m->model && strcmp(m->model, "patch")) {
            dem_mesh_free(&mesh);
            snprintf(p, sizeof p, "membranes[%u].model", k);
            return scene_fail(sc, err, errlen, p, "unknown model '%s' (patch or particle)", m->model);
        }
        /* the mesh itself before its material: a vertex out of range or two corners at one point would otherwise
         * show as a vertex_radius (a quarter of the shortest edge) of nan or 0 */
        double se = shortest_edge(&mesh);
        if (!(se > 0) || !isfinite(se)) {
            dem_mesh_free(&mesh);
            return scene_fail(sc, err, errlen, p, "its shortest edge comes out %g m: %s", se,
                              se == 0 ? "two corners of a triangle coincide" : "its coordinates are too large (their "
                              "squares overflow) or not finite");
        }
        snprintf(p, sizeof p, "membranes[%u].material.vertex_radius", k);
        double vr = scene_has(sc->loc, p) ? mt->vertex_radius : 0.25 * se;
        dem_membrane dm = {mt->young, mt->poisson, mt->thickness, mt->density * scene_mass_scale(sc),
                           mt->restitution, mt->friction, mt->damping, mt->kel, mt->kdiss, vr, model};
        dem_membrane_info info;
        snprintf(p, sizeof p, "membranes[%u]", k);
        if (dem_add_membrane(s, &mesh, &dm, &info)) {
            dem_mesh_free(&mesh);
            return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
        }
        for (int i = 0; m->fixed && i < info.nvertices; i++)
            dem_set_particle_flags(s, info.first_particle + i, DEM_PARTICLE_FIXED);
        run->membrane[k] = info; /* k < 16: the schema's limit */
        for (unsigned a = 0; a < m->attach_count; a++)
            if (attach(sc, s, k, a, mesh.x, info.first_particle, info.nvertices, first_wall, err, errlen)) {
                dem_mesh_free(&mesh);
                return 1;
            }
        dem_mesh_free(&mesh);
        if (pressure(sc, s, k, &set_by, err, errlen))
            return 1;
    }
    run->effects |= dem_effects(s) & (DEM_EFFECT_CHANNEL | DEM_EFFECT_PATCHES | DEM_EFFECT_RIDERS);
    return 0;
}
