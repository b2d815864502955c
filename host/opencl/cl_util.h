/* cl_util.h - OpenCL plumbing: error names, device lookup, program build with its log. */
#ifndef DEM_CL_UTIL_H
#define DEM_CL_UTIL_H
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stddef.h>

const char *cl_errname(cl_int e);

/* Formats "where: CL_ERROR_NAME (code)" into err and returns 1 when e != CL_SUCCESS, else 0. */
int cl_check(cl_int e, const char *where, char *err, size_t errlen);

typedef struct {
    cl_platform_id platform;
    cl_device_id device;
    char platform_name[128], device_name[128], device_version[128], driver_version[64];
    int fp64;                     /* cl_khr_fp64 with a non-empty double FP config */
    int fp32_correct_div_sqrt;    /* CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT */
    cl_uint compute_units;
    cl_uint clock_mhz;            /* CL_DEVICE_MAX_CLOCK_FREQUENCY */
    size_t max_wg;
    cl_ulong global_mem;
} cl_device_info_t;

/* Number of OpenCL devices over all platforms (0 when there is no platform). */
int cl_device_count(void);
/* The k-th device over all platforms, in platform order. */
int cl_device_get(int k, cl_device_info_t *info, char *err, size_t errlen);

/* The build options every OpenCL program of the project starts from - the library's kernels and a test's own probe
 * kernels alike: OpenCL C 1.2, the precision (DEM_REAL_SIZE), the correctly rounded fp32 divide and sqrt without
 * which a GPU's fp32 bits are not the reference's (NVIDIA's OpenCL), and dir's kernels/, common/ and include/ as -I
 * folders. Into buf; its length, or -1 when it does not fit. */
int cl_build_options(char *buf, size_t len, const char *dir, int real_size);
/* Builds `source` for the device; on failure the message holds the device's build log. */
int cl_build(cl_context ctx, cl_device_id dev, const char *source, const char *options, cl_program *out, char *err,
             size_t errlen);
#endif
