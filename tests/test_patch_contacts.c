/* test_patch_contacts.c - spheres touching a membrane's patches (common/patch_contacts.h; seed 001 section 2.5):
 * issue 10's tests 5 (a sphere held at a fixed overlap against a pinned patched sheet feels the Hertz force of that
 * overlap wherever it is: face, edge or vertex; the MSS_particle model does not), 6 (no sphere passes through a
 * closed patched membrane under a high pressure with edges of twice the spheres' diameter; the same membrane as
 * vertex particles lets them out) and 7 (OpenCL equals the reference bit for bit; a restart continues bit for bit). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "test_util.h"

/* the membrane of test_membrane.c (Table 2 of seed 001: rubber) */
static const dem_membrane rubber = {1.25e6, 1.0 / 3, 3e-4, 1000, 0.5, 1.2, 0.3, 1e-4, 1e-6, 0.001, DEM_MEMBRANE_PATCH};
static const dem_material glass = {2500, 5e6, 0.3, 0.5, 0.5, 0, 0};

/* ---- test 5: Hertz force across a pinned sheet ---- */
#define SHEET_EDGE 0.01
#define SPHERE_R 0.005
#define OVERLAP 2e-4

/* A simulation holding the generated mesh sp as a membrane of model `model` (vertex radius vr, 0: rubber's);
 * *nv: its vertices (particles 0 .. nv-1) */
static dem_sim *membrane_sim(const dem_mesh_spec *sp, int model, double vr, int *nv)
{
    dem_sim *s = dem_create();
    dem_mesh m;
    char err[256];
    if (dem_mesh_make(sp, &m, err, sizeof err))
        fail_msg("%s", err);
    dem_membrane mm = rubber;
    mm.model = model;
    if (vr > 0)
        mm.vertex_radius = vr;
    if (dem_add_membrane(s, &m, &mm, NULL))
        fail_msg("%s", dem_error(s));
    *nv = m.nv;
    dem_mesh_free(&m);
    return s;
}

typedef struct {
    double x, y;   /* the sphere's centre over the sheet (z = SPHERE_R - OVERLAP) */
    int model;
    int nv;        /* out: the sheet's vertices (the sphere is particle nv) */
} sheet_case;

static dem_sim *build_sheet(void *ctx)
{
    sheet_case *sc = ctx;
    dem_mesh_spec sp = {DEM_MESH_SHEET, {0, 0, 0}, 0.06, 0.06, SHEET_EDGE};
    /* vertex radius edge/5: the sheet's side edges are half edges */
    dem_sim *s = membrane_sim(&sp, sc->model, 0.2 * SHEET_EDGE, &sc->nv);
    for (int i = 0; i < sc->nv; i++)
        assert_int_equal(dem_set_particle_flags(s, i, DEM_PARTICLE_FIXED), 0);
    int mat = dem_add_material(s, &glass);
    int id = dem_add_particle(s, (double[3]){sc->x, sc->y, SPHERE_R - OVERLAP}, NULL, SPHERE_R, mat);
    assert_int_equal(id, sc->nv);
    assert_int_equal(dem_set_particle_flags(s, id, DEM_PARTICLE_FIXED), 0);
    dem_set_domain(s, (double[3]){-0.04, -0.04, -0.02}, (double[3]){0.04, 0.04, 0.02});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

static double hertz(const dem_material *a, const dem_membrane *b, double r, double d)
{
    double estar = 1 / ((1 - a->poisson * a->poisson) / a->young + (1 - b->poisson * b->poisson) / b->young);
    return 4.0 / 3 * estar * sqrt(r) * d * sqrt(d);
}

/* The force on the sphere and the sum of the forces on the vertices, after dem_start */
static void sheet_forces(const dem_config *c, sheet_case *sc, double fs[3], double fv[3])
{
    dem_sim *s = build_sheet(sc);
    start_or_fail(s, c);
    int n = dem_count(s);
    double *f = malloc(sizeof(double) * 3 * (size_t)n);
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
    for (int d = 0; d < 3; d++) {
        fs[d] = f[3 * sc->nv + d];
        fv[d] = 0;
        for (int i = 0; i < sc->nv; i++)
            fv[d] += f[3 * i + d];
    }
    free(f);
    dem_destroy(s);
}

static void test_hertz_across_sheet(void **st)
{
    (void)st;
    /* a path across the sheet's lattice (spacing SHEET_EDGE along x, rows SHEET_EDGE sqrt(3)/2 apart in y), and a
     * vertex, an edge's midpoint and a face's centre found from the mesh */
    dem_mesh m;
    char err[256];
    dem_mesh_spec sp = {DEM_MESH_SHEET, {0, 0, 0}, 0.06, 0.06, SHEET_EDGE};
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    int t = m.nt / 2;
    const double *a = m.x + 3 * m.tri[3 * t], *b = m.x + 3 * m.tri[3 * t + 1], *c = m.x + 3 * m.tri[3 * t + 2];
    double pts[24][2] = {{a[0], a[1]},
                         {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])},
                         {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3}};
    const char *what[24] = {"vertex", "edge", "face"};
    int np = 3;
    for (int k = 0; k < 21; k++, np++) { /* along a slanted line through the three */
        pts[np][0] = a[0] - 0.5 * SHEET_EDGE + k * 0.057 * SHEET_EDGE;
        pts[np][1] = a[1] - 0.3 * SHEET_EDGE + k * 0.041 * SHEET_EDGE;
        what[np] = "path";
    }
    dem_mesh_free(&m);
    double want = hertz(&glass, &rubber, SPHERE_R, OVERLAP);
    FOR_EACH_BACKEND(bc)
    {
        dem_config c = cfg_of(bc->backend, bc->precision);
        double worst = 0, worst_xy = 0, worst_sum = 0;
        for (int k = 0; k < np; k++) {
            sheet_case sc = {pts[k][0], pts[k][1], DEM_MEMBRANE_PATCH, 0};
            double fs[3], fv[3];
            sheet_forces(&c, &sc, fs, fv);
            worst = fmax(worst, fabs(fs[2] / want - 1));
            worst_xy = fmax(worst_xy, fmax(fabs(fs[0]), fabs(fs[1])) / want);
            for (int d = 0; d < 3; d++)
                worst_sum = fmax(worst_sum, fabs(fs[d] + fv[d]) / want);
            if (k < 3)
                printf("  %s: sphere over a %s: F_z %.6g N (Hertz %.6g N)\n", bc->name, what[k], fs[2], want);
        }
        printf("  %s, patches: %d positions, largest |F_z/Hertz - 1| %.2g, |F_xy|/Hertz %.2g, "
               "|F_sphere + sum F_vertices|/Hertz %.2g\n", bc->name, np, worst, worst_xy, worst_sum);
        assert_true(worst < 1e-3);
        assert_true(worst_xy < 1e-3);
        assert_true(worst_sum < 64 * bc->eps);
        if (bc->backend != DEM_BACKEND_REFERENCE || bc->precision != DEM_FP64)
            continue;
        /* the MSS_particle model: the same sphere touches vertex spheres of radius edge/5 */
        double lo = INFINITY, hi = 0;
        for (int k = 0; k < np; k++) {
            sheet_case sc = {pts[k][0], pts[k][1], DEM_MEMBRANE_PARTICLE, 0};
            double fs[3], fv[3];
            sheet_forces(&c, &sc, fs, fv);
            double f = sqrt(fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]);
            lo = fmin(lo, f), hi = fmax(hi, f);
        }
        printf("  MSS_particle (vertex radius edge/5), same centres: |F| from %.4g to %.4g N (%.3g to %.3g x Hertz "
               "of a flat patch)\n", lo, hi, lo / want, hi / want);
        assert_true(hi - lo > 0.5 * want); /* the force depends on where the sphere is */
    }
}

/* The tangential spring crosses edges: a sphere held at a fixed overlap and dragged slowly (both bodies moved, so
 * no damping) across a pinned sheet of 1 mm patches over 3 mm, with friction high enough that it never slides: the
 * friction force grows steadily, never dropping where the sphere passes onto the next patch - the new contact takes
 * the ended one's spring (patch_contacts.h). Without that it falls to zero at every crossing. */
typedef struct {
    int nv;
    long steps;
} drag_case;

static dem_sim *build_drag(void *ctx)
{
    drag_case *dc = ctx;
    dem_mesh_spec sp = {DEM_MESH_SHEET, {0, 0, 0}, 0.03, 0.03, 0.001};
    dem_membrane mm = rubber;
    mm.friction = 50;
    dem_sim *s = dem_create();
    dem_mesh m;
    char err[256];
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    mm.vertex_radius = 0.0002;
    if (dem_add_membrane(s, &m, &mm, NULL))
        fail_msg("%s", dem_error(s));
    dc->nv = m.nv;
    dem_mesh_free(&m);
    for (int i = 0; i < dc->nv; i++)
        dem_set_particle_flags(s, i, DEM_PARTICLE_FIXED);
    dem_material g = glass;
    g.friction = 50;
    int id = dem_add_particle(s, (double[3]){-0.0013, 0.0004, SPHERE_R - OVERLAP}, (double[3]){0.1, 0, 0}, SPHERE_R,
                              dem_add_material(s, &g));
    dem_set_particle_flags(s, id, DEM_PARTICLE_FIXED);
    dem_set_domain(s, (double[3]){-0.02, -0.02, -0.01}, (double[3]){0.02, 0.02, 0.01});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    dc->steps = (long)(0.003 / (0.1 * ts.recommended_dt));
    return s;
}

static void check_drag(dem_sim *s, const backend_case *bc, void *ctx)
{
    drag_case *dc = ctx;
    double *f = malloc(sizeof(double) * 3 * (size_t)dem_count(s)), prev = 0, worst_drop = 0, first = 0;
    for (long k = 0; k < dc->steps; k += 10) {
        step_or_fail(s, 10);
        assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
        double ft = -f[3 * dc->nv]; /* against the motion (+x) */
        if (k == 0)
            first = ft;
        worst_drop = fmax(worst_drop, prev - ft);
        prev = ft;
    }
    printf("  %s: dragged 3 mm over 1 mm patches: friction from %.4g to %.4g N, largest drop between samples %.2g N\n",
           bc->name, first, prev, worst_drop);
    assert_true(prev > 10 * first);           /* the spring kept building */
    assert_true(worst_drop <= 1e-6 * prev);   /* and never restarted */
    free(f);
}

static void test_spring_across_edges(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        if (bc->precision != DEM_FP64) /* the rule is integer logic; fp64 shows it (and OpenCL = reference) */
            continue;
        drag_case dc;
        backend_run(bc, build_drag, 0, check_drag, &dc);
    }
}

/* Energy: a sphere released at an overlap of 0.2 mm on a pinned patched sheet, without damping or friction, bounces
 * with its total energy (kinetic + potential + the patch contact's Hertz energy in dem_energy) kept to 1e-4 */
static void test_patch_energy(void **st)
{
    (void)st;
    sheet_case sc = {0.0013, 0.0007, DEM_MEMBRANE_PATCH, 0};
    FOR_EACH_BACKEND(bc)
    {
        if (bc->precision != DEM_FP64)
            continue;
        dem_sim *s = build_sheet(&sc);
        assert_int_equal(dem_set_particle_flags(s, sc.nv, 0), 0); /* the sphere free */
        dem_set_effects(s, dem_effects(s) & ~(unsigned)(DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION));
        dem_set_gravity(s, (double[3]){0, 0, -9.81});
        dem_config c = cfg_of(bc->backend, bc->precision);
        start_or_fail(s, &c);
        dem_energy_t e0, e;
        assert_int_equal(dem_energy(s, &e0), 0);
        double worst = 0, emax = 0;
        long touching = 0;
        for (int k = 0; k < 400; k++) {
            step_or_fail(s, 5);
            assert_int_equal(dem_energy(s, &e), 0);
            worst = fmax(worst, fabs(e.total - e0.total));
            emax = fmax(emax, e.elastic);
            touching += e.patch_contacts > 0;
        }
        printf("  %s: bouncing on patches, elastic energy up to %.3g J, total energy %.6g J kept to %.2g of it "
               "(%ld of 400 samples in contact)\n", bc->name, emax, e0.total, worst / fabs(e0.total), touching);
        assert_true(touching > 10 && emax > 0);
        assert_true(worst < 1e-4 * fabs(e0.total));
        dem_destroy(s);
    }
}

/* ---- test 6: no tunnelling; test 7: bitwise ---- */
#define BALL_R 0.03
#define BALL_EDGE 0.01        /* twice the spheres' diameter */
#define BEAD_R 0.0025

typedef struct {
    int model;
    double pressure;
    double half;   /* half the domain's side [m] */
    int nv, nbeads;
} ball_case;

static dem_sim *build_ball(void *ctx)
{
    ball_case *bc = ctx;
    dem_mesh_spec sp = {DEM_MESH_SPHERE, {0, 0, 0}, BALL_R, 0, BALL_EDGE};
    dem_sim *s = membrane_sim(&sp, bc->model, 0, &bc->nv);
    int mat = dem_add_material(s, &glass);
    bc->nbeads = 0;
    double h = 2.2 * BEAD_R; /* a loose lattice of beads inside */
    for (int i = -5; i <= 5; i++)
        for (int j = -5; j <= 5; j++)
            for (int k = -5; k <= 5; k++) {
                double p[3] = {i * h + 1e-4 * j, j * h + 1e-4 * k, k * h + 1e-4 * i};
                if (sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) > BALL_R - 2 * BEAD_R)
                    continue;
                assert_true(dem_add_particle(s, p, NULL, BEAD_R, mat) >= 0);
                bc->nbeads++;
            }
    assert_int_equal(dem_set_pressure(s, bc->pressure), 0);
    dem_set_domain(s, (double[3]){-bc->half, -bc->half, -bc->half}, (double[3]){bc->half, bc->half, bc->half});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

/* The winding number of the closed mesh (the membrane's triangles, vertices = particles 0..nv-1) about p: 1 inside,
 * 0 outside (Van Oosterom and Strackee's solid angle of each triangle, summed over 4 pi). */
static double winding(const double *x, const int *tri, int nt, const double *p)
{
    double sum = 0;
    for (int t = 0; t < nt; t++) {
        double r[3][3], l[3];
        for (int c = 0; c < 3; c++) {
            for (int d = 0; d < 3; d++)
                r[c][d] = x[3 * tri[3 * t + c] + d] - p[d];
            l[c] = sqrt(r[c][0] * r[c][0] + r[c][1] * r[c][1] + r[c][2] * r[c][2]);
        }
        double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                     r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        double d01 = r[0][0] * r[1][0] + r[0][1] * r[1][1] + r[0][2] * r[1][2];
        double d02 = r[0][0] * r[2][0] + r[0][1] * r[2][1] + r[0][2] * r[2][2];
        double d12 = r[1][0] * r[2][0] + r[1][1] * r[2][1] + r[1][2] * r[2][2];
        sum += 2 * atan2(det, l[0] * l[1] * l[2] + d01 * l[2] + d02 * l[1] + d12 * l[0]);
    }
    return fabs(sum) / (4 * M_PI);
}

/* Beads outside the membrane, and the membrane's mean radius */
static int escaped(dem_sim *s, const ball_case *bc, double *mean_r)
{
    int n = dem_count(s), nt = dem_triangle_count(s), out = 0;
    double *x = malloc(sizeof(double) * 3 * (size_t)n);
    int *tri = malloc(sizeof(int) * 3 * (size_t)nt);
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    dem_mesh m;
    char err[256];
    dem_mesh_spec sp = {DEM_MESH_SPHERE, {0, 0, 0}, BALL_R, 0, BALL_EDGE};
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    memcpy(tri, m.tri, sizeof(int) * 3 * (size_t)nt);
    dem_mesh_free(&m);
    for (int i = bc->nv; i < n; i++)
        out += winding(x, tri, nt, x + 3 * i) < 0.5;
    *mean_r = 0;
    for (int i = 0; i < bc->nv; i++)
        *mean_r += sqrt(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] + x[3 * i + 2] * x[3 * i + 2]) / bc->nv;
    free(x), free(tri);
    return out;
}

#define SQUEEZE_STEPS 3000
#define SQUEEZE_P 4000.0

static void check_squeeze(dem_sim *s, const backend_case *bc, void *ctx)
{
    ball_case *b = ctx;
    double r0 = 0, r;
    int out = 0;
    for (int round = 0; round < 3; round++) {
        step_or_fail(s, SQUEEZE_STEPS / 3);
        out += escaped(s, b, round == 0 ? &r0 : &r);
    }
    printf("  %s, patches: %d beads of diameter %.3g m in a membrane of edge %.3g m at %.0f Pa: mean radius %.4f m "
           "after %d steps (%.4f m at a third), %d outside\n", bc->name, b->nbeads, 2 * BEAD_R, BALL_EDGE, b->pressure,
           r, SQUEEZE_STEPS, r0, out);
    assert_int_equal(out, 0);
    assert_true(r < 0.8 * BALL_R); /* the pressure did squeeze the membrane onto the beads */
}

static void test_no_tunnelling(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        ball_case b = {DEM_MEMBRANE_PATCH, SQUEEZE_P, 0.05, 0, 0};
        backend_run(bc, build_ball, 0, check_squeeze, &b);
    }
    /* the control: the same membrane as vertex particles (radius 1 mm: the gaps between them are wider than a bead) */
    ball_case b = {DEM_MEMBRANE_PARTICLE, SQUEEZE_P, 1.0, 0, 0}; /* the beads that get out fly far */
    dem_sim *s = build_ball(&b);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    step_or_fail(s, SQUEEZE_STEPS);
    double r;
    int out = escaped(s, &b, &r);
    printf("  control, MSS_particle with vertex radius %.3g m: %d of %d beads outside after %d steps\n",
           rubber.vertex_radius, out, b.nbeads, SQUEEZE_STEPS);
    assert_true(out > 0);
    dem_destroy(s);
}

/* A restart in the middle of the squeeze continues bit for bit (the patch contacts' history is in the state) */
static void test_patch_restart(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        dem_config c = cfg_of(bc->backend, bc->precision);
        ball_case ba = {DEM_MEMBRANE_PATCH, SQUEEZE_P, 0.05, 0, 0}, bb = ba;
        dem_sim *a = build_ball(&ba), *b = build_ball(&bb);
        restart_check(a, b, &c, 1500, 500, bc->name);
        dem_destroy(a);
        dem_destroy(b);
    }
}

/* The squeeze with other work-group sizes, cell sizes and skins (and a second run) has the reference's bits at every
 * 100th step, in both precisions: the rows differ, the sums do not */
static void test_patch_variants(void **st)
{
    (void)st;
    static const struct {
        const char *name;
        dem_backend_kind backend;
        size_t local;
        double cell, skin; /* [m]; 0: the default */
    } v[] = {{"PoCL, work groups of 1", DEM_BACKEND_OPENCL, 1, 0, 0},
             {"PoCL, work groups of 64, cells 0.02 m", DEM_BACKEND_OPENCL, 64, 0.02, 0},
             {"PoCL, skin 2 mm", DEM_BACKEND_OPENCL, 0, 0, 0.002},
             {"reference, cells 0.013 m, skin 0.3 mm", DEM_BACKEND_REFERENCE, 0, 0.013, 3e-4}};
    for (int p = 0; p < 2; p++) {
        dem_precision prec = p ? DEM_FP32 : DEM_FP64;
        ball_case b = {DEM_MEMBRANE_PATCH, SQUEEZE_P, 0.05, 0, 0};
        dem_sim *ref = build_ball(&b), *sims[4];
        dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
        start_or_fail(ref, &rc);
        for (int k = 0; k < 4; k++) {
            sims[k] = build_ball(&b);
            dem_config c = cfg_of(v[k].backend, prec);
            c.local_size = v[k].local, c.cell_size = v[k].cell, c.skin = v[k].skin;
            start_or_fail(sims[k], &c);
        }
        char msg[512];
        for (int round = 0; round < 15; round++) {
            step_or_fail(ref, 100);
            for (int k = 0; k < 4; k++) {
                step_or_fail(sims[k], 100);
                if (state_diff(ref, sims[k], msg, sizeof msg))
                    fail_msg("%s, %s, step %ld: %s", v[k].name, p ? "fp32" : "fp64", dem_step_index(ref), msg);
            }
        }
        printf("  %s: 4 variants equal the reference bit for bit over 1500 steps (%ld rebuilds)\n", p ? "fp32" : "fp64",
               dem_rebuild_count(ref));
        assert_true(dem_rebuild_count(ref) > 3);
        for (int k = 0; k < 4; k++)
            dem_destroy(sims[k]);
        dem_destroy(ref);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hertz_across_sheet),
        cmocka_unit_test(test_spring_across_edges),
        cmocka_unit_test(test_patch_energy),
        cmocka_unit_test(test_no_tunnelling),
        cmocka_unit_test(test_patch_restart),
        cmocka_unit_test(test_patch_variants),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
