/* test_api.c - the public interface's error rule (dem.h, at the top): a function that does something returns 0 or a
 * negative dem_status; one that answers with an id, an index, a count or a yes/no returns it (>= 0) or a negative
 * dem_status, the code of what went wrong (a call out of order DEM_ERR_STATE, a bad argument DEM_ERR_ARG), with
 * dem_error saying why. Also: the internal fields (dem_debug.h) and bits (common/dem_internal_bits.h) stay apart from
 * the public ones. */
#include "test_util.h"
#include <stdio.h>
#include "dem_internal_bits.h"
#include "dem_layout.h" /* PR_STRIDE */
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const dem_material glass = {2500, 1e7, 0.3, 0.5, 0.3};

static void test_status_values(void **st)
{
    (void)st;
    const int codes[] = {DEM_ERR_ARG, DEM_ERR_NOMEM, DEM_ERR_DEVICE, DEM_ERR_DOMAIN, DEM_ERR_DT, DEM_ERR_STATE};
    int n = (int)(sizeof codes / sizeof codes[0]);
    assert_int_equal(DEM_OK, 0);
    for (int a = 0; a < n; a++) {
        assert_true(codes[a] < 0);
        for (int b = 0; b < a; b++)
            assert_int_not_equal(codes[a], codes[b]);
    }
}

/* A set-up of two materials, two particles and a box; started when `start` */
static dem_sim *small(int start)
{
    dem_sim *s = dem_create();
    assert_int_equal(dem_add_material(s, &glass), 0);
    assert_int_equal(dem_add_material(s, &glass), 1);
    assert_int_equal(dem_add_particle(s, (double[3]){0.01, 0.01, 0.01}, NULL, 0.002, 0), 0);
    assert_int_equal(dem_add_particle(s, (double[3]){0.02, 0.02, 0.02}, NULL, 0.002, 1), 1);
    assert_int_equal(dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){0.03, 0.03, 0.03}, 0), 0);
    assert_int_equal(dem_wall_count(s), 6);
    assert_int_equal(dem_set_dt(s, 1e-6), DEM_OK);
    if (start) {
        dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
        start_or_fail(s, &c);
    }
    return s;
}

/* Refused arguments: DEM_ERR_ARG from every kind of function, and nothing added */
static void test_bad_arguments(void **st)
{
    (void)st;
    dem_sim *s = small(0);
    assert_int_equal(dem_add_particle(s, (double[3]){0, 0, 0}, NULL, 0.001, 7), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "unknown material"));
    assert_int_equal(dem_count(s), 2);
    assert_int_equal(dem_particle_material(s, 1), 1);
    assert_int_equal(dem_particle_material(s, 2), DEM_ERR_ARG);
    assert_int_equal(dem_particle_source(s, -1), DEM_ERR_ARG);
    assert_int_equal(dem_particle_source(s, 1), 1);
    assert_int_equal(dem_effect_bit("friction"), 2);
    assert_int_equal(dem_effect_bit("no such effect"), DEM_ERR_ARG);
    assert_int_equal(dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){1, 1, 1}, 9), DEM_ERR_ARG);
    assert_int_equal(dem_add_wall(s, &(dem_wall){.kind = DEM_WALL_CYLINDER, .material = 0, .normal = {0, 0, 1}}),
                     DEM_ERR_ARG); /* a cylinder of radius 0 */
    assert_int_equal(dem_wall_count(s), 6);
    assert_int_equal(dem_add_spring(s, 0, 0, 1, 0, 0), DEM_ERR_ARG);
    assert_int_equal(dem_add_triangle(s, 0, 1, 5), DEM_ERR_ARG);
    assert_int_equal(dem_add_hinge(s, 0, 1, 2, 3, 1, 0, 0), DEM_ERR_ARG);
    assert_int_equal(dem_add_patches(s, 0, 1), DEM_ERR_ARG);
    assert_int_equal(dem_set_particle_mass(s, 5, 1, 0), DEM_ERR_ARG);
    double p[3], fn;
    assert_int_equal(dem_wall_position(s, 6, p), DEM_ERR_ARG);
    assert_int_equal(dem_wall_position(s, 5, p), DEM_OK);
    /* the press's queries: a box has no die, and wall 40 is not there */
    int die, other;
    assert_int_equal(dem_density_walls(s, 0, &die, &other), DEM_ERR_ARG);
    assert_int_equal(dem_cup_in_bore(s, 0, 40), DEM_ERR_ARG);
    assert_int_equal(dem_cup_in_bore(s, 0, 1), 1); /* a flat punch */
    assert_int_equal(dem_wall_normal_force(s, 40, &fn), DEM_ERR_ARG);
    /* the caller's bits only: the host's own are refused */
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_CLASSICAL | DEM_KEEP_WALL_FORCES), DEM_ERR_ARG);
    assert_int_equal(dem_set_mc_stress_convention(s, DEM_MCS_DEFAULT | DEM_MC_REACH), DEM_ERR_ARG);
    dem_destroy(s);
}

/* After dem_start the set-up is fixed: every adding function, id or not, returns DEM_ERR_STATE */
static void test_after_start(void **st)
{
    (void)st;
    dem_sim *s = small(1);
    assert_int_equal(dem_add_material(s, &glass), DEM_ERR_STATE);
    assert_non_null(strstr(dem_error(s), "started"));
    assert_int_equal(dem_add_particle(s, (double[3]){0.015, 0.015, 0.015}, NULL, 0.001, 0), DEM_ERR_STATE);
    assert_int_equal(dem_add_wall(s, &(dem_wall){.kind = DEM_WALL_PLANE, .material = 0, .normal = {0, 0, 1}}),
                     DEM_ERR_STATE);
    assert_int_equal(dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){1, 1, 1}, 0), DEM_ERR_STATE);
    assert_int_equal(dem_add_spring(s, 0, 1, 1, -1, 0), DEM_ERR_STATE);
    assert_int_equal(dem_add_triangle(s, 0, 1, 0), DEM_ERR_STATE);
    assert_int_equal(dem_add_hinge(s, 0, 1, 0, 1, 1, 0, 0), DEM_ERR_STATE);
    assert_int_equal(dem_add_patches(s, 0, 1), DEM_ERR_STATE);
    assert_int_equal(dem_set_dt(s, 2e-6), DEM_ERR_STATE);
    assert_int_equal(dem_start(s, &(dem_config){0}), DEM_ERR_STATE);
    dem_mesh m;
    char err[256];
    assert_int_equal(dem_mesh_make(&(dem_mesh_spec){DEM_MESH_SHEET, {0.015, 0.015, 0.015}, 0.01, 0.01, 0.005}, &m, err,
                                   sizeof err),
                     DEM_OK);
    dem_membrane mm = {1e6, 0.4, 1e-3, 1000, 0.5, 0.3, 0.1, 0, 0, 0.001, DEM_MEMBRANE_PARTICLE};
    assert_int_equal(dem_add_membrane(s, &m, &mm, NULL), DEM_ERR_STATE);
    dem_mesh_free(&m);
    assert_int_equal(dem_count(s), 2);
    assert_int_equal(dem_step(s, 3), DEM_OK);
    assert_int_equal(dem_step_index(s), 3);
    dem_destroy(s);
}

/* The mesh functions: a refused spec or file DEM_ERR_ARG with the reason in err; and a membrane whose material the
 * simulation cannot take returns that call's code and adds nothing */
static void test_meshes(void **st)
{
    (void)st;
    dem_mesh m;
    char err[256] = "";
    assert_int_equal(dem_mesh_make(&(dem_mesh_spec){DEM_MESH_SHEET, {0, 0, 0}, 0.05, 0.05, 0}, &m, err, sizeof err),
                     DEM_ERR_ARG);
    assert_non_null(strstr(err, "edge"));
    double n1, n2, dx, dy;
    assert_int_equal(dem_mesh_grid(&(dem_mesh_spec){DEM_MESH_SPHERE, {0, 0, 0}, 0.05, 0, 0.01}, &n1, &n2, &dx, &dy),
                     DEM_ERR_ARG);
    assert_int_equal(dem_mesh_grid(&(dem_mesh_spec){DEM_MESH_SHEET, {0, 0, 0}, 0.05, 0.05, 0.01}, &n1, &n2, &dx, &dy),
                     DEM_OK);
    err[0] = 0;
    assert_int_equal(dem_mesh_read("/nonexistent/mesh.obj", &m, err, sizeof err), DEM_ERR_ARG);
    assert_non_null(strstr(err, "cannot open"));
    assert_int_equal(dem_mesh_read("mesh.ply", &m, err, sizeof err), DEM_ERR_ARG);

    assert_int_equal(dem_mesh_make(&(dem_mesh_spec){DEM_MESH_SHEET, {0, 0, 0}, 0.05, 0.05, 0.01}, &m, err, sizeof err),
                     DEM_OK);
    dem_mesh_topo t;
    int keep = m.tri[1];
    m.tri[1] = m.tri[0]; /* a triangle with a vertex twice */
    assert_int_equal(dem_mesh_topology(&m, &t, err, sizeof err), DEM_ERR_ARG);
    m.tri[1] = keep;
    assert_int_equal(dem_mesh_topology(&m, &t, err, sizeof err), DEM_OK);
    assert_true(t.ne > 0);
    dem_mesh_topo_free(&t);

    dem_sim *s = dem_create();
    for (int k = 0; k < 64; k++) /* every material a simulation can have: the membrane's own is refused */
        assert_int_equal(dem_add_material(s, &glass), k);
    dem_membrane mm = {1e6, 0.4, 1e-3, 1000, 0.5, 0.3, 0.1, 0, 0, 0.001, DEM_MEMBRANE_PARTICLE};
    assert_int_equal(dem_add_membrane(s, &m, &mm, NULL), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "too many materials"));
    assert_int_equal(dem_count(s), 0);
    assert_int_equal(dem_spring_count(s), 0);
    dem_destroy(s);
    dem_mesh_free(&m);
}

/* The fields: dem.h's and dem_debug.h's share one numbering, each number once */
static void test_field_numbers(void **st)
{
    (void)st;
    const int pub[] = {DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W, DEM_FIELD_FORCE, DEM_FIELD_TORQUE, DEM_FIELD_WALL_FORCE,
                       DEM_FIELD_STRESS, DEM_FIELD_STRESS_TRACE, DEM_FIELD_WALL_NORMAL_FORCE,
                       DEM_FIELD_RADIUS};
    const int internal[] = {DEM_FIELD_X_BUILD, DEM_FIELD_NBR_COUNT, DEM_FIELD_NBR_LIST, DEM_FIELD_HIST,
                            DEM_FIELD_WALL_HIST, DEM_FIELD_CELL_START, DEM_FIELD_CELL_PARTICLES, DEM_FIELD_FLAGS,
                            DEM_FIELD_WALL_REAL, DEM_FIELD_TOUCH, DEM_FIELD_WALL_MASK, DEM_FIELD_MC_FORCE,
                            DEM_FIELD_MC_WALL_FORCE, DEM_FIELD_MC_DISP, DEM_FIELD_MC_WALL_DISP, DEM_FIELD_PAIR_RECORDS,
                            DEM_FIELD_IN_START, DEM_FIELD_WALL_PF, DEM_FIELD_IN_PAIR, DEM_FIELD_NBR_START};
    int seen[DEM_FIELD__COUNT] = {0};
    int npub = (int)(sizeof pub / sizeof pub[0]), nint = (int)(sizeof internal / sizeof internal[0]);
    for (int k = 0; k < npub + nint; k++) {
        int f = k < npub ? pub[k] : internal[k - npub];
        assert_in_range(f, 0, DEM_FIELD__COUNT - 1);
        assert_int_equal(seen[f]++, 0);
    }
    assert_int_equal(npub + nint, DEM_FIELD__COUNT);
}

/* The devices: PoCL's CPU device is there (make deps installs it), it names itself and says what it has; an index
 * that is no device is an error */
static void test_devices(void **st)
{
    (void)st;
    int n = dem_device_count();
    assert_true(n >= 1);
    char name[512], what[512];
    assert_int_equal(dem_device_name(0, name, sizeof name), 0);
    assert_int_equal(dem_device_describe(0, what, sizeof what), 0);
    unsigned cu = 0, mhz = 0;
    double gib = 0;
    printf("  device 0: %s\n            %s\n", name, what);
    assert_int_equal(sscanf(what, "%u compute units at %u MHz, %lf GiB global memory", &cu, &mhz, &gib), 3);
    assert_true(cu >= 1 && gib > 0);
    assert_int_equal(dem_device_describe(n, what, sizeof what), DEM_ERR_DEVICE);
    assert_int_equal(dem_device_describe(-1, what, sizeof what), DEM_ERR_DEVICE);
}

/* make bench's byte count of a kernel (dem_kernel_bytes) buffer by buffer (dem_kernel_buffers): the parts add up to
 * the whole, the particle arrays are as long as their particles, a pair's record is PR_STRIDE reals beside its one
 * index (fp32: four bytes each), and a short list says how many there are */
static size_t buffer_of(const char *const *names, const double *bytes, int count, const char *name)
{
    for (int a = 0; a < count; a++)
        if (!strcmp(names[a], name))
            return (size_t)bytes[a];
    fail_msg("no buffer %s", name);
    return 0;
}

static void test_kernel_buffers(void **st)
{
    (void)st;
    int had_profile = getenv("DEM_PROFILE") != NULL;
    setenv("DEM_PROFILE", "1", 1); /* dem_kernel_times' names and count */
    packing_opts o;
    packing_defaults(&o);
    dem_sim *s = packing_build(&o);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP32);
    start_or_fail(s, &c);
    step_or_fail(s, 3);
    if (!had_profile)
        unsetenv("DEM_PROFILE");
    const char **kn;
    const double *secs;
    int kc = 0, seen = 0, n = dem_count(s);
    assert_int_equal(dem_kernel_times(s, &kn, &secs, &kc), 0);
    assert_true(kc > 0);
    for (int k = 0; k < kc; k++) {
        const char *names[DEM_KERNEL_BUFFERS_MAX];
        double bytes[DEM_KERNEL_BUFFERS_MAX], sum = 0;
        int count = dem_kernel_buffers(s, k, names, bytes, DEM_KERNEL_BUFFERS_MAX);
        assert_true(count > 0 && count <= DEM_KERNEL_BUFFERS_MAX);
        for (int a = 0; a < count; a++)
            sum += bytes[a];
        assert_true(sum == dem_kernel_bytes(s, k));
        if (!strcmp(kn[k], "contact_forces")) {
            size_t x = buffer_of(names, bytes, count, "x");
            assert_true(x >= (size_t)12 * (size_t)n);
            assert_true(buffer_of(names, bytes, count, "force") == x);
            const char *two[3] = {0, 0, "untouched"};
            double b2[3] = {0, 0, -1};
            assert_int_equal(dem_kernel_buffers(s, k, two, b2, 2), count);
            assert_true(two[0] && !strcmp(two[2], "untouched") && b2[2] == -1);
            seen++;
        } else if (!strcmp(kn[k], "contact_pairs")) {
            size_t host = buffer_of(names, bytes, count, "pair_host");
            assert_true(host > 0 && buffer_of(names, bytes, count, "pair") == PR_STRIDE * host);
            assert_true(buffer_of(names, bytes, count, "pair_guest") == host);
            seen++;
        }
    }
    assert_int_equal(seen, 2);
    assert_int_equal(dem_kernel_buffers(s, kc, (const char *[1]){0}, (double[1]){0}, 1), 0);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_status_values), cmocka_unit_test(test_bad_arguments), cmocka_unit_test(test_after_start),
        cmocka_unit_test(test_meshes),        cmocka_unit_test(test_field_numbers), cmocka_unit_test(test_devices),
        cmocka_unit_test(test_kernel_buffers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
