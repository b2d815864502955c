/* test_determinism.c - the determinism contract of the classical DEM core.
 * A dense (solid fraction 0.58), polydisperse (radius ratio > 2), frictional packing of 2331 particles in a box with a moving lid runs
 * 1000 steps on the reference and on PoCL; after every step positions, velocities, angular velocities, forces,
 * torques, wall forces and contact history must be bitwise identical. Variants of work-group size, cell size and
 * skin run in lockstep with the reference and must match it too; so must a second run and a run with one thread. */
#include "test_util.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define NSTEPS 1000

typedef struct {
    const char *name;
    dem_backend_kind backend;
    size_t local;
    double cell_factor; /* x the minimum cell */
    double skin_factor; /* x the smallest radius; 0 = default */
} variant;

static void lockstep(dem_precision prec, const variant *v, int nv)
{
    packing_opts o;
    packing_defaults(&o);
    dem_sim *ref = packing_build(&o);
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(ref, &rc);
    dem_sim *sims[8];
    for (int k = 0; k < nv; k++) {
        sims[k] = packing_build(&o);
        dem_config c = cfg_of(v[k].backend, prec);
        c.local_size = v[k].local;
        double rmin = 0.45 * o.rmax;
        c.skin = v[k].skin_factor > 0 ? v[k].skin_factor * rmin : 0;
        double skin = c.skin > 0 ? c.skin : 0.3 * rmin;
        c.cell_size = v[k].cell_factor * 1.01 * (2 * o.rmax + skin);
        start_or_fail(sims[k], &c);
    }
    char msg[512];
    long contacts_seen = 0;
    for (int step = 0; step <= NSTEPS; step++) {
        if (step > 0) {
            step_or_fail(ref, 1);
            for (int k = 0; k < nv; k++)
                step_or_fail(sims[k], 1);
        }
        int k = state_diff_each(ref, sims, nv, msg, sizeof msg);
        if (k >= 0)
            fail_msg("%s, %s, step %d: %s", v[k].name, prec == DEM_FP64 ? "fp64" : "fp32", step, msg);
        if (step == NSTEPS / 2) {
            double f[3];
            dem_wall_force(ref, 5, f);
            contacts_seen = f[2] != 0;
        }
    }
    /* the scene must actually exercise contacts, rebuilds and the lid */
    assert_true(dem_rebuild_count(ref) > 5);
    assert_true(contacts_seen);
    for (int k = 0; k < nv; k++)
        dem_destroy(sims[k]);
    dem_destroy(ref);
}

static const variant variants[] = {
    {"PoCL, auto work-group", DEM_BACKEND_OPENCL, 0, 1.0, 0},
    {"PoCL, work-group 16", DEM_BACKEND_OPENCL, 16, 1.0, 0},
    {"PoCL, work-group 64", DEM_BACKEND_OPENCL, 64, 1.0, 0},
    {"PoCL, work-group 256", DEM_BACKEND_OPENCL, 256, 1.0, 0},
    {"PoCL, cells 1.7x", DEM_BACKEND_OPENCL, 0, 1.7, 0},
    {"PoCL, skin 0.8 r_min", DEM_BACKEND_OPENCL, 0, 1.0, 0.8},
    {"reference, cells 1.7x and skin 0.8 r_min", DEM_BACKEND_REFERENCE, 0, 1.7, 0.8},
};

static void test_lockstep_fp64(void **st) { (void)st; lockstep(DEM_FP64, variants, 7); }
static void test_lockstep_fp32(void **st) { (void)st; lockstep(DEM_FP32, variants, 7); }

/* The same OpenCL run twice in one process, and once in a child process whose PoCL uses a single thread. */
static uint64_t run_hash(dem_precision prec, long steps)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 8;
    dem_sim *s = packing_build(&o);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec);
    start_or_fail(s, &c);
    step_or_fail(s, steps);
    uint64_t h = state_hash(s);
    dem_destroy(s);
    return h;
}

static char self_path[4096];

/* The same OpenCL run twice in this process (its PoCL on two threads at least: main), then once in a fresh process
 * (exec, not fork: PoCL's worker threads do not survive a fork) whose PoCL runs a single thread. */
static void test_repeat_and_threads(void **st)
{
    (void)st;
    for (int p = 0; p < 2; p++) {
        dem_precision prec = p ? DEM_FP64 : DEM_FP32;
        uint64_t h1 = run_hash(prec, 300), h2 = run_hash(prec, 300);
        assert_true(h1 == h2);
        char cmd[4200];
        snprintf(cmd, sizeof cmd, "POCL_MAX_PTHREAD_COUNT=1 '%s' --hash %s", self_path, p ? "fp64" : "fp32");
        FILE *fp = popen(cmd, "r");
        assert_non_null(fp);
        unsigned long long hc = 0;
        int got = fscanf(fp, "%llx", &hc);
        int status = pclose(fp);
        assert_int_equal(got, 1);
        assert_int_equal(status, 0);
        if ((uint64_t)hc != h1)
            fail_msg("%s: one-thread PoCL run differs from the default run", p ? "fp64" : "fp32");
    }
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--hash")) { /* child of test_repeat_and_threads */
        printf("%llx\n", (unsigned long long)run_hash(strcmp(argv[2], "fp64") ? DEM_FP32 : DEM_FP64, 300));
        return 0;
    }
    /* this process's PoCL on two threads at least whatever its caller set (test_pocl_threads): the child's one-thread
     * run is compared with a many-thread one even on a one-core machine */
    test_pocl_threads();
    ssize_t len = readlink("/proc/self/exe", self_path, sizeof self_path - 1);
    if (len > 0)
        self_path[len] = 0;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lockstep_fp64),
        cmocka_unit_test(test_lockstep_fp32),
        cmocka_unit_test(test_repeat_and_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
