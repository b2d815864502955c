/* dem_families.h - every kernel family's header, the one list of them: the OpenCL program (kernels/program.cl) and
 * the reference loops (reference/loops.c) include it and then make every kernel of DEM_KERNEL_LIST
 * (common/dem_kernels.h) from the DEM_ITEM bodies found here. A new family is its header, one line here, and its
 * kernels' lists in dem_kernels.h. A header that only a family header includes (vec3.h, hertz_mindlin.h, ...) needs
 * no line. In the order the program held them when each family had a .cl file of its own. */
#ifndef DEM_FAMILIES_H
#define DEM_FAMILIES_H
#include "binning.h"
#include "neighbor.h"
#include "contact_forces.h"
#include "contact_rows.h"
#include "wall_forces.h"
#include "integrate.h"
#include "particle_stress.h"
#include "mc_strain.h"
#include "springs.h"
#include "pressure.h"
#include "bending.h"
#include "riders.h"
#include "patch_contacts.h"
#include "mdr_particle.h"
#include "halo.h"
#endif /* DEM_FAMILIES_H */
