/* series.c - the Hertz contact energy of common/series.h for the host's energies in double (host/physics/energy.c); the
 * series terms themselves are written by the kernels that have them (integrate_kick, contact_forces,
 * wall_reduce_block). */
#include "ref_kernels.h"
#include "series.h"

real REF(dem_hertz_energy)(real estar, real rstar, real delta) { return hertz_energy(estar, rstar, delta); }
/* the law's normal and tangential stiffness at overlap delta (common/hertz_mindlin.h), for host/physics/stability.c */
void REF(dem_hertz_stiffness)(real estar, real gstar, real rstar, real delta, real *kn, real *kt)
{
    real srd = dem_sqrt(rstar * delta);
    *kn = hm_normal_stiffness(estar, srd);
    *kt = hm_tangential_stiffness(gstar, srd);
}
