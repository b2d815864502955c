/* dem_real.h - the one precision switch and the C / OpenCL C shim.
 *
 * Every header in common/ compiles both as C99 (reference twin, host) and as OpenCL C 1.2 (kernels).
 * The floating-point type `real` is chosen at compile time:
 *   OpenCL: the host passes -DDEM_REAL_SIZE=4 or 8 when it builds the program;
 *   C:      the reference is compiled twice, once per value of DEM_REAL_SIZE (see Makefile).
 * Determinism rules that live here: no FP contraction (a fused multiply-add rounds once where the other
 * side rounds twice), and only + - * / sqrt in force laws (correctly rounded on every conforming device).
 */
#ifndef DEM_REAL_H
#define DEM_REAL_H

#ifndef DEM_REAL_SIZE
#error "DEM_REAL_SIZE must be 4 (fp32) or 8 (fp64)"
#endif

#ifdef __OPENCL_C_VERSION__
/* ---------------- OpenCL C ---------------- */
#pragma OPENCL FP_CONTRACT OFF
#if DEM_REAL_SIZE == 8
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
#else
typedef float real;
#endif
#define DEM_INLINE static inline __attribute__((always_inline))
#define DEM_GLOBAL __global
#define DEM_CONST_GLOBAL __global const
#define dem_sqrt(x) sqrt(x)
/* Integer atomics only: counts and flags, never floating-point sums. */
#define DEM_ATOMIC_INC(p) atomic_inc(p)
#define DEM_ATOMIC_DEC(p) atomic_dec(p)
#define DEM_ATOMIC_ADD(p, v) atomic_add((p), (v))
#define DEM_ATOMIC_MAX(p, v) atomic_max((p), (v))
#define DEM_ATOMIC_MIN(p, v) atomic_min((p), (v))
#else
/* ---------------- C99 (reference, host) ---------------- */
#include <math.h>
#if DEM_REAL_SIZE == 8
typedef double real;
#define dem_sqrt(x) sqrt(x)
#else
typedef float real;
#define dem_sqrt(x) sqrtf(x)
#endif
#define DEM_INLINE static inline
#define DEM_GLOBAL
#define DEM_CONST_GLOBAL const
/* The reference runs serially: the "atomics" are plain updates that return the old value. */
static inline int dem_serial_inc(int *p) { return (*p)++; }
static inline int dem_serial_dec(int *p) { return (*p)--; }
static inline int dem_serial_add(int *p, int v) { int o = *p; *p += v; return o; }
static inline int dem_serial_max(int *p, int v) { int o = *p; if (v > o) *p = v; return o; }
static inline int dem_serial_min(int *p, int v) { int o = *p; if (v < o) *p = v; return o; }
#define DEM_ATOMIC_INC(p) dem_serial_inc(p)
#define DEM_ATOMIC_DEC(p) dem_serial_dec(p)
#define DEM_ATOMIC_ADD(p, v) dem_serial_add((p), (v))
#define DEM_ATOMIC_MAX(p, v) dem_serial_max((p), (v))
#define DEM_ATOMIC_MIN(p, v) dem_serial_min((p), (v))
#endif

/* one byte per element (the row slots' touching flags): one token, so that the kernels' argument lists
 * (dem_kernels.h) can name it */
typedef unsigned char dem_byte;

#endif /* DEM_REAL_H */
