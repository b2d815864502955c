/* cli.c - see cli.h. */
#include "cli.h"
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char cli_usage[] =
    "usage: dem run SCENE.yaml [-o OUT.h5] [--device N] [--precision fp32|fp64] [--checkpoint FILE]\n"
    "                          [--progress | --quiet] [--verbose] [--stop-after STEPS] [--backend opencl|reference]\n"
    "                          [--model classical|mc_stress|mc_strain|mc_strain_iterated|thornton_ning|mdr]\n"
    "       dem run [SCENE.yaml] --restart CHECKPOINT.h5 [-o OUT.h5] [options as above]\n"
    "                                continue a run from its checkpoint, under the scene text the checkpoint holds\n"
    "                                or under SCENE.yaml: that scene with a longer duration, other output, or the\n"
    "                                stages a wall has not finished changed\n"
    "       dem check SCENE.yaml [--model M] [--probe] [--device N] [--precision fp32|fp64]\n"
    "                                validate a scene and print what it implies (time scales, memory, effects, wall\n"
    "                                time), under contact model M if given; --probe times its first steps on the\n"
    "                                device and predicts the whole run's wall time from them\n"
    "       dem devices              list OpenCL devices (index for --device)\n"
    "       dem conform [--device N] [--precision fp32|fp64] [--backend opencl|reference] [--only SCENE]\n"
    "                   [--table FILE]   run the conformance set (every shipped scene x model x precision, 150\n"
    "                                    steps) and compare each state hash with the reference's record\n"
    "       dem hash CHECKPOINT.h5   the state hash of a checkpoint (the one dem conform compares)\n"
    "       dem --help | --version\n"
    "\n"
    "run writes OUT.h5 (frames and time series; OUT.h5.part until it completes), OUT.xmf for ParaView, and\n"
    "checkpoints to OUT.ckpt.h5 (the scene's output.checkpoint_every, and at the end). A progress line goes to\n"
    "stderr when it is a terminal (--progress: always; --quiet: never). Units are SI. --model replaces the\n"
    "scene's normal law (same scene, another contact model; kept in the checkpoint for --restart); --backend\n"
    "replaces the scene's backend. --verbose adds the kernels each step and each neighbour rebuild launched\n"
    "to the report at the end.\n"
    "SIGINT, SIGTERM, SIGHUP, SIGUSR1 or SIGUSR2 ends a run within about a second, its output and checkpoint\n"
    "complete (under mpirun send SIGUSR2 to mpirun: it passes it on at once, where a SIGTERM gives the ranks 1 s).\n"
    "\n"
    "exit status: 0 done; 1 the simulation failed while running; 2 bad command line; 65 invalid scene or\n"
    "checkpoint; 66 a file could not be opened; 69 no usable OpenCL device; 74 output could not be written;\n"
    "128 + N stopped by signal N.\n";

const char *cli_show(const char *s, char *buf, size_t len)
{
    size_t o = 0;
    for (; *s && o + 8 < len; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch < 0x20 || ch == 0x7f)
            o += (size_t)snprintf(buf + o, len - o, "\\x%02x", ch);
        else
            buf[o++] = (char)ch;
    }
    if (*s && len >= 4)
        o = o + 4 > len ? len - 4 : o, memcpy(buf + o, "...", 3), o += 3;
    if (len)
        buf[o < len ? o : len - 1] = 0;
    return buf;
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

static int usage_error(char *err, size_t errlen, int *with_usage, int show_usage, const char *msg)
{
    snprintf(err, errlen, "%s", msg);
    *with_usage = show_usage;
    return EXIT_USAGE;
}

/* A path argument: not empty, at most DEM_MAX_PATH characters. */
static int path_ok(const char *what, const char *p, char *err, size_t errlen)
{
    size_t l = strlen(p);
    if (l == 0)
        snprintf(err, errlen, "%s needs a file name, not an empty string", what);
    else if (l > DEM_MAX_PATH)
        snprintf(err, errlen, "%s: a path of %zu characters; at most %d are accepted", what, l, DEM_MAX_PATH);
    return l > 0 && l <= DEM_MAX_PATH;
}

/* --device's value: an index in 0..65535; 1 with the reason in err otherwise */
static int parse_device(const char *val, int *dev, char *err, size_t errlen)
{
    long v;
    char q[CLI_SHOW_LEN];
    if (!parse_long(val, &v, 0, 65535)) {
        snprintf(err, errlen, "--device needs an index in 0..65535 (see dem devices), not '%s'", cli_show(val, q, 200));
        return 1;
    }
    *dev = (int)v;
    return 0;
}

/* --precision's value: fp32 or fp64, as DEM_FP32 / DEM_FP64; --backend's: opencl or reference, as a
 * dem_backend_kind. 0, or EXIT_USAGE with the reason in err. */
static int parse_precision(const char *val, int *p, char *err, size_t errlen)
{
    *p = !strcmp(val, "fp32") ? DEM_FP32 : !strcmp(val, "fp64") ? DEM_FP64 : 0;
    return *p ? 0 : (snprintf(err, errlen, "--precision must be fp32 or fp64"), EXIT_USAGE);
}

static int parse_backend(const char *val, int *b, char *err, size_t errlen)
{
    *b = !strcmp(val, "opencl") ? DEM_BACKEND_OPENCL : !strcmp(val, "reference") ? DEM_BACKEND_REFERENCE : -1;
    return *b >= 0 ? 0 : (snprintf(err, errlen, "--backend must be opencl or reference"), EXIT_USAGE);
}

static int parse_conform(int argc, char **argv, cli *c, char *err, size_t errlen, int *with_usage)
{
    c->cmd = CLI_CONFORM;
    conform_opts *o = &c->conform;
    *o = (conform_opts){-1, 0, 0, NULL, NULL};
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        char q[CLI_SHOW_LEN];
        int b = -1;
        if (strcmp(a, "--device") && strcmp(a, "--precision") && strcmp(a, "--backend") && strcmp(a, "--only") &&
            strcmp(a, "--table")) {
            snprintf(err, errlen, "conform: unknown option '%s'", cli_show(a, q, 200));
            *with_usage = 1;
            return EXIT_USAGE;
        }
        if (k + 1 >= argc)
            return snprintf(err, errlen, "option %s needs a value", a), *with_usage = 1, EXIT_USAGE;
        const char *val = argv[++k];
        int rc = !strcmp(a, "--device")      ? parse_device(val, &o->device, err, errlen)
                 : !strcmp(a, "--precision") ? parse_precision(val, &o->precision, err, errlen)
                 : !strcmp(a, "--backend")   ? parse_backend(val, &b, err, errlen)
                                             : 0;
        if (rc || (!strcmp(a, "--table") && !path_ok("--table", val, err, errlen)))
            return EXIT_USAGE;
        if (!strcmp(a, "--backend"))
            o->reference = b == DEM_BACKEND_REFERENCE;
        else if (!strcmp(a, "--only"))
            o->only = val;
        else if (!strcmp(a, "--table"))
            o->table = val;
    }
    return 0;
}

int cli_parse(int argc, char **argv, cli *c, char *err, size_t errlen, int *with_usage)
{
    memset(c, 0, sizeof *c);
    *with_usage = 0;
    if (argc < 2)
        return usage_error(err, errlen, with_usage, 1, "no command given");
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        c->cmd = CLI_HELP;
        return argc == 2 ? 0 : usage_error(err, errlen, with_usage, 1, "help takes no arguments");
    }
    if (!strcmp(cmd, "--version")) {
        c->cmd = CLI_VERSION;
        return argc == 2 ? 0 : usage_error(err, errlen, with_usage, 1, "--version takes no arguments");
    }
    if (!strcmp(cmd, "devices")) {
        c->cmd = CLI_DEVICES;
        return argc == 2 ? 0 : usage_error(err, errlen, with_usage, 1, "devices takes no arguments");
    }
    if (!strcmp(cmd, "check")) {
        c->cmd = CLI_CHECK;
        c->check_device = -1;
        for (int k = 2; k < argc; k++) {
            const char *a = argv[k];
            char q[CLI_SHOW_LEN];
            if (!strcmp(a, "--probe")) {
                c->check_probe = 1;
                continue;
            }
            if (!strcmp(a, "--model") || !strcmp(a, "--device") || !strcmp(a, "--precision")) {
                if (k + 1 >= argc || !strncmp(argv[k + 1], "--", 2))
                    return snprintf(err, errlen, "option %s needs a value", a), *with_usage = 1, EXIT_USAGE;
                const char *val = argv[++k];
                if (!strcmp(a, "--model"))
                    c->check_model = val; /* checked against the list by scene_apply_model */
                else if (!strcmp(a, "--precision")) {
                    if (parse_precision(val, &c->check_precision, err, errlen))
                        return EXIT_USAGE;
                } else if (parse_device(val, &c->check_device, err, errlen))
                    return EXIT_USAGE;
                continue;
            }
            if (a[0] == '-' || c->check_path) {
                snprintf(err, errlen, a[0] == '-' ? "check: unknown option '%s'" : "check takes one scene file, not also '%s'",
                         cli_show(a, q, 200));
                *with_usage = 1;
                return EXIT_USAGE;
            }
            if (!path_ok("the scene", a, err, errlen))
                return EXIT_USAGE;
            c->check_path = a;
        }
        if (!c->check_path)
            return usage_error(err, errlen, with_usage, 1, "check takes one scene file (and --model M, --probe ...)");
        return 0;
    }
    if (!strcmp(cmd, "hash")) {
        c->cmd = CLI_HASH;
        if (argc != 3)
            return usage_error(err, errlen, with_usage, 1, "hash takes one checkpoint file");
        c->hash_path = argv[2];
        return path_ok("the checkpoint", argv[2], err, errlen) ? 0 : EXIT_USAGE;
    }
    if (!strcmp(cmd, "conform"))
        return parse_conform(argc, argv, c, err, errlen, with_usage);
    if (strcmp(cmd, "run")) {
        char q[CLI_SHOW_LEN];
        snprintf(err, errlen, "unknown command '%s'", cli_show(cmd, q, 200));
        *with_usage = 1;
        return EXIT_USAGE;
    }
    c->cmd = CLI_RUN;
    run_opts *o = &c->run;
    *o = (run_opts){NULL, NULL, NULL, NULL, -1, 0, -1, 0, NULL, 0, -1};
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        long v;
        char q[CLI_SHOW_LEN];
        int takes = !strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--checkpoint") ||
                    !strcmp(a, "--restart") || !strcmp(a, "--device") || !strcmp(a, "--precision") ||
                    !strcmp(a, "--stop-after") || !strcmp(a, "--model") || !strcmp(a, "--backend");
        if (takes && k + 1 >= argc) {
            snprintf(err, errlen, "option %s needs a value", a); /* a is one of the known options */
            *with_usage = 1;
            return EXIT_USAGE;
        }
        const char *val = takes ? argv[++k] : NULL;
        if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!path_ok(a, val, err, errlen))
                return EXIT_USAGE;
            o->out = val;
        } else if (!strcmp(a, "--checkpoint")) {
            if (!path_ok(a, val, err, errlen))
                return EXIT_USAGE;
            o->checkpoint = val;
        } else if (!strcmp(a, "--restart")) {
            if (!path_ok(a, val, err, errlen))
                return EXIT_USAGE;
            o->restart = val;
        } else if (!strcmp(a, "--device")) {
            if (parse_device(val, &o->device, err, errlen))
                return EXIT_USAGE;
        } else if (!strcmp(a, "--precision")) {
            if (parse_precision(val, &o->precision, err, errlen))
                return EXIT_USAGE;
        } else if (!strcmp(a, "--backend")) {
            if (parse_backend(val, &o->backend, err, errlen))
                return EXIT_USAGE;
        } else if (!strcmp(a, "--stop-after")) {
            if (!parse_long(val, &v, 1, LONG_MAX)) {
                snprintf(err, errlen, "--stop-after needs a step count >= 1, not '%s'", cli_show(val, q, 200));
                return EXIT_USAGE;
            }
            o->stop_after = v;
        } else if (!strcmp(a, "--model")) {
            o->model = val; /* checked against the list by scene_apply_model, which knows it */
        } else if (!strcmp(a, "--progress")) {
            o->progress = 1;
        } else if (!strcmp(a, "--quiet")) {
            o->progress = 0;
        } else if (!strcmp(a, "--verbose")) {
            o->verbose = 1;
        } else if (a[0] == '-') {
            snprintf(err, errlen, "unknown option '%s'", cli_show(a, q, 200));
            *with_usage = 1;
            return EXIT_USAGE;
        } else if (!o->scene_path) {
            if (!path_ok("the scene", a, err, errlen))
                return EXIT_USAGE;
            o->scene_path = a;
        } else {
            snprintf(err, errlen, "more than one scene given ('%s')", cli_show(a, q, 200));
            return EXIT_USAGE;
        }
    }
    if (!o->scene_path && !o->restart)
        return usage_error(err, errlen, with_usage, 1, "run needs a scene file or --restart");
    return 0;
}
