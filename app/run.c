/* run.c - see run.h. */
#include "run.h"
#include "checkpoint.h"
#include "output.h"
#include "h5util.h"
#include "dem_debug.h" /* dem_kernel_sequence, dem_kernel_times */
#include "cli.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <errno.h>
#include <libgen.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

/* A run asked to stop (SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGUSR2: Ctrl-C, `timeout`, a batch system's notice
 * before it kills, a stop passed on by mpirun) ends
 * within about a second (the stretch of steps under way, capped at about a second, then one step) as if its scene
 * ended there: the last frame, series row and checkpoint at that step, the output file completed, and exit status
 * 128 + the signal - for SIGINT by dying of it once all is written, so that a shell script or make running dem stops
 * too. A signal that comes while the last stretch, the output's completion or the report is under way finds the run
 * done: exit status 0. Further signals change nothing (`timeout` signals its child and then its process group,
 * launchers forward a terminal's Ctrl-C: the same request twice); Ctrl-\ (SIGQUIT) or SIGKILL kills at once. A
 * kill that cannot be caught (SIGKILL, a power cut) loses the output file, whose HDF5 metadata is then incomplete:
 * only the last checkpoint survives - which is why a run longer than a sitting is better run in parts (--stop-after,
 * then --restart; tools/plot_tablet.py joins the parts). SIGPIPE is ignored while a run goes (a
 * progress line to a pipe whose reader died - `| tee` after a hang-up - would kill it before its output is done). */
static _Atomic int run_signal; /* set by the waiter thread or a handler, read by the steps (lock-free: signal-safe) */
static void run_on_signal(int sig)
{
    if (!run_signal)
        run_signal = sig;
}
/* SIGUSR1 and SIGUSR2 too: Open MPI's mpirun (4.1) passes a SIGUSR2 on to every rank at once ("Forwarding signal 12
 * to job"), where a SIGTERM to mpirun reaches the ranks only after odls_base_sigkill_timeout (1 s) and is followed
 * by SIGKILL as long again later - too short for rank 0 to write the output and checkpoint of a large run
 * (docs/design.md "Runs over MPI"); SIGUSR1, which batch systems send as a notice, it does not pass on */
static const int run_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGUSR2, SIGPIPE};
#define RUN_NSIG (sizeof run_signals / sizeof run_signals[0])
static struct sigaction run_signal_old[RUN_NSIG];
/* The stop signals are taken by one thread, in sigwait, and blocked in every other: the main thread blocks them
 * before the device starts, so the OpenCL runtime's threads inherit the mask. A handler alone is not enough: PoCL
 * compiles a kernel in-process with LLVM at its first launch, and libLLVM installs its own SIGINT and SIGTERM
 * handlers then (an LD_PRELOAD trace of sigaction shows the calls from libLLVM-15.so.1); a Ctrl-C that came while it
 * compiled killed the run at once, its output left as .part and no checkpoint (seen in CI; reproduced with an empty
 * PoCL cache, and tests/test_tablet.c checks the masks). A signal blocked in every thread but the waiter goes to
 * sigwait whoever installed a handler. run_on_signal stays installed so that the disposition is never the default.
 * A stop signal the caller ignores (nohup's SIGHUP) is blocked too - LLVM installs its handler over SIG_IGN as well -
 * and the waiter drops it (run_signal_ignored). */
static sigset_t run_wait_set, run_mask_old, run_signal_ignored;
static pthread_t run_waiter;
static int run_waiting;
static void *run_signal_wait(void *arg)
{
    (void)arg;
    for (;;) { /* sigwait is a cancellation point: run_catch_signals(0) ends this loop */
        int sig;
        if (!sigwait(&run_wait_set, &sig) && !sigismember(&run_signal_ignored, sig))
            run_on_signal(sig);
    }
    return NULL;
}
static void run_catch_signals(int on)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_flags = SA_RESTART; /* reads and writes of ours, HDF5's or the OpenCL runtime's do not fail with EINTR */
    sigemptyset(&sa.sa_mask);
    if (!on) {
        if (run_waiting) {
            pthread_cancel(run_waiter);
            pthread_join(run_waiter, NULL);
            run_waiting = 0;
            /* what came after the waiter ended: the run is done, as for a signal during its report */
            struct timespec zero = {0, 0};
            while (sigtimedwait(&run_wait_set, NULL, &zero) > 0)
                ;
        }
        for (size_t k = 0; k < RUN_NSIG; k++) /* as the caller had them */
            sigaction(run_signals[k], &run_signal_old[k], NULL);
        pthread_sigmask(SIG_SETMASK, &run_mask_old, NULL);
        return;
    }
    sigemptyset(&run_wait_set);
    sigemptyset(&run_signal_ignored);
    for (size_t k = 0; k < RUN_NSIG; k++) {
        sigaction(run_signals[k], NULL, &run_signal_old[k]);
        if (run_signals[k] != SIGPIPE)
            sigaddset(&run_wait_set, run_signals[k]);
        if (run_signal_old[k].sa_handler == SIG_IGN) { /* a signal the caller ignores (nohup's SIGHUP) stays ignored */
            sigaddset(&run_signal_ignored, run_signals[k]);
            continue;
        }
        sa.sa_handler = run_signals[k] == SIGPIPE ? SIG_IGN : run_on_signal;
        sigaction(run_signals[k], &sa, NULL);
    }
    pthread_sigmask(SIG_BLOCK, &run_wait_set, &run_mask_old);
    run_waiting = pthread_create(&run_waiter, NULL, run_signal_wait, NULL) == 0;
    if (!run_waiting) /* no thread to take them: the handler takes them, as before */
        pthread_sigmask(SIG_SETMASK, &run_mask_old, NULL);
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
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

/* A rank other than 0 of a run over MPI ranks (run_scene_ranks) is quiet: its first message is held, and said
 * only where that rank alone failed (run_scene_ranks). */
static int run_quiet;
static char run_held[8192];
static int fail_with(int code, const char *msg)
{
    if (!run_quiet)
        fprintf(stderr, "dem: %s\n", msg);
    else if (!run_held[0])
        snprintf(run_held, sizeof run_held, "%s", msg);
    return code;
}

/* Both name the same existing file (a link or another spelling included). */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* path with its folder resolved (links, "..", "./"), so that two spellings of a file not yet there compare equal;
 * path itself when its folder cannot be resolved */
static void resolved(const char *path, char *buf, size_t len)
{
    char dir[RUN_PATH_LEN + 16], base[RUN_PATH_LEN + 16], *real;
    snprintf(dir, sizeof dir, "%s", path);
    snprintf(base, sizeof base, "%s", path);
    if ((real = realpath(dirname(dir), NULL)))
        snprintf(buf, len, "%s/%s", real, basename(base));
    else
        snprintf(buf, len, "%s", path);
    free(real);
}

/* Can s stand in XML text (the XDMF sidecar names the HDF5 file)? Valid UTF-8 (no overlong forms or surrogates) and
 * no control character: XML 1.0 has no way to write those. */
static int xml_text_ok(const char *s)
{
    const unsigned char *u = (const unsigned char *)s;
    while (*u) {
        int n = *u < 0x80 ? 0 : (*u & 0xe0) == 0xc0 ? 1 : (*u & 0xf0) == 0xe0 ? 2 : (*u & 0xf8) == 0xf0 ? 3 : -1;
        if (n < 0 || (n == 0 && (*u < 0x20 || *u == 0x7f)) || (n == 1 && *u < 0xc2) ||
            (n == 2 && *u == 0xe0 && u[1] < 0xa0) || (n == 2 && *u == 0xed && u[1] >= 0xa0) ||
            (n == 3 && ((*u == 0xf0 && u[1] < 0x90) || (*u == 0xf4 && u[1] >= 0x90) || *u > 0xf4)))
            return 0;
        for (int k = 1; k <= n; k++)
            if ((u[k] & 0xc0) != 0x80)
                return 0;
        u += n + 1;
    }
    return 1;
}

void run_output_files(const char *outp, const char *ckp, char outs[6][RUN_OUT_LEN])
{
    snprintf(outs[0], RUN_OUT_LEN, "%s", outp);
    snprintf(outs[1], RUN_OUT_LEN, "%s.part", outp);
    char xmf[RUN_OUT_LEN];
    output_xmf_path(outp, xmf, sizeof xmf);
    snprintf(outs[2], RUN_OUT_LEN, "%s", xmf);
    snprintf(outs[3], RUN_OUT_LEN, "%s.part", xmf);
    snprintf(outs[4], RUN_OUT_LEN, "%s", ckp);
    snprintf(outs[5], RUN_OUT_LEN, "%s" CHECKPOINT_TMP_SUFFIX, ckp);
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
    const char *base = strrchr(outp, '/') ? strrchr(outp, '/') + 1 : outp;
    if (!xml_text_ok(base)) {
        char shown[CLI_SHOW_LEN];
        snprintf(err, errlen, "%s: the output's name has a control character or is not UTF-8; the XDMF sidecar (XML) "
                              "names it and cannot hold that: choose another -o", cli_show(outp, shown, 200));
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
    char outs[6][RUN_OUT_LEN];
    run_output_files(outp, ckp, outs);
    const char *in[82];
    const char *what[82];
    char csv[64][4400], mesh[16][4400];
    int nin = 0;
    in[nin] = sc->path, what[nin++] = "the scene";
    if (o->restart)
        in[nin] = o->restart, what[nin++] = "the checkpoint this run restarts from";
    for (unsigned k = 0; k < sc->f->particles_count && k < 64; k++)
        if (sc->f->particles[k].csv) {
            scene_file_path(sc, sc->f->particles[k].csv, csv[k], sizeof csv[k]); /* an absolute one too */
            in[nin] = csv[k], what[nin++] = "a CSV file the scene reads";
        }
    for (unsigned k = 0; k < sc->f->membranes_count && k < 16; k++)
        if (sc->f->membranes[k].mesh.path) {
            scene_file_path(sc, sc->f->membranes[k].mesh.path, mesh[k], sizeof mesh[k]);
            in[nin] = mesh[k], what[nin++] = "a mesh file the scene reads";
        }
    static const char *const role[6] = {"the output", "the output's .part", "the XDMF sidecar",
                                        "the XDMF sidecar's .part", "the checkpoint", "the checkpoint's .tmp"};
    char real[6][RUN_OUT_LEN + 16];
    for (int q = 0; q < 6; q++)
        resolved(outs[q], real[q], sizeof real[q]);
    for (int q = 0; q < 6; q++) {
        struct stat st;
        char shown[CLI_SHOW_LEN], shown2[CLI_SHOW_LEN];
        cli_show(outs[q], shown, sizeof shown);
        /* one file for two of the run's outputs (--checkpoint naming OUT.h5, OUT.xmf or OUT.h5.part): the later one
         * would replace the earlier, and the run end with one of them lost */
        for (int r = 0; r < q; r++)
            if (!strcmp(real[q], real[r]) || same_file(outs[q], outs[r])) {
                snprintf(err, errlen, "%s: the run would write %s and %s to this one file; choose another %s", shown,
                         role[r], role[q], q >= 4 && r < 4 ? "--checkpoint" : "-o");
                return EXIT_USAGE;
            }
        if (stat(outs[q], &st) == 0 && S_ISDIR(st.st_mode)) { /* cannot be written as a file: exit 74 */
            snprintf(err, errlen, "%s: cannot write it: is a directory; %s names the file to write (e.g. %s/run.h5)",
                     shown, q >= 4 ? "--checkpoint" : "-o", shown);
            return EXIT_IO;
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

void run_contact_advice(dem_sim *s, const scene *sc, int info, FILE *out)
{
    dem_contact_advice a;
    if (dem_contact_advice_get(s, &a))
        return;
    char which[1200] = "";
    if (a.wall >= 0 && a.wall_time <= a.pair_time) {
        char name[1100];
        scene_wall_label(sc, a.wall, name, sizeof name);
        snprintf(which, sizeof which, "particle on wall %d '%.1000s'", a.wall, name);
    } else {
        snprintf(which, sizeof which, "two smallest like particles");
    }
    if (!isfinite(a.contact_time)) {
        if (info)
            fprintf(out, "contacts       nothing moves in the set-up (no speed, gravity or wall motion): no contact time"
                         "\n");
        return;
    }
    if (info) {
        fprintf(out, "approach       fastest %.3g m/s between particles, %.3g m/s onto walls (initial speeds, and the "
                     "wall stages that reach the particles as placed; a fall under gravity adds sqrt(2 g h))\n",
                a.pair_speed, a.wall_speed);
        fprintf(out, "contact time   %.4g s (%s, Hertz closed form): %.1f steps of dt (at least %d wanted)\n",
                a.contact_time, which, a.steps, DEM_MIN_STEPS_PER_CONTACT);
    }
    if (a.steps < DEM_MIN_STEPS_PER_CONTACT)
        fprintf(stderr, "dem: warning: %s: the shortest contact (%s, %.3g s at %.3g m/s) spans %.1f steps of dt; below %d "
                        "a collision is resolved badly (a restitution of 0.7 comes out 0.5 %% off at 20 steps, 1 %% at 10, "
                        "6 %% at 5; one of 0.5 1.4 %% at 16): dt <= %.3g s would give %d%s\n",
                sc->path, which, a.contact_time, a.wall_time <= a.pair_time ? a.wall_speed : a.pair_speed, a.steps,
                DEM_MIN_STEPS_PER_CONTACT, a.contact_time / DEM_MIN_STEPS_PER_CONTACT, DEM_MIN_STEPS_PER_CONTACT,
                /* a wall's stage speed: a press, where no rebound is resolved (make run's piston at 2 cm/s) */
                a.wall >= 0 && a.wall_time <= a.pair_time
                    ? ". Expected where the wall presses a packing slowly instead of striking particles (a press, "
                      "such as make run's piston at 2 cm/s): there is no rebound to resolve; it matters for impacts"
                    : "");
}

/* Lagged MC-strain (docs/multicontact.md "When lagged MC-strain rings"). The lagged scheme
 * evaluates each contact force from the displacements the particle's other contacts induced with their forces of the
 * previous step: one Jacobi iteration per step. A force change df_k comes back at contact c one step later as
 *   df_c = (df/dd)_c d_k->c = 2 E* a_c K g_kc df_k / d_kc,   K = gamma (1 + nu) / (2 pi E)   (common/mc_strain.h),
 * and where the sum of these gains over the contacts that feed c (the other contacts of both particles) exceeds 1, the
 * lag amplifies every disturbance step by step: the forces ring, and only damping holds them. For like spheres
 * (E* = E / (2 (1 - nu^2)), a = sqrt(r delta / 2)) with the largest factor, opposite contacts (g = 3 - 2 nu,
 * d_kc = 2 r), and z contacts per sphere, the gain is
 *   G = 2 (z - 1) gamma (3 - 2 nu) / (4 pi (1 - nu)) sqrt(delta / (2 r)),
 * which reaches 1 at delta_1 / r = 2 (4 pi (1 - nu) / (2 (z - 1) gamma (3 - 2 nu)))^2, taken with z = 6 (a dense
 * packing). The criterion: lagged MC-strain rings once the contacts' mean overlap passes delta_1. Measured
 * (tests/test_stability.c, test_mc_lag and test_compaction_09; the mean over touching pairs of overlap / smaller
 * radius): the glass die (gamma 4.5, nu 0.24: delta_1 1.42 %) reaches a mean of 2.4 % and rings - the kinetic energy
 * 26x the classical run's as the piston turns - and is smooth iterated (1.05x); the 514 hydrogels at 13.4 % strain
 * (gamma 1.12, nu 0.5: delta_1 15.7 %) reach 7 % and do not ring (0.8x); a compact of 300 spheres at relative
 * density 0.9 (gamma 1.12, nu 0.3: delta_1 21.4 %) reaches 22 % and rings (kinetic energy 28x at 0.9, a pair overlap
 * passing the smaller radius). dem check cannot know the mean overlap a scene will reach, so it warns when delta_1 is below
 * MC_LAG_WARN_OVERLAP of a radius, the mean a compaction to relative density 0.9 reaches; the real network's gain
 * differs (its geometric factors vary and partly cancel): a rule of thumb that separates the runs we measured. */
#define MC_LAG_WARN_OVERLAP 0.25 /* (run_mc_lag_overlap is in run_overlap.c, which the checkpoint fuzzer links alone) */

void run_mc_lag_advice(dem_sim *s, const scene *sc, const scene_run *run, int info, FILE *out)
{
    if (!(run->effects & DEM_EFFECT_MC_STRAIN))
        return;
    for (unsigned q = 0; q < sc->f->materials_count; q++) {
        const scene_material *m = &sc->f->materials[q];
        int used = 0;
        for (int i = 0; i < dem_count(s) && !used; i++)
            used = dem_particle_material(s, i) == (int)q;
        double d1 = run_mc_lag_overlap(m->gamma, m->poisson);
        if (!used || !isfinite(d1))
            continue;
        if (info)
            fprintf(out, "MC-strain      %s; material '%s' (gamma %g, nu %g): the lagged scheme's loop gain reaches 1 "
                         "at a mean overlap of %.3g %% of a radius (%d contacts per sphere)\n",
                    run->mc_cap > 0 ? "iterated" : "lagged", m->name, m->gamma, m->poisson, 100 * d1,
                    MC_LAG_CONTACTS);
        if (run->mc_cap == 0 && d1 < MC_LAG_WARN_OVERLAP)
            fprintf(stderr, "dem: warning: %s: lagged MC-strain on material '%s' (gamma %g, nu %g) rings once the "
                            "contacts' mean overlap passes %.3g %% of a radius (its loop gain passes 1 there): the "
                            "kinetic energy rises tens of times above the classical run's and overlaps jump "
                            "(docs/multicontact.md, \"When lagged MC-strain rings\"); if the scene compresses that "
                            "far, iterate it (--model mc_strain_iterated, or mc_iterations in the scene)\n",
                    sc->path, m->name, m->gamma, m->poisson, 100 * d1);
    }
}

/* The particles' order in memory (dem_order_scatter): with info, one line for dem check; a note when the order is
 * scattered in a run large enough for it to matter (from about 1e4 particles: the bed of make bench ran 1.5x faster
 * sorted at 9 468 spheres, 2.3x at 1e5 in make bench and 1.8-2x in make bench-peer's whole runs; below, the arrays
 * stay in cache). */
void run_order_advice(dem_sim *s, const scene *sc, int info, FILE *out)
{
    double q = dem_order_scatter(s);
    int scattered = q > DEM_ORDER_SCATTERED && dem_count(s) >= 5000;
    if (info)
        fprintf(out, "order          consecutive particles a median %.3g radius sums apart (%s)\n", q,
                scattered ? "scattered: particle_order: spatial (the default) would sort them at load"
                          : "close enough, or too few particles for the order to matter");
    if (scattered && !info)
        fprintf(stderr, "dem: note: %s: the particles are in a scattered order (consecutive ones a median %.3g radius sums "
                        "apart, as a random packing or another code's file): particle_order: spatial (the default, not input) "
                        "sorts them at load "
                        "(a poured bed of 1e5 spheres ran 1.8x faster sorted: make bench-peer; ids then change, /particles/input_index "
                        "maps back)\n",
                sc->path, q);
}

void run_rolling_advice(const scene *sc, unsigned effects)
{
    if (!(effects & DEM_EFFECT_ROLLING_SPRING))
        return;
    const scene_file *f = sc->f;
    double worst = 0;
    for (unsigned a = 0; a < f->materials_count; a++) /* the mean rule's pairs */
        for (unsigned b = a; b < f->materials_count; b++)
            worst = fmax(worst, 0.5 * (f->materials[a].rolling_friction + f->materials[b].rolling_friction));
    for (unsigned k = 0; k < f->material_pairs_count; k++) { /* and the pairs given their own */
        char p[64];
        snprintf(p, sizeof p, "material_pairs[%u].rolling_friction", k);
        if (scene_has(sc->loc, p))
            worst = fmax(worst, f->material_pairs[k].rolling_friction);
    }
    if (worst >= 0.88)
        fprintf(stderr, "dem: warning: %s: a rolling coefficient of %.3g with rolling_spring: the spring's own mode is "
                        "about %.2g times the tangential one the time step is sized for, past it from 0.88 "
                        "(docs/design.md \"Rolling resistance\"): a smaller dt_rayleigh keeps it stable\n",
                sc->path, worst, 1.14 * worst);
}

/* Position resolution (dem_position_resolution): with info, one line for dem check; a warning when the run's
 * precision resolves positions more coarsely than DEM_RESOLUTION_WARN of the smallest radius - an overlap of 1e-3
 * of a radius (stiff grains) then spans fewer than 10 steps of the grid (fp32 far from the origin). */
void run_precision_advice(dem_sim *s, const scene *sc, dem_precision p, int info, FILE *out)
{
    double far = 0, res = dem_position_resolution(s, p, &far), rmin = INFINITY;
    for (int i = 0; i < dem_count(s); i++)
        rmin = fmin(rmin, dem_particle_radius(s, i));
    if (!(rmin < INFINITY) || !(rmin > 0))
        return;
    const char *pn = p == DEM_FP32 ? "fp32" : "fp64";
    if (info)
        fprintf(out, "resolution     %s resolves positions to %.3g m out to %.3g m from the origin: %.2g of the smallest "
                     "radius\n", pn, res, far, res / rmin);
    if (res > DEM_RESOLUTION_WARN * rmin)
        fprintf(stderr, "dem: warning: %s: %s resolves positions only to %.3g m this far from the origin (%.3g m): %.2g "
                        "of the smallest radius, so an overlap of 1e-3 of a radius spans %.1f steps of that grid; move "
                        "the scene near the origin or run in fp64\n",
                sc->path, pn, res, far, res / rmin, 1e-3 * rmin / res);
}

/* A membrane's springs and hinges recommend a step of their own (dem_time_scales: 50 steps per spring or hinge period,
 * half the hinges' damping time), which can be below the 0.2 Rayleigh times that dt_rayleigh: 0.2 gives: a closed
 * membrane sphere's run took 1.03e-6 s where its hinge damping recommends 6.8e-7 s, and nothing said so. Stable up to
 * the bound, but a spring's period is then resolved by fewer than 50 steps (its frequency 0.07 % off at 50, 1.6 % at
 * 10) or the hinges' damping removes more than half of a fold's speed in one step. A warning (the grains' is the
 * contact time's, run_contact_advice), for dt given either way. */
void run_dt_advice(const scene *sc, const scene_run *run)
{
    const dem_time_scales *ts = &run->ts;
    if (!(ts->recommended_dt < 0.2 * ts->rayleigh_time) || !(run->dt > ts->recommended_dt * (1 + 1e-9)))
        return; /* the grains' recommendation, or met */
    char why[200];
    if (ts->recommended_dt == 0.5 * ts->hinge_damping_time)
        snprintf(why, sizeof why, "the membrane hinges' damping recommends (half their damping time %.4g s: kdiss)",
                 ts->hinge_damping_time);
    else if (ts->recommended_dt == ts->spring_period / 50)
        snprintf(why, sizeof why, "the membrane's edge springs recommend (50 steps per shortest period, %.4g s)",
                 ts->spring_period);
    else
        snprintf(why, sizeof why, "the membrane hinges recommend (50 steps per shortest fold period, %.4g s)",
                 ts->hinge_period);
    int fr = scene_has(sc->loc, "time.dt_rayleigh");
    fprintf(stderr, "dem: warning: %s: %s: the time step %.4g s is above the %.4g s that %s, below the stability bound "
                    "%.4g s: stable, but the membrane's motion is resolved coarsely; %s <= %.3g%s would meet it\n",
            sc->path, fr ? "time.dt_rayleigh" : "time.dt", run->dt, ts->recommended_dt, why, ts->max_dt,
            fr ? "dt_rayleigh" : "dt", fr ? ts->recommended_dt / ts->rayleigh_time : ts->recommended_dt,
            fr ? "" : " s");
}

/* Steps one call of dem_step_sampled takes at most, and the samples it holds at most. */
#define RUN_STRETCH 65536
#define RUN_SAMPLE_CHUNK 1024

/* The step of the series row that step t leads to: the next multiple of series_every, or the run's end. */
static long row_step(const scene_run *run, long t, long end)
{
    long at = (t + run->series_every - 1) / run->series_every * run->series_every;
    return at < end ? at : end;
}

/* The first step of that row's window (series_average N: the N steps that end at it; none before this run's first,
 * and none of the row before it: the last row, at the run's end, may come sooner than series_every after it) */
static long row_window(const scene_run *run, long t, long end, long step0)
{
    long at = row_step(run, t, end), prev = (at - 1) / run->series_every * run->series_every;
    long from = at - (run->series_average > 1 ? run->series_average : 1) + 1;
    from = from > prev + 1 ? from : prev + 1;
    return from > step0 + 1 ? from : step0 + 1;
}

/* A run's state across its phases (run_scene): what was loaded, what was built, where it writes. */
typedef struct {
    const run_opts *o;
    checkpoint ck;
    int have_ck;
    scene *sc;
    scene_run run;
    dem_sim *s;
    output *out;
    char outp[RUN_PATH_LEN], ckp[RUN_PATH_LEN];
    int show;     /* progress lines */
    int stopped;  /* the signal that ended the run before its scene's end (run_on_signal), or 0 */
    double t0;    /* wall clock at the first step */
    long step0;   /* the step it started from */
    char err[8192];
    dem_sample rows[RUN_SAMPLE_CHUNK]; /* the samples of one stretch */
    unsigned char want[RUN_STRETCH];   /* which of its steps are sampled */
    overlap_watch ov;                  /* the overlaps at the frames (not with membranes: run_overlap.c) */
    dem_mc_stats mc0;                  /* the MC-strain counts at the run's first step (a restart's earlier ones) */
    double *x0;                        /* the positions at the run's first step, with a closed membrane (else NULL) */
    int *tri;                          /* the triangles' particles then (dem_triangles_get) */
    long stage_seen;                   /* the stage ends logged so far (stage_ends) */
    run_ranks *R;                      /* a run split over MPI ranks (s: the whole run, never stepped), or NULL */
    const char *model;                 /* the model asked for (the command line's or the checkpoint's), or NULL */
} run_ctx;

/* the step the run is at: the parts' when it is split over ranks */
static long run_step(const run_ctx *c) { return c->R ? c->R->step_index(c->R) : dem_step_index(c->s); }

/* A membrane is closed when each of its edges (springs) borders two triangles: 2 edges = 3 triangles */
static int membrane_closed(const dem_membrane_info *m)
{
    return m->ntriangles > 0 && 2 * m->nsprings == 3 * m->ntriangles;
}

/* The winding number of the closed surface of triangles tri (particle ids into x) about point p: the solid angles
 * the triangles subtend (Van Oosterom and Strackee) over 4 pi; +-1 inside (the sign follows the orientation), 0
 * outside. */
static double winding_number(const double *x, const int *tri, int ntri, const double p[3])
{
    double sum = 0;
    for (int t = 0; t < ntri; t++) {
        double v[3][3], l[3];
        for (int k = 0; k < 3; k++) {
            for (int d = 0; d < 3; d++)
                v[k][d] = x[3 * (size_t)tri[3 * t + k] + d] - p[d];
            l[k] = sqrt(v[k][0] * v[k][0] + v[k][1] * v[k][1] + v[k][2] * v[k][2]);
        }
        double cr[3] = {v[1][1] * v[2][2] - v[1][2] * v[2][1], v[1][2] * v[2][0] - v[1][0] * v[2][2],
                        v[1][0] * v[2][1] - v[1][1] * v[2][0]};
        double det = v[0][0] * cr[0] + v[0][1] * cr[1] + v[0][2] * cr[2];
#define DOT(a, b) (v[a][0] * v[b][0] + v[a][1] * v[b][1] + v[a][2] * v[b][2])
        double den = l[0] * l[1] * l[2] + DOT(0, 1) * l[2] + DOT(0, 2) * l[1] + DOT(1, 2) * l[0];
#undef DOT
        sum += 2 * atan2(det, den);
    }
    return sum / (4 * M_PI);
}

/* With a closed membrane: the positions and triangles at the run's first step, for membrane_left */
static void membrane_watch(run_ctx *c)
{
    int closed = 0, n = dem_count(c->s), nt = dem_triangle_count(c->s);
    for (unsigned k = 0; k < c->sc->f->membranes_count && k < 16; k++)
        closed |= membrane_closed(&c->run.membrane[k]);
    if (!closed || !(c->x0 = malloc(sizeof(double) * 3 * (size_t)n)) ||
        !(c->tri = malloc(sizeof(int) * 3 * (size_t)nt)) || dem_get_field(c->s, DEM_FIELD_X, c->x0)) {
        free(c->x0), free(c->tri);
        c->x0 = NULL, c->tri = NULL;
        return;
    }
    dem_triangles_get(c->s, c->tri);
}

/* A particle that left the domain or went non-finite (dem_error_particle): when it is not a membrane's vertex, was
 * inside a closed membrane at the run's first step and its centre is outside it now, say that it left through that
 * membrane (the bare error says only "outside the binning domain"). On the host, at the failure only. */
static void membrane_left(const run_ctx *c)
{
    int id = dem_error_particle(c->s), n = dem_count(c->s);
    if (!c->x0 || id < 0 || id >= n)
        return;
    double *x = malloc(sizeof(double) * 3 * (size_t)n);
    if (!x || dem_get_field(c->s, DEM_FIELD_X, x)) {
        free(x);
        return;
    }
    const double *p = x + 3 * (size_t)id, *p0 = c->x0 + 3 * (size_t)id;
    for (unsigned k = 0; k < c->sc->f->membranes_count && k < 16 && isfinite(p[0] + p[1] + p[2]); k++) {
        const dem_membrane_info *m = &c->run.membrane[k];
        if (!membrane_closed(m) || (id >= m->first_particle && id < m->first_particle + m->nvertices))
            continue;
        const int *tri = c->tri + 3 * (size_t)m->first_triangle;
        double w0 = winding_number(c->x0, tri, m->ntriangles, p0), w = winding_number(x, tri, m->ntriangles, p);
        if (fabs(w0) > 0.5 && fabs(w) < 0.5)
            fprintf(stderr, "dem: particle %d left through the membrane '%s' (membranes[%u]): inside it when the run "
                            "began at step %ld (%.6g, %.6g, %.6g) m, its centre is outside it now (the winding number "
                            "of the membrane's triangles about it %.0f then, %.0f now): it passed between or through "
                            "them - a time step too coarse for the contact, a pressure that pushed the membrane apart, "
                            "or a vertex_radius (MSS_particle) that leaves gaps between the vertices\n",
                    id, c->sc->f->membranes[k].name ? c->sc->f->membranes[k].name : "", k, c->step0, p0[0], p0[1],
                    p0[2], fabs(w0), fabs(w));
    }
    free(x);
}

/* The run that steps: c->s, or over ranks this rank's part, whose records (MC-strain's iterations, stage ends,
 * servo stages) are every rank's and one process's; the whole run where no part is held (a split that failed) */
static dem_sim *stepped(const run_ctx *c)
{
    dem_sim *p = c->R ? c->R->stepped(c->R) : NULL;
    return p ? p : c->s;
}

/* What preceded a run's failure, said after its error (a hydrogel run can hit the MC-strain cap in 1777 steps before
 * it diverges, and the error alone would not say so): the steps of this run that hit the iteration cap, from the
 * first to the failure. */
static void failure_preceded(const run_ctx *c)
{
    dem_mc_stats mc;
    dem_mc_stats_get(stepped(c), &mc);
    long capped = mc.unconverged - c->mc0.unconverged, at = dem_step_index(stepped(c));
    if (!(c->run.effects & DEM_EFFECT_MC_STRAIN) || c->run.mc_cap <= 0 || capped <= 0 || mc.first_capped < 0)
        return;
    long to = mc.last_capped > at ? mc.last_capped : at;
    fprintf(stderr, "dem: before it stopped, iterated MC-strain hit its cap of %d iterations (mc_iterations) in %ld of "
                    "the %ld steps from step %ld (t = %.9g s, the first that did) to step %ld, the last at step %ld: "
                    "their forces had not settled to mc_tolerance %g (the series mc_capped in %s.part counts them); "
                    "a higher cap or a smaller time step may carry the run further\n",
            c->run.mc_cap, capped, to - mc.first_capped + 1, mc.first_capped, (double)mc.first_capped * dem_dt(c->s),
            to, mc.last_capped, c->run.mc_tol, c->outp);
}

/* 1. The scene, from its file or from the checkpoint restarted from, built into a simulation (not started). */
static int phase_load(run_ctx *c)
{
    const run_opts *o = c->o;
    if (o->restart) {
        /* over ranks every rank reads what the checks below read (the head), then its own part of the state when
         * the parts are made (run_ranks.start): no rank reads the whole */
        int head = c->R != NULL;
        if ((head ? checkpoint_read_head : checkpoint_read)(o->restart, &c->ck, c->err, sizeof c->err)) /* 66: cannot
                                                                                  be opened; 65: damaged */
            return fail_with(strstr(c->err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT, c->err);
        c->have_ck = 1;
        /* `dem run SCENE --restart CK` continues CK under SCENE as it is now (a longer duration, a stage added or
         * lengthened), checked against the checkpoint in phase_configure; `dem run --restart CK` under the text the
         * checkpoint holds */
        c->sc = o->scene_path ? scene_load(o->scene_path, c->err, sizeof c->err)
                              : scene_load_text(c->ck.scene_path, c->ck.scene_text, strlen(c->ck.scene_text), c->err,
                                                sizeof c->err);
        /* the order the checkpoint's run was built in, whatever the default is now (a checkpoint without it is
         * older than the spatial default: its run was in the scene's order) */
        if (c->sc)
            c->sc->order_default = !strcmp(c->ck.order, "spatial") ? "spatial" : "input";
        /* a scene that orders its particles otherwise would give the checkpoint's state to other ids */
        if (c->sc && o->scene_path && strcmp(scene_particle_order(c->sc), c->sc->order_default)) {
            snprintf(c->err, sizeof c->err, "%s: particle_order: %s, but the run of %s was built in %s order; a "
                     "continuation keeps it (remove the key or set it to %s)", o->scene_path,
                     scene_particle_order(c->sc), o->restart, c->sc->order_default, c->sc->order_default);
            return fail_with(EXIT_BAD_INPUT, c->err);
        }
    } else {
        c->sc = scene_load(o->scene_path, c->err, sizeof c->err);
    }
    if (!c->sc)
        return fail_with(strstr(c->err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT, c->err);
    c->s = scene_build(c->sc, &c->run, c->err, sizeof c->err);
    if (!c->s) /* a file the scene names (a CSV) that cannot be opened: 66, like the scene itself */
        return fail_with(strstr(c->err, "cannot open") ? EXIT_NO_INPUT : EXIT_BAD_INPUT, c->err);
    return 0;
}

/* 2. The command line's choices (model, device, precision), the output paths, and the checkpoint against the
 * scene: everything refusable before the device is touched. */
static int phase_configure(run_ctx *c)
{
    const run_opts *o = c->o;
    scene_run *run = &c->run;
    const char *model = o->model ? o->model : c->have_ck && c->ck.model[0] ? c->ck.model : NULL;
    if (c->have_ck && o->model && strcmp(o->model, c->ck.model[0] ? c->ck.model : o->model)) {
        snprintf(c->err, sizeof c->err, "%s: the checkpoint was run with --model %s, not %s", o->restart, c->ck.model,
                 o->model);
        return fail_with(EXIT_USAGE, c->err);
    }
    c->model = model;
    if (model && scene_apply_model(c->sc, c->s, run, model, c->err, sizeof c->err))
        return fail_with(o->model ? EXIT_USAGE : EXIT_BAD_INPUT, c->err);
    if (o->device >= 0)
        run->cfg.device = o->device;
    if (o->backend >= 0)
        run->cfg.backend = (dem_backend_kind)o->backend;
    if (c->have_ck) /* a restart continues in the checkpoint's precision */
        run->cfg.precision = (dem_precision)c->ck.st.real_size;
    if (o->precision)
        run->cfg.precision = (dem_precision)o->precision;
    int pc = run_output_paths(c->sc, o, c->outp, c->ckp, c->err, sizeof c->err);
    if (pc)
        return fail_with(pc, c->err);
    if (!c->have_ck)
        return 0;
    /* continued under a scene file: the checkpoint's scene but for what a continuation may change (restart_scene.c) */
    if (o->scene_path && restart_scene_check(c->sc, &c->ck, o->restart, c->err, sizeof c->err))
        return fail_with(EXIT_BAD_INPUT, c->err);
    if (o->scene_path && o->progress != 0 && !run_quiet)
        fprintf(stderr, "dem: continuing %s at step %ld under %s as it is now (not the scene text the checkpoint "
                        "holds)\n", o->restart, c->ck.st.step, o->scene_path);
    /* a finished run's checkpoint has nothing left to run: refused, not a run of no steps that exits 0 and writes
     * neither output nor checkpoint */
    if (c->ck.st.step >= run->steps) {
        snprintf(c->err, sizeof c->err, "%s: the checkpoint is at step %ld, %s of the scene (%ld steps of %g s): "
                 "nothing is left to run (a restart continues a run stopped before its end, by --stop-after or a "
                 "signal; to go on, raise time.duration in a copy of the scene and run dem run COPY.yaml --restart %s)", o->restart, c->ck.st.step, c->ck.st.step > run->steps ? "past the end"
                 : "the end", run->steps, run->dt, o->restart);
        return fail_with(EXIT_BAD_INPUT, c->err);
    }
    if ((dem_effects(c->s) & DEM_EFFECT_ADHESION) && c->ck.st.has_law == 1 && c->ck.st.npairs + c->ck.st.nwalls > 0 &&
        strcmp(c->ck.law_state, CHECKPOINT_JKR_STATE)) {
        snprintf(c->err, sizeof c->err, "%s: /state: law_state: the checkpoint was written before 2026-12-06, when the "
                 "adhesive contacts' state was their largest overlap; this libdem keeps their largest contact radius "
                 "(common/laws/thornton_ning.h) and cannot continue it: run the scene again from its start",
                 o->restart);
        return fail_with(EXIT_BAD_INPUT, c->err);
    }
    if (c->ck.st.n != dem_count(c->s) || c->ck.st.real_size != (int)run->cfg.precision) {
        snprintf(c->err, sizeof c->err, "%s: the checkpoint has %d particles in %s; the scene gives %d in %s",
                 o->restart, c->ck.st.n, c->ck.st.real_size == 8 ? "fp64" : "fp32", dem_count(c->s),
                 run->cfg.precision == DEM_FP64 ? "fp64" : "fp32");
        return fail_with(EXIT_BAD_INPUT, c->err);
    }
    for (int i = 0; c->ck.radius && i < c->ck.st.n; i++) /* (over ranks: each rank's of its part, run_mpi.c) */
        if (c->ck.radius[i] != dem_particle_radius(c->s, i)) {
            snprintf(c->err, sizeof c->err, "%s: particle %d has radius %g m in the checkpoint and %g m in the scene "
                     "(did a CSV file change?)", o->restart, i, c->ck.radius[i], dem_particle_radius(c->s, i));
            return fail_with(EXIT_BAD_INPUT, c->err);
        }
    return 0;
}

/* The note while a device compiles the kernels: OpenCL builds the program from source when a run starts, which a
 * driver with a cache (PoCL's, in ~/.cache/pocl) does once per build of the kernels and device - 2.3 s for the
 * 514-hydrogel scene on the idle 2-core development VM with an empty cache, 15 s reported on a busy one - and later
 * runs find in its cache (0.13 s for the same start). The library cannot tell which
 * it will be, so a watcher thread says it once dem_start has taken longer than COMPILE_NOTE_S: a run that starts
 * at once prints nothing, a silent pause of 15 s gets a reason. */
#define COMPILE_NOTE_S 1.5
typedef struct {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int done;
    char device[600];
} compile_note;

static void *compile_note_wait(void *arg)
{
    compile_note *n = arg;
    struct timespec until;
    double after = COMPILE_NOTE_S;
    const char *e = getenv("DEM_TEST_COMPILE_NOTE_S"); /* tests/test_scene.c: 0 shows it on every start, cached or not */
    if (e && atof(e) >= 0)
        after = atof(e);
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += (time_t)after;
    until.tv_nsec += (long)((after - (double)(time_t)after) * 1e9);
    if (until.tv_nsec >= 1000000000L)
        until.tv_sec++, until.tv_nsec -= 1000000000L;
    pthread_mutex_lock(&n->mu);
    int rc = 0;
    while (!n->done && rc == 0)
        rc = pthread_cond_timedwait(&n->cv, &n->mu, &until);
    if (!n->done)
        fprintf(stderr, "dem: compiling the kernels for %s (once for this build and device: seconds, up to ~15 s on "
                        "a busy 2-core machine; later runs take them from the driver's cache)\n", n->device);
    pthread_mutex_unlock(&n->mu);
    return NULL;
}

/* dem_start, with the note above when it is slow and the run is not --quiet */
static int start_with_note(dem_sim *s, const scene_run *run, int note)
{
    compile_note n = {.done = 0};
    pthread_t th;
    int watching = 0;
    if (note && run->cfg.backend == DEM_BACKEND_OPENCL) {
        if (dem_device_name(run->cfg.device, n.device, sizeof n.device))
            snprintf(n.device, sizeof n.device, "device %d", run->cfg.device);
        pthread_mutex_init(&n.mu, NULL);
        pthread_cond_init(&n.cv, NULL);
        /* the watcher takes no signal: a Ctrl-C is run_signal_wait's (run_catch_signals) */
        sigset_t all, old;
        sigfillset(&all);
        pthread_sigmask(SIG_BLOCK, &all, &old);
        watching = pthread_create(&th, NULL, compile_note_wait, &n) == 0;
        pthread_sigmask(SIG_SETMASK, &old, NULL);
    }
    int se = dem_start(s, &run->cfg);
    if (watching) {
        pthread_mutex_lock(&n.mu);
        n.done = 1;
        pthread_cond_signal(&n.cv);
        pthread_mutex_unlock(&n.mu);
        pthread_join(th, NULL);
    }
    if (note && run->cfg.backend == DEM_BACKEND_OPENCL) {
        pthread_mutex_destroy(&n.mu);
        pthread_cond_destroy(&n.cv);
    }
    return se;
}

/* 3. The device started, the checkpoint's state restored, the run announced. */
static int phase_start(run_ctx *c)
{
    const run_opts *o = c->o;
    const scene_run *run = &c->run;
    /* run->cfg.contacts: set by scene_build when frames carry contacts */
    int who = -1;
    if (c->R) { /* split over ranks: the parts, each cut from its rank's whole run, which no rank starts (the
                 * scene's set-up: its memory is its particles' description, not a run's buffers) */
        int e = c->R->start(c->R, c->s, c->have_ck ? &c->ck : NULL, o->restart, &run->cfg, c->sc->path, c->err,
                            sizeof c->err);
        if ((e = c->R->agree(c->R, e, &who))) {
            c->R->share(c->R, who, c->err, sizeof c->err);
            return fail_with(e == DEM_ERR_DEVICE ? EXIT_DEVICE : EXIT_BAD_INPUT, c->err);
        }
    } else {
        int se = start_with_note(c->s, run, o->progress != 0);
        if (se) {
            snprintf(c->err, sizeof c->err, "%s: %s", c->sc->path, dem_error(c->s));
            return fail_with(se == DEM_ERR_DEVICE ? EXIT_DEVICE : EXIT_BAD_INPUT, c->err);
        }
        if (c->have_ck && dem_state_set(c->s, &c->ck.st)) {
            snprintf(c->err, sizeof c->err, "%s: %s", o->restart, dem_error(c->s));
            return fail_with(EXIT_BAD_INPUT, c->err);
        }
    }
    if (c->have_ck) /* the checkpoint's state is in the run (over ranks: in the parts) */
        dem_state_free(&c->ck.st);
    c->show = run_quiet ? 0 : o->progress < 0 ? isatty(2) : o->progress;
    if (run_quiet)
        return 0;
    if (!c->show && o->progress == 0)
        return 0;
    fprintf(stderr, "dem: %s: %d particles, %d walls, dt %.4g s, %ld steps, %s\n", c->sc->path, dem_count(c->s),
            dem_wall_count(c->s), run->dt, run->steps, c->R ? "split over MPI ranks" : dem_describe(c->s));
    if (c->R) {
        char line[1024];
        c->R->describe(c->R, line, sizeof line);
        fprintf(stderr, "dem: %s\n", line);
    }
    run_contact_advice(c->s, c->sc, 0, stderr); /* a warning only, when dt is coarse for the fastest contact */
    run_dt_advice(c->sc, &c->run);              /* a warning only, when dt is coarse for a membrane */
    run_rolling_advice(c->sc, run->effects);    /* a warning only, a stiff rolling spring */
    run_mc_lag_advice(c->s, c->sc, &c->run, 0, stderr); /* a warning only, lagged MC-strain where it rings */
    run_order_advice(c->s, c->sc, 0, stderr);   /* a note only, when the order is scattered */
    run_precision_advice(c->s, c->sc, run->cfg.precision, 0, stderr); /* a warning only, far from the origin */
    if (run->effects & DEM_EFFECT_MC_STRESS) {
        char conv[128];
        dem_mc_stress_convention_string(run->mcs_conv, conv, sizeof conv);
        fprintf(stderr, "dem: MC-stress pressure convention: %s%s\n", conv,
                run->mcs_conv == DEM_MCS_DEFAULT ? " (the default: Eq. 11's reading)" : "");
    }
    if (scene_mass_scale(c->sc) != 1 && scene_keeps_acceleration(c->sc))
        fprintf(stderr, "dem: note: masses scaled x %g (time.mass_scale; gravity as given: weights %g times too heavy): "
                        "inertia and kinetic energies are the scaled system's\n", scene_mass_scale(c->sc),
                scene_mass_scale(c->sc));
    else if (scene_mass_scale(c->sc) != 1)
        fprintf(stderr, "dem: note: masses scaled x %g (time.mass_scale; gravity / %g): inertia and kinetic energies "
                        "are the scaled system's\n", scene_mass_scale(c->sc), scene_mass_scale(c->sc));
    if ((run->effects & DEM_EFFECT_MC_STRAIN) && c->sc->f->mc_contact_distance > 1)
        fprintf(stderr, "dem: MC-strain contact distance %g (r_i + r_j): gaps that the induced displacements close are "
                        "contacts\n", c->sc->f->mc_contact_distance);
    return 0;
}

/* A test hook "STEP ARG" from the environment variable name: STEP -1 when unset or malformed */
static void test_hook(const char *name, long *step, long *arg)
{
    const char *v = getenv(name);
    *step = -1;
    *arg = 0;
    if (v && sscanf(v, "%ld %ld", step, arg) != 2)
        *step = -1;
}

/* DEM_TEST_POISON's act: particle id's velocity becomes NAN in the run's own state */
static int poison_hook(dem_sim *s, long id)
{
    dem_state st;
    if (id < 0 || id >= dem_count(s) || dem_state_get(s, &st))
        return -1;
    void *v = dem_state_find(&st, "v")->data;
    for (int d = 0; d < 3; d++) {
        if (st.real_size == 8)
            ((double *)v)[3 * id + d] = NAN;
        else
            ((float *)v)[3 * id + d] = NAN;
    }
    int e = dem_state_set(s, &st);
    dem_state_free(&st);
    return e;
}

/* The scene's own words for stage st of wall k: "time.settle" (the settling pause, which every wall holds as its
 * first stage) or "motion[j]" (its index in the wall's motion list, repeats folded). */
static void stage_label(const scene *sc, int k, int st, char *buf, size_t len)
{
    int at = 0, settle = sc->f->time.settle > 0;
    for (unsigned i = 0; i < sc->f->walls_count; i++) {
        const scene_wall *w = &sc->f->walls[i];
        at += w->type && !strcmp(w->type, "box") ? 6 : 1;
        if (k >= at)
            continue;
        if (settle && st == 0)
            snprintf(buf, len, "time.settle");
        else if (w->motion_count)
            snprintf(buf, len, "motion[%u]", (unsigned)(st - settle) % w->motion_count);
        else
            snprintf(buf, len, "stage %d", st);
        return;
    }
    snprintf(buf, len, "stage %d", st);
}

/* Logs each motion stage that ended since the last look (dem_stage_ends, the library's record of what it decided):
 * "wall 'piston' stage 2 of 4 (motion[0]) ended at step S (t = ...): until_force 0.5 N reached (0.53 N)". Walls
 * whose only stage is the settling pause are not logged. */
static void stage_ends(run_ctx *c, int print)
{
    dem_sim *s = c->s, *log = stepped(c); /* over ranks: the part's log (the same on each) */
    long n = dem_stage_ends(log, 0, NULL);
    for (; c->stage_seen < n; c->stage_seen++) {
        dem_stage_end e;
        dem_stage_ends(log, c->stage_seen, &e);
        dem_wall w;
        if (!print || e.wall < 0 || dem_wall_get(s, e.wall, &w) || w.nstages <= (c->sc->f->time.settle > 0))
            continue;
        const dem_stage *g = &w.stages[e.stage];
        char name[1100], lab[64], why[200];
        scene_wall_label(c->sc, e.wall, name, sizeof name);
        stage_label(c->sc, e.wall, e.stage, lab, sizeof lab);
        if (e.why == DEM_STAGE_END_FORCE)
            snprintf(why, sizeof why, "until_force %g N reached (%.4g N)", g->until_force, e.value);
        else if (e.why == DEM_STAGE_END_DISTANCE)
            snprintf(why, sizeof why, "until_distance %g m reached (%.4g m)", g->until_distance, e.value);
        else if (e.why == DEM_STAGE_END_DENSITY)
            snprintf(why, sizeof why, "until_density %g reached (%.4g)", g->until_density, e.value);
        else if (g->until_force > 0 || g->until_distance > 0 || g->until_density > 0)
            snprintf(why, sizeof why, "its duration (%g s) ran out before its end condition held", g->duration);
        else
            snprintf(why, sizeof why, "its duration (%g s) ran out", g->duration);
        fprintf(stderr, "dem: wall '%s' stage %d of %d (%s) ended at step %ld (t = %.6g s): %s\n", name, e.stage + 1,
                w.nstages, lab, e.step, (double)e.step * dem_dt(s), why);
    }
}

/* 4. The steps, with frames, series, checkpoints and progress, to the end (or --stop-after); the output finished. */
static int phase_steps(run_ctx *c)
{
    const run_opts *o = c->o;
    const scene_run *run = &c->run;
    dem_sim *s = c->s;
    run_ranks *R = c->R;
    int sig0 = R ? (int)-R->agree_min(R, -(long)run_signal) : run_signal; /* over ranks: any rank's */
    if (sig0) { /* asked to stop while the run was being set up: nothing is written */
        c->stopped = sig0;
        return 0;
    }
    int writer = !R || R->rank == 0, who; /* a run over ranks: rank 0 writes */
    double box[6];
    /* the particles' box at the start, for the walls' drawn planes: the parts' (where a rank could not read its
     * positions, the set-up's: the drawn planes only, and a failing device stops the run at its first step) */
    int parts_box = R && !R->bounds(R, box);
    if (writer) /* (over ranks: the header from the whole run's set-up, the device from rank 0's part) */
        c->out = output_open(c->outp, c->sc, run, s, stepped(c), parts_box ? box : NULL, c->err, sizeof c->err);
    if (R && R->agree(R, writer && !c->out ? EXIT_IO : 0, &who))
        return fail_with(EXIT_IO, c->err);
    if (!R && !c->out)
        return fail_with(EXIT_IO, c->err);
    double last;
    c->t0 = last = now();
    long step0 = run_step(c), end = run->steps;
    c->step0 = step0;
    dem_mc_stats_get(stepped(c), &c->mc0);
    membrane_watch(c);
    c->stage_seen = dem_stage_ends(stepped(c), 0, NULL); /* a restart logs the ends from its first step */
    if (o->stop_after > 0 && step0 + o->stop_after < end)
        end = step0 + o->stop_after;
    int tty = isatty(2);
    series_row row, sum;
    int nsum = 0; /* samples in sum since its last row (a stop shortens the last window: it averages those taken) */
    memset(&sum, 0, sizeof sum);
    int nw = dem_wall_count(s);
    errno = 0;
    char why0[8192];
    int bad = R ? R->frame(R, writer ? c->out : NULL, why0, sizeof why0) : output_frame(c->out, s);
    if (bad == -2) {
        snprintf(c->err, sizeof c->err, "%s: run stopped at its first frame: %s", c->sc->path, why0);
        return fail_with(EXIT_RUN_FAILED, c->err);
    }
    if (R) { /* the parts' own sums merged (every rank); rank 0 writes the row */
        dem_sample smp;
        int se = R->sample(R, &smp, why0, sizeof why0); /* collective: whatever rank 0's frame gave */
        if (se) {
            snprintf(c->err, sizeof c->err, "%s: run stopped at its first frame: %s", c->sc->path, why0);
            return fail_with(EXIT_RUN_FAILED, c->err);
        }
        output_row_of(&smp, run, dem_wall_count(s), &row);
        bad = bad || (writer && output_series(c->out, &row));
        bad = R->agree(R, bad, &who); /* every rank, whatever rank 0's write gave: none may skip the collective */
    } else
        bad = bad || output_sample(s, run, &row) || output_series(c->out, &row);
    if (bad) {
        int e = errno;
        snprintf(c->err, sizeof c->err, "%s.part: cannot write the first frame to the output file: %s", c->outp,
                 h5_io_reason(e));
        return fail_with(EXIT_IO, c->err);
    }
    long ck_step = -1; /* step of the last checkpoint this run wrote */
    /* A test-only hook (tests/test_scene.c): DEM_TEST_POISON="STEP PARTICLE" makes that particle's velocity
     * not a number once STEP is reached, to show how a run that goes non-finite stops and what it keeps. */
    long poison_step, poison_id, signal_step, signal_no;
    test_hook("DEM_TEST_POISON", &poison_step, &poison_id);
    /* Another (tests/test_tablet.c): DEM_TEST_SIGNAL="STEP SIGNAL" raises that signal once STEP is reached, so a
     * test can stop a run at a step of its choosing through the real handler. */
    test_hook("DEM_TEST_SIGNAL", &signal_step, &signal_no);
    long prev_st = step0; /* the last stretch: its first step and when it began */
    double prev_t = 0;
    while (run_step(c) < end) {
        long st = run_step(c), next;
        if (st == signal_step) { /* to the process, as kill(1) sends it (raise() would go to this thread, which
                                  * blocks it), and taken by the waiter before this step goes on, so that the run
                                  * stops at the step the test names */
            kill(getpid(), (int)signal_no);
            for (int k = 0; k < 20000 && !run_signal; k++)
                nanosleep(&(struct timespec){0, 1000000L}, NULL);
        }
        int sig = R ? (int)-R->agree_min(R, -(long)run_signal) : run_signal; /* over ranks: any rank's */
        if (sig && st + 1 < end) { /* stop: one more step, which ends the run as the scene's last would */
            end = st + 1;
            c->stopped = sig;
        }
        next = end;
        if (st == poison_step && !R && poison_hook(s, poison_id))
            return fail_with(EXIT_RUN_FAILED, "DEM_TEST_POISON: cannot poison that particle");
        long hooks[2] = {poison_step, signal_step}; /* a stretch ends where a test hook acts */
        for (int k = 0; k < 2; k++)
            if (hooks[k] > st && hooks[k] < next)
                next = hooks[k];
        long evs[2] = {run->frame_every, run->checkpoint_every}; /* the series rows are sampled within a stretch */
        for (int k = 0; k < 2; k++)
            if (evs[k] > 0 && (st / evs[k] + 1) * evs[k] < next)
                next = (st / evs[k] + 1) * evs[k];
        { /* at most ~1 s between progress lines, and between looks at run_signal: a stretch as long as the last
             one's steps took a second (steps slow down as a powder is pressed); the first, 8 steps */
            double tn = now();
            long per_s = prev_t > 0 && tn > prev_t ? (long)((double)(st - prev_st) / (tn - prev_t)) : 7;
            /* over ranks, a quarter second: mpirun gives its ranks one second after it forwards a SIGTERM before it
             * kills them (Open MPI's odls_base_sigkill_timeout), and they must look, agree, step once more and
             * write in that time */
            long cap = st + (R ? per_s / 4 : per_s) + 1;
            prev_st = st;
            prev_t = tn;
            if (cap < next)
                next = cap;
            if (R) /* every rank's stretch the same: the shortest */
                next = R->agree_min(R, next);
        }
        /* The steps to sample: each series row's step, and with series_average N the N - 1 before it (its window).
         * dem_step_sampled samples them on the device without a synchronisation per row. */
        long nrows = 0;
        if (next - st > RUN_STRETCH)
            next = st + RUN_STRETCH;
        for (long t = st + 1; t <= next; t++) {
            c->want[t - st - 1] = t >= row_window(run, t, end, step0);
            if (c->want[t - st - 1] && ++nrows == RUN_SAMPLE_CHUNK)
                next = t;
        }
        char why[8192];
        if (R ? R->step(R, next - st, c->want, c->rows, why, sizeof why)
              : (dem_step_sampled(s, next - st, c->want, c->rows) ? (snprintf(why, sizeof why, "%s", dem_error(s)), 1)
                                                                   : 0)) {
            char cknote[4400];
            checkpoint_note(cknote, sizeof cknote, c->ckp, ck_step, o->restart);
            snprintf(c->err, sizeof c->err, "%s: run stopped at step %ld: %s (output so far: %s.part; %s)",
                     c->sc->path, run_step(c), why, c->outp, cknote);
            fail_with(EXIT_RUN_FAILED, c->err);
            membrane_left(c);
            failure_preceded(c);
            return EXIT_RUN_FAILED;
        }
        st = run_step(c);
        stage_ends(c, o->progress != 0 && !run_quiet);
        int io = 0, ck_due = (run->checkpoint_every > 0 && st % run->checkpoint_every == 0) || st == end;
        errno = 0;
        if (st % run->frame_every == 0 || st == end) {
            int fr = R ? R->frame(R, writer ? c->out : NULL, why, sizeof why) : output_frame(c->out, s);
            if (fr == -2) {
                snprintf(c->err, sizeof c->err, "%s: run stopped at step %ld: %s (output so far: %s.part)",
                         c->sc->path, st, why, c->outp);
                return fail_with(EXIT_RUN_FAILED, c->err);
            }
            io |= fr != 0;
            if (!c->sc->f->membranes_count && R) /* over ranks: the parts' own pairs, merged into rank 0's watch */
                R->overlaps(R, &c->ov);
            else if (!c->sc->f->membranes_count)
                overlap_watch_sample(&c->ov, s);
        }
        for (long k = 0; writer && !io && k < nrows; k++) {
            long t = c->rows[k].step, at = row_step(run, t, end);
            output_row_of(&c->rows[k], run, nw, &row);
            if (run->series_average > 1) { /* a step of the averaging window: into the sum, a row at its end */
                output_row_add(&sum, &row, nw);
                nsum++;
                if (t == at) { /* nsum: the window's steps (row_window), fewer where a stop shortened it */
                    output_row_mean(&sum, nsum, nw);
                    io = output_series(c->out, &sum);
                    memset(&sum, 0, sizeof sum);
                    nsum = 0;
                }
            } else if (t == at) {
                io = output_series(c->out, &row);
            }
        }
        if (R)
            io = R->agree(R, io, &who);
        if (io) {
            int e = errno;
            char cknote[4400];
            checkpoint_note(cknote, sizeof cknote, c->ckp, ck_step, o->restart);
            snprintf(c->err, sizeof c->err, "%s.part: cannot write step %ld to the output file: %s (%s)", c->outp, st,
                     h5_io_reason(e), cknote);
            return fail_with(EXIT_IO, c->err);
        }
        if (ck_due) {
            errno = 0;
            if (writer && output_flush(c->out)) { /* the series up to the checkpoint reach OUT.part with it */
                int e = errno;
                snprintf(c->err, sizeof c->err, "%s.part: cannot write to the output file: %s", c->outp,
                         h5_io_reason(e));
                io = 1;
            } else if (!R && checkpoint_write(c->ckp, s, c->sc, run, c->err, sizeof c->err)) {
                io = 1;
            }
            if (R) { /* over ranks: written from the parts, slab by slab (no rank holds the whole state) */
                io = R->agree(R, io, &who);
                int ck = io ? 0 : R->checkpoint(R, c->ckp, c->sc, run, why, sizeof why);
                if (ck == -2) {
                    char cknote[4400];
                    checkpoint_note(cknote, sizeof cknote, c->ckp, ck_step, o->restart);
                    snprintf(c->err, sizeof c->err, "%s: run stopped at step %ld: %s (output so far: %s.part; %s)",
                             c->sc->path, st, why, c->outp, cknote);
                    return fail_with(EXIT_RUN_FAILED, c->err);
                }
                if (ck)
                    snprintf(c->err, sizeof c->err, "%s", why), io = 1;
            }
            if (io)
                return fail_with(EXIT_IO, c->err);
            ck_step = st;
        }
        double tn = now();
        if (c->show && (tn - last > 1 || st == end)) {
            double rate = (double)(st - step0) / (tn - c->t0 + 1e-12);
            dem_mc_stats mc;
            dem_mc_stats_get(stepped(c), &mc);
            progress_line(tty, st, run->steps, (double)st * run->dt, rate * dem_count(s), (double)(end - st) / (rate + 1e-12),
                          (double)mc.total / (double)(st > 0 ? st : 1), run->mc_cap > 0 ? mc.unconverged : -1);
            last = tn;
        }
    }
    if (c->show && tty)
        fputc('\n', stderr);
    int rc = writer ? output_finish(c->out, c->err, sizeof c->err) : 0;
    c->out = NULL;
    if (R)
        rc = R->agree(R, rc, &who);
    return rc ? fail_with(EXIT_IO, c->err) : 0;
}

/* The device memory held at the end (the pair arrays and rows only grow: the run's largest), per particle by part,
 * largest first. */
static void print_memory(dem_sim *s)
{
    double n = dem_count(s) > 0 ? (double)dem_count(s) : 1.0, per[DEM_MEM__COUNT];
    int order[DEM_MEM__COUNT];
    for (int k = 0; k < DEM_MEM__COUNT; k++) {
        per[k] = (double)dem_device_bytes_part(s, (dem_memory_part)k) / n;
        int m = k;
        for (; m > 0 && per[order[m - 1]] < per[k]; m--)
            order[m] = order[m - 1];
        order[m] = k;
    }
    fprintf(stderr, "dem: device memory held: %.3g MB (%.0f bytes per particle:", (double)dem_device_bytes(s) / 1e6,
            (double)dem_device_bytes(s) / n);
    for (int k = 0, first = 1; k < DEM_MEM__COUNT; k++)
        if (per[order[k]] >= 0.5) {
            fprintf(stderr, "%s %s %.0f", first ? "" : ",", dem_memory_part_name((dem_memory_part)order[k]),
                    per[order[k]]);
            first = 0;
        }
    fprintf(stderr, ")\n");
}

/* 5. What the run did: files, kernels, memory, MC-strain iterations (and a warning, even with --quiet, for steps
 * whose forces did not converge to the tolerance). */
static void phase_report(run_ctx *c)
{
    const scene_run *run = &c->run;
    dem_sim *s = c->s;
    dem_mc_stats mc;
    dem_mc_stats_get(stepped(c), &mc);
    int iterated = (run->effects & DEM_EFFECT_MC_STRAIN) && run->mc_cap > 0;
    if (c->o->progress != 0 || c->show) {
        fprintf(stderr, "dem: wrote %s (+ .xmf) and checkpoint %s at step %ld; %.2f s wall time\n", c->outp, c->ckp,
                run_step(c), now() - c->t0); /* over ranks: the parts' step (the whole run is not started) */
        char seq[2048];
        /* the library's internals, on request: over ranks, rank 0's part's (the whole run is not started) */
        if (c->o->verbose && dem_kernel_sequence(stepped(c), 0, seq, sizeof seq))
            fprintf(stderr, "dem: kernels of the last step: %s\n", seq);
        if (!c->o->verbose || !dem_kernel_sequence(stepped(c), 1, seq, sizeof seq))
            seq[0] = 0;
        if (c->R) { /* the whole run is not started: the split's account instead */
            char line[1024];
            c->R->describe(c->R, line, sizeof line);
            fprintf(stderr, "dem: %s\n", line);
        } else
        fprintf(stderr, "dem: neighbour rebuilds: %ld (%ld storing the particles anew; skin now %.3g m)%s%s\n",
                dem_rebuild_count(s), dem_reorder_count(s), dem_neighbor_skin(s), seq[0] ? "; kernels at each: " : "",
                seq);
        const char **kn;
        const double *ks;
        int kc = 0;
        if (!c->R) /* split: the whole run has no kernels (the parts' are each rank's) */
            dem_kernel_times(s, &kn, &ks, &kc); /* DEM_PROFILE set: where the device time went */
        long ksteps = dem_step_index(s) - c->step0;
        int first = 1; /* the start's rebuild and forces are in the sums too: a short run's rebuild kernels read high */
        for (int k = 0; k < kc && ksteps > 0; k++)
            if (1e6 * ks[k] / (double)ksteps >= 0.5) {
                fprintf(stderr, "%s%s %.0f", first ? "dem: device time per step by kernel (DEM_PROFILE) [us]: " : ", ",
                        kn[k], 1e6 * ks[k] / (double)ksteps);
                first = 0;
            }
        if (!first)
            fprintf(stderr, "\n");
        if (!c->R) /* split: the whole run holds no device memory (the parts' are each rank's) */
            print_memory(s);
        if (iterated)
            fprintf(stderr, "dem: MC-strain iterations: %ld in all, %.2f per step, at most %ld; %ld steps hit the cap "
                            "of %d\n", mc.total, (double)mc.total / (double)(run_step(c) > 0 ? run_step(c) : 1),
                    mc.max, mc.unconverged, run->mc_cap);
    }
    for (int k = 0; k < dem_wall_count(s); k++) { /* servo stages: what force they held, and whether they chattered */
        dem_servo_stats sv; /* over ranks: the part's record (the whole run is not started) */
        if (dem_servo_stats_get(stepped(c), k, &sv) || sv.stage < 0)
            continue;
        char name[1100];
        scene_wall_label(c->sc, k, name, sizeof name);
        double off = (sv.held - sv.force) / sv.force, chatter = (double)sv.chatter / (double)sv.steps;
        if (c->o->progress != 0 || c->show)
            fprintf(stderr, "dem: wall '%s' servo stage %d: target %.6g N, held %.6g N on average over the %ld steps of "
                            "its last tenth (%+.2g %%); force error reversed beyond 10 %% of the target in %ld of %ld "
                            "steps\n", name, sv.stage, sv.force, sv.held, sv.tail, 100 * off, sv.chatter, sv.steps);
        if (chatter > 0.1 || (sv.tail > 0 && fabs(off) > 0.05))
            fprintf(stderr, "dem: warning: wall '%s' servo stage %d held %.6g N on average over its last tenth for a "
                            "target of %.6g N (%+.2g %%), its force error reversing in %.0f %% of its steps: %s\n", name,
                    sv.stage, sv.held, sv.force, 100 * off, 100 * chatter,
                    chatter > 0.1 ? "it chatters - the wall touches and leaves the particles in turn - because gain x "
                                    "the contacts' stiffness x dt is above 1: lower the gain (docs/scenes.md)"
                                  : "it had not settled: a longer stage, or a higher gain within gain x stiffness x dt "
                                    "< 1 (docs/scenes.md)");
    }
    overlap_watch_report(&c->ov, c->sc, run, c->o->progress != 0 || c->show);
    long capped_id, capped_at = dem_mdr_capped(stepped(c), &capped_id);
    if (capped_at >= 0)
        fprintf(stderr, "dem: warning: MDR: from step %ld (t = %.9g s, particle %ld the first) a sphere's apparent "
                        "radius met the law's cap of 1.5 times its own radius: past it the law no longer keeps the "
                        "sphere's volume and the compact is past MDR's range (docs/laws/mdr.md \"Range\")\n",
                capped_at, (double)capped_at * dem_dt(c->s), capped_id);
    if (iterated && mc.unconverged > 0)
        fprintf(stderr, "dem: warning: %ld of %ld steps hit the MC-strain iteration cap of %d (mc_iterations) before "
                        "every contact force settled to mc_tolerance %g; the series mc_capped counts them. Raise "
                        "mc_iterations, or loosen mc_tolerance, if that matters here\n",
                mc.unconverged, run_step(c), run->mc_cap, run->mc_tol);
}

int run_scene(const run_opts *o) { return run_scene_ranks(o, NULL); }

int run_scene_ranks(const run_opts *o, run_ranks *R)
{
    run_ctx *c = calloc(1, sizeof *c);
    if (R && R->agree(R, c ? 0 : EXIT_IO, NULL)) { /* every rank goes on, or none */
        free(c);
        return fail_with(EXIT_IO, "out of memory");
    }
    if (!c)
        return fail_with(EXIT_IO, "out of memory");
    c->ov.largest_i = c->ov.largest_j = -1; /* no overlap seen yet */
    c->o = o;
    c->R = R;
    run_quiet = R && R->rank != 0;
    run_held[0] = 0;
    run_signal = 0;
    run_catch_signals(1);
    int code = phase_load(c);
    if (!code)
        code = phase_configure(c);
    if (R) { /* the scene's errors: rank 0's, said once; another rank's where rank 0 had none */
        int who, mine = code;
        code = R->agree(R, code, &who);
        if (code && who == R->rank && R->rank != 0 && mine)
            fprintf(stderr, "dem: rank %d: %s\n", R->rank, run_held);
    }
    if (!code)
        code = phase_start(c);
    if (!code)
        code = phase_steps(c);
    if (!code && c->stopped && run_quiet) {
        code = 128 + c->stopped;
    } else if (!code && c->stopped) {
        if (!c->t0) /* stopped before the first step */
            fprintf(stderr, "dem: stopped by signal %d (%s) before the first step: nothing written\n", c->stopped,
                    strsignal(c->stopped));
        else {
            phase_report(c);
            fprintf(stderr, "dem: stopped by signal %d (%s) at step %ld of %ld (t = %.9g s): %s holds the run to "
                            "there and %s its state; continue with: dem run --restart %s -o MORE.h5\n", c->stopped,
                    strsignal(c->stopped), run_step(c), c->run.steps, dem_time(stepped(c)), c->outp, c->ckp, c->ckp);
        }
        code = 128 + c->stopped;
    } else if (!code && !run_quiet)
        phase_report(c);
    if (c->out)
        output_abort(c->out);
    if (R)
        R->finish(R);
    dem_destroy(c->s);
    scene_free(c->sc);
    if (c->have_ck)
        checkpoint_free(&c->ck);
    overlap_watch_free(&c->ov);
    free(c->x0), free(c->tri);
    int stopped = c->stopped;
    free(c);
    run_catch_signals(0);
    if (stopped == SIGINT && !R) { /* everything written: die of it, so that a script or make running dem stops too
                                     * (over ranks: run_mpi does, after MPI_Finalize) */
        fflush(NULL);
        signal(SIGINT, SIG_DFL);
        raise(SIGINT);
    }
    return code;
}
