/* membrane.c - dem_add_membrane: a mesh (host/mesh/mesh.c) becomes particles, springs, triangles and hinges with the
 * membrane's material (seed 001 section 2.2; the parameters are documented at dem_membrane in dem_membrane.h). */
#include "sim.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double tri_area(const double *x, const int *t)
{
    const double *a = x + 3 * t[0], *b = x + 3 * t[1], *c = x + 3 * t[2];
    double u[3], v[3];
    for (int q = 0; q < 3; q++)
        u[q] = b[q] - a[q], v[q] = c[q] - a[q];
    double n0 = u[1] * v[2] - u[2] * v[1], n1 = u[2] * v[0] - u[0] * v[2], n2 = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
}

#define POSITIVE(v) ((v) > 0 && isfinite(v))
#define NONNEG(v) ((v) >= 0 && isfinite(v))

static int check_material(dem_sim *s, const dem_membrane *mm)
{
    if (!POSITIVE(mm->young) || !POSITIVE(mm->thickness) || !POSITIVE(mm->density) || !POSITIVE(mm->vertex_radius))
        return sim_fail(s, DEM_ERR_ARG, "membrane: young, thickness, density and vertex_radius must be > 0 and finite "
                        "(got %g Pa, %g m, %g kg/m^3, %g m)", mm->young, mm->thickness, mm->density,
                        mm->vertex_radius);
    if (mm->model != DEM_MEMBRANE_PARTICLE && mm->model != DEM_MEMBRANE_PATCH)
        return sim_fail(s, DEM_ERR_ARG, "membrane: model %d (DEM_MEMBRANE_PARTICLE 0 or DEM_MEMBRANE_PATCH 1)", mm->model);
    if (!NONNEG(mm->damping) || !NONNEG(mm->kel) || !NONNEG(mm->kdiss))
        return sim_fail(s, DEM_ERR_ARG, "membrane: damping, kel and kdiss must be >= 0 and finite (got %g, %g N m, "
                        "%g N s)", mm->damping, mm->kel, mm->kdiss);
    return 0;
}

/* Each vertex's mass (a third of each of its triangles'), and the mesh's area in *area, once the triangles, vertices
 * and edges are checked against the membrane (every triangle has an area, every vertex a triangle, no edge is
 * shorter than vertex_radius); NULL otherwise, reported, with its dem_status in *rc. The caller frees the result. */
static double *vertex_masses(dem_sim *s, const dem_mesh *m, const dem_membrane *mm, const dem_mesh_topo *t,
                             double *area, int *rc)
{
    double *vmass = calloc((size_t)m->nv, sizeof(double)), shortest = INFINITY;
    if (!vmass)
        return *rc = sim_fail(s, DEM_ERR_NOMEM, "out of host memory"), NULL;
    for (int k = 0; k < m->nt; k++) {
        double a = tri_area(m->x, m->tri + 3 * k);
        if (!(a > 0)) {
            free(vmass);
            return *rc = sim_fail(s, DEM_ERR_ARG, "membrane: triangle %d (vertices %d, %d, %d) has no area", k,
                            m->tri[3 * k], m->tri[3 * k + 1], m->tri[3 * k + 2]), NULL;
        }
        *area += a;
        for (int j = 0; j < 3; j++) /* a third of each triangle's mass to each of its vertices */
            vmass[m->tri[3 * k + j]] += mm->density * mm->thickness * a / 3;
    }
    for (int e = 0; e < t->ne; e++) {
        const double *a = m->x + 3 * t->edge[2 * e], *b = m->x + 3 * t->edge[2 * e + 1];
        shortest = fmin(shortest, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                       (a[2] - b[2]) * (a[2] - b[2])));
    }
    int bad = -1;
    for (int i = 0; i < m->nv && bad < 0; i++)
        if (!(vmass[i] > 0))
            bad = i;
    if (bad >= 0 || mm->vertex_radius > shortest) {
        free(vmass);
        if (bad >= 0)
            return *rc = sim_fail(s, DEM_ERR_ARG, "membrane: vertex %d belongs to no triangle", bad), NULL;
        return *rc = sim_fail(s, DEM_ERR_ARG, "membrane: vertex_radius %g m is more than the shortest edge, %g m (a vertex "
                        "would reach past its neighbours)", mm->vertex_radius, shortest), NULL;
    }
    return vmass;
}

int dem_add_membrane(dem_sim *s, const dem_mesh *m, const dem_membrane *mm, dem_membrane_info *info)
{
    if (s->run.started || s->split_started)
        return sim_fail(s, DEM_ERR_STATE, "dem_add_membrane after dem_start");
    if (!m || !mm || m->nv < 3 || m->nt < 1 || !m->x || !m->tri)
        return sim_fail(s, DEM_ERR_ARG, "membrane: a mesh of at least 3 vertices and one triangle is needed");
    int rc = check_material(s, mm);
    if (rc)
        return rc;
    for (int i = 0; i < 3 * m->nv; i++)
        if (!isfinite(m->x[i]))
            return sim_fail(s, DEM_ERR_ARG, "membrane: vertex %d is not finite", i / 3);
    char err[256];
    dem_mesh_topo t;
    if ((rc = dem_mesh_topology(m, &t, err, sizeof err)))
        return sim_fail(s, rc, "membrane: %s", err);
    double area = 0, *vmass = vertex_masses(s, m, mm, &t, &area, &rc);
    if (!vmass)
        return dem_mesh_topo_free(&t), rc;
    /* everything checked; what follows fails only for memory, and then is undone */
    int n0 = s->n, ns0 = s->mesh.nsprings, nt0 = s->mesh.ntri, nh0 = s->mesh.nhinges, nm0 = s->nmat, np0 = s->mesh.npatch;
    unsigned eff0 = s->effects;
    double k = sqrt(3.0) / 2 * mm->young * mm->thickness;
    int mat = dem_add_material(s, &(dem_material){mm->density, mm->young, mm->poisson, mm->restitution,
                                                  mm->friction, 0, 0});
    int ok = mat >= 0;
    rc = mat; /* each call's return: when !ok, the failed call's dem_status */
    if (ok) /* its vertices do not touch each other: their spheres may overlap (neighbor.h) */
        s->mat_apart[mat] = 1;
    for (int i = 0; ok && i < m->nv; i++)
        ok = (rc = dem_add_particle(s, m->x + 3 * i, NULL, mm->vertex_radius, mat)) >= 0 &&
             (rc = dem_set_particle_mass(s, n0 + i, vmass[i], 0)) == 0;
    for (int e = 0; ok && e < t.ne; e++)
        ok = (rc = dem_add_spring(s, n0 + t.edge[2 * e], n0 + t.edge[2 * e + 1], k, -1, mm->damping)) >= 0;
    for (int j = 0; ok && j < m->nt; j++)
        ok = (rc = dem_add_triangle(s, n0 + m->tri[3 * j], n0 + m->tri[3 * j + 1], n0 + m->tri[3 * j + 2])) >= 0;
    int hinges = mm->kel > 0 || mm->kdiss > 0;
    for (int h = 0; ok && hinges && h < t.nhinges; h++) {
        const int *g = t.hinge + 4 * h;
        ok = (rc = dem_add_hinge(s, n0 + g[0], n0 + g[1], n0 + g[2], n0 + g[3], mm->kel, mm->kdiss, NAN)) >= 0;
    }
    if (ok && mm->model == DEM_MEMBRANE_PATCH)
        ok = (rc = dem_add_patches(s, nt0, m->nt)) == 0;
    if (ok && info)
        *info = (dem_membrane_info){n0, m->nv, ns0, t.ne, nt0, m->nt, nh0, hinges ? t.nhinges : 0, area,
                                    mm->density * mm->thickness * area};
    free(vmass), dem_mesh_topo_free(&t);
    if (!ok) { /* undo: the message of the failed call stays */
        s->n = n0, s->mesh.nsprings = ns0, s->mesh.ntri = nt0, s->mesh.nhinges = nh0, s->nmat = nm0, s->effects = eff0;
        if (mat >= 0)
            s->mat_apart[mat] = 0;
        s->mesh.npatch = np0;
        return rc;
    }
    return 0;
}
