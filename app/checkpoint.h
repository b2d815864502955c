/* checkpoint.h - checkpoints: everything needed to continue a run bit for bit, in one HDF5 file.
 * A checkpoint is written to PATH.tmp, flushed to disk, and renamed over PATH, so that a kill at any moment leaves
 * either the previous checkpoint or the new one, never a torn file. */
#ifndef DEM_CHECKPOINT_H
#define DEM_CHECKPOINT_H
#include "scene.h"

typedef struct {
    dem_state st;
    char *scene_text;  /* the scene the run was built from */
    char *scene_path;  /* where it was (CSV paths are relative to its folder) */
    char model[32];    /* dem run --model of the run ("" = the scene's own law) */
    char order[16];    /* the particles' order the run was built in (scene_particle_order); "" in a checkpoint older
                          than that attribute, whose default order was "input" */
    double *radius;    /* [n], checked against the rebuilt scene */
    char law_state[32]; /* what the law's state per contact is where a run's effects leave two readings: "" or
                           CHECKPOINT_JKR_STATE (below) */
} checkpoint;

/* /state's law_state of a run with JKR adhesion (DEM_EFFECT_ADHESION): each contact's state is its largest contact
 * radius (common/laws/thornton_ning.h). Until 2026-12-06 such runs kept the largest overlap, in the same dataset and
 * unit, without the attribute: a restart with adhesion refuses a checkpoint without it (run.c) */
#define CHECKPOINT_JKR_STATE "jkr_largest_contact_radius"

/* A checkpoint is written to PATH CHECKPOINT_TMP_SUFFIX, flushed, then renamed over PATH. */
#define CHECKPOINT_TMP_SUFFIX ".tmp"
int checkpoint_write(const char *path, dem_sim *s, const scene *sc, const scene_run *run, char *err, size_t errlen);
/* Where a checkpoint's particles and contacts come from when no one state holds them (the ranks of a split run,
 * app/run_mpi.c): slab by slab of particle ids, so that no process holds them all. */
typedef struct {
    void *ctx;
    long n, npairs; /* the whole run's particles and contacts */
    long slab;      /* particles per slab, >= 1 */
    /* particles [a, b): *part a state of b - a particles (ids a.. as 0..) with each array's rows of them (an array
     * of groups of n rows, one per wall: each group's rows of the slab, group after group), the contacts whose lower
     * id is in [a, b) with the whole run's ids in ascending (i, j), and *radius their radii (dem_particle_radius);
     * kept by the source until its next call. 0, or -1 (the source's words in the writer's err) */
    int (*slab_get)(void *ctx, long a, long b, const dem_state **part, const double **radius);
} checkpoint_source;
/* The checkpoint of a run whose header is head (step, counts, walls, stages, MC-strain's counts, patch contacts,
 * the walls' arrays - DEM_MOVE_STAY: their sums - and each particle array's whole count, an empty one written where
 * its data is not NULL; its particle arrays' data and its contacts are not read otherwise) and whose particles and contacts are src's: the file checkpoint_write writes of
 * the whole run. s: a started run of the scene (its time, the arrays' layout). 0; -1 where the file failed (err
 * says so, the previous checkpoint kept), -2 where src did (its words in err). */
int checkpoint_write_from(const char *path, dem_sim *s, const dem_state *head, const checkpoint_source *src,
                          const scene *sc, const scene_run *run, char *err, size_t errlen);
int checkpoint_read(const char *path, checkpoint *ck, char *err, size_t errlen);
/* The same but for what grows with the run: the scene, the attributes (step, n, precision, has_*: ck->st.npairs the
 * contacts' count), the walls' positions and stages; no particle arrays, radii (ck->radius NULL), contacts or patch
 * contacts, and their values unchecked. What every rank of a split run reads first on restart (then its part). */
int checkpoint_read_head(const char *path, checkpoint *ck, char *err, size_t errlen);
/* A restart split over ranks reads no more of the checkpoint than its part (app/run_mpi.c), after the head:
 * checkpoint_read_x every particle's position (3 n doubles, an fp32 run's widened: what the split is cut by);
 * checkpoint_read_part the state of the particles of ascending global ids keep[0..m): head's header, each array's
 * rows of them, the contacts with both ends among them (renumbered to their places in keep, ascending i, then j),
 * their radii into radius[m], read slab by slab of ids; s, a started run of the part, gives the arrays' layout. Each
 * number read is checked finite as checkpoint_read checks it (the same words, the whole file's element). 0, or
 * non-zero with err (and part freed). */
int checkpoint_read_x(const char *path, const checkpoint *head, double *x, char *err, size_t errlen);
int checkpoint_read_part(const char *path, const checkpoint *head, dem_sim *s, long m, const long *keep,
                         dem_state *part, double *radius, char *err, size_t errlen);
void checkpoint_free(checkpoint *ck);
/* restart_scene.c: whether the scene now may continue the checkpoint ck (read from ck_path) - the scene ck was run
 * with but for time.duration, the output section and the stages a wall has not finished; 1 with err naming the first
 * field that differs otherwise, and its line */
int restart_scene_check(const scene *now, const checkpoint *ck, const char *ck_path, char *err, size_t errlen);
#endif
