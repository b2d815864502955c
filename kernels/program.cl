/* program.cl - the OpenCL program: every kernel of DEM_KERNEL_LIST (common/dem_kernels.h), each one work item per
 * item of its family's DEM_ITEM body (common/dem_families.h). Its twin is reference/loops.c, made from the same two
 * lists. Headers are named by their path from this folder (docs/design.md "Kernel sources are read at run time"). */
#include "../common/dem_families.h"
DEM_KERNEL_LIST(DEM_KERNEL)
