/* ref_kernels.h - the plain serial C twins of the OpenCL kernels: for each kernel of common/dem_kernels.h,
 * REF(ref_<name>)(fx, <the kernel's arguments>), a loop over the item function the kernel runs per work item
 * (reference/<family>.c). Compiled once per precision: REF(name) appends _f32 or _f64 so both precisions link into
 * one program. */
#ifndef DEM_REF_KERNELS_H
#define DEM_REF_KERNELS_H
#include "dem_real.h"
#include "vec3.h"

#if DEM_REAL_SIZE == 8
#define REF(name) name##_f64
#else
#define REF(name) name##_f32
#endif

#include "dem_kernels.h"
#define DEM_REF_DECLARE(name) DEM_REF_PROTO(name);
DEM_KERNEL_LIST(DEM_REF_DECLARE)
#undef DEM_REF_DECLARE
#endif
