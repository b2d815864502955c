/* backend.h - what a backend is: the plain C reference (reference/) and OpenCL (host/opencl/cl_backend.c).
 *
 * A backend owns buffers and runs kernels; it makes no decisions. It implements a handful of primitives (allocate a
 * registry buffer, launch a kernel of common/dem_kernels.h with its arguments looked up by their sources, fill,
 * copy, read, write); everything else is written once on top of them: the buffers a run needs (walking the registry,
 * common/dem_buffers.h, in backend/backend.c), and the steps of a time step (host/steps/: binning, neighbour rows,
 * contact forces, wall forces, integration, stress, MC-strain). The driver (host/core/) decides when to rebuild,
 * grows capacities, moves walls and checks flags, identically for every backend, so two backends given the same
 * setup execute the same sequence of launches.
 * Arrays cross this interface as raw bytes in the backend's precision (real_size 4 or 8).
 */
#ifndef DEM_BACKEND_H
#define DEM_BACKEND_H
#include <stddef.h>
#include "dem.h" /* dem_field */
#include "dem_debug.h" /* the fields the backends keep for the driver */
#include "dem_buffers.h"
#include "dem_kernels.h"

/* Everything a backend needs, already packed into its precision by the driver. */
typedef struct {
    int real_size; /* 4 or 8 */
    unsigned effects; /* DEM_EFFECT_* mask (include/dem_effects.h); OpenCL compiles it in as DEM_EFFECTS */
    int n, nmat, nwalls;
    const void *x, *v, *w, *radius, *invmass, *invinertia; /* real arrays */
    const void *invvol;     /* real[n]: 1 / particle volume [1/m^3] (stress, particle_stress.h) */
    const void *roll_inertia; /* real[n]: 1 / (I + m r^2), a body's term of the rolling spring's 1/I_r (rolling.h;
                                 0 for an immovable one) [1/(kg m^2)] */
    const void *mdr_part;   /* real[MDR_P_STRIDE*n]: each particle's MDR row as created (laws/mdr_core.h
                               mdr_particle_new; DEM_EFFECT_MDR) */
    const int *mat;
    const void *pairmat;    /* real[PM_STRIDE*nmat*nmat] */
    const int *wall_int;    /* int[WI_STRIDE*nwalls] */
    const void *wall_real;  /* real[W_STRIDE*nwalls] */
    /* The tables below name particles by stable id (sid), never by storage place: they stay as they are when the
     * particles are stored anew (host/core/reorder.c); the kernels read a particle's data at order[id]. */
    int nsprings;           /* springs (seed 001 Eq. 6): their particles, constants, and their records' channel */
    const int *spring_int;  /* int[2*nsprings] */
    const void *spring_real; /* real[SP_STRIDE*nsprings] */
    int ntriangles;         /* triangles under the pressure (seed 001 Eq. 18) */
    const int *tri;         /* int[3*ntriangles] */
    double pressure;        /* [Pa] */
    int nhinges;            /* hinges (seed 001 Eq. 8-16) */
    const int *hinge_int;   /* int[4*nhinges] */
    const void *hinge_real; /* real[HG_STRIDE*nhinges] */
    const int *chan_slot;   /* int[2*nsprings + 3*ntriangles + 4*nhinges]: where each spring end's, triangle vertex's
                               and hinge vertex's record goes */
    const int *chan_start;  /* int[n+1], by stable id: each particle's records: its springs, its triangles, its hinges,
                               in order */
    int nriders;            /* particles riding on walls (dem_attach_to_wall) */
    const int *rider_int;   /* int[2*nriders]: particle, wall */
    const void *rider_off;  /* real[3*nriders]: the particle's place relative to its wall's point */
    const unsigned *ride;   /* unsigned[n]: bit k set when the particle rides on wall k (it does not touch it) */
    const unsigned *ghost;  /* unsigned[n]: 1 for a ghost (another rank's particle: DEM_HAS_GHOSTS), else 0 */
    const unsigned *hold;   /* unsigned[n]: bits 0, 1, 2: the particle keeps its velocity along x, y, z */
    const int *sid;         /* int[n]: the stable id (the id of dem_start) of the particle at each place: every sum's
                               order */
    const int *order;       /* int[n]: where the particle of each stable id is stored (the inverse of sid) */
    const int *identity;    /* int[n]: 0, 1, ..., n - 1 (OLD_SLOT: where each particle was when the rows were built) */
    /* binning grid, computed by the driver */
    double lo[3], inv_cell;
    int ncell[3];           /* the domain's cells per axis */
    int cell0[3], cells[3]; /* the cells the particles hold at set-up (first, count per axis): what the cell buffers
                               start at (the device finds the cells of each build: binning.h) */
    /* per-step scalars (converted to real by the backend with a plain C cast) */
    double dt, gravity[3], skin, half_skin2;
    int maxn; /* slots each neighbour-row set starts with (its rows packed together) */
    /* patch contacts (patch_contacts.h) */
    const int *vtri_start;  /* int[n+1], by stable id: each particle's patch triangles at vtri_list[vtri_start[p] ..] */
    const int *vtri_list;   /* int[3*ntriangles]: ascending triangle ids per particle (the tail unused) */
    double reach, rmax;     /* the search reach (> every patch edge) and the largest sphere radius [m] */
    int maxp, maxv;         /* initial capacities of the sphere and vertex patch rows */
    /* OpenCL only */
    int platform, device;
    size_t local_size; /* 0: let the runtime choose */
    const char *source_dir; /* project folder holding kernels/ and common/ */
    const char *extra_build_options;
} dem_setup;

/* The kernels, by id (K_bin_index, ...), in the order of DEM_KERNEL_LIST. */
#define DEM_ENUM_KERNEL(name) K_##name,
typedef enum { DEM_KERNEL_LIST(DEM_ENUM_KERNEL) K__COUNT } dem_kernel_id;
#undef DEM_ENUM_KERNEL
extern const char *const dem_kernel_names[K__COUNT];

/* Where a buffer is: a DEM_BUFFERS id, or a DEM_ROWS id of the current set or of the set being built. */
typedef enum { TABLE_ONE, TABLE_CUR, TABLE_NEW } dem_table;
typedef struct {
    dem_table table;
    int id;
} dem_bufref;

#define DEM_TRACE_MAX 256 /* launches recorded per step (dem_kernel_sequence) */
/* Slots per particle the packed neighbour rows start with (all rows together: DEM_ROWS); a build that needs more
 * grows them before it fills them (host/core/rebuild.c row_capacity). */
#define DEM_INITIAL_ROW_CAPACITY 8
/* Pair records per particle assumed by dem_memory_estimate (a dense packing has about 3 partners of higher id). */
#define DEM_ESTIMATE_PAIRS_PER_PARTICLE 3

/* What every backend keeps alike, as the first member of its struct dem_backend (DEM_CORE): dimensions, scalar
 * argument values, the row sets, the aliases, and the size of every buffer held. */
typedef struct {
    unsigned fx;
    int rs;
    int n, nmat, nwalls, ncells, nblocks_red, nmid_red, nsprings, ntriangles, nhinges, nriders;
    int cell_cap;    /* cells the cell buffers hold (ncells: in use; host/steps/binning.c) */
    int series_rows; /* rows of the series ring (common/series.h) */
    int maxn[2], cur;  /* slots of each row set (its rows packed together); the set in use (1 - cur is built into) */
    int maxp, maxp_old, maxv; /* patch rows' capacities (patch_contacts.h) */
    size_t pair_cap;   /* pair records allocated */
    int halo_cap;      /* message rows of a split run's halo (halo.h: NSEND + NRECV; 0 in one process) */
    int si[SI__COUNT];
    double sr[SR__COUNT];
    dem_bufref alias[ALIAS__COUNT];        /* the buffer each alias names */
    size_t bytes[BUF__COUNT];              /* bytes held */
    size_t row_bytes[2][ROW__COUNT];
    double ktime[K__COUNT]; /* seconds per kernel, when timed (OpenCL: DEM_PROFILE set; reference: always) */
    int timed;
    int ntrace;                            /* launches since the driver last cleared it (step_loop.c) */
    unsigned char trace[DEM_TRACE_MAX];    /* their kernel ids, the first DEM_TRACE_MAX */
    char build[2048]; /* provenance: how the kernels were built (dem_build_info) */
    char err[4096];
} dem_core;

typedef struct dem_backend dem_backend;
#define DEM_CORE(b) ((dem_core *)(void *)(b))

typedef struct {
    const char *name;
    /* Allocates the backend with its core filled from the setup (dem_core_init) and every buffer (dem_buffers_create).
     * On failure returns non-zero with a message in err. */
    int (*create)(dem_backend **out, const dem_setup *s, char *err, size_t errlen);
    void (*destroy)(dem_backend *b);
    const char *(*describe)(dem_backend *b); /* device / build description */
    /* (Re)allocates a buffer: bytes (0 allowed), uploaded from init or zero-filled; the old contents are dropped.
     * set: the row set (0 or 1) for a DEM_ROWS id. */
    int (*alloc)(dem_backend *b, dem_table table, int set, int id, size_t bytes, const void *init);
    int (*launch)(dem_backend *b, dem_kernel_id k); /* the kernel over DEM_ITEMS of its arguments */
    int (*fill_int)(dem_backend *b, dem_bufref r, int value, size_t count);
    int (*copy)(dem_backend *b, dem_bufref from, dem_bufref to, size_t bytes);
    /* blocking = 0 may return before dst is filled: finish() waits (several reads, one synchronisation) */
    int (*read)(dem_backend *b, dem_bufref r, size_t offset, void *dst, size_t bytes, int blocking);
    /* blocking = 0 may return before the copy is done: the caller keeps src unchanged until its next blocking call */
    int (*write)(dem_backend *b, dem_bufref r, size_t offset, const void *src, size_t bytes, int blocking);
    int (*finish)(dem_backend *b); /* wait for queued work (timing) */
    /* The first `bytes` of a buffer for the host to read where it lies (a CPU device's own memory: no copy), once the
     * queued work is done (a synchronisation); unmap hands it back, before anything is queued that writes it. */
    int (*map)(dem_backend *b, dem_bufref r, size_t bytes, const void **host);
    int (*unmap)(dem_backend *b, dem_bufref r, const void *host);
    /* Exchanges two buffers of the one-of-a-kind table, contents and sizes (a double-buffered pair: the kernels and
     * every reader find the current copy under its own id). Queued work already holds its buffers. */
    void (*swap)(dem_backend *b, int id1, int id2);
} dem_backend_ops;

extern const dem_backend_ops dem_reference_ops_f32, dem_reference_ops_f64;
extern const dem_backend_ops dem_opencl_ops;

/* ---- backend/backend.c: the registry walked ---- */
/* Fills the core's dimensions and scalars from the setup. */
void dem_core_init(dem_core *c, const dem_setup *s);
/* Element size and the bytes a buffer needs now. */
size_t dem_elem_size(int elem, int rs);
size_t dem_buffer_bytes(const dem_core *c, int id);
size_t dem_row_bytes(const dem_core *c, int id, int maxn);
/* The part of the memory report (dem_memory_part) a DEM_BUFFERS id belongs to. */
int dem_buffer_part(int id);
/* The setup's host copy a buffer is created from (the registry's init column), NULL for a zero-filled one. */
const void *dem_buffer_init(const dem_setup *s, int id);
/* How a buffer follows its particles (the registry's move column): DEM_MOVE_STAY, DEM_MOVE_P (particle-major: the
 * first n items of *item bytes), DEM_MOVE_G (groups of n items of *item bytes). */
int dem_buffer_move(const dem_core *c, int id, size_t *item);
/* A buffer a state saves whole (the registry's checkpoint column): its id, element type and gate, its name (the
 * checkpoint's dataset under /state/), unit (NULL: none), elements per dataset row, and whether a state must hold
 * it. dem_saved_buffers: one per registry buffer (BUF__COUNT, by id), name NULL where it is not saved. */
typedef struct {
    int id, elem;
    unsigned gate;
    const char *name, *unit;
    int width, required;
} dem_saved_buffer;
const dem_saved_buffer *dem_saved_buffers(void);
/* Every buffer of the registry, at the setup's sizes, uploaded from the setup where the registry says so. */
int dem_buffers_create(const dem_backend_ops *ops, dem_backend *b, const dem_setup *s);
/* The current buffer behind a field, and its size. -1 when the field has none. */
int dem_field_ref(const dem_core *c, dem_field f, dem_bufref *r, size_t *bytes);
/* Size in bytes of a field for the effect mask, n particles, rows of capacity maxn, nwalls walls, ncells cells,
 * rs-byte reals (from the registry). */
size_t dem_field_size(dem_field f, unsigned effects, size_t n, size_t maxn, size_t nwalls, size_t ncells, size_t rs);
/* Makes a lazy buffer (DEM_GATE_LAZY) at its full size when first needed. */
int dem_buffer_ensure(const dem_backend_ops *ops, dem_backend *b, int id);
/* Records a message in the core's err; returns 1. */
int dem_core_fail(dem_core *c, const char *fmt, ...);
/* The buffer a kernel argument of each buffer kind names, from its source (common/dem_kernels.h). */
#define DEM_REF_BIN(c, src) ((dem_bufref){TABLE_ONE, BUF_##src})
#define DEM_REF_BOUT DEM_REF_BIN
#define DEM_REF_CIN(c, src) ((dem_bufref){TABLE_CUR, ROW_##src})
#define DEM_REF_COUT DEM_REF_CIN
#define DEM_REF_NIN(c, src) ((dem_bufref){TABLE_NEW, ROW_##src})
#define DEM_REF_NOUT DEM_REF_NIN
#define DEM_REF_AIN(c, src) ((c)->alias[ALIAS_##src])
#define DEM_REF_AOUT DEM_REF_AIN
/* The bytes a buffer reference holds now. */
size_t dem_ref_bytes(const dem_core *c, dem_bufref r);
/* Number of work items of kernel k with the core's current scalars. */
size_t dem_kernel_items(const dem_core *c, dem_kernel_id k);
size_t dem_kernel_bound_list(const dem_core *c, dem_kernel_id k, const char **names, double *bytes, int max, int *count);

/* Launches kernel k (o->launch), recording it in the core's trace. The steps launch through it; a step that is one
 * launch has no wrapper: the driver calls dem_launch(o, b, K_<kernel>) itself. */
int dem_launch(const dem_backend_ops *o, dem_backend *b, dem_kernel_id k);

/* ---- the steps of more than one launch, written once for every backend (host/steps/) ---- */
int dem_stage_reset_flags(const dem_backend_ops *o, dem_backend *b);
/* The binning (common/binning.h) in two steps, for the host to read the flags between them: bin_bounds finds the
 * cells the particles hold (and any particle outside the domain); bin_cells takes those cells for the build (from
 * the flags read after bin_bounds), growing the cell buffers when they hold fewer; bin sorts the particles into them. */
int dem_stage_bin_bounds(const dem_backend_ops *o, dem_backend *b);
int dem_stage_bin_cells(const dem_backend_ops *o, dem_backend *b, const int *flags);
int dem_stage_bin(const dem_backend_ops *o, dem_backend *b);
/* Exclusive prefix sum of count[0..items) into start[0..items] (fixed blocks of DEM_SCAN_BLOCK, integers; block_sum
 * holds a sum per block). */
int dem_stage_scan(const dem_backend_ops *o, dem_backend *b, dem_bufref count, dem_bufref start, dem_bufref block_sum,
                   int items);
/* A build of the rows (common/neighbor.h) in two steps: count counts each row's partners and scans the counts into
 * the rows' starts, returning the slots they need in *slots; build fills the rows, once reserve has given the set
 * being built at least those slots. */
int dem_stage_nbr_count(const dem_backend_ops *o, dem_backend *b, int *slots);
int dem_stage_nbr_reserve(const dem_backend_ops *o, dem_backend *b, int slots); /* slots of the rows being built */
int dem_stage_nbr_build(const dem_backend_ops *o, dem_backend *b);
int dem_stage_nbr_commit(const dem_backend_ops *o, dem_backend *b); /* carry history, swap, offsets, x_build */
int dem_stage_wall_reduce(const dem_backend_ops *o, dem_backend *b); /* the walls' exact sums, block to final */
/* Series rows (common/series.h): arm(1, row) has the next step write its terms to row `row` of the device's ring
 * (arm(0, 0) after it); series_map maps the first `rows` rows for the host to read (real[rows][n][SE_STRIDE] and
 * real[rows][nwalls][WP_STRIDE], the walls' sums of each row's step; walls NULL without walls) with one
 * synchronisation, series_unmap hands them back. */
int dem_stage_series_arm(const dem_backend_ops *o, dem_backend *b, int on, int row);
int dem_stage_series_map(const dem_backend_ops *o, dem_backend *b, int rows, const void **terms, const void **walls);
int dem_stage_series_unmap(const dem_backend_ops *o, dem_backend *b, const void *terms, const void *walls);
int dem_stage_stress_tensor(const dem_backend_ops *o, dem_backend *b);  /* DEM_FIELD_STRESS from the positions */
int dem_stage_mc_strain_update(const dem_backend_ops *o, dem_backend *b, double tol); /* sets FLAG_MC_PENDING */
int dem_stage_set_walls(const dem_backend_ops *o, dem_backend *b, const void *src); /* non-blocking */
/* Patch rows (first: the current sphere rows become the old ones first; a retry after growth passes 0;
 * patch_contacts.h). */
int dem_stage_patch_build(const dem_backend_ops *o, dem_backend *b, int first, int maxp, int maxv, double reach);
int dem_stage_read_field(const dem_backend_ops *o, dem_backend *b, dem_field f, void *dst, size_t bytes);
/* Several fields with one synchronisation (the series of a step read everything at once). */
int dem_stage_read_fields(const dem_backend_ops *o, dem_backend *b, int count, const dem_field *f, void *const *dst,
                          const size_t *bytes);
int dem_stage_write_field(const dem_backend_ops *o, dem_backend *b, dem_field f, const void *src, size_t bytes);

#endif /* DEM_BACKEND_H */
