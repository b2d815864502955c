/* contact_forces.c - the contact step (kernels/contact_forces.cl): contact_pairs (each pair once), then
 * contact_forces (per-particle sums in canonical order, walls); the walls' sums (host/steps/wall_forces.c) may run between
 * them. Written once for every backend. */
#include "backend.h"

int dem_stage_contact_pairs(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_contact_pairs); }

int dem_stage_contact_sums(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_contact_forces); }
