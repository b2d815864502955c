/* contact_forces.c - the contact step (kernels/contact_forces.cl): contact_pairs (each pair once), then
 * contact_forces (per-particle sums in canonical order, walls). Written once for every backend. */
#include "backend.h"

int dem_stage_contact_forces(const dem_backend_ops *o, dem_backend *b)
{
    return dem_launch(o, b, K_contact_pairs) || dem_launch(o, b, K_contact_forces);
}
