/* linear_spring.h - a test-only law (built with -DDEM_TEST_LAWS, tests/test_law_toy.c): a linear normal spring,
 *   F = k delta n,  energy k delta^2 / 2,  stiffness k (normal), 0 (tangential),
 * with no damping, friction or clamp to add (it never pulls: delta > 0 wherever a caller asks). It proves that a law
 * is one header plus its line in laws.h: the particle pairs, walls and patches, the stress, the series rows and the
 * host's energy and stability estimate reach it only through the registry.
 *
 * Pair-table columns (dem_layout.h): k [N/m] is read from the E* column (PM_ESTAR), so a run sets it through the
 * materials (E* = 1 / ((1 - nu_a^2) / E_a + (1 - nu_b^2) / E_b)) and the host's set-up needs no new column.
 */
#ifndef DEM_LAW_LINEAR_SPRING_H
#define DEM_LAW_LINEAR_SPRING_H
#include "law.h"

#define PM_LINEAR_K PM_ESTAR
#define LAW_COLUMNS_linear_spring(C) C(PM_LINEAR_K)

DEM_INLINE real linear_spring_elastic(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return pm[PM_LINEAR_K] * delta;
}
DEM_INLINE law_result linear_spring_force(unsigned fx, law_in c, law_ctx ctx)
{
    law_result r;
    r.active = 1;
    r.st = (real)0;
    r.fel = linear_spring_elastic(c.pm, c.rstar, c.delta, 0);
    r.force = v3_scale(c.n, r.fel);
    r.ft = r.hist = v3_zero();
    return r;
}
DEM_INLINE real linear_spring_energy_kept(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real fel, real st)
{
    return (real)0.5 * fel * delta;
}
DEM_INLINE real linear_spring_energy(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return linear_spring_energy_kept(pm, rstar, delta, linear_spring_elastic(pm, rstar, delta, 0), st);
}
DEM_INLINE void linear_spring_stiffness(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real *kn, real *kt)
{
    *kn = pm[PM_LINEAR_K];
    *kt = (real)0;
}
#endif /* DEM_LAW_LINEAR_SPRING_H */
