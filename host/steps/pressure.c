/* pressure.c - the pressure step (kernels/pressure.cl): each triangle's load into its vertices' channel records.
 * Written once for every backend. */
#include "backend.h"

int dem_stage_pressure(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_pressure_forces); }
