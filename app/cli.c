/* cli.c - see cli.h. */
#include "cli.h"
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char cli_usage[] =
    "usage: dem run SCENE.yaml [-o OUT.h5] [--device N] [--precision fp32|fp64] [--checkpoint FILE]\n"
    "                          [--progress | --quiet] [--verbose] [--stop-after STEPS]\n"
    "                          [--model classical|mc_stress|mc_strain|mc_strain_iterated]\n"
    "       dem run --restart CHECKPOINT.h5 [-o OUT.h5] [options as above]\n"
    "       dem check SCENE.yaml [--model M]   validate a scene and print what it implies (time scales, memory,\n"
    "                                           effects), under contact model M if given\n"
    "       dem devices              list OpenCL devices (index for --device)\n"
    "       dem --help | --version\n"
    "\n"
    "run writes OUT.h5 (frames and time series; OUT.h5.part until it completes), OUT.xmf for ParaView, and\n"
    "checkpoints to OUT.ckpt.h5 (the scene's output.checkpoint_every, and at the end). A progress line goes to\n"
    "stderr when it is a terminal (--progress: always; --quiet: never). Units are SI. --model replaces the\n"
    "scene's normal law (same scene, another contact model; kept in the checkpoint for --restart). --verbose\n"
    "adds the kernels each step and each neighbour rebuild launched to the report at the end.\n"
    "SIGINT, SIGTERM or SIGHUP ends a run within about a second, its output and checkpoint complete.\n"
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
        if (argc == 5 && !strcmp(argv[3], "--model"))
            c->check_model = argv[4]; /* checked against the list by scene_apply_model */
        else if (argc != 3)
            return usage_error(err, errlen, with_usage, 1, "check takes one scene file (and --model M)");
        c->check_path = argv[2];
        return path_ok("the scene", argv[2], err, errlen) ? 0 : EXIT_USAGE;
    }
    if (strcmp(cmd, "run")) {
        char q[CLI_SHOW_LEN];
        snprintf(err, errlen, "unknown command '%s'", cli_show(cmd, q, 200));
        *with_usage = 1;
        return EXIT_USAGE;
    }
    c->cmd = CLI_RUN;
    run_opts *o = &c->run;
    *o = (run_opts){NULL, NULL, NULL, NULL, -1, 0, -1, 0, NULL};
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        long v;
        char q[CLI_SHOW_LEN];
        int takes = !strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--checkpoint") ||
                    !strcmp(a, "--restart") || !strcmp(a, "--device") || !strcmp(a, "--precision") ||
                    !strcmp(a, "--stop-after") || !strcmp(a, "--model");
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
            if (!parse_long(val, &v, 0, 65535)) {
                snprintf(err, errlen, "--device needs an index in 0..65535 (see dem devices), not '%s'",
                         cli_show(val, q, 200));
                return EXIT_USAGE;
            }
            o->device = (int)v;
        } else if (!strcmp(a, "--precision")) {
            if (!strcmp(val, "fp32"))
                o->precision = DEM_FP32;
            else if (!strcmp(val, "fp64"))
                o->precision = DEM_FP64;
            else
                return usage_error(err, errlen, with_usage, 0, "--precision must be fp32 or fp64");
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
