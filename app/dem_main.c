/* dem_main.c - the `dem` command: run a scene, check it, list devices. */
#include "cli.h"
#include "run.h"
#include "scene.h"
#include "dem_debug.h" /* dem_particle_added_position */
#include <hdf5.h>
#include <math.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h> /* readlink: this program, for dem conform */

/* The wall-time estimate of dem check: a rate measured with dem run on the 2-core development VM (AMD EPYC, PoCL
 * 3.1, fp64, classical Hertz-Mindlin): about 60 us per step whatever the size (kernel launches, the host's stage
 * and wall work) plus 0.12 us per particle-step in a packed bed. Measured: 300 beads poured 85 us/step, the
 * 514-hydrogel compression 150, examples/pour_press.yaml (2500 beads) 377, tablet_3k about 270 on average,
 * tablet_100k 10 000 (54 minutes for 323 977 steps); the formula gives 96, 122, 360, 420 and 12 060: within about a
 * factor 1.5. Loose packings cost less per particle, the multi-contact laws more (docs/multicontact.md), and other
 * devices differ altogether: dem run's progress line measures the real rate. */
#define CHECK_STEP_S 6.0e-5
#define CHECK_PARTICLE_STEP_S 1.2e-7
#define CHECK_STAGE_LINES 12 /* stage lines per wall at most (repeat: load-unload cycles by the hundred) */

static void print_duration(double sec, char *buf, size_t len)
{
    if (sec < 120)
        snprintf(buf, len, "%.2g s", sec);
    else if (sec < 7200)
        snprintf(buf, len, "%.2g minutes", sec / 60);
    else if (sec < 3 * 86400)
        snprintf(buf, len, "%.2g hours", sec / 3600);
    else
        snprintf(buf, len, "%.2g days", sec / 86400);
}

/* Each moving wall's stages: how long each runs at most, where it goes, and for a plane moving along its normal
 * whether it reaches the particles as the scene places them (their initial positions: a pour settles them lower,
 * so a wall that reaches the placed particles may still stop short of the bed; the stage-end lines of dem run say
 * what happened). */
static void print_stages(dem_sim *s, const scene *sc, int gravity)
{
    int n = dem_count(s), settle = sc->f->time.settle > 0;
    for (int k = 0; k < dem_wall_count(s); k++) {
        dem_wall w;
        dem_wall_get(s, k, &w);
        if (w.nstages <= settle)
            continue;
        char name[1100];
        scene_wall_label(sc, k, name, sizeof name);
        double gap = INFINITY, nn = sqrt(w.normal[0] * w.normal[0] + w.normal[1] * w.normal[1] +
                                         w.normal[2] * w.normal[2]);
        double p0[3];
        dem_wall_position(s, k, p0);
        if (w.kind == DEM_WALL_PLANE && nn > 0)
            for (int i = 0; i < n; i++) {
                double x[3];
                if (dem_particle_added_position(s, i, x))
                    continue;
                double h = ((x[0] - p0[0]) * w.normal[0] + (x[1] - p0[1]) * w.normal[1] + (x[2] - p0[2]) * w.normal[2]) /
                           nn - dem_particle_radius(s, i);
                gap = h < gap ? h : gap;
            }
        double t = 0, travel = 0, most = 0; /* time since the start; travel towards the particles along the normal, and
                                               its largest */
        int reached = 0;
        for (int st = 0; st < w.nstages; st++) {
            const dem_stage *g = &w.stages[st];
            char lab[64], what[400] = "", ends[300] = "", reach[300] = "";
            if (settle && st == 0)
                snprintf(lab, sizeof lab, "time.settle");
            else
                snprintf(lab, sizeof lab, "motion[%d]", st - settle); /* repeats: the list played again */
            double vn = w.kind == DEM_WALL_PLANE && nn > 0
                            ? (g->velocity[0] * w.normal[0] + g->velocity[1] * w.normal[1] +
                               g->velocity[2] * w.normal[2]) / nn : 0;
            double speed = sqrt(g->velocity[0] * g->velocity[0] + g->velocity[1] * g->velocity[1] +
                                g->velocity[2] * g->velocity[2]);
            if (g->force > 0)
                snprintf(what, sizeof what, "a servo at %g N (at most %g m/s)", g->force, g->max_speed);
            else if (speed == 0)
                snprintf(what, sizeof what, "holds still");
            else
                snprintf(what, sizeof what, "%g m/s, %g m at most%s", speed, dem_stage_travel(w.stages, st, g->velocity),
                         w.kind != DEM_WALL_PLANE ? "" : vn > 0 ? ", towards the particles" : vn < 0 ? ", away from them"
                                                                                                     : ", along its plane");
            if (g->until_force > 0)
                snprintf(ends + strlen(ends), sizeof ends - strlen(ends), "; ends early at until_force %g N", g->until_force);
            if (g->until_distance > 0)
                snprintf(ends + strlen(ends), sizeof ends - strlen(ends), "; ends early at until_distance %g m",
                         g->until_distance);
            if (g->until_density > 0)
                snprintf(ends + strlen(ends), sizeof ends - strlen(ends), "; ends early at until_density %g",
                         g->until_density);
            if (g->ramp > 0)
                snprintf(ends + strlen(ends), sizeof ends - strlen(ends), "; ramps up over %g s", g->ramp);
            if (g->after_wall || g->after_stage) {
                char other[1100];
                scene_wall_label(sc, g->after_wall, other, sizeof other);
                snprintf(ends + strlen(ends), sizeof ends - strlen(ends), "; waits for wall '%s' to run its stages "
                         "(the times here leave the wait out)", other);
            }
            if (t + g->duration > sc->f->time.duration)
                snprintf(ends + strlen(ends), sizeof ends - strlen(ends), "; the run ends at %g s",
                         sc->f->time.duration);
            double after = travel + (w.kind == DEM_WALL_PLANE ? dem_stage_travel(w.stages, st, w.normal) : 0);
            if (isfinite(gap) && !reached && gap - travel <= 0) {
                reached = 1;
                snprintf(reach, sizeof reach, "; touches the particles as placed from its start");
            } else if (isfinite(gap) && !reached && vn > 0 && g->force <= 0 && after >= gap) {
                reached = 1;
                snprintf(reach, sizeof reach, "; meets the particles as placed %.3g s into the stage (t = %.4g s)",
                         (gap - travel) / vn, t + (gap - travel) / vn);
            }
            travel = g->force > 0 ? travel : after;
            most = travel > most ? travel : most;
            if (st < CHECK_STAGE_LINES || reach[0]) /* a long repeat list: its first stages, and where it reaches */
                printf("stage          wall '%s' %d/%d (%s): up to %g s (t = %.4g to %.4g s), %s%s%s\n", name, st + 1,
                       w.nstages, lab, g->duration, t, t + g->duration, what, ends, reach);
            else if (st == CHECK_STAGE_LINES)
                printf("               wall '%s': %d stages more (its motion list repeated)\n", name,
                       w.nstages - CHECK_STAGE_LINES);
            t += g->duration;
        }
        if (isfinite(gap) && !reached && most > 0)
            printf("               warning: wall '%s' never reaches the particles as placed (%.3g m away, it moves %.3g m "
                   "towards them at most): a press that stops %.3g m short, unless the particles move to it\n", name,
                   gap, most, gap - most);
        if (isfinite(gap) && gravity)
            printf("               (with gravity the particles fall first, so the bed lies lower than placed: dem run "
                   "logs where and why each stage ended)\n");
    }
}

static double wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* dem check --probe: the run's first steps timed on its device, and the whole run's wall time predicted from them.
 * The first step (the first neighbour build, the device warming up) is left out; then steps in doubling batches
 * until PROBE_S seconds or PROBE_STEPS steps have passed. The state is the scene's start: a press steps slower once
 * its compact is dense (more contacts per sphere; tablet_100k's whole cycle averaged 2.2 times the step of its loose
 * fill on 2 cores), a pour faster once settled; the progress line of dem run gives the rate as it goes. */
#define PROBE_S 3.0
#define PROBE_STEPS 4000
static int probe(dem_sim *s, const scene_run *run, const char *path)
{
    double t0 = wall_now();
    int e = dem_start(s, &run->cfg);
    if (e || dem_step(s, 1)) {
        fprintf(stderr, "dem: %s: the probe could not run: %s\n", path, dem_error(s));
        return e == DEM_ERR_DEVICE ? EXIT_DEVICE : EXIT_RUN_FAILED;
    }
    double ready = wall_now() - t0, t = 0;
    long done = 0;
    for (long k = 1; t < PROBE_S && done < PROBE_STEPS && done + 1 < run->steps; k *= 2) {
        long m = k < run->steps - 1 - done ? k : run->steps - 1 - done;
        double a = wall_now();
        if (dem_step(s, m)) {
            fprintf(stderr, "dem: %s: the probe stopped at step %ld: %s\n", path, done + 1, dem_error(s));
            return EXIT_RUN_FAILED;
        }
        t += wall_now() - a, done += m;
    }
    char dev[512] = "the reference", wt[64];
    if (run->cfg.backend == DEM_BACKEND_OPENCL && dem_device_name(run->cfg.device, dev, sizeof dev))
        snprintf(dev, sizeof dev, "device %d", run->cfg.device);
    double per = done ? t / (double)done : 0;
    print_duration(per * (double)run->steps + ready, wt, sizeof wt);
    printf("probe          %ld steps in %s from the start on %s, after %.2g s to start and take the first: %.4g us "
           "per step, %.3g particle-steps/s\n", done, run->cfg.precision == DEM_FP64 ? "fp64" : "fp32", dev, ready,
           per * 1e6, per > 0 ? (double)dem_count(s) / per : 0.0);
    printf("wall time      about %s on that device at the probe's rate (a dense compact steps slower than its loose "
           "fill: tablet_100k's cycle averaged 2.2 times its fill's step), output and checkpoints not counted\n", wt);
    return 0;
}

static int check(const cli *cl)
{
    const char *path = cl->check_path, *model = cl->check_model;
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
    if (model && scene_apply_model(sc, s, &run, model, err, sizeof err)) {
        fprintf(stderr, "dem: %s\n", err);
        dem_destroy(s);
        scene_free(sc);
        return EXIT_USAGE;
    }
    char dn[512];
    if (cl->check_device >= 0 && dem_device_name(cl->check_device, dn, sizeof dn)) {
        fprintf(stderr, "dem: no OpenCL device %d (dem devices lists them)\n", cl->check_device);
        dem_destroy(s);
        scene_free(sc);
        return EXIT_DEVICE;
    }
    if (cl->check_device >= 0)
        run.cfg.device = cl->check_device, run.cfg.backend = DEM_BACKEND_OPENCL;
    if (cl->check_precision)
        run.cfg.precision = (dem_precision)cl->check_precision;
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
    size_t dev_bytes = 0; /* the library's own estimate, from its buffer registry */
    if (dem_memory_estimate(s, &run.cfg, &dev_bytes)) {
        fprintf(stderr, "dem: %s: %s\n", path, dem_error(s));
        dem_destroy(s);
        scene_free(sc);
        return EXIT_BAD_INPUT;
    }
    long frames = run.steps / run.frame_every + 1;
    int nfields = 0;
    for (unsigned b = run.fields & ~(unsigned)(OUT_RADIUS | OUT_MATERIAL); b; b >>= 1)
        nfields += b & 1;
    if ((run.fields & OUT_RADIUS) && (run.effects & DEM_EFFECT_MDR))
        nfields++; /* /frames/apparent_radius: a third of a vector field, counted as one (an estimate) */
    printf("scene          %s%s%s\n", path, sc->f->name ? ": " : "", sc->f->name ? sc->f->name : "");
    printf("particles      %d (radius %.4g to %.4g m), %d walls, %u materials\n", n, rmin, rmax, dem_wall_count(s),
           sc->f->materials_count);
    printf("effects        %s\n", fx);
    if (run.effects & DEM_EFFECT_MC_STRESS) {
        char conv[128];
        dem_mc_stress_convention_string(run.mcs_conv, conv, sizeof conv);
        printf("MC-stress      %s\n", conv);
    }
    run_mc_lag_advice(s, sc, &run, 1, stdout);
    printf("Rayleigh time  %.4g s (smallest particle)\n", ts.rayleigh_time);
    printf("Hertz time     %.4g s (two smallest like spheres, head-on at 1 m/s)\n", ts.hertz_time);
    fflush(stdout);
    run_contact_advice(s, sc, 1, stdout);
    run_order_advice(s, sc, 1, stdout);
    run_precision_advice(s, sc, run.cfg.precision, 1, stdout);
    printf("time step      %.4g s = %.3g x Rayleigh time (recommended %.4g s, bound %.4g s)\n", run.dt,
           run.dt / ts.rayleigh_time, ts.recommended_dt, ts.max_dt);
    fflush(stdout);
    run_dt_advice(sc, &run); /* a warning, above a membrane's recommendation */
    run_rolling_advice(sc, run.effects);
    if (run.dt > 0.35 * ts.rayleigh_time) /* docs/accuracy.md: stable up to the bound, not accurate */
        printf("               above 0.35 x Rayleigh time: stable, but make accuracy measured the 514-hydrogel "
               "compression 10-19 %% off at 0.5 under every model, within 0.6 %% at 0.35 (docs/accuracy.md)\n");
    if (scene_mass_scale(sc) != 1) {
        double S = scene_mass_scale(sc);
        if (scene_keeps_acceleration(sc))
            printf("mass scale     x %g (time.mass_scale): every mass %g times its density's, gravity as given "
                   "(mass_scale_keeps: acceleration: a fall at the real rate, weights %g times too heavy)", S, S, S);
        else
            printf("mass scale     x %g (time.mass_scale): every mass %g times its density's, gravity / %g (the weights "
                   "stay real)", S, S, S);
        printf("; the time scales above and the step are %.3g times the real ones, inertia %g times too strong "
               "(docs/scenes.md \"Mass scaling\")\n", sqrt(S), S);
    }
    printf("duration       %.6g s = %ld steps (%.3g particle-steps)\n", sc->f->time.duration, run.steps,
           (double)run.steps * n);
    char wt[64];
    print_duration((double)run.steps * (CHECK_STEP_S + CHECK_PARTICLE_STEP_S * n), wt, sizeof wt);
    printf("wall time      about %s on 2 CPU cores with PoCL (%.0f us per step + %.2f us per particle-step, measured "
           "with dem run on the development VM, classical law, within a factor of about 1.5; a GPU or the "
           "multi-contact laws differ: the progress line of dem run gives the real rate)\n", wt, CHECK_STEP_S * 1e6,
           CHECK_PARTICLE_STEP_S * 1e6);
    print_stages(s, sc, (run.effects & DEM_EFFECT_GRAVITY) != 0);
    printf("output         frame every %ld steps (%ld frames, %d vector fields), series every %ld steps, "
           "checkpoint every %ld steps (0: end only)\n", run.frame_every, frames, nfields, run.series_every,
           run.checkpoint_every);
    printf("memory         about %.3g MB on the device at the start (%s, %.0f bytes per particle; dem run reports what "
           "it held), frames about %.3g MB before compression\n", (double)dev_bytes / 1e6, rs == 8 ? "fp64" : "fp32",
           n > 0 ? (double)dev_bytes / n : 0.0, (double)frames * nfields * 3 * 8 * n / 1e6);
    printf("backend        %s, device %d\n", run.cfg.backend == DEM_BACKEND_OPENCL ? "OpenCL" : "reference",
           run.cfg.device);
    if (run.piston >= 0)
        printf("sample         piston = wall %d, height %.6g m, area %.6g m^2\n", run.piston, run.sample_height,
               run.sample_area);
    for (int k = 0; k < dem_wall_count(s); k++) { /* punches whose stages end at a relative density */
        dem_wall w, dw;
        int die, other, wants = 0;
        dem_wall_get(s, k, &w);
        for (int st = 0; st < w.nstages; st++)
            wants |= w.stages[st].until_density > 0;
        double rho;
        if (!wants || dem_density_walls(s, k, &die, &other) || dem_relative_density(s, k, &rho))
            continue;
        dem_wall_get(s, die, &dw);
        char a[1100], b[1100], cyl[1100];
        scene_wall_label(sc, k, a, sizeof a);
        scene_wall_label(sc, other, b, sizeof b);
        scene_wall_label(sc, die, cyl, sizeof cyl);
        dem_wall ow;
        dem_wall_get(s, other, &ow);
        char cups[256] = "";
        for (int q = 0; q < 2; q++) {
            const dem_wall *p = q ? &ow : &w;
            if (p->cup_depth > 0) {
                size_t at = strlen(cups);
                snprintf(cups + at, sizeof cups - at, "; '%.60s' concave (cup radius %.4g m, depth %.4g m)", q ? b : a,
                         p->cup_radius, p->cup_depth);
            }
        }
        printf("press          punch '%s' faces '%s' in die '%s' (radius %.4g m): relative density %.4g at the start "
               "(the spheres' volume over the bore between them and their cups)%s\n", a, b, cyl, dw.radius, rho, cups);
    }
    if (run.fill[0])
        printf("fill           %s\n", run.fill);
    if (run.note[0])
        printf("note           %s\n", run.note);
    fflush(stdout);
    int rc = cl->check_probe ? probe(s, &run, path) : 0;
    dem_destroy(s);
    scene_free(sc);
    return rc;
}

static int devices(void)
{
    int n = dem_device_count();
    if (n <= 0) {
        fprintf(stderr, "dem: no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)\n");
        return EXIT_DEVICE;
    }
    for (int k = 0; k < n; k++) {
        char name[512], what[512];
        dem_device_name(k, name, sizeof name);
        printf("%d  %s\n", k, name);
        if (!dem_device_describe(k, what, sizeof what))
            printf("   %s\n", what);
    }
    return 0;
}

int main(int argc, char **argv)
{
    /* HDF5 1.10 crashes in its exit handler when a file's close had failed (a full disk, a file-size limit): it
     * closes the half-closed file again. Its exit handler only frees memory, every file we write is closed (or
     * abandoned as .part) by us before exit, so it is switched off; must come before any other HDF5 call. */
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* HDF5's own error stack never reaches the user: our messages say it */
    cli c;
    char err[8192];
    int with_usage;
    int code = cli_parse(argc, argv, &c, err, sizeof err, &with_usage);
    if (code) {
        fprintf(stderr, "dem: %s\n%s", err, with_usage ? cli_usage : "");
        return code;
    }
    switch (c.cmd) {
    case CLI_HELP:
        fputs(cli_usage, stdout);
        return 0;
    case CLI_VERSION:
        printf("dem (libdem) %s\n", DEM_VERSION);
        return 0;
    case CLI_DEVICES:
        return devices();
    case CLI_CHECK:
        return check(&c);
    case CLI_HASH: {
        char hex[17];
        int h = conform_hash_file(c.hash_path, hex, err, sizeof err);
        if (h) {
            fprintf(stderr, "dem: %s\n", err);
            return h == -2 ? EXIT_NO_INPUT : EXIT_BAD_INPUT;
        }
        printf("%s\n", hex);
        return 0;
    }
    case CLI_CONFORM: {
        char self[4096];
        ssize_t l = readlink("/proc/self/exe", self, sizeof self - 1);
        if (l > 0)
            self[l] = 0;
        else
            snprintf(self, sizeof self, "%s", argv[0]);
        return conform_run(&c.conform, self);
    }
    case CLI_RUN:
        break;
    }
    return run_mpi_wanted() ? run_mpi(&c.run) : run_scene(&c.run); /* under mpirun -np N > 1: split over ranks */
}
