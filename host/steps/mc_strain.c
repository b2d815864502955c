/* mc_strain.c - MC-strain's fixed-point update of the forces with its tolerance (common/mc_strain.h; the induced
 * displacements are one launch, mc_strain_disp; the iteration loop itself is the driver's, host/core/step_loop.c). Written
 * once for every backend. */
#include "backend.h"

int dem_stage_mc_strain_update(const dem_backend_ops *o, dem_backend *b, double tol)
{
    DEM_CORE(b)->sr[SR_MC_TOL] = tol;
    return dem_launch(o, b, K_mc_strain_update);
}
