/* test_mesh_file.c - dem_mesh_read (host/mesh/mesh_file.c): OBJ and STL (ASCII, binary) give the same octahedron; a
 * generated sphere written as OBJ comes back bit for bit and makes the same membrane; every refusal names the file's
 * line and the reason. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "test_util.h"

static char dir[256];

static const char *write_file(const char *name, const char *text, size_t len)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    assert_int_equal(fwrite(text, 1, len, fp), len);
    fclose(fp);
    return path;
}

/* the octahedron: vertices +-x, +-y, +-z; faces outward */
static const double oct_x[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const int oct_t[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};

static void check_octahedron(const dem_mesh *m, const char *what)
{
    if (m->nv != 6 || m->nt != 8)
        fail_msg("%s: %d vertices, %d triangles (want 6, 8)", what, m->nv, m->nt);
    /* the same corners in the same triangles (STL numbers its vertices by first use) */
    for (int t = 0; t < 8; t++)
        for (int c = 0; c < 3; c++)
            assert_memory_equal(m->x + 3 * m->tri[3 * t + c], oct_x[oct_t[t][c]], sizeof oct_x[0]);
    dem_mesh_topo t;
    char err[256];
    assert_int_equal(dem_mesh_topology(m, &t, err, sizeof err), 0);
    assert_int_equal(t.ne, 12);
    assert_int_equal(t.nboundary, 0);
    dem_mesh_topo_free(&t);
}

static void test_octahedron(void **st)
{
    (void)st;
    char obj[4096], stl[8192];
    int at = snprintf(obj, sizeof obj, "# an octahedron\no octa\n");
    for (int i = 0; i < 6; i++)
        at += snprintf(obj + at, sizeof obj - at, "v %g %g %g\n", oct_x[i][0], oct_x[i][1], oct_x[i][2]);
    at += snprintf(obj + at, sizeof obj - at, "vn 0 0 1\nvt 0 0\ns off\n");
    for (int t = 0; t < 8; t++) /* the index forms OBJ allows: plain, a/t/n, a//n, negative */
        at += snprintf(obj + at, sizeof obj - at, t == 1 ? "f %d/1/1 %d/1/1 %d/1/1\n" : t == 2 ? "f %d//1 %d//1 %d//1\n"
                                                      : "f %d %d %d\n", oct_t[t][0] + 1, oct_t[t][1] + 1,
                       oct_t[t][2] + 1);
    at += snprintf(obj + at, sizeof obj - at, "f -6 -4 -2\n"); /* a ninth face, counted back: 0 2 4 again */
    dem_mesh m;
    char err[512];
    if (dem_mesh_read(write_file("octa.obj", obj, strlen(obj)), &m, err, sizeof err))
        fail_msg("%s", err);
    assert_int_equal(m.nt, 9);
    assert_memory_equal(m.tri + 24, oct_t[0], sizeof oct_t[0]);
    m.nt = 8;
    check_octahedron(&m, "OBJ");
    dem_mesh_free(&m);

    at = snprintf(stl, sizeof stl, "solid octa\n");
    for (int t = 0; t < 8; t++) {
        at += snprintf(stl + at, sizeof stl - at, "  facet normal 0 0 0\n    outer loop\n");
        for (int c = 0; c < 3; c++)
            at += snprintf(stl + at, sizeof stl - at, "      vertex %g %g %g\n", oct_x[oct_t[t][c]][0],
                           oct_x[oct_t[t][c]][1], oct_x[oct_t[t][c]][2]);
        at += snprintf(stl + at, sizeof stl - at, "    endloop\n  endfacet\n");
    }
    at += snprintf(stl + at, sizeof stl - at, "endsolid octa\n");
    if (dem_mesh_read(write_file("octa.stl", stl, strlen(stl)), &m, err, sizeof err))
        fail_msg("%s", err);
    check_octahedron(&m, "ASCII STL");
    dem_mesh_free(&m);

    unsigned char bin[84 + 8 * 50];
    memset(bin, 0, sizeof bin);
    memcpy(bin, "solid but binary", 16); /* a binary header may start with "solid" too */
    bin[80] = 8;
    for (int t = 0; t < 8; t++)
        for (int c = 0; c < 3; c++)
            for (int d = 0; d < 3; d++) {
                float v = (float)oct_x[oct_t[t][c]][d];
                memcpy(bin + 84 + 50 * t + 12 + 12 * c + 4 * d, &v, 4); /* little-endian host */
            }
    if (dem_mesh_read(write_file("octa_bin.stl", (const char *)bin, sizeof bin), &m, err, sizeof err))
        fail_msg("%s", err);
    check_octahedron(&m, "binary STL");
    dem_mesh_free(&m);
}

/* A generated sphere written with %.17g comes back bit for bit, and makes the same membrane */
static void test_round_trip(void **st)
{
    (void)st;
    dem_mesh g, r;
    char err[512];
    dem_mesh_spec sp = {DEM_MESH_SPHERE, {0.01, 0, 0}, 0.03, 0, 0.006};
    assert_int_equal(dem_mesh_make(&sp, &g, err, sizeof err), 0);
    char path[512];
    snprintf(path, sizeof path, "%s/sphere.obj", dir);
    mesh_write_obj(&g, path);
    if (dem_mesh_read(path, &r, err, sizeof err))
        fail_msg("%s", err);
    assert_int_equal(r.nv, g.nv);
    assert_int_equal(r.nt, g.nt);
    assert_memory_equal(r.x, g.x, sizeof(double) * 3 * (size_t)g.nv);
    assert_memory_equal(r.tri, g.tri, sizeof(int) * 3 * (size_t)g.nt);
    dem_membrane mm = {1.25e6, 1.0 / 3, 3e-4, 1000, 0.5, 1.2, 0.3, 1e-4, 1e-6, 0.001, DEM_MEMBRANE_PATCH};
    dem_membrane_info a, b;
    dem_sim *s1 = dem_create(), *s2 = dem_create();
    assert_int_equal(dem_add_membrane(s1, &g, &mm, &a), 0);
    assert_int_equal(dem_add_membrane(s2, &r, &mm, &b), 0);
    assert_memory_equal(&a, &b, sizeof a);
    printf("  sphere of %d vertices and %d triangles: OBJ round trip bit for bit, same membrane (%d springs, %d "
           "hinges, area %.6g m^2)\n", r.nv, r.nt, a.nsprings, a.nhinges, a.area);
    dem_destroy(s1), dem_destroy(s2);
    dem_mesh_free(&g), dem_mesh_free(&r);
}

static void refused(const char *name, const char *text, size_t len, const char *expect)
{
    dem_mesh m;
    char err[512];
    const char *path = write_file(name, text, len);
    if (dem_mesh_read(path, &m, err, sizeof err) == 0)
        fail_msg("%s was read", name);
    if (!strstr(err, expect) || strncmp(err, path, strlen(path)))
        fail_msg("%s: message '%s' (expected the path and '%s')", name, err, expect);
    assert_null(m.x);
}

static void test_refusals(void **st)
{
    (void)st;
#define OBJ_HEAD "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
    static const struct {
        const char *text, *expect;
    } obj[] = {{OBJ_HEAD "f 1 2 3 4\n", ".obj:5: face: 4 corners (only triangles)"},
               {OBJ_HEAD "f 1 2 9\n", ".obj:5: face: vertex 9 does not exist (4 so far)"},
               {OBJ_HEAD "f 1 2 -5\n", ".obj:5: face: vertex -5 does not exist"},
               {OBJ_HEAD "f 1 2 2\n", ".obj:5: face: a corner is repeated"},
               {OBJ_HEAD "f 1 2 x\n", ".obj:5: face: 'x' is not a vertex index"},
               {"v 0 0 0\nv 1 0 abc\n", ".obj:2: vertex: 'abc' is not a finite number"},
               {"v 0 0 0\nv 1 0 inf\n", ".obj:2: vertex: 'inf' is not a finite number"},
               {"v 0 0\n", ".obj:1: vertex: 2 numbers"},
               {OBJ_HEAD "curv 1 2\n", ".obj:5: unknown statement 'curv'"},
               {OBJ_HEAD, ": 4 vertices and 0 triangles (a mesh needs a triangle)"}};
    for (size_t k = 0; k < sizeof obj / sizeof obj[0]; k++)
        refused("bad.obj", obj[k].text, strlen(obj[k].text), obj[k].expect);
#define FACET "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
    static const struct {
        const char *text, *expect;
    } stl[] = {{"solid x\n" FACET "endsolid x\nfacet\n", ".stl:10: 'facet' after endsolid"},
               {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
                ".stl:6: 'endloop' where 'vertex' was due"},
               {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n", ".stl:4: vertex: want three finite numbers"},
               {"solid x\n" FACET, ": the file ends inside a solid"},
               {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 1 0\nendloop\n"
                "endfacet\nendsolid\n", ".stl: facet 1: two of its corners are the same point"}};
    for (size_t k = 0; k < sizeof stl / sizeof stl[0]; k++)
        refused("bad.stl", stl[k].text, strlen(stl[k].text), stl[k].expect);
    unsigned char bin[84 + 50 + 7] = {0};
    bin[80] = 1;
    refused("short.stl", (const char *)bin, sizeof bin, "binary STL of 141 bytes says 1 triangles (134 bytes");
    refused("mesh.ply", "ply\n", 4, ": a mesh file is .obj (Wavefront) or .stl");
    dem_mesh m;
    char err[512];
    assert_int_equal(dem_mesh_read("/nonexistent/x.obj", &m, err, sizeof err), DEM_ERR_ARG);
    assert_non_null(strstr(err, "/nonexistent/x.obj: cannot open the mesh file: No such file or directory"));
    /* what is not a regular file is refused without being read: a named pipe would block the open for ever */
    char fifo[512];
    snprintf(fifo, sizeof fifo, "%s/pipe.obj", dir);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    assert_int_equal(dem_mesh_read(fifo, &m, err, sizeof err), DEM_ERR_ARG);
    assert_non_null(strstr(err, "pipe.obj: cannot open the mesh file: not a regular file"));
    assert_int_equal(dem_mesh_read("/dev/zero", &m, err, sizeof err), DEM_ERR_ARG);
    assert_non_null(strstr(err, "/dev/zero: cannot open the mesh file: not a regular file"));
    assert_int_equal(dem_mesh_read(dir, &m, err, sizeof err), DEM_ERR_ARG);
    assert_non_null(strstr(err, "cannot open the mesh file: not a regular file"));
}

/* The vertex count of a generated mesh is counted before anything is made, in double: sizes whose grid would overflow a
 * long (a tube of radius 1e-30 m and height 5.3e18 m would come out 2051 vertices and crash) are refused, and the count
 * is the one dem_mesh_make makes. */
static void test_generated_counts(void **st)
{
    (void)st;
    dem_mesh m;
    char err[512];
    dem_mesh_spec huge[] = {{DEM_MESH_TUBE, {0, 0, 0}, 1e-30, 5.3e18, 1}, {DEM_MESH_SHEET, {0, 0, 0}, 1e18, 1e18, 1e-3},
                            {DEM_MESH_SHEET, {0, 0, 0}, 4e9, 1, 1}, {DEM_MESH_SPHERE, {0, 0, 0}, 1e300, 0, 1e-300}};
    for (size_t k = 0; k < sizeof huge / sizeof huge[0]; k++) {
        assert_false(dem_mesh_vertices(&huge[k]) <= 2e6);
        if (dem_mesh_make(&huge[k], &m, err, sizeof err) == 0)
            fail_msg("spec %zu: made %d vertices of a mesh of %g", k, m.nv, dem_mesh_vertices(&huge[k]));
        assert_non_null(strstr(err, "vertices"));
    }
    dem_mesh_spec fine[] = {{DEM_MESH_TUBE, {0, 0, 0.02}, 0.02, 0.04, 0.006}, {DEM_MESH_SHEET, {0, 0, 0}, 0.1, 0.05, 0.01},
                            {DEM_MESH_SHEET, {0, 0, 0}, 0.1, 0.06, 0.01}, {DEM_MESH_SPHERE, {0, 0, 0}, 0.05, 0, 0.01}};
    for (size_t k = 0; k < sizeof fine / sizeof fine[0]; k++) {
        assert_int_equal(dem_mesh_make(&fine[k], &m, err, sizeof err), 0);
        assert_true(dem_mesh_vertices(&fine[k]) == m.nv);
        dem_mesh_free(&m);
    }
    dem_mesh_spec bad = {DEM_MESH_TUBE, {0, 0, 0}, INFINITY, 1, 1};
    assert_true(isnan(dem_mesh_vertices(&bad)));
}

int main(void)
{
    if (test_tmpdir_make(dir, sizeof dir, "dem-test-mesh-file"))
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_octahedron),
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_generated_counts),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    test_tmpdir_remove(dir);
    return rc;
}
