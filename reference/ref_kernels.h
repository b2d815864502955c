/* ref_kernels.h - the plain serial C twins of the OpenCL kernels. Same arguments as the kernels in kernels/<name>.cl;
 * each loops over the item function the kernel runs per work item. Compiled once per precision: REF(name) appends
 * _f32 or _f64 so both precisions link into one program. */
#ifndef DEM_REF_KERNELS_H
#define DEM_REF_KERNELS_H
#include "dem_real.h"
#include "vec3.h"

#if DEM_REAL_SIZE == 8
#define REF(name) name##_f64
#else
#define REF(name) name##_f32
#endif

/* binning.c */
void REF(ref_bin_index)(int n, vec3 lo, real inv_cell, int ncx, int ncy, int ncz, const real *x, int *cell_of,
                        int *cell_count, int *flags);
void REF(ref_scan)(int ncells, const int *count, int *block_sum, int *start);
void REF(ref_bin_scatter)(int n, const int *cell_of, const int *start, int *fill, int *cell_particles);
void REF(ref_bin_sort)(int ncells, const int *start, int *cell_particles);
/* neighbor.c */
void REF(ref_nbr_build)(int n, int maxn, real skin, int ncx, int ncy, int ncz, const real *x, const real *radius,
                        const int *cell_of, const int *cell_start, const int *cell_particles, int *nbr_count,
                        int *nbr_list, int *in_count, int *flags);
void REF(ref_nbr_carry)(unsigned fx, int n, int maxn, int old_maxn, const int *nbr_count, const int *nbr_list, const int *old_count,
                        const int *old_list, const real *old_hist, const unsigned char *old_touch, real *hist,
                        unsigned char *touch, int *mirror, int *flags, const real *old_mc_fn, real *mc_fn);
/* contact_forces.c */
void REF(ref_contact_pairs)(unsigned fx, int n, int maxn, int nmat, real dt, const real *x, const real *v, const real *w,
                            const real *radius, const real *invmass, const int *mat, const real *pairmat,
                            const int *nbr_count, const int *nbr_list, const int *nbr_mirror, real *hist,
                            unsigned char *touch, const int *in_start, real *pair, real *force, real *torque,
                            const real *trace, const real *invvol, const real *mc_disp, real *mc_fn);
void REF(ref_contact_forces)(unsigned fx, int n, int maxn, int nmat, real dt, const real *x, const real *v, const real *w,
                             const real *radius, const real *invmass, const int *mat, const real *pairmat,
                             const int *nbr_count, const int *nbr_list, const int *nbr_mirror,
                             const unsigned char *touch, const int *in_start, const real *pair,
                             real *force, real *torque, int nwalls, const int *wall_int, const real *wall_real,
                             real *wall_hist, real *wall_pf, unsigned *wall_mask, const real *trace,
                             const real *invvol, const real *mc_wall_disp, real *mc_wall_fn);
/* particle_stress.c */
void REF(ref_stress_trace)(unsigned fx, int n, int maxn, int nmat, const real *x, const real *radius,
                           const real *invvol, const int *mat, const real *pairmat, const int *nbr_count,
                           const int *nbr_list, int nwalls, const int *wall_int, const real *wall_real, real *trace);
void REF(ref_stress_tensor)(unsigned fx, int n, int maxn, int nmat, const real *x, const real *radius,
                            const real *invvol, const int *mat, const real *pairmat, const int *nbr_count,
                            const int *nbr_list, int nwalls, const int *wall_int, const real *wall_real,
                            real *stress);
/* mc_strain.c */
void REF(ref_mc_strain_disp)(unsigned fx, int n, int maxn, int nmat, const real *x, const real *radius, const int *mat,
                             const real *pairmat, const int *nbr_count, const int *nbr_list, int nwalls,
                             const int *wall_int, const real *wall_real, const real *fn, const real *wall_fn,
                             real *disp, real *wall_disp);
void REF(ref_mc_strain_update)(unsigned fx, int n, int maxn, int nmat, real tol, const real *x, const real *radius,
                               const int *mat, const real *pairmat, const int *nbr_count, const int *nbr_list,
                               const int *nbr_mirror, int nwalls, const int *wall_int, const real *wall_real,
                               const real *disp, const real *wall_disp, real *fn, real *wall_fn, int *flags);
/* wall_forces.c */
void REF(ref_wall_reduce)(int n, int nwalls, int nblocks, const real *wall_pf, const unsigned *wall_mask,
                          real *partial, real *wall_force);
/* integrate.c */
void REF(ref_integrate_kick_drift)(unsigned fx, int n, real dt, vec3 g, real half_skin2, real *x, real *v, real *w,
                                   const real *force, const real *torque, const real *invmass,
                                   const real *invinertia, const real *x_build, int *flags);
void REF(ref_integrate_kick)(unsigned fx, int n, real dt, vec3 g, real *v, real *w, const real *force, const real *torque,
                             const real *invmass, const real *invinertia);
#endif
