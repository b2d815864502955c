/* bending.c - the bending step (kernels/bending.cl): each hinge's four forces into the channel records. Written once
 * for every backend. */
#include "backend.h"

int dem_stage_bending(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_hinge_forces); }
