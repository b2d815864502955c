/* conform.c - see conform.h. */
#include "conform.h"
#include "dem.h"
#include "h5util.h"
#include "run.h"
#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define FNV_OFFSET 14695981039346656037ULL
#define FNV_PRIME 1099511628211ULL

static uint64_t fnv(uint64_t h, const void *p, size_t len)
{
    const unsigned char *c = p;
    for (size_t k = 0; k < len; k++)
        h = (h ^ c[k]) * FNV_PRIME;
    return h;
}

/* the value's bytes least significant first, whatever the host's order */
static uint64_t fnv_u64(uint64_t h, uint64_t v)
{
    unsigned char b[8];
    for (int k = 0; k < 8; k++)
        b[k] = (unsigned char)(v >> (8 * k));
    return fnv(h, b, 8);
}

int conform_hash_file(const char *path, char hex[17], char *err, size_t errlen)
{
    static const char *names[] = {CONFORM_DATASETS, CONFORM_DATASETS_LATER};
    const size_t first_later = sizeof (const char *[]){CONFORM_DATASETS} / sizeof(const char *);
    if (access(path, R_OK)) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -2;
    }
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) {
        snprintf(err, errlen, "%s: not an HDF5 file: not a checkpoint of dem run", path);
        return -1;
    }
    uint64_t h = FNV_OFFSET;
    int rc = 0, found = 0;
    hid_t g = H5Lexists(f, "state", H5P_DEFAULT) > 0 ? H5Gopen2(f, "state", H5P_DEFAULT) : -1;
    for (size_t k = 0; g >= 0 && k < sizeof names / sizeof *names && !rc; k++) {
        long count = h5_count(g, names[k]);
        if (count < 0 || (k >= first_later && count == 0))
            continue; /* not in this run's checkpoint (or, added later, empty: conform.h) */
        hid_t d = H5Dopen2(g, names[k], H5P_DEFAULT), t = d < 0 ? -1 : H5Dget_type(d); /* as stored: float, double, int */
        hid_t nt = t < 0 ? -1 : H5Tget_native_type(t, H5T_DIR_ASCEND);
        size_t esz = nt < 0 ? 0 : H5Tget_size(nt);
        void *buf = esz ? malloc((size_t)count * esz + 1) : NULL;
        if (!buf || h5_read(g, names[k], nt, buf, (size_t)count)) {
            snprintf(err, errlen, "%s: cannot read /state/%s", path, names[k]);
            rc = -1;
        } else { /* its name, element size and count, then its bytes (little-endian on every host we build for) */
            h = fnv(h, names[k], strlen(names[k]) + 1);
            h = fnv(fnv_u64(fnv_u64(h, esz), (uint64_t)count), buf, (size_t)count * esz);
            found++;
        }
        free(buf);
        if (nt >= 0)
            H5Tclose(nt);
        if (t >= 0)
            H5Tclose(t);
        if (d >= 0)
            H5Dclose(d);
    }
    if (g >= 0)
        H5Gclose(g);
    H5Fclose(f);
    if (!rc && !found) {
        snprintf(err, errlen, "%s: no /state/x: not a checkpoint of dem run", path);
        rc = -1;
    }
    if (!rc)
        snprintf(hex, 17, "%016llx", (unsigned long long)h);
    return rc;
}

/* ---- dem conform ---- */

typedef struct {
    char scene[128], model[64], prec[8], hash[32];
} conform_line;

static const char *source_dir(void)
{
    const char *d = getenv("DEM_SOURCE_DIR");
    return d && *d ? d : DEM_DEFAULT_SOURCE_DIR;
}

/* The scene file of a table line's name: the folders tools/state_hashes.sh runs. */
static int find_scene(const char *root, const char *name, char *path, size_t len)
{
    static const char *dirs[] = {"scenes", "scenes/validation", "tests/scenes"};
    for (size_t k = 0; k < sizeof dirs / sizeof *dirs; k++) {
        snprintf(path, len, "%s/%s/%s.yaml", root, dirs[k], name);
        if (access(path, R_OK) == 0)
            return 0;
    }
    return -1;
}

/* SIGINT or SIGTERM: the run under way is stopped, and the table ends with what was compared */
static volatile sig_atomic_t stop_signal;
static void on_stop(int sig) { stop_signal = sig; }

/* One `dem run` of 150 steps into dir on device `device` (-1: the reference); its exit status (-1: it could not be
 * started or was killed). */
static int run_child(const char *self, const char *scene, const conform_line *l, int device, const char *dir)
{
    char out[4200], log[4200], dev[16];
    snprintf(out, sizeof out, "%s/o.h5", dir);
    snprintf(log, sizeof log, "%s/log", dir);
    snprintf(dev, sizeof dev, "%d", device);
    const char *argv[24];
    int a = 0;
    argv[a++] = self, argv[a++] = "run", argv[a++] = scene, argv[a++] = "-o", argv[a++] = out;
    argv[a++] = "--quiet", argv[a++] = "--stop-after", argv[a++] = "150", argv[a++] = "--precision";
    argv[a++] = l->prec, argv[a++] = "--backend", argv[a++] = device < 0 ? "reference" : "opencl";
    if (strcmp(l->model, "scene"))
        argv[a++] = "--model", argv[a++] = l->model;
    if (device >= 0)
        argv[a++] = "--device", argv[a++] = dev;
    argv[a] = NULL;
    fflush(stdout);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0)
            dup2(fd, 1), dup2(fd, 2), close(fd);
        execv(self, (char *const *)argv);
        fprintf(stderr, "dem conform: cannot run %s: %s\n", self, strerror(errno));
        _exit(127);
    }
    int st, told = 0;
    while (waitpid(pid, &st, 0) < 0) {
        if (errno != EINTR)
            return -1;
        if (stop_signal && !told) /* the run ends within about a second, as dem run does on a signal */
            kill(pid, SIGTERM), told = 1;
    }
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* The last non-empty line of the run's log, for a failed run's line. */
static void last_line(const char *dir, char *buf, size_t len)
{
    char p[4200], line[1024];
    snprintf(p, sizeof p, "%s/log", dir);
    buf[0] = 0;
    FILE *f = fopen(p, "r");
    while (f && fgets(line, sizeof line, f))
        if (line[0] && line[0] != '\n') {
            line[strcspn(line, "\n")] = 0;
            snprintf(buf, len, "%s", line);
        }
    if (f)
        fclose(f);
}

static void clean_dir(const char *dir)
{
    static const char *files[] = {"o.h5", "o.h5.part", "o.xmf", "o.ckpt.h5", "o.ckpt.h5.tmp", "log"};
    char p[4200];
    for (size_t k = 0; k < sizeof files / sizeof *files; k++) {
        snprintf(p, sizeof p, "%s/%s", dir, files[k]);
        unlink(p);
    }
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int conform_run(const conform_opts *o, const char *self)
{
    const char *root = source_dir();
    char table[4200];
    if (o->table)
        snprintf(table, sizeof table, "%s", o->table);
    else
        snprintf(table, sizeof table, "%s/docs/state_hashes.txt", root);
    FILE *f = fopen(table, "r");
    if (!f) {
        fprintf(stderr, "dem conform: cannot open the table %s: %s (set DEM_SOURCE_DIR to the project folder, or give "
                        "--table)\n", table, strerror(errno));
        return EXIT_NO_INPUT;
    }
    conform_line *lines = NULL;
    int n = 0, cap = 0, lineno = 0, bad = 0;
    char buf[1024];
    while (fgets(buf, sizeof buf, f)) {
        lineno++;
        if (buf[0] == '#' || buf[strspn(buf, " \t\r\n")] == 0)
            continue;
        conform_line l;
        char be[32];
        if (sscanf(buf, "%127s %31s %63s %7s %31s", l.scene, be, l.model, l.prec, l.hash) != 5 ||
            (strcmp(l.prec, "fp32") && strcmp(l.prec, "fp64"))) {
            fprintf(stderr, "dem conform: %s:%d: not a line 'scene backend model precision hash'\n", table, lineno);
            bad = 1;
            break;
        }
        if (strcmp(be, "reference")) /* the reference's line is the record; the OpenCL lines repeat it */
            continue;
        if ((o->precision == DEM_FP32 && strcmp(l.prec, "fp32")) || (o->precision == DEM_FP64 && strcmp(l.prec, "fp64")))
            continue;
        if (o->only && strcmp(o->only, l.scene))
            continue;
        if (n == cap) {
            conform_line *g = realloc(lines, sizeof *lines * (size_t)(cap = cap ? 2 * cap : 64));
            if (!g) {
                bad = 1;
                break;
            }
            lines = g;
        }
        lines[n++] = l;
    }
    fclose(f);
    if (bad || !n) {
        if (!bad)
            fprintf(stderr, "dem conform: %s has no reference line%s%s\n", table, o->only ? " for scene " : "",
                    o->only ? o->only : "");
        free(lines);
        return bad ? EXIT_BAD_INPUT : EXIT_USAGE;
    }
    const char *tmp = getenv("TMPDIR");
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/dem-conform-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        fprintf(stderr, "dem conform: cannot make a folder %s: %s\n", dir, strerror(errno));
        free(lines);
        return EXIT_IO;
    }
    /* the device as dem run would choose it (--device, else $DEM_DEVICE, else 0), named before anything runs */
    int device = -1;
    char devname[512] = "the reference (plain C)";
    if (!o->reference) {
        dem_config dc;
        dem_config_default(&dc);
        device = o->device >= 0 ? o->device : dc.device;
        if (dem_device_name(device, devname, sizeof devname)) {
            fprintf(stderr, "dem conform: no OpenCL device %d (dem devices lists them)\n", device);
            rmdir(dir);
            free(lines);
            return EXIT_DEVICE;
        }
    }
    printf("dem conform: %d runs of 150 steps on %s against %s\n", n, devname, table);
    printf("%-26s %-19s %-5s %-17s %-17s %s\n", "scene", "model", "prec", "reference", "this run", "result");
    int equal = 0, refused = 0, missing = 0, done = 0;
    double t0 = now_s();
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop; /* no SA_RESTART: the wait for a run returns to pass the signal on */
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    for (int k = 0; k < n && !stop_signal; k++) {
        const conform_line *l = &lines[k];
        char scene[4400], got[32] = "", note[1024] = "";
        int same = 0;
        double t = now_s();
        if (find_scene(root, l->scene, scene, sizeof scene)) {
            snprintf(got, sizeof got, "missing");
            snprintf(note, sizeof note, " (no %s.yaml under %s/scenes, scenes/validation or tests/scenes)", l->scene,
                     root);
            missing++;
        } else {
            int rc = run_child(self, scene, l, device, dir);
            char ck[4300], herr[512];
            snprintf(ck, sizeof ck, "%s/o.ckpt.h5", dir);
            if (rc == 0 && !conform_hash_file(ck, got, herr, sizeof herr))
                same = !strcmp(got, l->hash);
            else if (rc == 0)
                snprintf(got, sizeof got, "unreadable"), snprintf(note, sizeof note, " (%s)", herr);
            else if (rc == EXIT_USAGE || rc == EXIT_BAD_INPUT) /* the scene or model refused, as recorded or not */
                snprintf(got, sizeof got, "refused"), same = !strcmp(l->hash, "refused");
            else {
                char last[900];
                last_line(dir, last, sizeof last);
                snprintf(got, sizeof got, "failed");
                snprintf(note, sizeof note, " (exit %d: %s)", rc, last);
            }
            if (!same && !strcmp(got, "refused")) {
                char last[900];
                last_line(dir, last, sizeof last);
                snprintf(note, sizeof note, " (%s)", last);
            }
            clean_dir(dir);
        }
        if (stop_signal && !same) /* a run stopped by the signal is not a result */
            break;
        equal += same, done++;
        refused += same && !strcmp(got, "refused");
        printf("%-26s %-19s %-5s %-17s %-17s %s%s  %.1f s\n", l->scene, l->model, l->prec, l->hash, got,
               same ? "equal" : missing && !strcmp(got, "missing") ? "MISSING" : "DIFFERS", note, now_s() - t);
        fflush(stdout);
    }
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    rmdir(dir);
    const char *verdict = equal == n ? ""
                          : missing ? ": scenes of the table are missing here (a tree other than the table's?)"
                          : done < n ? ""
                                     : ": this device does not reproduce the reference bits";
    if (done < n)
        printf("dem conform: stopped by signal %d after %d of %d runs; %d equal to the reference (%d of them refusals "
               "as recorded)\n", (int)stop_signal, done, n, equal, refused);
    else
        printf("dem conform: %d of %d equal to the reference (%d of them refusals as recorded) in %.0f s%s\n", equal, n,
               refused, now_s() - t0, verdict);
    free(lines);
    return done < n ? 128 + (int)stop_signal : equal == n ? 0 : missing ? EXIT_NO_INPUT : EXIT_RUN_FAILED;
}
