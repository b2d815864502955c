/* sim.h - internal state of a simulation and what the driver's files share. The driver (host/core/): sim.c (the
 * object, particles, materials), mesh_elements.c, walls.c, effects.c (the set-up), sim_setup.c (validated and packed
 * at dem_start), step_loop.c (dem_start, dem_step), rebuild.c (the neighbour rows), fields.c (the callers' reads),
 * state.c (dem_state), reorder.c and particle_order.c (the storage order), diagnostics.c (errors, trace, memory). */
#ifndef DEM_SIM_H
#define DEM_SIM_H
#include "dem.h"
#include "dem_debug.h" /* dem_stage_end */
#include "backend.h"
#include <math.h>

/* The automatic neighbour skin (dem_config.skin 0; rebuild.c's skin_choose): between LO and HI x the smallest radius
 * (HI sizes the cells); R / B of its cost model, measured on a settled bed of 1e5 spheres on PoCL (2 cores): a rebuild
 * cost 4.5 steps, and 0.25 r_min less skin saved 13 % of the contact kernels' time (docs/design.md "The neighbour
 * skin"); rows that lasted PROBE steps are rebuilt to try a smaller skin. */
#define DEM_SKIN_AUTO_LO 0.05
#define DEM_SKIN_AUTO_HI 0.3
#define DEM_SKIN_COST_RATIO 8.7
#define DEM_SKIN_PROBE 200

/* The parts of a simulation, one job each (struct dem_sim below holds one of each). */

/* Membranes and riders, by particle index: springs, triangles and the pressure on them, hinges, patches, riders
 * (mesh_elements.c, host/mesh/attach.c) */
struct sim_mesh {
    int nsprings, spring_cap;
    int *spring_ij;      /* [2 * nsprings] */
    double *spring_kr;   /* [3 * nsprings]: k, rest (< 0: at the start), gamma */
    int ntri, tri_cap;
    int *tri;            /* [3 * ntri] */
    double pressure;     /* [Pa] on every triangle (DEM_EFFECT_PRESSURE); the start of the schedule: */
    int npstages;
    dem_pressure_stage pstages[DEM_MAX_STAGES];
    double pressure_now; /* of the last force computation */
    int nhinges, hinge_cap;
    int *hinge;          /* [4 * nhinges] */
    double *hinge_k;     /* [3 * nhinges]: kel, kdiss, theta0 (NAN: from the initial positions) */
    int npatch, patch_cap;
    int *patch;          /* [npatch]: triangles that spheres touch as surfaces (dem_add_patches) */
    int natt, att_cap;
    int *att;            /* [2 * natt]: particle, wall it rides on (dem_attach_to_wall; host/mesh/attach.c) */
};

/* The walls' motion in a run (walls.c): where each wall is, its stage, its servo */
struct sim_motion {
    double pos[DEM_MAX_WALLS][3];     /* wall reference point now [m] */
    double servo_v[DEM_MAX_WALLS][3]; /* the velocity of each wall in a servo stage, this step [m/s] */
    dem_servo_stats servo[DEM_MAX_WALLS]; /* how each wall's latest servo stage went (.held: dem_servo_stats_get) */
    double servo_sum[DEM_MAX_WALLS];       /* the normal force summed over its last tenth so far [N] */
    double servo_err[DEM_MAX_WALLS];       /* its force error in the step before [N] */
    int servo_walls;                       /* a wall has a servo stage: the sums are due every step (dem_start) */
    long stage_steps[DEM_MAX_WALLS][DEM_MAX_STAGES];
    int stage_cur[DEM_MAX_WALLS];          /* each wall's current motion stage (nstages: past the last) */
    long stage_first[DEM_MAX_WALLS];       /* the step it began */
    double stage_from[DEM_MAX_WALLS][3];   /* the wall's position then [m] */
    dem_stage_end stage_log[DEM_STAGE_LOG]; /* the last stage ends, a ring by their count (dem_stage_ends) */
    long stage_log_n;                      /* stage ends since dem_start or the last restore */
    int density_die[DEM_MAX_WALLS];        /* until_density: the die (cylinder) and the facing punch of each wall with */
    int density_other[DEM_MAX_WALLS];      /* such a stage (sim_validate), -1 for the others */
    double particle_volume;                /* sum of 4/3 pi r^3 [m^3] (sim_validate) */
    void *table;                           /* packed wall table uploaded each step */
};

/* The storage order (host/core/reorder.c, particle_order.c) */
struct sim_order {
    int *source, source_n; /* after dem_sort_particles: each particle's id before it (the first source_n) */
    /* dem_config.reorder (host/core/reorder.c): times the particles were stored anew. Once they were, the host's
     * per-particle arrays of dem_sim follow the storage order, and setup.sid / setup.order map places to the ids of
     * dem_start and back (sim_api, sim_dev). */
    long count;
    int hold;      /* 1: rebuilds keep the storage order (dem_state_set) */
    int reordered; /* the particles were stored anew since the rows were built: OLD_SLOT holds where they were */
    double ref;    /* the storage's mean spacing of neighbours in memory when last looked at (reorder.c) [m] */
};

/* The neighbour and patch rows (rebuild.c): their capacities, the rebuilds, the skin */
struct sim_rows {
    int maxn;            /* slots of the current neighbour rows (all rows together) */
    long rebuilds;
    int maxp, maxv;      /* capacities of the patch rows (patch_contacts.h), grown on overflow */
    double reach;        /* patch search reach [m], widened when an edge reaches it */
    /* the neighbour skin (docs/design.md "The neighbour skin"): the range it is chosen in at each rebuild (equal ends
     * when dem_config.skin fixes it), the current rows' skin, the step they were built (-1: none yet), and the rows'
     * extra reach under MC-strain's contact distance [m] */
    double skin_lo, skin_hi, skin_now, skin_extra;
    long skin_built;
};

/* The multi-contact laws' settings and MC-strain's iteration counts (effects.c, step_loop.c) */
struct sim_mc {
    unsigned stress_conv; /* DEM_MCS_* bits; DEM_MCS_DEFAULT unless set (compiled in with mc_stress: sim_pack) */
    int max_iter;         /* MC-strain: 0 lagged, else the iteration cap */
    double tol;           /* MC-strain: relative force tolerance of the iteration */
    double reach;         /* MC-strain contact distance factor (1: geometric contacts only) */
    dem_mc_stats stats;
};

/* The kernels launched (ids, dem_kernel_names): by the last step, without a rebuild's, and by the last rebuild
 * (diagnostics.c) */
struct sim_trace {
    unsigned char step[DEM_TRACE_MAX], rebuild[DEM_TRACE_MAX];
    int nstep, nrebuild;
    int rebuild_at, rebuild_len; /* the current step's rebuild within the core's trace */
};

/* The binning domain (dem_set_domain; sim_setup.c rounds it to whole cells) */
struct sim_domain {
    double lo[3], hi[3];
    double grid_hi[3], grid_cell; /* upper corner of the binning grid (lo + whole cells) and its cell size [m] */
    int given;
};

/* Where the run is (step_loop.c) */
struct sim_run {
    int started;
    long step;
    long force_step;   /* step index of the positions the forces are computed at (walls, pressure schedule) */
    int wall_sums_due; /* this step's force stages sum the force each wall received (dem_step) */
    int sample_row;    /* >= 0: this step is sampled into that row of the series ring (series.h) */
    int kick_pending;  /* the last step's second kick is left to the next step's first launch
                          (integrate_kick_kick_drift): only inside a dem_step or dem_step_sampled call, never after
                          its last step */
    int one_pass;      /* this step's particle contacts in one pass (contact_rows, dem_config.one_pass): a step whose
                          pair records nothing reads (step_loop.c) */
    int forces_due;    /* started by sim_start_deferred: the start's forces not computed yet (sim_start_forces) */
    int halo_agreed;   /* a split run (halo_hook): this step's failure was agreed at a meeting of the ranks */
    int halo_learned;  /* ... and this rank's own step had not failed: another rank's did (its caller reports that
                          rank's words, app/run_mpi.c) */
};

/* The texts handed to the caller (diagnostics.c, sim_fail) */
struct sim_report {
    char err[4096];
    int err_particle; /* the particle a DEM_ERR_DOMAIN error named (dem_error_particle), -1 none */
    long mdr_capped_step, mdr_capped_particle; /* MDR: the first step of this process at which a particle's apparent
                                                  radius met the law's cap, and that particle (the whole run's id);
                                                  -1 none (dem_mdr_capped; carried over a split: sim_run_record) */
    char desc[1024];
    char build[4096];
};

/* Host scratch of dem_energy / dem_sample_get, kept between calls (host/physics/energy.c) */
struct sim_scratch {
    void *buf;
    size_t bytes;
};

struct dem_sim {
    /* description, double precision, as given */
    int n, cap;
    double *x, *v, *w, *radius;
    int *mat;
    unsigned *pflags;
    unsigned char *ghost; /* per particle, 1: another rank's (sim_set_ghosts); NULL: none */
    double whole_volume;  /* a part's (sim_part_copy): the whole scene's spheres' volume [m^3]; 0: not a part */
    /* a part of a run split over ranks (host/mpi/halo.c): called within the step where a value its ghosts got wrong
     * (their partners outside the halo missing) is about to be read, to put the owners' values into them, or where a
     * decision needs every rank's view (SIM_HOOK_*). Each call is a meeting of every rank that first agrees on any
     * rank's failure, so a step that fails on one rank ends on all. NULL in a run that is not split. */
    int (*halo_hook)(dem_sim *s, void *ctx, int event, int *value);
    void *halo_ctx;
    /* a run split over the ranks of an MPI communicator by a program (dem_create_mpi, host/mpi/api.c): this dem_sim
     * is the whole set-up, never started itself; from dem_start on, split_ops (the MPI layer's) do the run's work
     * on this rank's part, split_started set. NULL in any other run: libdem.a calls through them, needing no MPI. */
    const long *said_ids; /* a part of a split run: each particle's id in the whole run, the one its step's messages
                             and dem_error_particle name (host/mpi/split.c); NULL: its own */
    const struct sim_split_ops *split_ops;
    void *split_ctx;
    int split_started;
    double *body;        /* per particle: explicit mass [kg] and moment of inertia [kg m^2]; 0 = from the material
                            (sim_mass, sim_inertia) */
    double rmin, rmax;
    int nmat;
    dem_material mats[64];
    unsigned char mat_apart[64]; /* 1: a membrane's material, whose particles do not touch each other (PM_APART) */
    dem_material_pair pair_props[64][64]; /* dem_set_material_pair's values, where pair_set says so; both orders */
    unsigned char pair_set[64][64];
    int nwalls;
    dem_wall walls[DEM_MAX_WALLS];
    double gravity[3];
    double dt;
    unsigned effects; /* DEM_EFFECT_* mask; DEM_EFFECT_CLASSICAL unless set */
    struct sim_mesh mesh;
    struct sim_domain domain;
    struct sim_mc mc;
    /* the run */
    dem_config cfg;
    dem_setup setup;
    void **setup_mem; /* the host arrays setup points to (sim_pack), freed when packed again or destroyed */
    int nsetup_mem, setup_mem_cap;
    const dem_backend_ops *ops;
    dem_backend *be;
    struct sim_run run;
    struct sim_motion motion;
    struct sim_order order;
    struct sim_rows rows;
    struct sim_trace trace;
    struct sim_report report;
    struct sim_scratch scratch;
    exact_acc row_acc[SE_STRIDE]; /* the last series row's exact sums from the ring (energy.c, sim_row_exact) */
};

/* sim.c: a particle's mass and moment of inertia (explicit, or a solid sphere of its material and radius) */
double sim_mass(const dem_sim *s, int i);
double sim_inertia(const dem_sim *s, int i);

/* step_loop.c: dem_start in two: everything but the forces of the start (the run's buffers, its first rebuild), then
 * those forces, once, before any step. A part of a run split over ranks is started so (host/mpi/halo.c), its halo
 * made between the two, so that the start's forces hold the ranks' meetings as a step's do (MC-stress's traces,
 * MDR's rows, MC-strain's iteration) and its own particles get one process's forces */
int sim_start_deferred(dem_sim *s, const dem_config *c);
int sim_start_forces(dem_sim *s);
/* sim_setup.c */
int sim_validate(dem_sim *s);
int sim_pack(dem_sim *s);            /* fills s->setup and the host arrays it points to */
void sim_setup_free(dem_sim *s);     /* frees those arrays */
/* The binning domain of s's particles before it is cut into cells (given, or their padded bounding box with r_max
 * rmax), their bounding box into pmin, pmax: what dem_start takes, from the set-up alone (app/run_mpi.c gives the
 * whole scene's to every part without starting it) */
void sim_domain_bounds(const dem_sim *s, double rmax, double lo[3], double hi[3], double pmin[3], double pmax[3]);
int sim_has_servo(const dem_sim *s); /* a wall has a servo stage, or one that ends at a force (both read every step's) */
/* The stage wall k is in at the current step (-1 after its last), its first step in *first. */
int sim_stage_now(const dem_sim *s, int k, long *first);
double sim_relative_density(const dem_sim *s, int k); /* walls.c: punch k's relative density now (until_density) */
double sim_particle_volume(const dem_sim *s); /* walls.c: the spheres' volume, an exact sum rounded once [m^3] */
/* fields.c: the per-particle field f set whole from vals, in the callers' order as dem_get_field gives it, in the
 * run's precision (a value of an fp32 run must be a float widened): app/run_mpi.c's test hook that makes a rank's
 * particle not a number */
int sim_set_field(dem_sim *s, dem_field f, const double *vals);
/* state.c: field f whole as stored (storage order), malloc'd, its size in *bytes; a failure into *e (0 before) */
void *sim_field_stored(dem_sim *s, dem_field f, size_t *bytes, int *e);
/* The points of a step where dem_sim.halo_hook is called: after a force stage of an effect (*value: its gate; MC-stress's
 * traces, MDR's rows), after each evaluation of MC-strain's displacements, at MC-strain's convergence test (*value:
 * this rank's "a force still moved", replaced by the run's), and at the step's end. A rank whose own step fails
 * calls it once more, SIM_HOOK_FAILED with *value its code, and returns: the other ranks meet it at their next point
 * (the step's end at the latest) and fail too. A call that returns non-zero has agreed that code on every rank. */
enum { SIM_HOOK_STAGE = 0, SIM_HOOK_MC_DISP = 1, SIM_HOOK_MC_PENDING = 2, SIM_HOOK_FAILED = 3, SIM_HOOK_STEP_END = 4 };
/* part.c: MC-strain's displacements, kept per row slot (D_i,c: particle i's at its contact with partner j, mc_strain.h),
 * as a list in the callers' ids: sim_mc_disp_get gives every row slot's (i, j, D) (arrays malloc'd, *count long);
 * sim_mc_disp_set writes the entries given, skipping a pair no row holds. What a run split over ranks puts into its
 * ghosts' slots from their owners (host/mpi/halo.c). */
int sim_mc_disp_get(dem_sim *s, long *count, int **pi, int **pj, double **d);
int sim_mc_disp_set(dem_sim *s, long count, const int *pi, const int *pj, const double *d);
/* state.c: how the saved array called name lies in a state of s's run: DEM_MOVE_P (per elements per particle),
 * DEM_MOVE_G (groups of n items of per elements each: one per wall), DEM_MOVE_STAY (not by particle: the walls'
 * sums); -1 for no such array. What a run split over ranks needs to gather a state and cut it (host/mpi/state.c). */
int sim_state_array_layout(const dem_sim *s, const char *name, int *per);
/* walls.c: wall k's exact sums of the last step that made them (WP_* of dem_layout.h), not rounded, over the
 * particles the run holds but its ghosts: the ranks of a split run merge them (host/mpi/mpi_layer.h) */
int sim_wall_sums_exact(dem_sim *s, int wall, exact_acc acc[WP_STRIDE]);
/* walls.c: every wall's sums (DEM_FIELD_WALL_FORCE, DEM_FIELD_WALL_NORMAL_FORCE) set from exact ones,
 * acc[WP_STRIDE * wall + WP_*], rounded as the device rounds them (common/wall_forces.h): what the ranks of a split
 * run set after merging theirs, so that a servo or a stage's end reads the one-process force (host/mpi/halo.c) */
int sim_wall_sums_set(dem_sim *s, const exact_acc *acc);
/* part.c: what a run records of the steps it took beyond its state (each servo stage's record, the stage ends' log,
 * the first and last step MC-strain's iteration hit its cap, the first MDR radius held at its cap), carried from a rank's run to the run of its next part
 * when a split run is split anew (app/run_mpi.c) */
typedef struct {
    dem_servo_stats servo[DEM_MAX_WALLS];
    double servo_sum[DEM_MAX_WALLS], servo_err[DEM_MAX_WALLS];
    dem_stage_end log[DEM_STAGE_LOG];
    long log_n;
    long mc_first_capped, mc_last_capped;
    long mdr_capped_step, mdr_capped_particle;
} sim_run_record;
void sim_run_record_get(const dem_sim *s, sim_run_record *r);
void sim_run_record_set(dem_sim *s, const sim_run_record *r);
/* part.c: in a run of part of a scene (a rank's of a run split over MPI ranks: sim_part_copy), before dem_start,
 * which particles are ghosts (copies of other ranks' particles: left out of the walls' and the series rows' sums,
 * DEM_HAS_GHOSTS) */
int sim_set_ghosts(dem_sim *s, const unsigned char *ghost);
/* part.c: where v is, or would go, in the ascending ids[0..n) (the first place whose id is >= v): a part's held
 * global ids searched (host/mpi/, app/checkpoint.c) */
long sim_id_from(const long *ids, long n, long v);
/* A new run, not started, with the set-up of src (not started either) and the particles of it that keep selects
 * (keep[i] != 0, in their order, so that ids keep the whole scene's order), the whole scene's volume kept for
 * until_density (host/mpi/split.c: a split anew reads no scene file and starts no whole run); refused for a scene
 * with membranes or riders (their tables name particles by index); NULL with the reason in err */
dem_sim *sim_part_copy(const dem_sim *src, const unsigned char *keep, char *err, size_t len);
/* contacts.c: dem_contacts_get's order of two dem_contact, a qsort comparator: ascending i, then j (a wall's -1 - w:
 * ascending w among the walls, which are sorted apart from the pairs); app/run_mpi.c orders a gathered frame by it */
int sim_contact_order(const void *a, const void *b);
/* part.c: a split run's messages made on the device (common/halo.h). sim_halo_set gives the particles this rank sends
 * (send[0..nsend): the callers' ids, one message row each, repeats allowed) and its ghosts (recv[0..nrecv)), after
 * dem_start; sim_halo_pack copies the sent particles' rows into out (nsend rows of HALO_W reals of the run's
 * precision: real_size bytes each); sim_halo_unpack copies the rows in (nrecv rows, the same layout) into the
 * ghosts. Plain copies: a ghost holds its owner's bits. */
int sim_halo_set(dem_sim *s, int nsend, const int *send, int nrecv, const int *recv);
int sim_halo_pack(dem_sim *s, void *out);
int sim_halo_unpack(dem_sim *s, const void *in);
/* The same for the registry buffer id (BUF_*) of width <= HALO_W reals per particle, in rows of width reals:
 * MC-stress's trace, MDR's particle row (host/mpi/halo.c) */
int sim_halo_pack_rows(dem_sim *s, int id, int width, void *out);
int sim_halo_unpack_rows(dem_sim *s, int id, int width, const void *in);
/* part.c: the check of the moves of a started part (its ghosts marked: DEM_HAS_GHOSTS), on the device (common/halo.h
 * move_mark, move_check). mark != 0: the positions now become where the particles were at the split and before the
 * next step, out 0 0; else out[0] is the largest distance an own particle has moved since the mark and out[1] its
 * largest move since the last call (a NaN, where a position is one), and the positions now are the next call's
 * last. Reads 2 reals per block of DEM_REDUCE_BLOCK particles, not the positions. */
int sim_move_check(dem_sim *s, int mark, double out[2]);
/* energy.c: the exact sums (SE_* of dem_layout.h) behind the last series row made from the device's ring, before
 * they were rounded: over the run's own particles (its ghosts left out). Runs split over ranks merge them. */
void sim_row_exact(const dem_sim *s, exact_acc acc[SE_STRIDE]);
/* energy.c: dem_sample_get of the state now, but its energies and contact counts as exact sums (SE_*) over the run's
 * own particles (its ghosts left out; the pairs of their lower stable id): the first series row of a run split over
 * ranks, merged (app/run_mpi.c), is one process's dem_sample_get. The walls' sums are the run's (merged at a split
 * run's start, host/mpi/halo.c). */
int sim_sample_own(dem_sim *s, dem_sample *out, exact_acc acc[SE_STRIDE]);
/* Each wall's stage state from the step alone, as if every stage ran its full duration (a start at step 0, a
 * checkpoint written before stages could end early). */
void sim_stages_from_step(dem_sim *s);
/* One step (dem_step's body); wall_sums: sum the force each wall received in it (always under a servo); sample_row
 * >= 0: a sampled step, whose series row goes to that row of the device's ring (common/series.h). */
int sim_step_once(dem_sim *s, int wall_sums, int sample_row);
void sim_pack_walls(dem_sim *s);     /* wall positions and velocities of the current step into s->motion.table */
/* The kernels' wall type of w (dem_layout.h WALL_*) and its W_RADIUS and W_HEIGHT (host/physics/wall_overlap.c) */
int sim_wall_table(const dem_wall *w, double *radius, double *height);
/* dem_wall_overlap for a contact that may hold across a gap of up to gap [m] (a JKR contact: contact_geometry.h,
 * wall_geometry_gap); gap 0 is dem_wall_overlap */
double sim_wall_overlap_gap(const dem_wall *w, const double point[3], const double x[3], double r, double gap,
                            double n[3]);
void sim_wall_velocity(const dem_sim *s, int k, double v[3]); /* wall k in its stage of the current step [m/s] */
int sim_fail(dem_sim *s, int code, const char *fmt, ...);
/* sim.c: 0 while the set-up may change, else DEM_ERR_STATE (reported) */
int sim_not_started(dem_sim *s);
/* sim.c: DEM_ERR_STATE for a call that reads a started run, on a run not started ("dem_start first") or split over
 * MPI ranks by dem_create_mpi (its parts are the ranks': the calls that work on it are named) */
int sim_need_started(dem_sim *s);
/* The run whose records a getter reads: s, or on a started run split by dem_create_mpi this rank's part (while it
 * holds one: not after a failed step) - the run's own for what every rank's part has alike (stages, servos, MC-strain
 * counts), this rank's for its device (bytes, rebuilds, skin, description) */
const dem_sim *sim_stepped(const dem_sim *s);
/* fields.c: the reals per particle of a public per-particle field (DEM_FIELD_X ... DEM_FIELD_RADIUS), 0 for any
 * other (the walls', the library's own) */
int sim_field_per_particle(dem_field f);
/* What a run split by dem_create_mpi does in the calls of dem.h that work on it (host/mpi/api.c): collective over
 * its communicator, each 0 or a dem_status set with sim_fail (the same on every rank) */
typedef struct sim_split_ops {
    int (*start)(dem_sim *s, const dem_config *c);
    int (*step)(dem_sim *s, long nsteps, const unsigned char *want, dem_sample *rows);
    int (*sample)(dem_sim *s, dem_sample *row);
    int (*state_get)(dem_sim *s, dem_state *st);
    dem_sim *(*part)(const dem_sim *s); /* this rank's part; NULL after a failed step (the run cannot go on) */
    long (*step_index)(const dem_sim *s); /* the run's step, the same on every rank (after a failed step too) */
    int (*get_field)(dem_sim *s, dem_field f, double *dst); /* dem_get_field of the whole run, on every rank */
    void (*destroy)(dem_sim *s);
} sim_split_ops;
static inline int sim_finite3(const double *a) { return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]); }
/* diagnostics.c: a backend failure reported as DEM_ERR_DEVICE with the backend's message; launches [a, z) of the
 * core's trace copied after the n already in dst (the new count) */
int sim_be_fail(dem_sim *s);
int sim_copy_trace(const dem_core *c, int a, int z, unsigned char *dst, int n);
/* step_loop.c: the device's flags (FLAG_COUNT ints) read, or DEM_ERR_DEVICE reported */
int sim_read_flags(dem_sim *s, int *flags);
/* rebuild.c: the neighbour rows (and the patch rows) built anew, the storage order first when due; whether an
 * automatic skin is to be tried smaller (a rebuild although none is needed) */
int sim_rebuild(dem_sim *s);
int sim_skin_probe_due(const dem_sim *s);
/* walls.c: each wall's stage, servo velocity and position for the step being taken, uploaded with the riders */
int sim_walls_move(dem_sim *s);
int sim_grow(dem_sim *s, int count, int *cap, int **ints, int ni, double **reals, int nr, const char *what);
/* A whole registry buffer read from the device (malloc'd; the patch rows have no field: their capacity is the
 * driver's). Sets *e (a dem_status) on failure unless it is set already; the caller frees the result. */
void *sim_buffer_get(dem_sim *s, int id, int *e);
/* particle_order.c: the order of n positions (3 doubles each) along a Morton curve: perm[k] is the index of the
 * k-th; -1 when out of memory */
int sim_morton_order(const double *x, int n, int *perm);
/* reorder.c: whether this rebuild stores the particles anew (dem_config.reorder), and doing it */
int sim_reorder_due(const dem_sim *s);
int sim_reorder(dem_sim *s);
/* A caller's particle id (the order of dem_start: the stable id) and where that particle is stored, both ways */
static inline int sim_dev(const dem_sim *s, int id) { return s->order.count ? s->setup.order[id] : id; }
static inline int sim_api(const dem_sim *s, int slot) { return s->order.count ? s->setup.sid[slot] : slot; }
/* element k of an array of the run's reals (float or double, rs bytes each) in double; count of them into dst */
static inline double sim_real_at(const void *raw, size_t k, int rs)
{
    return rs == 8 ? ((const double *)raw)[k] : (double)((const float *)raw)[k];
}
/* v into element k of such an array (v a float's value where rs is 4: stored exactly) */
static inline void sim_real_put(void *raw, size_t k, int rs, double v)
{
    if (rs == 8)
        ((double *)raw)[k] = v;
    else
        ((float *)raw)[k] = (float)v;
}
static inline void sim_widen(const void *raw, double *dst, size_t count, int rs)
{
    for (size_t k = 0; k < count; k++)
        dst[k] = sim_real_at(raw, k, rs);
}
/* whether particle i (stored at i) rides on wall k: the packed table the kernels get (contact_geometry.h, wall_met) */
static inline int sim_rides_on(const dem_sim *s, int i, int k)
{
    return (s->setup.effects & DEM_EFFECT_RIDERS) && s->setup.ride && ((s->setup.ride[i] >> k) & 1u);
}
/* reorder.c: a field read from the device in storage order put in the callers' order (particles by their ids,
 * the rows' partners renamed) in place; fields not sized by particles are left as they are */
int sim_field_to_api(dem_sim *s, dem_field f, void *buf, size_t bytes);
int sim_field_from_api(dem_sim *s, dem_field f, const void *src, void *dst, size_t bytes);
/* the same for a registry buffer, by its move column (common/dem_buffers.h): sim_buffer_to_api in place */
int sim_buffer_to_api(dem_sim *s, int id, void *buf, size_t bytes);
void sim_buffer_from_api(dem_sim *s, int id, const void *src, void *dst, size_t bytes);
/* state.c: where each particle's hosted pairs (partners stored after it) start in the pair list of rows cnt, list
 * (neighbor.h's own_start; malloc'd, n + 1 entries) */
int *sim_own_starts(const int *cnt, const int *list, const int *start, int n);
/* energy.c: a law with memory's rows on the host, widened to double: the pairs' states by pair number (neighbor.h;
 * row_pair_of finds one from a row slot, own the hosts' starts), the particle-wall slots' and MDR's particle rows
 * (storage order); read once for the energies and the stability estimate (stability.c) */
typedef struct {
    double *pair_st, *wall_st, *mdr; /* DEM_LAW_PAIR_W reals per pair, DEM_LAW_WALL_W per wall slot, MDR_P_STRIDE */
    int *own;
    size_t npairs; /* the pairs pair_st holds room for */
} sim_law_rows;
int sim_law_rows_read(dem_sim *s, const int *cnt, const int *list, const int *start, sim_law_rows *lr);
void sim_law_rows_free(sim_law_rows *lr);
int sim_mc_force_slots(dem_sim *s, unsigned char *buf, size_t all); /* state.c */
size_t sim_stored_bytes(const dem_sim *s, dem_field f);          /* fields.c: a field's bytes as the device holds it */

/* host/mesh/attach.c: riders take their walls' velocities of the current step on the host (sim_pack, once the stage
 * lengths are known; the device places them each step: common/riders.h) */
void sim_attach_start(dem_sim *s);

#endif
