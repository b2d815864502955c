/* springs.c - the springs step (kernels/springs.cl): each spring's force into its two records; and the channel's
 * gather, which adds each particle's records (springs, then triangles: pressure.c) to its force in order. Written
 * once for every backend. */
#include "backend.h"

int dem_stage_springs(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_spring_forces); }
int dem_stage_channel_gather(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_channel_gather); }
