/* conform.h - `dem hash` and `dem conform`: the state hash of a checkpoint, and the conformance set (every shipped
 * scene x contact model x precision of docs/state_hashes.txt, 150 steps each) run on a device and compared with the
 * recorded reference. */
#ifndef DEM_CONFORM_H
#define DEM_CONFORM_H
#include <stddef.h>

/* The datasets of a checkpoint's dynamic state a hash covers, in this order, each where the checkpoint has it:
 * positions, velocities, spins, forces, contact histories, wall forces, MC-strain forces, and the contact law's
 * states (a law with memory); then those added after docs/state_hashes.txt was recorded (the rolling springs), which
 * count only where they hold values: a checkpoint lists a gated array empty in a run without its effect, and such a
 * run hashes as it did before. */
#define CONFORM_DATASETS "x", "v", "w", "force", "pair_hist", "wall_force", "pair_mc_fn", "pair_law", "wall_law"
#define CONFORM_DATASETS_LATER "pair_rspring", "wall_rspring"

/* The state hash of checkpoint `path` as 16 hex digits into hex[17]: 64-bit FNV-1a over each dataset of
 * CONFORM_DATASETS present under /state - its name, its element size and count, then its values as stored
 * (little-endian, the checkpoint's own precision). Two runs hash equal exactly when those arrays are bit for bit
 * equal (up to a collision: 2^-64 per pair). 0, or -1 (not a checkpoint) or -2 (cannot be opened) with a message in
 * err. */
int conform_hash_file(const char *path, char hex[17], char *err, size_t errlen); /* -2: cannot be opened */

typedef struct {
    int device;        /* --device N; -1 = dem run's default ($DEM_DEVICE, else 0) */
    int precision;     /* 0 both, else DEM_FP32 / DEM_FP64 */
    int reference;     /* 1: run the reference backend instead of OpenCL (--backend reference) */
    const char *table; /* --table FILE; NULL = docs/state_hashes.txt of the source folder */
    const char *only;  /* --only SCENE: that scene's lines alone */
} conform_opts;

/* Runs the set (each line as its own `dem run` process, so that one failing run does not end the others), prints
 * one table line per run and a summary to stdout. Exit status: 0 every hash equal (and every refusal refused), 1 any
 * difference, 2 no line selected, 65 a malformed table line, 66 the table or one of its scenes missing, 69 no such
 * device, 128 + N stopped by signal N (the summary then says how many runs were compared). self: this program's
 * path, to run `dem run`. */
int conform_run(const conform_opts *o, const char *self);
#endif
