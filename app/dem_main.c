/* dem_main.c - the `dem` command: run a scene, check it, list devices. */
#include "run.h"
#include "scene.h"
#include <hdf5.h>
#include <math.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage[] =
    "usage: dem run SCENE.yaml [-o OUT.h5] [--device N] [--precision fp32|fp64] [--checkpoint FILE]\n"
    "                          [--progress | --quiet] [--stop-after STEPS]\n"
    "                          [--model classical|mc_stress|mc_strain|mc_strain_iterated]\n"
    "       dem run --restart CHECKPOINT.h5 [-o OUT.h5] [options as above]\n"
    "       dem check SCENE.yaml     validate a scene and print what it implies (time scales, memory, effects)\n"
    "       dem devices              list OpenCL devices (index for --device)\n"
    "       dem --help | --version\n"
    "\n"
    "run writes OUT.h5 (frames and time series; OUT.h5.part until it completes), OUT.xmf for ParaView, and\n"
    "checkpoints to OUT.ckpt.h5 (the scene's output.checkpoint_every, and at the end). A progress line goes to\n"
    "stderr when it is a terminal (--progress: always; --quiet: never). Units are SI. --model replaces the\n"
    "scene's normal law (same scene, another contact model; kept in the checkpoint for --restart).\n"
    "\n"
    "exit status: 0 done; 1 the simulation failed while running; 2 bad command line; 65 invalid scene or\n"
    "checkpoint; 66 a file could not be opened; 69 no usable OpenCL device; 74 output could not be written.\n";

static int check(const char *path)
{
    char err[8192];
    scene *sc = scene_load(path, err, sizeof err);
    if (!sc) {
        fprintf(stderr, "dem: %s\n", err);
        return strstr(err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT;
    }
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s) {
        fprintf(stderr, "dem: %s\n", err);
        scene_free(sc);
        return strstr(err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT;
    }
    int n = dem_count(s);
    double rmin = INFINITY, rmax = 0;
    for (int i = 0; i < n; i++) {
        rmin = fmin(rmin, dem_particle_radius(s, i));
        rmax = fmax(rmax, dem_particle_radius(s, i));
    }
    /* the Hertz time at 1 m/s, a common impact speed; it scales as v^(-1/5) */
    dem_time_scales ts;
    dem_time_scales_get(s, 1.0, &ts);
    char fx[128];
    dem_effects_string(run.effects, fx, sizeof fx);
    int rs = (int)run.cfg.precision;
    /* memory: per particle about 24 reals and 8 ints, plus two sets of neighbour rows (16 slots to start: list,
     * mirror, touch, and the tangential history with friction), plus 3 contacts per particle of pair records */
    int fr = (run.effects & DEM_EFFECT_FRICTION) != 0;
    double per = 24.0 * rs + 8 * 4 + 2 * 16 * (4 + 4 + 1 + (fr ? 3 * rs : 0)) + 3 * 8 * rs +
                 (fr ? 3.0 * rs * dem_wall_count(s) : 0) + 2 * 3.0 * rs * dem_wall_count(s);
    long frames = run.steps / run.frame_every + 1;
    int nfields = 0;
    for (unsigned b = run.fields & ~(unsigned)(OUT_RADIUS | OUT_MATERIAL); b; b >>= 1)
        nfields += b & 1;
    printf("scene          %s%s%s\n", path, sc->f->name ? ": " : "", sc->f->name ? sc->f->name : "");
    printf("particles      %d (radius %.4g to %.4g m), %d walls, %u materials\n", n, rmin, rmax, dem_wall_count(s),
           sc->f->materials_count);
    printf("effects        %s\n", fx);
    if (run.effects & DEM_EFFECT_MC_STRESS) {
        char conv[128];
        dem_mc_stress_convention_string(run.mcs_conv, conv, sizeof conv);
        printf("MC-stress      %s\n", conv);
    }
    printf("Rayleigh time  %.4g s (smallest particle)\n", ts.rayleigh_time);
    printf("Hertz time     %.4g s (two smallest like spheres, head-on at 1 m/s)\n", ts.hertz_time);
    printf("time step      %.4g s = %.3g x Rayleigh time (recommended %.4g s, bound %.4g s)\n", run.dt,
           run.dt / ts.rayleigh_time, ts.recommended_dt, ts.max_dt);
    printf("duration       %.6g s = %ld steps (%.3g particle-steps)\n", sc->f->time.duration, run.steps,
           (double)run.steps * n);
    printf("output         frame every %ld steps (%ld frames, %d vector fields), series every %ld steps, "
           "checkpoint every %ld steps (0: end only)\n", run.frame_every, frames, nfields, run.series_every,
           run.checkpoint_every);
    printf("memory         about %.3g MB on the device (%s), frames about %.3g MB before compression\n",
           per * n / 1e6, rs == 8 ? "fp64" : "fp32", (double)frames * nfields * 3 * 8 * n / 1e6);
    printf("backend        %s, device %d\n", run.cfg.backend == DEM_BACKEND_OPENCL ? "OpenCL" : "reference",
           run.cfg.device);
    if (run.piston >= 0)
        printf("sample         piston = wall %d, height %.6g m, area %.6g m^2\n", run.piston, run.sample_height,
               run.sample_area);
    if (run.note[0])
        printf("note           %s\n", run.note);
    dem_destroy(s);
    scene_free(sc);
    return 0;
}

static int devices(void)
{
    int n = dem_device_count();
    if (n <= 0) {
        fprintf(stderr, "dem: no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)\n");
        return EXIT_DEVICE;
    }
    for (int k = 0; k < n; k++) {
        char name[512];
        dem_device_name(k, name, sizeof name);
        printf("%d  %s\n", k, name);
    }
    return 0;
}

static int need_value(int argc, char **argv, int k)
{
    if (k + 1 >= argc) {
        fprintf(stderr, "dem: option %s needs a value\n%s", argv[k], usage);
        return 0;
    }
    return 1;
}

/* A whole decimal integer in [lo, hi] (lo >= 0): digits only, no sign or blanks, no trailing text, no overflow
 * (strtol's ERANGE), no wrap into int. */
static int parse_long(const char *s, long *v, long lo, long hi)
{
    char *end;
    errno = 0;
    *v = strtol(s, &end, 10);
    return *s >= '0' && *s <= '9' && !*end && errno == 0 && *v >= lo && *v <= hi;
}

int main(int argc, char **argv)
{
    /* HDF5 1.10 crashes in its exit handler when a file's close had failed (a full disk, a file-size limit): it
     * closes the half-closed file again. Its exit handler only frees memory, every file we write is closed (or
     * abandoned as .part) by us before exit, so it is switched off; must come before any other HDF5 call. */
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* HDF5's own error stack never reaches the user: our messages say it */
    if (argc < 2) {
        fputs(usage, stderr);
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        fputs(usage, stdout);
        return 0;
    }
    if (!strcmp(cmd, "--version")) {
        printf("dem (libdem) %s\n", DEM_VERSION);
        return 0;
    }
    if (!strcmp(cmd, "devices"))
        return argc == 2 ? devices() : (fputs(usage, stderr), EXIT_USAGE);
    if (!strcmp(cmd, "check")) {
        if (argc != 3) {
            fputs(usage, stderr);
            return EXIT_USAGE;
        }
        return check(argv[2]);
    }
    if (strcmp(cmd, "run")) {
        fprintf(stderr, "dem: unknown command '%s'\n%s", cmd, usage);
        return EXIT_USAGE;
    }
    run_opts o = {NULL, NULL, NULL, NULL, -1, 0, -1, 0, NULL};
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        long v;
        if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!need_value(argc, argv, k))
                return EXIT_USAGE;
            o.out = argv[++k];
        } else if (!strcmp(a, "--checkpoint")) {
            if (!need_value(argc, argv, k))
                return EXIT_USAGE;
            o.checkpoint = argv[++k];
        } else if (!strcmp(a, "--restart")) {
            if (!need_value(argc, argv, k))
                return EXIT_USAGE;
            o.restart = argv[++k];
        } else if (!strcmp(a, "--device")) {
            if (!need_value(argc, argv, k))
                return EXIT_USAGE;
            if (!parse_long(argv[++k], &v, 0, 65535)) {
                fprintf(stderr, "dem: --device needs an index in 0..65535 (see dem devices), not '%s'\n", argv[k]);
                return EXIT_USAGE;
            }
            o.device = (int)v;
        } else if (!strcmp(a, "--precision")) {
            if (!need_value(argc, argv, k))
                return EXIT_USAGE;
            const char *p = argv[++k];
            if (!strcmp(p, "fp32"))
                o.precision = DEM_FP32;
            else if (!strcmp(p, "fp64"))
                o.precision = DEM_FP64;
            else {
                fprintf(stderr, "dem: --precision must be fp32 or fp64\n");
                return EXIT_USAGE;
            }
        } else if (!strcmp(a, "--stop-after")) {
            if (!need_value(argc, argv, k))
                return EXIT_USAGE;
            if (!parse_long(argv[++k], &v, 1, LONG_MAX)) {
                fprintf(stderr, "dem: --stop-after needs a step count >= 1, not '%s'\n", argv[k]);
                return EXIT_USAGE;
            }
            o.stop_after = v;
        } else if (!strcmp(a, "--model")) {
            if (!need_value(argc, argv, k))
                return EXIT_USAGE;
            o.model = argv[++k];
        } else if (!strcmp(a, "--progress")) {
            o.progress = 1;
        } else if (!strcmp(a, "--quiet")) {
            o.progress = 0;
        } else if (a[0] == '-') {
            fprintf(stderr, "dem: unknown option '%s'\n%s", a, usage);
            return EXIT_USAGE;
        } else if (!o.scene_path) {
            o.scene_path = a;
        } else {
            fprintf(stderr, "dem: more than one scene given ('%s')\n", a);
            return EXIT_USAGE;
        }
    }
    if (!o.scene_path && !o.restart) {
        fprintf(stderr, "dem: run needs a scene file or --restart\n%s", usage);
        return EXIT_USAGE;
    }
    return run_scene(&o);
}
