/* mdr.c - reference twin of the MDR contact walked along a prescribed approach (common/laws/mdr_core.h mdr_walk), for
 * tests/test_mdr.c, which runs the same walk in an OpenCL kernel and compares the bits. */
#include "ref_kernels.h"
#include "laws/mdr_core.h"

void REF(dem_mdr_walk)(int kind, int nsteps, const real *u, const real *mat, real r, real r2, real mass1, real mass2,
                       real dt, real *delta, real *radius, real *psi, real *force)
{
    mdr_material m = mdr_material_from(mat);
    mdr_walk(kind, nsteps, u, &m, r, r2, mass1, mass2, dt, delta, radius, psi, force);
}

void REF(dem_mdr_fixed)(int which, int n, const real *x, real *y)
{
    mdr_fixed(which, n, x, y);
}
