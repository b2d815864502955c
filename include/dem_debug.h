/* dem_debug.h - what the tests, the benchmarks and the dem command read of libdem's internals: the fields that
 * follow the storage (neighbour rows, pair records, contact history, cells, flags), the rows' and the grid's sizes,
 * the kernels launched and their times, and the build's provenance. Not installed, and not exported by libdem.so
 * (no DEM_API: the shared library hides them); programs built in this tree link the static library, which has them.
 * Their layout may change with any version. The error rule of dem.h holds here too.
 */
#ifndef DEM_DEBUG_H
#define DEM_DEBUG_H
#include "dem.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The fields the library keeps for itself, in the numbering of dem.h's (dem_get_raw, dem_field_bytes): their layout
 * follows the storage (row slots, pair records in storage order, common/dem_layout.h's records) and changes with it. */
enum {
    DEM_FIELD_X_BUILD = 5,          /* positions at the last neighbour build: real[3n] */
    DEM_FIELD_NBR_COUNT = 6,        /* int[n] */
    DEM_FIELD_NBR_LIST = 7,         /* int[slots]: the rows packed one after the other, row i at
                                       [start[i], start[i] + count[i]) (DEM_FIELD_NBR_START), sorted by partner id
                                       (ids of dem_start); slots (dem_neighbor_capacity) >= start[n] */
    DEM_FIELD_HIST = 8,             /* real[3*pairs]: elastic tangential force per listed pair [N], pairs numbered in the
                                       order of the particles' storage (each pair by the one stored first, in its row
                                       order: host/core/reorder.c; the ids' order unless dem_config.reorder moved them);
                                       empty without friction */
    DEM_FIELD_WALL_HIST = 9,        /* real[3*n*nwalls]; empty without friction */
    DEM_FIELD_CELL_START = 11,      /* int[dem_cell_count() + 1] (the buffer may hold more, which mean nothing) */
    DEM_FIELD_CELL_PARTICLES = 12,  /* int[n] */
    DEM_FIELD_FLAGS = 13,           /* int[FLAG_COUNT] (common/dem_layout.h) */
    DEM_FIELD_WALL_REAL = 14,       /* real[11*nwalls] (common/dem_layout.h W_*) */
    DEM_FIELD_TOUCH = 15,           /* unsigned char[pairs]: 1 where the pair touched in the last step, one byte per
                                       listed pair, numbered like PAIR_RECORDS and HIST */
    DEM_FIELD_WALL_MASK = 16,       /* unsigned[n]: bit k set where the particle touched wall k in the last step */
    DEM_FIELD_MC_FORCE = 19,        /* real[slots]: MC-strain elastic normal force per row slot (indexed like
                                       NBR_LIST; the device keeps one per pair, spread over both slots when read)
                                       [N]; mc_strain only */
    DEM_FIELD_MC_WALL_FORCE = 20,   /* real[n*nwalls]: the same per particle-wall slot [N]; mc_strain only */
    DEM_FIELD_MC_DISP = 21,         /* real[>= slots]: MC-strain displacement induced at each row slot's contact [m] */
    DEM_FIELD_MC_WALL_DISP = 22,    /* real[n*nwalls]: the same per particle-wall slot [m] */
    DEM_FIELD_PAIR_RECORDS = 23,    /* real[7*pairs]: each touching pair's force on its lower id (common/dem_layout.h
                                       PR_*), one record per listed pair, numbered like HIST (dem_contacts_get
                                       reads them) */
    DEM_FIELD_IN_START = 24,        /* int[n+1]: where each particle's incoming pairs (partners stored before it) start
                                       in DEM_FIELD_IN_PAIR */
    DEM_FIELD_WALL_PF = 25,         /* real[3*n*nwalls]: the force wall k exerts on particle i at [k*n + i] [N];
                                       kept only by runs with dem_config.contacts or a servo wall, else empty */
    DEM_FIELD_IN_PAIR = 26,         /* int[pairs]: the pair record of each incoming pair: in_start[i] + g for the g-th
                                       partner stored before i in its row. IN_START and the pair-sized fields are in
                                       storage order (the ids' unless dem_config.reorder moved the particles).
                                       The pair-sized fields (HIST, TOUCH, PAIR_RECORDS, IN_PAIR) hold the pairs
                                       allocated, which grow at rebuilds: take dem_field_bytes just before each read;
                                       entries beyond the pairs listed (in_start[n]) hold nothing meaningful */
    DEM_FIELD_NBR_START = 28,       /* int[n+1]: where each particle's row starts in NBR_LIST (the exclusive prefix sum
                                       of NBR_COUNT; start[n] the slots in use) */
    DEM_FIELD__COUNT = 30           /* every field, public and internal, is below this */
};

int dem_neighbor_capacity(const dem_sim *s);  /* slots held by the current rows, all rows together (NBR_LIST) */
/* Cells the last binning used (DEM_FIELD_CELL_START holds one more entry); before dem_start, those the particles'
 * positions hold. */
int dem_cell_count(const dem_sim *s);
/* The binning grid of a started run: its lower corner [m], 1 / cell size [1/m] (as the kernels get it, before the
 * cast to the run's precision) and the domain's cells per axis. Cell of a position x along an axis:
 * floor((x - lo) * inv_cell), in the run's precision. */
int dem_grid_get(const dem_sim *s, double lo[3], double *inv_cell, int ncell[3]);
/* The cells the last binning used: along each axis count[d] cells of that grid from first[d] on, the particles'
 * bounding box (common/binning.h); cell (cx, cy, cz) of the grid is cell index
 * ((cz - first[2]) * count[1] + cy - first[1]) * count[0] + cx - first[0] of DEM_FIELD_CELL_START. */
int dem_grid_cells(const dem_sim *s, int first[3], int count[3]);
/* Per-kernel seconds when the environment has DEM_PROFILE set (OpenCL only); count 0 otherwise. */
int dem_kernel_times(dem_sim *s, const char ***names, const double **seconds, int *count);
/* The bytes of every buffer kernel k (an index of dem_kernel_times' names) is given, as now allocated: what one launch
 * would move if it touched each byte once (make bench divides it by the kernel's time: a bandwidth to set against
 * the device's copy rate). */
double dem_kernel_bytes(const dem_sim *s, int k);
/* dem_kernel_bytes buffer by buffer: the first max of kernel k's buffers, each one's argument name (as the kernel's
 * source names it) and bytes as now allocated, in argument order; returns how many buffers it is given (0 before
 * dem_start). */
int dem_kernel_buffers(const dem_sim *s, int k, const char **names, double *bytes, int max);
/* room for every kernel's buffers today (contact_forces has 36; tests/test_api.c checks each kernel's count) */
#define DEM_KERNEL_BUFFERS_MAX 64
/* The work items kernel k (an index of dem_kernel_times' names) would be launched with now (its DEM_ITEMS_ rule at the
 * run's present sizes; make bench sets it against the device's compute units). 0 before dem_start. */
long dem_kernel_item_count(const dem_sim *s, int k);
/* The kernels the last step launched, in order, without a rebuild's (rebuild = 0), or those of the last neighbour
 * rebuild (rebuild = 1), as "name, name, N x (name, name), ..." (an iteration's pair once, with its count).
 * Returns the number of launches (0 before the first step). */
int dem_kernel_sequence(const dem_sim *s, int rebuild, char *buf, size_t len);
/* Whether the last step (rebuild = 0) or the last neighbour rebuild (rebuild = 1) launched the kernel of that name
 * (the whole name: integrate_kick is not integrate_kick_drift). */
int dem_kernel_launched(const dem_sim *s, int rebuild, const char *name);
/* A motion stage's end (dem_stage_ends): which wall and stage (an index into its dem_wall.stages), the step at which
 * it ended (the first step of the next), and why: DEM_STAGE_END_DURATION (its duration ran out), _FORCE (until_force:
 * value is the normal force [N] the particles exerted in the step before), _DISTANCE (until_distance: value is the
 * distance [m] from where the stage began) or _DENSITY (until_density: value is the relative density). */
enum { DEM_STAGE_END_DURATION, DEM_STAGE_END_FORCE, DEM_STAGE_END_DISTANCE, DEM_STAGE_END_DENSITY };
typedef struct {
    int wall, stage, why;
    long step;
    double value;
} dem_stage_end;
#define DEM_STAGE_LOG 256
/* The stage ends since dem_start or the last dem_state_set, counted from 0 in the order they happened: returns
 * their count, and when 0 <= k < count puts the k-th in *e (only the last DEM_STAGE_LOG are kept: an older k
 * leaves *e with wall -1). The dem command logs them after each stretch of steps. */
long dem_stage_ends(const dem_sim *s, long k, dem_stage_end *e);
/* Particle i's position as it was added (dem_add_particle: the scene's, before any step) [m]; DEM_ERR_ARG for no
 * such particle. dem check measures from it how far a moving wall is from the particles. */
int dem_particle_added_position(const dem_sim *s, int i, double x[3]);
/* Provenance of a started run's arithmetic: the library version, the compiler and numeric flags of the host code and
 * the reference, and for OpenCL the device, driver and the program's build options (with the source hash). */
const char *dem_build_info(dem_sim *s);

#ifdef __cplusplus
}
#endif
#endif /* DEM_DEBUG_H */
