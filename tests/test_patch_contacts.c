/* test_patch_contacts.c - spheres touching a membrane's patches (common/patch_contacts.h; seed 001 section 2.5):
 * a sphere held at a fixed overlap against a pinned patched sheet feels the Hertz force of that overlap wherever it
 * is: face, edge or vertex (the MSS_particle model does not); no sphere passes through a closed patched membrane
 * under a high pressure with edges of twice the spheres' diameter (the same membrane as vertex particles lets them
 * out); OpenCL equals the reference bit for bit, and a restart continues bit for bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "test_util.h"
#include "ref_kernels.h" /* dem_patch_probe_f64 */

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

/* Points exactly on shared edges and vertices, in every orientation: a sphere centred over a vertex, over
 * the midpoint of each of the six edges at it and a third of the way along them, at the overlap OVERLAP, against a
 * pinned sheet turned by each of seven rotations (the vertices and the centre rounded in the turned frame, so that
 * the two faces at an edge classify the point each by its own rounding). Each position is one contact of the Hertz
 * force of that overlap along the sheet's normal: two face contacts at a point of the edge they share doubled it
 * (a slide along a vertex row felt up to 1.88 times its weight). */
typedef struct {
    double rot[3][3];
    double p[3];    /* the centre before the rotation */
    int nv;         /* out */
} turned_case;

static void turn(const double r[3][3], const double *p, double *q)
{
    for (int d = 0; d < 3; d++)
        q[d] = r[d][0] * p[0] + r[d][1] * p[1] + r[d][2] * p[2];
}

/* A pinned sheet turned by rot, and a pinned sphere at rot p moving at rot v (v: NULL, at rest), the effects `off`
 * turned off; *nv: the sheet's vertices, *dt: the recommended step it runs at */
static dem_sim *turned_sheet(const double rot[3][3], const double *p, const double *v, unsigned off, int *nv,
                             double *dt)
{
    dem_mesh_spec sp = {DEM_MESH_SHEET, {0, 0, 0}, 0.06, 0.06, SHEET_EDGE};
    dem_mesh m;
    char err[256];
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    for (int i = 0; i < m.nv; i++) {
        double q[3];
        turn(rot, m.x + 3 * i, q);
        memcpy(m.x + 3 * i, q, sizeof q);
    }
    dem_membrane mm = rubber;
    mm.vertex_radius = 0.2 * SHEET_EDGE;
    dem_sim *s = dem_create();
    if (dem_add_membrane(s, &m, &mm, NULL))
        fail_msg("%s", dem_error(s));
    *nv = m.nv;
    dem_mesh_free(&m);
    for (int i = 0; i < *nv; i++)
        assert_int_equal(dem_set_particle_flags(s, i, DEM_PARTICLE_FIXED), 0);
    double c[3], u[3] = {0, 0, 0};
    turn(rot, p, c);
    if (v)
        turn(rot, v, u);
    int id = dem_add_particle(s, c, u, SPHERE_R, dem_add_material(s, &glass));
    assert_int_equal(dem_set_particle_flags(s, id, DEM_PARTICLE_FIXED), 0);
    dem_set_effects(s, dem_effects(s) & ~off);
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    *dt = ts.recommended_dt;
    dem_set_dt(s, *dt);
    return s;
}

static dem_sim *build_turned(const turned_case *tc, int *nv)
{
    double dt;
    return turned_sheet(tc->rot, tc->p, NULL, 0, nv, &dt);
}

static void rotation(double ax, double ay, double az, double r[3][3]) /* z(az) y(ay) x(ax) */
{
    double cx = cos(ax), sx = sin(ax), cy = cos(ay), sy = sin(ay), cz = cos(az), sz = sin(az);
    double m[3][3] = {{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
                      {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
                      {-sy, cy * sx, cy * cx}};
    memcpy(r, m, sizeof m);
}

static void test_edge_points(void **st)
{
    (void)st;
    /* the interior vertex nearest the sheet's centre and its neighbours, from the mesh */
    dem_mesh_spec sp = {DEM_MESH_SHEET, {0, 0, 0}, 0.06, 0.06, SHEET_EDGE};
    dem_mesh m;
    char err[256];
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    int v = 0;
    for (int i = 1; i < m.nv; i++)
        if (m.x[3 * i] * m.x[3 * i] + m.x[3 * i + 1] * m.x[3 * i + 1] <
            m.x[3 * v] * m.x[3 * v] + m.x[3 * v + 1] * m.x[3 * v + 1])
            v = i;
    double pts[16][3];
    int np = 0, nb = 0;
    memcpy(pts[np++], m.x + 3 * v, sizeof(double) * 3);
    for (int t = 0; t < m.nt && np < 16; t++)
        for (int k = 0; k < 3; k++) {
            if (m.tri[3 * t + k] != v)
                continue;
            int w = m.tri[3 * t + (k + 1) % 3]; /* each edge from v once: the next vertex of each triangle at v */
            const double *a = m.x + 3 * v, *b = m.x + 3 * w;
            for (int d = 0; d < 3; d++)
                pts[np][d] = 0.5 * (a[d] + b[d]), pts[np + 1][d] = a[d] + (b[d] - a[d]) / 3;
            np += 2, nb++;
        }
    dem_mesh_free(&m);
    assert_int_equal(nb, 6);
    for (int k = 0; k < np; k++)
        pts[k][2] = SPHERE_R - OVERLAP;
    static const double angles[7][3] = {{0, 0, 0},      {0, 0, M_PI / 6}, {0, 0, M_PI / 4}, {0, 0, 0.3},
                                        {M_PI / 3, 0, 0}, {0.4, 0.7, 1.1}, {2.5, -0.9, 0.2}};
    double want = hertz(&glass, &rubber, SPHERE_R, OVERLAP);
    FOR_EACH_BACKEND(bc)
    {
        dem_config c = cfg_of(bc->backend, bc->precision);
        double worst = 0;
        int bad = 0;
        for (int r = 0; r < 7; r++)
            for (int k = 0; k < np; k++) {
                turned_case tc;
                rotation(angles[r][0], angles[r][1], angles[r][2], tc.rot);
                memcpy(tc.p, pts[k], sizeof tc.p);
                int nv;
                dem_sim *s = build_turned(&tc, &nv);
                start_or_fail(s, &c);
                double *f = malloc(sizeof(double) * 3 * (size_t)(nv + 1)), nz[3];
                assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
                dem_energy_t e;
                assert_int_equal(dem_energy(s, &e), 0);
                turn(tc.rot, (double[3]){0, 0, 1}, nz);
                const double *fs = f + 3 * nv;
                double along = fs[0] * nz[0] + fs[1] * nz[1] + fs[2] * nz[2];
                double off = sqrt(fmax(0, fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2] - along * along));
                double dev = fmax(fabs(along / want - 1), off / want);
                if (e.patch_contacts != 1 || !(dev < 1e-3)) {
                    if (bad++ < 5)
                        printf("  %s, rotation %d, point %d: %ld contacts, F along the normal %.6g N, across %.3g N "
                               "(Hertz %.6g N)\n", bc->name, r, k, e.patch_contacts, along, off, want);
                }
                worst = fmax(worst, dev);
                free(f);
                dem_destroy(s);
            }
        printf("  %s: %d points on a vertex and its edges x 7 rotations: one contact each, largest deviation from "
               "Hertz %.2g\n", bc->name, np, worst);
        assert_int_equal(bad, 0);
    }
}

/* Pressed through: a sphere driven at constant speed through a pinned sheet - straight down over a face's
 * centre, an edge's midpoint and a vertex of the sheet and of the sheet turned three ways (the two faces at an edge
 * then round apart), and down and sideways from a face's centre across an edge into the next face, reached 0.3 r
 * below the plane. The contact never flips: the force on the sphere points back to the side it came from all the
 * way until the centre is a radius past the sheet, and the pinned vertices take it back (their sum is minus the
 * sphere's). Straight down it is the law of patch_contacts.h for the overlap r - z (z the centre's height; more than
 * r once the centre is below the sheet): Hertz's force up to 0.8 r, the barrier 0.8 r + 0.2 r u / (1 - u)
 * (u = (d - 0.8 r) / 0.2 r) up to u = 0.95, its tangent beyond - written here from that description; then it lets
 * go. A restart half way through (0.5 r past the plane) continues bit for bit: the state carries the sides. With the
 * normal from the closest point to the centre alone the force turned as the centre crossed the sheet and threw the
 * sphere out (grains left a closed membrane from ~270 kPa); with sides kept only for the contacts the selection kept,
 * the turned sheets' edges threw it through (the two faces' contacts took turns), and a sphere sliding while crossed
 * was thrown through the next face. */
static double law_overlap(double d, double r)
{
    double db = 0.8 * r, span = 0.2 * r, u = (d - db) / span;
    return d <= db ? d : u < 0.95 ? db + span * u / (1 - u) : db + 19 * span + (d - db - 0.95 * span) * 400;
}

typedef struct {
    double rot[3][3];
    double p[3], v[3]; /* the sphere's start and velocity, before the turn */
    int straight;      /* straight down: the force is the law's */
    int nv;
    double dt;
    long steps;
} push_case;

#define PUSH_V 0.5

static dem_sim *build_push(void *ctx)
{
    push_case *pc = ctx;
    dem_sim *s = turned_sheet(pc->rot, pc->p, pc->v, DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION, &pc->nv, &pc->dt);
    pc->steps = (long)((pc->p[2] + SPHERE_R + 1e-4) / (-pc->v[2] * pc->dt));
    return s;
}

static void check_push(dem_sim *s, const backend_case *bc, void *ctx)
{
    push_case *pc = ctx;
    int n = dem_count(s), samples = 0, released = 0;
    double *x = malloc(sizeof(double) * 3 * (size_t)n), *f = malloc(sizeof(double) * 3 * (size_t)n), nz[3];
    double worst = 0, worst_sum = 0, deepest = 0, estar = 1 / ((1 - glass.poisson * glass.poisson) / glass.young +
                                                                (1 - rubber.poisson * rubber.poisson) / rubber.young);
    double tol = bc->precision == DEM_FP64 ? 1e-9 : 2e-3;
    turn(pc->rot, (double[3]){0, 0, 1}, nz);
    for (long k = 0; k < pc->steps; k += 5) {
        step_or_fail(s, 5);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
        const double *xs = x + 3 * pc->nv, *fs = f + 3 * pc->nv;
        double z = xs[0] * nz[0] + xs[1] * nz[1] + xs[2] * nz[2], up = fs[0] * nz[0] + fs[1] * nz[1] + fs[2] * nz[2];
        double d = SPHERE_R - z, fabs_s = sqrt(fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]);
        if (d > 0 && d < 2 * SPHERE_R - 1e-6) {
            samples++;
            deepest = fmax(deepest, d);
            if (!(up > 0))
                fail_msg("%s, %s path: the force turned at overlap %.4g r: %g N along the sheet's normal", bc->name,
                         pc->straight ? "straight" : "sliding", d / SPHERE_R, up);
            double sum[3] = {fs[0], fs[1], fs[2]};
            for (int i = 0; i < pc->nv; i++)
                for (int c = 0; c < 3; c++)
                    sum[c] += f[3 * i + c];
            worst_sum = fmax(worst_sum, sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / fabs_s);
            if (pc->straight) {
                double want = 4.0 / 3 * estar * sqrt(SPHERE_R) * pow(law_overlap(d, SPHERE_R), 1.5);
                worst = fmax(worst, fabs(up / want - 1));
                double ax = fs[0] - up * nz[0], ay = fs[1] - up * nz[1], az = fs[2] - up * nz[2]; /* across */
                worst = fmax(worst, sqrt(ax * ax + ay * ay + az * az) / want);
            }
        }
        if (d > 2 * SPHERE_R + 1e-6) {
            released++;
            assert_true(fs[0] == 0 && fs[1] == 0 && fs[2] == 0);
        }
    }
    printf("  %s, %s path: %d samples to an overlap of %.3g r, force back all the way, vertices' sum %.2g of it%s",
           bc->name, pc->straight ? "straight" : "sliding", samples, deepest / SPHERE_R, worst_sum,
           pc->straight ? ", largest deviation from the law " : "\n");
    if (pc->straight)
        printf("%.2g\n", worst);
    assert_true(deepest > 1.9 * SPHERE_R && released > 0);
    assert_true(worst < tol && worst_sum < 64 * bc->eps * 1e3);
    free(x), free(f);
}

static void test_pushed_through(void **st)
{
    (void)st;
    dem_mesh_spec sp = {DEM_MESH_SHEET, {0, 0, 0}, 0.06, 0.06, SHEET_EDGE};
    dem_mesh m;
    char err[256];
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    int t = m.nt / 2;
    const double *a = m.x + 3 * m.tri[3 * t], *b = m.x + 3 * m.tri[3 * t + 1], *c = m.x + 3 * m.tri[3 * t + 2];
    double cen[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3}, mid[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
    double pts[3][2] = {{cen[0], cen[1]}, {mid[0], mid[1]}, {a[0], a[1]}};
    dem_mesh_free(&m);
    static const double angles[4][3] = {{0, 0, 0}, {M_PI / 3, 0, 0}, {0.4, 0.7, 1.1}, {2.5, -0.9, 0.2}};
    double z0 = SPHERE_R + 1e-4, dir[2] = {mid[0] - cen[0], mid[1] - cen[1]}, len = hypot(dir[0], dir[1]);
    double lateral = len / ((z0 + 0.3 * SPHERE_R) / PUSH_V); /* at the edge 0.3 r below the plane */
    FOR_EACH_BACKEND(bc)
    {
        for (int r = 0; r < 4; r++)
            for (int k = 0; k < 4; k++) {
                if (r && k != 1)
                    continue; /* turned: the edge's midpoint */
                push_case pc = {.p = {k < 3 ? pts[k][0] : cen[0], k < 3 ? pts[k][1] : cen[1], z0},
                                .v = {k < 3 ? 0 : lateral * dir[0] / len, k < 3 ? 0 : lateral * dir[1] / len, -PUSH_V},
                                .straight = k < 3};
                rotation(angles[r][0], angles[r][1], angles[r][2], pc.rot);
                backend_run(bc, build_push, 0, check_push, &pc);
            }
        /* a restart half way: the state carries each contact's side */
        push_case pa = {.p = {mid[0], mid[1], z0}, .v = {0, 0, -PUSH_V}, .straight = 1}, pb;
        rotation(angles[2][0], angles[2][1], angles[2][2], pa.rot);
        pb = pa;
        dem_sim *sa = build_push(&pa), *sb = build_push(&pb);
        dem_config cfg = cfg_of(bc->backend, bc->precision);
        long half = (long)((z0 + 0.5 * SPHERE_R) / (PUSH_V * pa.dt));
        restart_check(sa, sb, &cfg, half, pa.steps - half, bc->name);
        dem_destroy(sa);
        dem_destroy(sb);
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

/* A closed membrane at 1 MPa: a sphere of R 10 mm (162 vertices, edges 2.5-3.1 mm) of seed 001's rubber
 * around 627 glass grains of radii 0.6-0.9 mm (Table 2) on an FCC lattice, the pressure ramped to 1 MPa over 3 ms and
 * held 1 ms. Every 0.5 ms no grain is outside the membrane by the winding number of its triangles (Van Oosterom and
 * Strackee, above), and at the end the grains lie against it: the nearest centre is closer to the membrane than
 * 0.2 r (the law's barrier at work). Hertz's law with a two-sided normal let the first grains through at about
 * 300 kPa here (docs/design.md). The hinges keep seed 001's k_el but no k_diss: their damping needs a step five times
 * shorter at this mesh size (dem check warns), and the test is about the contact. */

static double lcg_unit(unsigned long long *q)
{
    *q = *q * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*q >> 11) / 9007199254740992.0;
}

static void test_one_megapascal(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    dem_mesh_spec sp = {DEM_MESH_SPHERE, {0, 0, 0}, 0.01, 0, 0.0028};
    dem_mesh m;
    char err[256];
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    dem_membrane mm = {1.25e6, 1.0 / 3, 3e-4, 1000, 0.5, 1.2, 0.15, 1e-3, 0, 1e-4, DEM_MEMBRANE_PATCH};
    if (dem_add_membrane(s, &m, &mm, NULL))
        fail_msg("%s", dem_error(s));
    int nv = m.nv, nt = m.nt, *tri = malloc(sizeof(int) * 3 * (size_t)nt);
    memcpy(tri, m.tri, sizeof(int) * 3 * (size_t)nt);
    dem_mesh_free(&m);
    dem_material grain = {2500, 4.6e10, 0.245, 0.5, 0.25, 0, 0};
    int mat = dem_add_material(s, &grain), ng = 0;
    unsigned long long q = 12345;
    double *radius = malloc(sizeof(double) * 4096);
    double h = 1.85e-3 / sqrt(2.0);
    for (int i = -7; i <= 7; i++)
        for (int j = -7; j <= 7; j++)
            for (int k = -7; k <= 7; k++) {
                double p[3] = {i * h, j * h, k * h};
                if ((i + j + k) % 2 || sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) > 0.01 - 1.2e-3)
                    continue;
                radius[nv + ng] = 0.6e-3 + 0.3e-3 * lcg_unit(&q);
                assert_true(dem_add_particle(s, p, NULL, radius[nv + ng], mat) == nv + ng);
                ng++;
            }
    dem_pressure_stage ramp = {0.003, 1e6};
    assert_int_equal(dem_set_pressure_stages(s, 1, &ramp), 0);
    dem_set_domain(s, (double[3]){-0.015, -0.015, -0.015}, (double[3]){0.015, 0.015, 0.015});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    int n = dem_count(s), out = 0;
    double *x = malloc(sizeof(double) * 3 * (size_t)n), nearest = INFINITY;
    long every = (long)(0.0005 / ts.recommended_dt);
    for (int round = 0; round < 8; round++) {
        step_or_fail(s, every);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        int now = 0;
        for (int i = nv; i < n; i++)
            now += winding(x, tri, nt, x + 3 * i) < 0.5;
        out = now > out ? now : out;
    }
    for (int i = nv; i < n; i++) /* the nearest grain centre to the membrane, in radii */
        for (int t = 0; t < nt; t++) {
            double tx[9], w[3], pt[3];
            int kind, index;
            for (int v = 0; v < 3; v++)
                memcpy(tx + 3 * v, x + 3 * tri[3 * t + v], sizeof(double) * 3);
            dem_patch_probe_f64(1, x + 3 * i, tx, &kind, &index, w, pt);
            const double *c = x + 3 * i;
            double d2 = (c[0] - pt[0]) * (c[0] - pt[0]) + (c[1] - pt[1]) * (c[1] - pt[1]) + (c[2] - pt[2]) * (c[2] - pt[2]);
            nearest = fmin(nearest, sqrt(d2) / radius[i]);
        }
    printf("  %d grains in a patch membrane of %d vertices at %.0f kPa: at most %d outside, the nearest centre %.3f r "
           "from the membrane\n", ng, nv, dem_pressure(s) / 1e3, out, nearest);
    assert_int_equal(out, 0);
    assert_true(nearest < 0.2 && nearest > 0);
    free(x), free(radius), free(tri);
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
            for (int k = 0; k < 4; k++)
                step_or_fail(sims[k], 100);
            int k = state_diff_each(ref, sims, 4, msg, sizeof msg);
            if (k >= 0)
                fail_msg("%s, %s, step %ld: %s", v[k].name, p ? "fp32" : "fp64", dem_step_index(ref), msg);
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
    test_pocl_threads(); /* the suite's multi-thread runs of these laws (test_util.h) */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hertz_across_sheet),
        cmocka_unit_test(test_edge_points),
        cmocka_unit_test(test_pushed_through),
        cmocka_unit_test(test_spring_across_edges),
        cmocka_unit_test(test_patch_energy),
        cmocka_unit_test(test_no_tunnelling),
        cmocka_unit_test(test_one_megapascal),
        cmocka_unit_test(test_patch_restart),
        cmocka_unit_test(test_patch_variants),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
