/* mesh_elements.c - the membrane elements a simulation holds, by particle index: springs, triangles (and the pressure
 * on them, with its schedule), patches (triangles that spheres touch as surfaces) and hinges. The meshes that make
 * them are built in host/mesh/. */
#include "sim.h"
#include "dem_layout.h"
#include <math.h>
#include <string.h>

int dem_add_spring(dem_sim *s, int i, int j, double k, double rest, double gamma)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (i < 0 || i >= s->n || j < 0 || j >= s->n || i == j)
        return sim_fail(s, DEM_ERR_ARG, "spring %d: particles %d and %d (two different particles of 0..%d)",
                        s->mesh.nsprings, i, j, s->n - 1);
    if (!(k > 0) || !isfinite(k) || !isfinite(rest) || !(gamma >= 0) || !isfinite(gamma))
        return sim_fail(s, DEM_ERR_ARG, "spring %d: k must be > 0 N/m, rest finite, gamma >= 0 (got %g, %g, %g)",
                        s->mesh.nsprings, k, rest, gamma);
    if (sim_grow(s, s->mesh.nsprings, &s->mesh.spring_cap, &s->mesh.spring_ij, 2, &s->mesh.spring_kr, 3, "springs"))
        return DEM_ERR_NOMEM;
    int id = s->mesh.nsprings++;
    s->mesh.spring_ij[2 * id] = i, s->mesh.spring_ij[2 * id + 1] = j;
    s->mesh.spring_kr[3 * id] = k, s->mesh.spring_kr[3 * id + 1] = rest, s->mesh.spring_kr[3 * id + 2] = gamma;
    s->effects |= DEM_EFFECT_SPRINGS;
    return id;
}

int dem_spring_count(const dem_sim *s) { return s->mesh.nsprings; }

int dem_add_triangle(dem_sim *s, int a, int b, int c)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (a < 0 || a >= s->n || b < 0 || b >= s->n || c < 0 || c >= s->n || a == b || b == c || a == c)
        return sim_fail(s, DEM_ERR_ARG, "triangle %d: particles %d, %d, %d (three different particles of 0..%d)",
                        s->mesh.ntri, a, b, c, s->n - 1);
    if (sim_grow(s, s->mesh.ntri, &s->mesh.tri_cap, &s->mesh.tri, 3, NULL, 0, "triangles"))
        return DEM_ERR_NOMEM;
    int id = s->mesh.ntri++;
    s->mesh.tri[3 * id] = a, s->mesh.tri[3 * id + 1] = b, s->mesh.tri[3 * id + 2] = c;
    return id;
}

int dem_triangle_count(const dem_sim *s) { return s->mesh.ntri; }
void dem_triangles_get(const dem_sim *s, int *tri) { memcpy(tri, s->mesh.tri, sizeof(int) * 3 * (size_t)s->mesh.ntri); }

int dem_add_patches(dem_sim *s, int first, int count)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (first < 0 || count < 1 || first > s->mesh.ntri - count)
        return sim_fail(s, DEM_ERR_ARG, "patches: triangles %d..%d (of 0..%d)", first, first + count - 1, s->mesh.ntri - 1);
    for (int k = 0; k < s->mesh.npatch; k++)
        if (s->mesh.patch[k] >= first && s->mesh.patch[k] < first + count)
            return sim_fail(s, DEM_ERR_ARG, "patches: triangle %d is a patch already", s->mesh.patch[k]);
    for (int t = first; t < first + count; t++) {
        if (sim_grow(s, s->mesh.npatch, &s->mesh.patch_cap, &s->mesh.patch, 1, NULL, 0, "patches"))
            return DEM_ERR_NOMEM;
        s->mesh.patch[s->mesh.npatch++] = t;
    }
    s->effects |= DEM_EFFECT_PATCHES;
    return 0;
}

int dem_add_hinge(dem_sim *s, int p1, int p2, int p3, int p4, double kel, double kdiss, double theta0)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    int p[4] = {p1, p2, p3, p4};
    for (int a = 0; a < 4; a++) {
        if (p[a] < 0 || p[a] >= s->n)
            return sim_fail(s, DEM_ERR_ARG, "hinge %d: no particle %d", s->mesh.nhinges, p[a]);
        for (int b = 0; b < a; b++)
            if (p[a] == p[b])
                return sim_fail(s, DEM_ERR_ARG, "hinge %d: particle %d twice", s->mesh.nhinges, p[a]);
    }
    if (!(kel >= 0) || !isfinite(kel) || !(kdiss >= 0) || !isfinite(kdiss) || isinf(theta0))
        return sim_fail(s, DEM_ERR_ARG, "hinge %d: kel and kdiss must be >= 0, theta0 finite or NAN (got %g, %g, %g)",
                        s->mesh.nhinges, kel, kdiss, theta0);
    if (sim_grow(s, s->mesh.nhinges, &s->mesh.hinge_cap, &s->mesh.hinge, 4, &s->mesh.hinge_k, 3, "hinges"))
        return DEM_ERR_NOMEM;
    int id = s->mesh.nhinges++;
    memcpy(s->mesh.hinge + 4 * id, p, sizeof p);
    s->mesh.hinge_k[3 * id] = kel, s->mesh.hinge_k[3 * id + 1] = kdiss, s->mesh.hinge_k[3 * id + 2] = theta0;
    s->effects |= DEM_EFFECT_BENDING;
    return id;
}

int dem_hinge_count(const dem_sim *s) { return s->mesh.nhinges; }

int dem_set_pressure_stages(dem_sim *s, int nstages, const dem_pressure_stage *st)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (nstages < 0 || nstages > DEM_MAX_STAGES || (nstages > 0 && !st))
        return sim_fail(s, DEM_ERR_ARG, "pressure stages: 0 to %d stages (got %d)", DEM_MAX_STAGES, nstages);
    for (int k = 0; k < nstages; k++)
        if (!(st[k].duration >= 0) || !isfinite(st[k].duration) || !isfinite(st[k].pressure))
            return sim_fail(s, DEM_ERR_ARG, "pressure stage %d: duration must be >= 0 and finite, pressure finite (got "
                            "%g s, %g Pa)", k, st[k].duration, st[k].pressure);
    memcpy(s->mesh.pstages, st, sizeof *st * (size_t)nstages);
    s->mesh.npstages = nstages;
    s->effects |= DEM_EFFECT_PRESSURE;
    return 0;
}

double dem_pressure(const dem_sim *s) { return s->run.started ? s->mesh.pressure_now : 0; }

int dem_set_pressure(dem_sim *s, double sigma)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    if (!isfinite(sigma))
        return sim_fail(s, DEM_ERR_ARG, "pressure must be finite (got %g Pa)", sigma);
    s->mesh.pressure = sigma;
    s->effects |= DEM_EFFECT_PRESSURE;
    return 0;
}
