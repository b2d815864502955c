/* wall_overlap.c - dem_wall_overlap: the kernels' own wall geometry (common/contact_geometry.h, wall_geometry),
 * compiled here in double, for the host's views of wall contacts (the contact network, energies, the scene's
 * start-up overlap check), so that a finite die's rim and faces are seen as the kernels see them. */
#define DEM_REAL_SIZE 8
#include "contact_geometry.h"
#include "dem.h"
#include "sim.h"

int sim_wall_table(const dem_wall *w, double *radius, double *height)
{
    if (w->kind == DEM_WALL_CYLINDER) {
        *radius = w->radius, *height = w->height;
        return WALL_CYLINDER_INSIDE;
    }
    *radius = w->cup_depth > 0 ? w->cup_radius : 0;
    *height = w->cup_depth > 0 ? w->cup_depth : 0;
    return w->cup_depth > 0 ? WALL_PLANE_CUP : WALL_PLANE;
}

double dem_wall_overlap(const dem_wall *w, const double point[3], const double x[3], double r, double n[3])
{
    return sim_wall_overlap_gap(w, point, x, r, 0, n);
}

double sim_wall_overlap_gap(const dem_wall *w, const double point[3], const double x[3], double r, double gap,
                            double n[3])
{
    real wr[W_STRIDE] = {0};
    for (int d = 0; d < 3; d++) {
        wr[W_PX + d] = point[d];
        wr[W_NX + d] = w->normal[d];
    }
    double rad, hgt;
    int type = sim_wall_table(w, &rad, &hgt);
    wr[W_RADIUS] = rad;
    wr[W_HEIGHT] = hgt;
    wall_geom g = wall_geometry_gap(type, wr, v3(x[0], x[1], x[2]), r, gap);
    if (n) {
        n[0] = g.n.x;
        n[1] = g.n.y;
        n[2] = g.n.z;
    }
    return g.active ? g.delta : (g.delta < 0 ? g.delta : 0);
}
