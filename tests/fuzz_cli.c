/* fuzz_cli.c - libFuzzer harness for the command line and the output-path check (make fuzz-cli).
 *
 * The input is a command line: arguments separated by NUL bytes, after "dem". It goes through cli_parse, and a run's
 * options then through run_output_paths against a fixed scene, in a scratch folder that holds the files a user could
 * name by mistake: the scene (scene.yaml, also as a hard link and a symbolic link), the CSV it reads (pts.csv), a
 * folder (d), a stand-in checkpoint to restart from (ck.ckpt.h5). Beyond no crash, leak or undefined behaviour
 * (ASan, UBSan), every outcome is checked against the promises, independently of the code under test:
 *   - a refusal is exit 2 (or 74 for an unwritable folder) with a one-line message;
 *   - an accepted command line holds paths of 1..DEM_MAX_PATH characters and in-range numbers;
 *   - accepted output paths are the ones given, uncut, and none of the six files a run writes (OUT, OUT.part, the
 *     XDMF and its .part, the checkpoint and its .tmp) is a folder, a device, pipe or socket, or the same file as an
 *     input, and each one's
 *     folder exists;
 *   - the checks write nothing: the scratch folder's listing is the same after every input. */
#include "checkpoint.h"
#include "cli.h"
#include "output.h"
#include "scene.h"
#include <dirent.h>
#include <libgen.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static scene *sc;
static char dir[256];
static long listing; /* a hash of the scratch folder's names */

static const char scene_text[] =
    "name: fuzz cli\n"
    "precision: fp64\n"
    "effects: [hertz]\n"
    "materials:\n"
    "  - {name: g, density: 2500, young: 1.0e7, poisson: 0.3, restitution: 0.6}\n"
    "particles:\n"
    "  - {material: g, csv: pts.csv}\n"
    "time: {dt: 1.0e-6, duration: 1.0e-5}\n";

static long list_dir(void)
{
    DIR *d = opendir(".");
    long h = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        for (const char *c = e->d_name; *c; c++)
            h += (long)(unsigned char)*c * (long)(c - e->d_name + 1) * 131;
    if (d)
        closedir(d);
    return h;
}

static int write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fputs(text, f);
    return fclose(f);
}

static void remove_scratch(void)
{
    const char *names[] = {"scene.yaml", "hard.yaml", "link.h5", "pts.csv", "ck.ckpt.h5"};
    if (chdir(dir))
        return;
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        unlink(names[k]);
    rmdir("d");
    if (chdir("/") == 0)
        rmdir(dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    char err[8192];
    snprintf(dir, sizeof dir, "/tmp/fuzz-cli-%d", (int)getpid());
    if (mkdir(dir, 0700) || chdir(dir) || write_file("scene.yaml", scene_text) ||
        write_file("pts.csv", "x,y,z,r\n0,0,0,0.001\n0.01,0,0,0.001\n") || write_file("ck.ckpt.h5", "") ||
        mkdir("d", 0700) || link("scene.yaml", "hard.yaml") || symlink("scene.yaml", "link.h5")) {
        perror("fuzz_cli: cannot make the scratch folder");
        exit(1);
    }
    atexit(remove_scratch);
    sc = scene_load("scene.yaml", err, sizeof err);
    if (!sc) {
        fprintf(stderr, "fuzz_cli: %s\n", err);
        exit(1);
    }
    listing = list_dir();
    return 0;
}

static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

static int path_len_ok(const char *p) { return !p || (strlen(p) >= 1 && strlen(p) <= DEM_MAX_PATH); }

/* The promises about the six files a run writes, checked with the operating system directly. */
static void check_accepted(const run_opts *o, const char *outp, const char *ckp)
{
    if ((o->out && strcmp(outp, o->out)) || (o->checkpoint && strcmp(ckp, o->checkpoint)))
        __builtin_trap(); /* a path was cut or changed */
    char outs[6][RUN_OUT_LEN]; /* the names are the run's; what the oracle checks about them is its own */
    run_output_files(outp, ckp, outs);
    const char *inputs[3] = {"scene.yaml", "pts.csv", o->restart};
    for (int q = 0; q < 6; q++) {
        struct stat st;
        if (stat(outs[q], &st) == 0 && !S_ISREG(st.st_mode))
            __builtin_trap(); /* a folder, device, pipe or socket */
        for (int k = 0; k < 3; k++)
            if (inputs[k] && same_file(outs[q], inputs[k]))
                __builtin_trap();
        char d[RUN_PATH_LEN + 16];
        snprintf(d, sizeof d, "%s", outs[q]);
        if (stat(dirname(d), &st) || !S_ISDIR(st.st_mode))
            __builtin_trap();
    }
    /* six different files (--checkpoint OUT.h5.part would make the finished output the checkpoint): the same
     * folder, resolved, and the same name is one file */
    char real[6][RUN_OUT_LEN + 16];
    for (int q = 0; q < 6; q++) {
        char d[RUN_OUT_LEN + 16], b[RUN_OUT_LEN + 16], *r;
        snprintf(d, sizeof d, "%s", outs[q]);
        snprintf(b, sizeof b, "%s", outs[q]);
        r = realpath(dirname(d), NULL);
        snprintf(real[q], sizeof real[q], "%s/%s", r ? r : "?", basename(b));
        free(r);
        for (int k = 0; k < q; k++)
            if (!strcmp(real[q], real[k]))
                __builtin_trap();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    enum { MAXARG = 24 };
    char *argv[MAXARG + 2];
    int argc = 0;
    argv[argc++] = strdup("dem");
    for (size_t a = 0; a <= size && argc < MAXARG;) { /* NUL-separated arguments, each in its own allocation */
        size_t b = a;
        while (b < size && data[b])
            b++;
        char *arg = malloc(b - a + 1);
        memcpy(arg, data + a, b - a);
        arg[b - a] = 0;
        argv[argc++] = arg;
        a = b + 1;
    }
    argv[argc] = NULL;
    cli c;
    char err[8192];
    int with_usage;
    int rc = cli_parse(argc, argv, &c, err, sizeof err, &with_usage);
    if (rc) {
        if (rc != EXIT_USAGE || !err[0] || strchr(err, '\n'))
            __builtin_trap();
    } else if (c.cmd == CLI_CHECK) {
        if (!path_len_ok(c.check_path) || !c.check_path)
            __builtin_trap();
    } else if (c.cmd == CLI_RUN) {
        const run_opts *o = &c.run;
        if (!path_len_ok(o->out) || !path_len_ok(o->checkpoint) || !path_len_ok(o->restart) ||
            !path_len_ok(o->scene_path) || (!o->scene_path && !o->restart) || o->device < -1 || o->device > 65535 ||
            o->stop_after < 0 || (o->precision != 0 && o->precision != DEM_FP32 && o->precision != DEM_FP64))
            __builtin_trap();
        char outp[RUN_PATH_LEN], ckp[RUN_PATH_LEN];
        int pc = run_output_paths(sc, o, outp, ckp, err, sizeof err);
        if (pc == 0)
            check_accepted(o, outp, ckp);
        else if ((pc != EXIT_USAGE && pc != EXIT_IO) || !err[0] || strchr(err, '\n'))
            __builtin_trap();
        if (list_dir() != listing)
            __builtin_trap(); /* the checks wrote or removed something */
    }
    for (int k = 0; k < argc; k++)
        free(argv[k]);
    return 0;
}
