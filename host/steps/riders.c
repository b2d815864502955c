/* riders.c - the riders step (kernels/riders.cl): particles put at their walls' places. Written once for every
 * backend. */
#include "backend.h"

int dem_stage_riders(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_rider_place); }
