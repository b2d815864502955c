/* run.h - `dem run`: a scene from start (or from a checkpoint) to its end, with output, checkpoints and progress. */
#ifndef DEM_RUN_H
#define DEM_RUN_H
#include "scene.h"
#include "checkpoint.h"
#include "exact_sum.h"
#include <stdio.h>

/* Exit statuses of the dem command (sysexits.h where one fits). */
enum { EXIT_RUN_FAILED = 1, EXIT_USAGE = 2, EXIT_BAD_INPUT = 65, EXIT_NO_INPUT = 66, EXIT_DEVICE = 69,
       EXIT_IO = 74 };

typedef struct {
    const char *scene_path;  /* NULL with restart: the checkpoint holds the scene */
    const char *out;         /* output file (.h5); NULL = scene name next to the scene file */
    const char *checkpoint;  /* checkpoint file; NULL = OUT without .h5 + ".ckpt.h5" */
    const char *restart;     /* continue from this checkpoint */
    int device;              /* -1: the scene's */
    int precision;           /* 0: the scene's, else DEM_FP32 / DEM_FP64 */
    int progress;            /* 1 always, 0 never, -1 when stderr is a terminal */
    long stop_after;         /* > 0: stop after this many steps (a checkpoint is written; for tests and staging) */
    const char *model;       /* NULL: the scene's normal law; else see scene_apply_model */
    int verbose;             /* 1: also the kernels launched and each rebuild's (--verbose) */
    int backend;             /* -1: the scene's, else a dem_backend_kind (--backend) */
} run_opts;

int run_scene(const run_opts *o);

/* A run split over MPI ranks (app/run_mpi.c, linked into dem with the MPI layer; docs/design.md "Runs over MPI"):
 * run.c drives it through these calls and needs no MPI itself. Every rank loads the scene and builds the whole run
 * as `whole`, which no rank starts: the scene's set-up, what the output's header reads (radii, materials, walls) and
 * each rank's part is cut from. The steps are the parts': each rank's dem_sim holds the particles of its subdomain
 * and, as ghosts, those of other ranks that can touch them; the first series row is merged from them, the frames
 * and checkpoints are written from them, slab by slab, and the report reads their step and time. Rank 0 writes the
 * output and the checkpoints and prints; every other rank is quiet. Each call is collective. */
struct output;        /* output.h */
struct overlap_watch; /* below */
typedef struct run_ranks run_ranks;
struct run_ranks {
    int rank, size;
    void *ctx;
    /* every rank's code agreed: 0 when all are 0, else the lowest; *who the lowest rank that had it */
    int (*agree)(run_ranks *r, int code, int *who);
    /* the least of every rank's v */
    long (*agree_min)(run_ranks *r, long v);
    /* message msg of rank who to every rank (msg of len bytes) */
    void (*share)(run_ranks *r, int who, char *msg, size_t len);
    /* the parts made and started (cfg: the run's device, precision, backend), each cut from its rank's whole run
     * (not started), with the state of its set-up or, where the run restarts, its part of the checkpoint ck_path,
     * whose head every rank has read into ck (NULL: a fresh start; checkpoint_read_head), each rank reading its own
     * particles and contacts; what dem_start would refuse of the whole scene said with the words of `what` (the
     * scene's path) first; dem_status, message in err */
    int (*start)(run_ranks *r, dem_sim *whole, const checkpoint *ck, const char *ck_path, const dem_config *cfg,
                 const char *what, char *err, size_t len);
    /* the series row of the state now (the run's first: dem_sample_get of one process), from the parts' own
     * particles' exact sums, merged (every rank gets it); dem_status, message in err */
    int (*sample)(run_ranks *r, dem_sample *row, char *err, size_t len);
    /* the box lo[3], hi[3] of every particle (x +- r) now, over the parts' own (every rank gets it); 0, or non-zero
     * on every rank where a rank could not read its positions */
    int (*bounds)(run_ranks *r, double box[6]);
    /* nsteps steps like dem_step_sampled, rows merged over the ranks (every rank gets them) */
    int (*step)(run_ranks *r, long nsteps, const unsigned char *want, dem_sample *rows, char *err, size_t len);
    long (*step_index)(run_ranks *r);
    /* the checkpoint of the parts' state written by rank 0 to path, gathered slab by slab of particle ids (no rank
     * holds the whole state): the file of one process (checkpoint_write_from). 0, -1 (rank 0's file failed, its
     * message in err there; the previous checkpoint kept) or -2 (a part could not be read: the words of the rank
     * that could not, in err); the same on every rank */
    int (*checkpoint)(run_ranks *r, const char *path, const scene *sc, const scene_run *run, char *err, size_t len);
    /* a frame of the output written from the parts' state, gathered slab by slab on rank 0, which writes it to o
     * (the others pass NULL): no rank holds the whole state or a whole frame. 0, -1 (rank 0's file failed) or -2 (a
     * part could not be read; the reason, that rank's, in err); the same on every rank */
    int (*frame)(run_ranks *r, struct output *o, char *err, size_t len);
    /* a frame's overlaps and stability, each part's own pairs and particles merged, into rank 0's w (the others
     * pass theirs, unused): what overlap_watch_sample of the whole run gives */
    void (*overlaps)(run_ranks *r, struct overlap_watch *w);
    /* this rank's part, the run that steps: what it records of the walls' stages (dem_stage_ends, from the start or
     * restart on; dem_servo_stats_get) is the same on every rank and the one-process run's */
    dem_sim *(*stepped)(run_ranks *r);
    /* a line on the split for the report (subdomains, ghosts, splits) */
    void (*describe)(run_ranks *r, char *buf, size_t len);
    void (*finish)(run_ranks *r);
};
int run_scene_ranks(const run_opts *o, run_ranks *r);
/* app/run_mpi.c: `dem run` under mpirun on more than one rank (run_mpi_wanted: the launcher's environment says so) */
int run_mpi_wanted(void);
int run_mpi(const run_opts *o);
/* The scene's shortest contact against its dt (dem_contact_advice_get): with info, two lines for `dem check` on out;
 * always, a warning on stderr when a contact spans fewer than DEM_MIN_STEPS_PER_CONTACT steps (`dem run` asks for it
 * unless --quiet). */
void run_contact_advice(dem_sim *s, const scene *sc, int info, FILE *out);
/* Lagged MC-strain: the mean overlap / radius at which its loop gain reaches 1 for a material (INFINITY for gamma 0),
 * and the advice: a warning on stderr where that overlap is one compactions reach; info: a line for dem check */
#define MC_LAG_CONTACTS 6 /* contacts per sphere of the estimate (a dense packing: app/run.c's derivation) */
double run_mc_lag_overlap(double gamma, double nu); /* app/run_overlap.c */
void run_mc_lag_advice(dem_sim *s, const scene *sc, const scene_run *run, int info, FILE *out);
/* the same for the particles' order in memory (dem_order_scatter) */
void run_order_advice(dem_sim *s, const scene *sc, int info, FILE *out);
/* the same for the precision's position resolution far from the origin (dem_position_resolution) */
void run_precision_advice(dem_sim *s, const scene *sc, dem_precision p, int info, FILE *out);
/* A warning on stderr when the rolling spring (effect rolling_spring) has a rolling coefficient of 0.88 or more for a
 * pair of materials: its own mode is then faster than the one the time step is sized for (docs/design.md) */
void run_rolling_advice(const scene *sc, unsigned effects);
/* A warning on stderr when the time step is above what a membrane's springs or hinges recommend (run->ts) */
void run_dt_advice(const scene *sc, const scene_run *run);

/* The overlaps of a run, measured at its frames (run_overlap.c): the largest pair overlap / smaller radius and the
 * largest mean over the touching pairs, with when; reported at the end with a warning where the contact model was
 * used beyond its range. With them the step's stability at those overlaps (dem_stability_get): the frame where it
 * came closest to the bound, warned about above DEM_STABILITY_LIMIT. */
typedef struct overlap_watch {
    int sampled;
    double largest, largest_t, mean, mean_t;
    int largest_i, largest_j;
    dem_stability stab; /* the frame of the largest ratio */
    double stab_t;
    int *list, *count;
    double *x;
    size_t cap, ncap;
} overlap_watch;
/* One frame's overlaps: the largest pair overlap / smaller radius (ties: the lowest ids i < j), its pair, the exact
 * sum of the touching pairs' overlaps and their count; over the pairs whose lower particle own selects (NULL: every
 * pair), ids named by ids[] (NULL: the run's own). A run split over ranks merges its parts' (app/run_mpi.c): the same
 * figures as one process. 0, or -1 where the frame could not be read (w's buffers kept). */
typedef struct {
    double worst;
    long wi, wj;
    exact_acc sum;
    long touching;
} overlap_frame;
int overlap_frame_scan(overlap_watch *w, dem_sim *s, const long *ids, const unsigned char *own, overlap_frame *f);
/* a frame at time t into the watch (st: its stability, NULL where it could not be had) */
void overlap_watch_add(overlap_watch *w, const overlap_frame *f, const dem_stability *st, double t);
void overlap_watch_sample(overlap_watch *w, dem_sim *s);
void overlap_watch_report(const overlap_watch *w, const scene *sc, const scene_run *run, int info);
void overlap_watch_free(overlap_watch *w);

/* Buffer length for the paths run_output_paths returns (DEM_MAX_PATH characters and more), and for the names
 * derived from them. */
#define RUN_PATH_LEN 4096
#define RUN_OUT_LEN (RUN_PATH_LEN + 16)
/* The six files a run writes: OUT, OUT.part, its XDMF and the XDMF's .part, the checkpoint and its .tmp. */
void run_output_files(const char *outp, const char *ckp, char outs[6][RUN_OUT_LEN]);
/* The output and checkpoint paths of a run (from -o / --checkpoint, or from the scene's file name), and the check of
 * everything the run will write (OUT, OUT.part, its XDMF and .xmf.part, the checkpoint and its .tmp) before it
 * starts: no path longer than DEM_MAX_PATH, none a directory, a device, pipe or socket, or the same file as an input
 * (the scene, a CSV it reads, the checkpoint restarted from): EXIT_USAGE; each output's folder must exist and be
 * writable: EXIT_IO with the system's reason. 0 when all is well. */
int run_output_paths(const scene *sc, const run_opts *o, char outp[RUN_PATH_LEN], char ckp[RUN_PATH_LEN], char *err,
                     size_t errlen);

#endif
