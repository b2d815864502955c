/* cl_util.c - OpenCL plumbing shared by every host driver (see cl_util.h). */
#include "cl_util.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *cl_errname(cl_int e)
{
    switch (e) {
#define E(x) case x: return #x;
        E(CL_SUCCESS) E(CL_DEVICE_NOT_FOUND) E(CL_DEVICE_NOT_AVAILABLE) E(CL_COMPILER_NOT_AVAILABLE)
        E(CL_MEM_OBJECT_ALLOCATION_FAILURE) E(CL_OUT_OF_RESOURCES) E(CL_OUT_OF_HOST_MEMORY)
        E(CL_PROFILING_INFO_NOT_AVAILABLE) E(CL_MEM_COPY_OVERLAP) E(CL_BUILD_PROGRAM_FAILURE)
        E(CL_MAP_FAILURE) E(CL_INVALID_VALUE) E(CL_INVALID_DEVICE_TYPE) E(CL_INVALID_PLATFORM)
        E(CL_INVALID_DEVICE) E(CL_INVALID_CONTEXT) E(CL_INVALID_QUEUE_PROPERTIES) E(CL_INVALID_COMMAND_QUEUE)
        E(CL_INVALID_HOST_PTR) E(CL_INVALID_MEM_OBJECT) E(CL_INVALID_BUILD_OPTIONS) E(CL_INVALID_PROGRAM)
        E(CL_INVALID_PROGRAM_EXECUTABLE) E(CL_INVALID_KERNEL_NAME) E(CL_INVALID_KERNEL_DEFINITION)
        E(CL_INVALID_KERNEL) E(CL_INVALID_ARG_INDEX) E(CL_INVALID_ARG_VALUE) E(CL_INVALID_ARG_SIZE)
        E(CL_INVALID_KERNEL_ARGS) E(CL_INVALID_WORK_DIMENSION) E(CL_INVALID_WORK_GROUP_SIZE)
        E(CL_INVALID_WORK_ITEM_SIZE) E(CL_INVALID_GLOBAL_OFFSET) E(CL_INVALID_EVENT_WAIT_LIST) E(CL_INVALID_EVENT)
        E(CL_INVALID_OPERATION) E(CL_INVALID_BUFFER_SIZE) E(CL_INVALID_GLOBAL_WORK_SIZE)
        E(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST) E(CL_MISALIGNED_SUB_BUFFER_OFFSET)
#undef E
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL platform: is an ICD such as pocl-opencl-icd installed?)";
    default: return "unknown OpenCL error";
    }
}

int cl_check(cl_int e, const char *where, char *err, size_t errlen)
{
    if (e == CL_SUCCESS)
        return 0;
    snprintf(err, errlen, "%s: %s (%d)", where, cl_errname(e), (int)e);
    return 1;
}

static int platforms(cl_platform_id **out, cl_uint *n)
{
    *out = NULL;
    *n = 0;
    if (clGetPlatformIDs(0, NULL, n) != CL_SUCCESS || *n == 0)
        return 0;
    *out = malloc(*n * sizeof **out);
    if (!*out || clGetPlatformIDs(*n, *out, NULL) != CL_SUCCESS) {
        free(*out);
        *out = NULL;
        *n = 0;
    }
    return (int)*n;
}

int cl_device_count(void)
{
    cl_platform_id *p;
    cl_uint np;
    int total = 0;
    platforms(&p, &np);
    for (cl_uint k = 0; k < np; k++) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(p[k], CL_DEVICE_TYPE_ALL, 0, NULL, &nd) == CL_SUCCESS)
            total += (int)nd;
    }
    free(p);
    return total;
}

int cl_device_get(int want, cl_device_info_t *info, char *err, size_t errlen)
{
    cl_platform_id *p;
    cl_uint np;
    memset(info, 0, sizeof *info);
    if (want < 0) {
        const char *env = getenv("DEM_DEVICE");
        snprintf(err, errlen, "OpenCL device index %d is not valid%s%s%s (an index from `dem devices` or `clinfo -l`)",
                 want, env ? " (DEM_DEVICE='" : "", env ? env : "", env ? "')" : "");
        return 1;
    }
    if (!platforms(&p, &np)) {
        snprintf(err, errlen, "no OpenCL platform found (install pocl-opencl-icd, or run `make deps`)");
        return 1;
    }
    int seen = 0, found = 0;
    for (cl_uint k = 0; k < np && !found; k++) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(p[k], CL_DEVICE_TYPE_ALL, 0, NULL, &nd) != CL_SUCCESS || nd == 0)
            continue;
        cl_device_id *d = malloc(nd * sizeof *d);
        if (d && clGetDeviceIDs(p[k], CL_DEVICE_TYPE_ALL, nd, d, NULL) == CL_SUCCESS && want < seen + (int)nd) {
            info->platform = p[k];
            info->device = d[want - seen];
            found = 1;
        }
        seen += (int)nd;
        free(d);
    }
    free(p);
    if (!found) {
        snprintf(err, errlen, "OpenCL device %d does not exist (%d found; `clinfo -l` lists them)", want, seen);
        return 1;
    }
    cl_device_id dv = info->device;
    cl_device_fp_config sfp = 0, dfp = 0;
    /* every query must answer (a device that cannot name itself or its limits is not used); only the double
     * configuration may be missing, which means no fp64 */
    if (cl_check(clGetPlatformInfo(info->platform, CL_PLATFORM_NAME, sizeof info->platform_name, info->platform_name,
                                   NULL), "clGetPlatformInfo(NAME)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DEVICE_NAME, sizeof info->device_name, info->device_name, NULL),
                 "clGetDeviceInfo(NAME)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DEVICE_VERSION, sizeof info->device_version, info->device_version, NULL),
                 "clGetDeviceInfo(VERSION)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DRIVER_VERSION, sizeof info->driver_version, info->driver_version, NULL),
                 "clGetDeviceInfo(DRIVER_VERSION)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof info->compute_units, &info->compute_units,
                                 NULL), "clGetDeviceInfo(MAX_COMPUTE_UNITS)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DEVICE_MAX_CLOCK_FREQUENCY, sizeof info->clock_mhz, &info->clock_mhz, NULL),
                 "clGetDeviceInfo(MAX_CLOCK_FREQUENCY)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof info->max_wg, &info->max_wg, NULL),
                 "clGetDeviceInfo(MAX_WORK_GROUP_SIZE)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof info->global_mem, &info->global_mem, NULL),
                 "clGetDeviceInfo(GLOBAL_MEM_SIZE)", err, errlen) ||
        cl_check(clGetDeviceInfo(dv, CL_DEVICE_SINGLE_FP_CONFIG, sizeof sfp, &sfp, NULL),
                 "clGetDeviceInfo(SINGLE_FP_CONFIG)", err, errlen))
        return 1;
    if (clGetDeviceInfo(dv, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof dfp, &dfp, NULL) != CL_SUCCESS)
        dfp = 0;
    info->fp32_correct_div_sqrt = (sfp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
    info->fp64 = dfp != 0;
    return 0;
}

int cl_build(cl_context ctx, cl_device_id dev, const char *source, const char *options, cl_program *out, char *err,
             size_t errlen)
{
    cl_int e;
    cl_program prog = clCreateProgramWithSource(ctx, 1, &source, NULL, &e);
    if (cl_check(e, "clCreateProgramWithSource", err, errlen))
        return 1;
    e = clBuildProgram(prog, 1, &dev, options, NULL, NULL);
    if (e != CL_SUCCESS) {
        size_t len = 0;
        char *log = NULL;
        if (clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, 0, NULL, &len) == CL_SUCCESS &&
            (log = malloc(len + 1)) != NULL) {
            if (clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, len, log, NULL) != CL_SUCCESS)
                len = 0; /* said as "(no log)" below */
            log[len] = 0;
        }
        snprintf(err, errlen, "kernel build failed: %s (%d)\noptions: %s\nbuild log:\n%s", cl_errname(e), (int)e,
                 options, log && log[0] ? log : "(no log)");
        free(log);
        clReleaseProgram(prog);
        return 1;
    }
    *out = prog;
    return 0;
}

int cl_build_options(char *buf, size_t len, const char *dir, int real_size)
{
    int w = snprintf(buf, len, "-cl-std=CL1.2 -DDEM_REAL_SIZE=%d -I%s/kernels -I%s/common -I%s/include%s", real_size,
                     dir, dir, dir, real_size == 4 ? " -cl-fp32-correctly-rounded-divide-sqrt" : "");
    return w < 0 || (size_t)w >= len ? -1 : w;
}
