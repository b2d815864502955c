/* cl_backend.h - state of the OpenCL backend, shared by its per-kernel host drivers
 * (host/binning.c, neighbor.c, contact_forces.c, wall_forces.c, integrate.c). */
#ifndef DEM_CL_BACKEND_H
#define DEM_CL_BACKEND_H
#include "cl_util.h"
#include "backend.h"
#include "dem_layout.h"

typedef enum {
    K_BIN_INDEX, K_SCAN_BLOCK_SUM, K_SCAN_BLOCK_SUMS, K_SCAN_APPLY, K_BIN_SCATTER, K_BIN_SORT,
    K_NBR_BUILD, K_NBR_CARRY, K_CONTACT_PAIRS, K_CONTACT_FORCES, K_WALL_REDUCE_BLOCK, K_WALL_REDUCE_FINAL,
    K_KICK_DRIFT, K_KICK, K_STRESS_TRACE, K_STRESS_TENSOR, K_MC_STRAIN_DISP, K_MC_STRAIN_UPDATE, K__COUNT
} kernel_id;

struct dem_backend {
    cl_device_info_t dev;
    cl_context ctx;
    cl_command_queue q;
    cl_program prog;
    cl_kernel k[K__COUNT];
    double ktime[K__COUNT]; /* seconds per kernel, when profiling */
    int profile;
    size_t local;           /* work-group size, 0 = runtime's choice */
    int rs;                 /* real size in bytes */
    unsigned fx;            /* effect mask, compiled into the program as DEM_EFFECTS */
    int n, nmat, nwalls, ncells, nblocks_scan, nblocks_red, ncx, ncy, ncz;
    double dt, skin, half_skin2, inv_cell, lo[3], g[3];
    cl_mem x, v, w, f, t, radius, invm, invi, x_build, mat, pairmat, wall_int, wall_real, wall_hist, wall_pf, wall_mask,
        partial, wall_force, cell_of, cell_count, cell_start, cell_fill, cell_particles, block_sum, flags;
    int maxn[2];
    cl_mem count[2], list[2], hist[2], touch[2], mirror[2];
    cl_mem in_count, in_start, in_block_sum; /* incoming pairs per particle and their offsets (see contact_forces.h) */
    cl_mem pair;     /* PR_STRIDE reals per incoming pair (contact_pairs -> contact_forces) */
    cl_mem invvol, trace, stress;        /* 1/V, MC-stress trace, output tensor (allocated when first asked) */
    cl_mem mc_fn[2], mc_disp[2];         /* MC-strain per row slot, one per row set */
    cl_mem mc_wall_fn, mc_wall_disp;
    size_t pair_cap; /* records allocated */
    int cur;
    char desc[512];
    char err[4096];
};

/* Argument helpers: a real argument is passed as float or double according to the precision. */
int clb_arg_int(dem_backend *b, cl_kernel k, cl_uint idx, int v);
int clb_arg_real(dem_backend *b, cl_kernel k, cl_uint idx, double v);
int clb_arg_mem(dem_backend *b, cl_kernel k, cl_uint idx, cl_mem m);
/* Enqueues kernel id over `items` work items (rounded up to the work-group size). */
int clb_launch(dem_backend *b, kernel_id id, size_t items);
int clb_fill_int(dem_backend *b, cl_mem m, int value, size_t count);

/* per-kernel host drivers */
int clb_integrate_kick_drift(dem_backend *b);
int clb_integrate_kick(dem_backend *b);
int clb_bin(dem_backend *b);
/* Exclusive prefix sum of count[0..items) into start[0..items] (fixed blocks of DEM_SCAN_BLOCK, integers). */
int clb_scan(dem_backend *b, cl_mem count, cl_mem start, int items, cl_mem block_sum);
int clb_nbr_build(dem_backend *b);
int clb_nbr_carry(dem_backend *b);
int clb_contact_forces(dem_backend *b);
int clb_wall_reduce(dem_backend *b);
int clb_stress_trace(dem_backend *b);
int clb_stress_tensor(dem_backend *b);
int clb_mc_strain_disp(dem_backend *b);
int clb_mc_strain_update(dem_backend *b, double tol);
/* Buffer of n bytes (zero-filled when init is NULL); on failure sets *fail and b->err. */
cl_mem clb_buffer(dem_backend *b, size_t bytes, const void *init, int *fail);
#endif
