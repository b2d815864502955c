/* springs.c - the springs step (kernels/springs.cl): each spring's force into its two records, then each particle's
 * records added to its force in spring order. Written once for every backend. */
#include "backend.h"

int dem_stage_springs(const dem_backend_ops *o, dem_backend *b)
{
    return dem_launch(o, b, K_spring_forces) || dem_launch(o, b, K_channel_gather);
}
