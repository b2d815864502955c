/* cli.h - the dem command line, parsed whole before anything is opened: every option known, every value
 * range-checked, every path non-empty and short enough that no derived name (.part, .xmf, .ckpt.h5, .tmp) is cut. */
#ifndef DEM_CLI_H
#define DEM_CLI_H
#include "conform.h"
#include "run.h"
#include <stddef.h>

/* Longest path accepted on the command line (characters); derived names add at most 13. */
#define DEM_MAX_PATH 4000

typedef enum { CLI_HELP, CLI_VERSION, CLI_DEVICES, CLI_CHECK, CLI_RUN, CLI_HASH, CLI_CONFORM } cli_command;

typedef struct {
    cli_command cmd;
    const char *check_path; /* CLI_CHECK */
    const char *check_model; /* CLI_CHECK: --model, NULL = the scene's */
    int check_probe;         /* CLI_CHECK: --probe */
    int check_device;        /* CLI_CHECK: --device, -1 = the scene's */
    int check_precision;     /* CLI_CHECK: --precision, 0 = the scene's */
    run_opts run;           /* CLI_RUN */
    const char *hash_path;  /* CLI_HASH */
    conform_opts conform;   /* CLI_CONFORM */
} cli;

extern const char cli_usage[];

/* s as it may appear in a one-line message: control characters as \xNN, cut to about len - 4 bytes with "..."
 * (a file name can hold a newline; a message cannot). Returns buf. */
#define CLI_SHOW_LEN 1100
const char *cli_show(const char *s, char *buf, size_t len);

/* 0 when parsed; else EXIT_USAGE with a one-line reason in err, and *with_usage set when the usage text should
 * follow it. argv is not copied: c points into it. */
int cli_parse(int argc, char **argv, cli *c, char *err, size_t errlen, int *with_usage);
#endif
