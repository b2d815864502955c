/* series.c - the Hertz contact energy of common/series.h for the host's energies in double (host/energy.c); the
 * series terms themselves are written by the kernels that have them (integrate_kick, contact_forces,
 * wall_reduce_block). */
#include "ref_kernels.h"
#include "series.h"

real REF(dem_hertz_energy)(real estar, real rstar, real delta) { return hertz_energy(estar, rstar, delta); }
