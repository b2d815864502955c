/* run.c - see run.h. */
#include "run.h"
#include "checkpoint.h"
#include "output.h"
#include "h5util.h"
#include "cli.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <errno.h>
#include <libgen.h>
#include <sys/stat.h>
#include <unistd.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void run_sample_state(dem_sim *s, const scene_run *run, double *strain, double *stress)
{
    *strain = *stress = NAN;
    if (run->piston < 0)
        return;
    double p[3], f[3];
    const double *n = run->piston_normal, *p0 = run->piston_point;
    if (dem_wall_position(s, run->piston, p) || dem_wall_force(s, run->piston, f))
        return;
    /* n points from the piston into the sample: travel into it is (p - p0).n */
    double travel = (p[0] - p0[0]) * n[0] + (p[1] - p0[1]) * n[1] + (p[2] - p0[2]) * n[2];
    *strain = (travel - run->contact_travel) / run->sample_height;
    *stress = -(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]) / run->sample_area;
}

static int default_out(const scene *sc, char *buf, size_t len)
{
    const char *base = strrchr(sc->path, '/') ? strrchr(sc->path, '/') + 1 : sc->path;
    const char *dot = strrchr(base, '.');
    return snprintf(buf, len, "%.*s.h5", (int)(dot ? (size_t)(dot - base) : strlen(base)), base);
}

/* capped < 0: not an iterated MC-strain run (no iteration column) */
static void progress_line(int tty, long step, long steps, double t, double rate_ps, double eta, double it_per_step,
                          long capped)
{
    char mc[96] = "";
    if (capped >= 0)
        snprintf(mc, sizeof mc, "  MC-strain %.1f it/step, %ld steps capped", it_per_step, capped);
    fprintf(stderr, "%sstep %ld/%ld (%5.1f %%)  t = %.6g s  %.3g particle-steps/s%s  ETA %.0f s%s",
            tty ? "\r" : "", step, steps, 100.0 * (double)step / (double)steps, t, rate_ps, mc, eta, tty ? "   " : "\n");
    fflush(stderr);
}

/* What a failed run leaves to restart from. */
static void checkpoint_note(char *buf, size_t len, const char *ckp, long ck_step, const char *restart)
{
    if (ck_step >= 0)
        snprintf(buf, len, "last checkpoint: %s, step %ld", ckp, ck_step);
    else if (restart)
        snprintf(buf, len, "no checkpoint written by this run; it started from %s", restart);
    else
        snprintf(buf, len, "no checkpoint written yet (output.checkpoint_every sets how often)");
}

static int fail_with(int code, const char *msg)
{
    fprintf(stderr, "dem: %s\n", msg);
    return code;
}

/* Both name the same existing file (a link or another spelling included). */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

int run_output_paths(const scene *sc, const run_opts *o, char outp[RUN_PATH_LEN], char ckp[RUN_PATH_LEN], char *err,
                     size_t errlen)
{
    int l;
    if (o->out)
        l = snprintf(outp, RUN_PATH_LEN, "%s", o->out);
    else
        l = default_out(sc, outp, RUN_PATH_LEN);
    if (l < 0 || l > DEM_MAX_PATH) {
        char shown[CLI_SHOW_LEN];
        snprintf(err, errlen, "%s: the output path has %d characters; at most %d are accepted",
                 cli_show(outp, shown, 200), l, DEM_MAX_PATH);
        return EXIT_USAGE;
    }
    if (o->checkpoint)
        l = snprintf(ckp, RUN_PATH_LEN, "%s", o->checkpoint);
    else {
        size_t n = strlen(outp);
        l = snprintf(ckp, RUN_PATH_LEN, "%.*s.ckpt.h5", (int)(n > 3 && !strcmp(outp + n - 3, ".h5") ? n - 3 : n),
                     outp);
    }
    if (l < 0 || l > DEM_MAX_PATH) {
        char shown[CLI_SHOW_LEN];
        snprintf(err, errlen, "%s: the checkpoint path has %d characters; at most %d are accepted (--checkpoint "
                              "names another)", cli_show(ckp, shown, 200), l, DEM_MAX_PATH);
        return EXIT_USAGE;
    }
    char outs[6][RUN_PATH_LEN + 16];
    snprintf(outs[0], sizeof outs[0], "%s", outp);
    snprintf(outs[1], sizeof outs[1], "%s.part", outp);
    output_xmf_path(outp, outs[2], sizeof outs[2]);
    snprintf(outs[3], sizeof outs[3], "%s.part", outs[2]);
    snprintf(outs[4], sizeof outs[4], "%s", ckp);
    snprintf(outs[5], sizeof outs[5], "%s" CHECKPOINT_TMP_SUFFIX, ckp);
    const char *in[66];
    const char *what[66];
    char csv[64][4400];
    int nin = 0;
    in[nin] = sc->path, what[nin++] = "the scene";
    if (o->restart)
        in[nin] = o->restart, what[nin++] = "the checkpoint this run restarts from";
    for (unsigned k = 0; k < sc->f->particles_count && k < 64; k++)
        if (sc->f->particles[k].csv) {
            snprintf(csv[k], sizeof csv[k], "%s/%s", sc->dir, sc->f->particles[k].csv);
            in[nin] = csv[k], what[nin++] = "a CSV file the scene reads";
        }
    for (int q = 0; q < 6; q++) {
        struct stat st;
        char shown[CLI_SHOW_LEN], shown2[CLI_SHOW_LEN];
        cli_show(outs[q], shown, sizeof shown);
        if (stat(outs[q], &st) == 0 && S_ISDIR(st.st_mode)) {
            snprintf(err, errlen, "%s: is a directory; -o names the HDF5 file to write (e.g. %s/run.h5)", shown, shown);
            return EXIT_USAGE;
        }
        /* a device, pipe or socket would be replaced by a regular file when the run renames its output into place
         * (as root, -o /dev/null would remove /dev/null) */
        if (stat(outs[q], &st) == 0 && !S_ISREG(st.st_mode)) {
            snprintf(err, errlen, "%s: is not a regular file (a device, pipe or socket); a run replaces what it "
                                  "writes, so -o and --checkpoint must name regular files or new ones", shown);
            return EXIT_USAGE;
        }
        for (int k = 0; k < nin; k++)
            if (same_file(outs[q], in[k])) {
                snprintf(err, errlen, "%s: writing it would replace %s (%s); choose another -o%s", shown, what[k],
                         cli_show(in[k], shown2, sizeof shown2), q >= 4 ? " or --checkpoint" : "");
                return EXIT_USAGE;
            }
        char dir[RUN_PATH_LEN + 16];
        snprintf(dir, sizeof dir, "%s", outs[q]);
        const char *d = dirname(dir);
        if (access(d, W_OK | X_OK) != 0) {
            int e = errno;
            snprintf(err, errlen, "%s: cannot write into the folder '%s': %s", shown,
                     cli_show(d, shown2, sizeof shown2), strerror(e));
            return EXIT_IO;
        }
    }
    return 0;
}

int run_scene(const run_opts *o)
{
    char err[8192];
    checkpoint ck;
    int have_ck = 0;
    scene *sc;
    if (o->restart) {
        if (checkpoint_read(o->restart, &ck, err, sizeof err)) /* 66 when it cannot be opened, 65 when damaged */
            return fail_with(strstr(err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT, err);
        have_ck = 1;
        sc = scene_load_text(o->scene_path ? o->scene_path : ck.scene_path, ck.scene_text, strlen(ck.scene_text), err,
                             sizeof err);
    } else {
        sc = scene_load(o->scene_path, err, sizeof err);
    }
    if (!sc) {
        if (have_ck)
            checkpoint_free(&ck);
        return fail_with(strstr(err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT, err);
    }
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    int code = 0;
    output *out = NULL;
    char outp[RUN_PATH_LEN], ckp[RUN_PATH_LEN];
    if (!s) { /* a file the scene names (a CSV) that cannot be opened: 66, like the scene itself */
        code = fail_with(strstr(err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT, err);
        goto done;
    }
    const char *model = o->model ? o->model : have_ck && ck.model[0] ? ck.model : NULL;
    if (have_ck && o->model && strcmp(o->model, ck.model[0] ? ck.model : o->model)) {
        snprintf(err, sizeof err, "%s: the checkpoint was run with --model %s, not %s", o->restart, ck.model, o->model);
        code = fail_with(EXIT_USAGE, err);
        goto done;
    }
    if (model && scene_apply_model(sc, s, &run, model, err, sizeof err)) {
        code = fail_with(o->model ? EXIT_USAGE : EXIT_BAD_INPUT, err);
        goto done;
    }
    if (o->device >= 0)
        run.cfg.device = o->device;
    if (have_ck) /* a restart continues in the checkpoint's precision */
        run.cfg.precision = (dem_precision)ck.st.real_size;
    if (o->precision)
        run.cfg.precision = (dem_precision)o->precision;
    int pc = run_output_paths(sc, o, outp, ckp, err, sizeof err);
    if (pc) {
        code = fail_with(pc, err);
        goto done;
    }
    if (have_ck) {
        if (ck.st.n != dem_count(s) || ck.st.real_size != (int)run.cfg.precision) {
            snprintf(err, sizeof err, "%s: the checkpoint has %d particles in %s; the scene gives %d in %s", o->restart,
                     ck.st.n, ck.st.real_size == 8 ? "fp64" : "fp32", dem_count(s),
                     run.cfg.precision == DEM_FP64 ? "fp64" : "fp32");
            code = fail_with(EXIT_BAD_INPUT, err);
            goto done;
        }
        for (int i = 0; i < ck.st.n; i++)
            if (ck.radius[i] != dem_particle_radius(s, i)) {
                snprintf(err, sizeof err, "%s: particle %d has radius %g m in the checkpoint and %g m in the scene "
                         "(did a CSV file change?)", o->restart, i, ck.radius[i], dem_particle_radius(s, i));
                code = fail_with(EXIT_BAD_INPUT, err);
                goto done;
            }
    }
    int se = dem_start(s, &run.cfg);
    if (se) {
        snprintf(err, sizeof err, "%s: %s", sc->path, dem_error(s));
        code = fail_with(se == DEM_ERR_DEVICE ? EXIT_DEVICE : EXIT_BAD_INPUT, err);
        goto done;
    }
    if (have_ck && ck.st.step > run.steps) {
        snprintf(err, sizeof err, "%s: the checkpoint is at step %ld, past the end of the scene (%ld steps of %g s)",
                 o->restart, ck.st.step, run.steps, run.dt);
        code = fail_with(EXIT_BAD_INPUT, err);
        goto done;
    }
    if (have_ck && dem_state_set(s, &ck.st)) {
        snprintf(err, sizeof err, "%s: %s", o->restart, dem_error(s));
        code = fail_with(EXIT_BAD_INPUT, err);
        goto done;
    }
    char fx[128];
    dem_effects_string(run.effects, fx, sizeof fx);
    int show = o->progress < 0 ? isatty(2) : o->progress;
    if (show || o->progress != 0)
        fprintf(stderr, "dem: %s: %d particles, %d walls, dt %.4g s, %ld steps, %s\n", sc->path, dem_count(s),
                dem_wall_count(s), run.dt, run.steps, dem_describe(s));
    if ((show || o->progress != 0) && (run.effects & DEM_EFFECT_MC_STRESS)) {
        char conv[128];
        dem_mc_stress_convention_string(run.mcs_conv, conv, sizeof conv);
        fprintf(stderr, "dem: MC-stress pressure convention: %s%s\n", conv,
                run.mcs_conv == DEM_MCS_DEFAULT ? " (the default: Eq. 11's reading)" : "");
    }
    if ((show || o->progress != 0) && (run.effects & DEM_EFFECT_MC_STRAIN) && sc->f->mc_contact_distance > 1)
        fprintf(stderr, "dem: MC-strain contact distance %g (r_i + r_j): gaps that the induced displacements close are "
                        "contacts\n", sc->f->mc_contact_distance);
    out = output_open(outp, sc, &run, s, err, sizeof err);
    if (!out) {
        code = fail_with(EXIT_IO, err);
        goto done;
    }
    double strain, stress, t0 = now(), last = t0;
    long step0 = dem_step_index(s), end = run.steps;
    if (o->stop_after > 0 && step0 + o->stop_after < end)
        end = step0 + o->stop_after;
    int tty = isatty(2);
    run_sample_state(s, &run, &strain, &stress);
    errno = 0;
    if (output_frame(out, s) || output_series(out, s, strain, stress)) {
        int e = errno;
        snprintf(err, sizeof err, "%s.part: cannot write the first frame to the output file: %s", outp,
                 h5_io_reason(e));
        code = fail_with(EXIT_IO, err);
        goto done;
    }
    long ck_step = -1; /* step of the last checkpoint this run wrote */
    while (dem_step_index(s) < end) {
        long st = dem_step_index(s), next = end;
        long evs[3] = {run.frame_every, run.series_every, run.checkpoint_every};
        for (int k = 0; k < 3; k++)
            if (evs[k] > 0 && (st / evs[k] + 1) * evs[k] < next)
                next = (st / evs[k] + 1) * evs[k];
        if (show) { /* at most ~1 s between progress lines */
            double rate = (double)(st - step0 + 1) / (now() - t0 + 1e-9);
            long cap = st + (long)(rate > 1 ? rate : 1) + 1;
            if (cap < next)
                next = cap;
        }
        if (dem_step(s, next - st)) {
            char cknote[4400];
            checkpoint_note(cknote, sizeof cknote, ckp, ck_step, o->restart);
            snprintf(err, sizeof err, "%s: run stopped at step %ld: %s (output so far: %s.part; %s)", sc->path,
                     dem_step_index(s), dem_error(s), outp, cknote);
            code = fail_with(EXIT_RUN_FAILED, err);
            goto done;
        }
        st = dem_step_index(s);
        int io = 0;
        errno = 0;
        if (st % run.frame_every == 0 || st == end)
            io |= output_frame(out, s);
        if (!io && (st % run.series_every == 0 || st == end)) {
            run_sample_state(s, &run, &strain, &stress);
            io |= output_series(out, s, strain, stress);
        }
        if (io) {
            int e = errno;
            char cknote[4400];
            checkpoint_note(cknote, sizeof cknote, ckp, ck_step, o->restart);
            snprintf(err, sizeof err, "%s.part: cannot write step %ld to the output file: %s (%s)", outp, st,
                     h5_io_reason(e), cknote);
            code = fail_with(EXIT_IO, err);
            goto done;
        }
        if ((run.checkpoint_every > 0 && st % run.checkpoint_every == 0) || st == end) {
            if (checkpoint_write(ckp, s, sc, &run, err, sizeof err)) {
                code = fail_with(EXIT_IO, err);
                goto done;
            }
            ck_step = st;
        }
        double tn = now();
        if (show && (tn - last > 1 || st == end)) {
            double rate = (double)(st - step0) / (tn - t0 + 1e-12);
            dem_mc_stats mc;
            dem_mc_stats_get(s, &mc);
            progress_line(tty, st, run.steps, dem_time(s), rate * dem_count(s), (double)(end - st) / (rate + 1e-12),
                          (double)mc.total / (double)(st > 0 ? st : 1), run.mc_cap > 0 ? mc.unconverged : -1);
            last = tn;
        }
    }
    if (show && tty)
        fputc('\n', stderr);
    if (output_finish(out, err, sizeof err)) {
        out = NULL;
        code = fail_with(EXIT_IO, err);
        goto done;
    }
    out = NULL;
    if (o->progress != 0 || show)
    {
        fprintf(stderr, "dem: wrote %s (+ .xmf) and checkpoint %s at step %ld; %.2f s wall time\n", outp, ckp,
                dem_step_index(s), now() - t0);
        char seq[2048];
        if (dem_kernel_sequence(s, 0, seq, sizeof seq))
            fprintf(stderr, "dem: kernels of the last step: %s\n", seq);
        if (dem_kernel_sequence(s, 1, seq, sizeof seq))
            fprintf(stderr, "dem: and at each neighbour rebuild (%ld in all): %s\n", dem_rebuild_count(s), seq);
        fprintf(stderr, "dem: device memory held: %.3g MB\n", (double)dem_device_bytes(s) / 1e6);
        dem_mc_stats mc;
        dem_mc_stats_get(s, &mc);
        if ((run.effects & DEM_EFFECT_MC_STRAIN) && run.mc_cap > 0)
            fprintf(stderr, "dem: MC-strain iterations: %ld in all, %.2f per step, at most %ld; %ld steps hit the cap "
                            "of %d\n", mc.total, (double)mc.total / (double)(dem_step_index(s) > 0 ? dem_step_index(s) : 1),
                    mc.max, mc.unconverged, run.mc_cap);
    }
    {   /* a warning, even with --quiet: steps whose forces did not converge to the tolerance */
        dem_mc_stats mc;
        dem_mc_stats_get(s, &mc);
        if ((run.effects & DEM_EFFECT_MC_STRAIN) && run.mc_cap > 0 && mc.unconverged > 0)
            fprintf(stderr, "dem: warning: %ld of %ld steps hit the MC-strain iteration cap of %d (mc_iterations) before "
                            "every contact force settled to mc_tolerance %g; the series mc_capped counts them. Raise "
                            "mc_iterations, or loosen mc_tolerance, if that matters here\n",
                    mc.unconverged, dem_step_index(s), run.mc_cap, run.mc_tol);
    }
done:
    if (out)
        output_abort(out);
    dem_destroy(s);
    scene_free(sc);
    if (have_ck)
        checkpoint_free(&ck);
    return code;
}
