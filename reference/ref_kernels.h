/* ref_kernels.h - every function of the reference that others call, declared once for both precisions:
 *   - for each kernel of common/dem_kernels.h, its serial loop ref_<name>_f32 / ref_<name>_f64 (fx, <the kernel's
 *     arguments>) (reference/loops.c), generated from the kernel's argument list;
 *   - the helpers the driver and the tests call: the patch geometry (reference/patch.c), the hinges' rest angle, period and damping rate (reference/bending.c, fp64 only).
 * Both sides include it: the reference's files, compiled once per precision, define REF(name) (name_f32 or name_f64)
 * against these declarations, so the compiler checks each definition's argument list; the host and the tests, which
 * have no precision (no DEM_REAL_SIZE), call them through it. */
#ifndef DEM_REF_KERNELS_H
#define DEM_REF_KERNELS_H
#ifdef DEM_REAL_SIZE
#include "dem_real.h"
#include "vec3.h"
#if DEM_REAL_SIZE == 8
#define REF(name) name##_f64
#else
#define REF(name) name##_f32
#endif
#endif
#include "dem_kernels.h"

/* a kernel argument in plain C with `real` spelt T (float or double); an element type missing here does not compile */
#define DEM_REF_T_int(T) int
#define DEM_REF_T_unsigned(T) unsigned
#define DEM_REF_T_dem_byte(T) unsigned char
#define DEM_REF_T_real(T) T
#define DEM_REF_ARG_I(T, type, name) int name
#define DEM_REF_ARG_R(T, type, name) T name
#define DEM_REF_ARG_BIN(T, type, name) const DEM_REF_T_##type(T) *name
#define DEM_REF_ARG_BOUT(T, type, name) DEM_REF_T_##type(T) *name
#define DEM_REF_ARG_CIN DEM_REF_ARG_BIN
#define DEM_REF_ARG_COUT DEM_REF_ARG_BOUT
#define DEM_REF_ARG_NIN DEM_REF_ARG_BIN
#define DEM_REF_ARG_NOUT DEM_REF_ARG_BOUT
#define DEM_REF_ARG_AIN DEM_REF_ARG_BIN
#define DEM_REF_ARG_AOUT DEM_REF_ARG_BOUT
#define DEM_REF_F32(kind, type, name, src) DEM_REF_ARG_##kind(float, type, name)
#define DEM_REF_N32(kind, type, name, src) , DEM_REF_ARG_##kind(float, type, name)
#define DEM_REF_F64(kind, type, name, src) DEM_REF_ARG_##kind(double, type, name)
#define DEM_REF_N64(kind, type, name, src) , DEM_REF_ARG_##kind(double, type, name)
#define DEM_REF_DECLARE(name)                                                                                        \
    void ref_##name##_f32(unsigned fx, DEM_ARGS_##name(DEM_REF_F32, DEM_REF_N32));                                  \
    void ref_##name##_f64(unsigned fx, DEM_ARGS_##name(DEM_REF_F64, DEM_REF_N64));
DEM_KERNEL_LIST(DEM_REF_DECLARE)
#undef DEM_REF_DECLARE

/* The helpers of both precisions (suffix S): the closest feature of point i to triangle i, which of a list of contacts stay,
 * a sphere's overlap on a patch and the overlap the patch law is given (common/patch.h, patch_contacts.h); an MDR
 * contact walked along a prescribed approach (common/laws/mdr_core.h mdr_walk; reference/mdr.c). */
#define DEM_REF_HELPERS(T, S)                                                                                        \
    void dem_patch_probe##S(int n, const T *p, const T *tri_x, int *kind, int *index, T *w, T *point);               \
    int dem_patch_keep##S(int i, int n, const int *id, const int *tri, const int *kind, const T *d2);                \
    T dem_patch_overlap##S(const T *p, const T *tri_x, unsigned flags, T radius);                                    \
    T dem_patch_law##S(T d, T radius);                                                                           \
    void dem_mdr_walk##S(int kind, int nsteps, const T *u, const T *mat, T r, T r2, T mass1, T mass2, T dt,          \
                         T *delta, T *radius, T *psi, T *force);                                                 \
    void dem_mdr_fixed##S(int which, int n, const T *x, T *y);
DEM_REF_HELPERS(float, _f32)
DEM_REF_HELPERS(double, _f64)
#undef DEM_REF_HELPERS

/* reference/bending.c, fp64 only (host/core/sim_setup.c): sin(theta / 2) of hinge p[0..3] at the positions x as the
 * item computes it; the fold period of a hinge of elastic constant kel and vertex masses mass[0..3]; the largest
 * decay rate of the hinges' damping (its comment there) */
double dem_hinge_rest_shalf(const double *x, const int *p);
double dem_hinge_period(const double *x, const int *p, double kel, const double *mass);
double dem_hinge_damping_rate(const double *x, const int *hinge, const double *hinge_k, int nh, const double *sqrt_im,
                              int n);
#endif
