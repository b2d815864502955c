/* backend.h - the interface every backend implements: the plain C reference (reference/) and OpenCL (host/cl_*.c).
 *
 * A backend owns the working arrays in its precision and runs the kernel steps; it makes no decisions. The driver
 * (host/sim.c) decides when to rebuild, grows capacities, moves walls and checks flags, identically for every
 * backend, so two backends given the same setup execute the same sequence of steps.
 * Arrays cross this interface as raw bytes in the backend's precision (real_size 4 or 8).
 */
#ifndef DEM_BACKEND_H
#define DEM_BACKEND_H
#include <stddef.h>
#include "dem.h" /* dem_field */


/* Everything a backend needs, already packed into its precision by the driver. */
typedef struct {
    int real_size; /* 4 or 8 */
    unsigned effects; /* DEM_EFFECT_* mask (common/dem_effects.h); OpenCL compiles it in as DEM_EFFECTS */
    int n, nmat, nwalls;
    const void *x, *v, *w, *radius, *invmass, *invinertia; /* real arrays */
    const void *invvol;     /* real[n]: 1 / particle volume [1/m^3] (stress, particle_stress.h) */
    const int *mat;
    const void *pairmat;    /* real[PM_STRIDE*nmat*nmat] */
    const int *wall_int;    /* int[WI_STRIDE*nwalls] */
    const void *wall_real;  /* real[W_STRIDE*nwalls] */
    /* binning grid, computed by the driver */
    double lo[3], inv_cell;
    int ncell[3];
    /* per-step scalars (converted to real by the backend with a plain C cast) */
    double dt, gravity[3], skin, half_skin2;
    int maxn; /* initial neighbour-row capacity */
    /* OpenCL only */
    int platform, device;
    size_t local_size; /* 0: let the runtime choose */
    const char *source_dir; /* project folder holding kernels/ and common/ */
    const char *extra_build_options;
} dem_setup;

/* Size in bytes of a field for the effect mask, n particles, rows of capacity maxn, nwalls walls, ncells cells, rs-byte reals.
 * The one place that knows every layout's size (host/sim.c, both backends). */
size_t dem_field_size(dem_field f, unsigned effects, size_t n, size_t maxn, size_t nwalls, size_t ncells, size_t rs);

typedef struct dem_backend dem_backend;

typedef struct {
    const char *name;
    /* Allocates and uploads. On failure returns non-zero with a message in err. */
    int (*create)(dem_backend **out, const dem_setup *s, char *err, size_t errlen);
    void (*destroy)(dem_backend *b);
    const char *(*error)(dem_backend *b); /* message of the last failure */
    const char *(*describe)(dem_backend *b); /* device / build description */
    int (*reset_flags)(dem_backend *b);
    int (*kick_drift)(dem_backend *b);
    int (*bin)(dem_backend *b);
    int (*nbr_reserve)(dem_backend *b, int maxn);  /* capacity of the rows being built */
    int (*nbr_build)(dem_backend *b);
    int (*nbr_commit)(dem_backend *b);             /* carry history, make the new rows current, save x_build */
    int (*contact_forces)(dem_backend *b);         /* particle and wall contacts */
    int (*wall_reduce)(dem_backend *b);            /* the force each wall received (contacts: contact_forces) */
    int (*kick)(dem_backend *b);
    int (*stress_trace)(dem_backend *b);           /* MC-stress pass 1: FIELD_STRESS_TRACE from the positions */
    int (*stress_tensor)(dem_backend *b);          /* FIELD_STRESS from the positions (output) */
    int (*mc_strain_disp)(dem_backend *b);         /* induced displacements from the stored MC-strain forces */
    int (*mc_strain_update)(dem_backend *b, double tol); /* one fixed-point iteration; sets FLAG_MC_PENDING */
    /* New wall positions and velocities (real[W_STRIDE*nwalls]). May return before the copy is done: the caller
     * keeps src unchanged until its next blocking call (the driver's flag read follows at once). */
    int (*set_walls)(dem_backend *b, const void *src);
    int (*read)(dem_backend *b, dem_field f, void *dst, size_t bytes);
    int (*write)(dem_backend *b, dem_field f, const void *src, size_t bytes);
    int (*finish)(dem_backend *b);                 /* wait for queued work (timing) */
    /* optional per-kernel timing: seconds spent in each named step since creation */
    int (*kernel_times)(dem_backend *b, const char ***names, const double **seconds, int *count);
} dem_backend_ops;

extern const dem_backend_ops dem_reference_ops_f32, dem_reference_ops_f64;
extern const dem_backend_ops dem_opencl_ops;

#endif /* DEM_BACKEND_H */
