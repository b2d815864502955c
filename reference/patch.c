/* patch.c - reference twin of the patch geometry (common/patch.h, common/patch_contacts.h) as tests/test_patch.c and
 * the energy probe it: the closest feature of point i to triangle i, which of a list of contacts stay, and a sphere's
 * overlap on a patch. The test runs the same items in an OpenCL program and compares the bits. */
#include "ref_kernels.h"
#include "patch_contacts.h"

void REF(dem_patch_probe)(int n, const real *p, const real *tri_x, int *kind, int *index, real *w, real *point)
{
    for (int i = 0; i < n; i++) {
        patch_point c = patch_closest(v3_load(p, i), v3_load(tri_x, 3 * i), v3_load(tri_x, 3 * i + 1),
                                      v3_load(tri_x, 3 * i + 2));
        kind[i] = c.kind, index[i] = c.index;
        w[3 * i] = c.w[0], w[3 * i + 1] = c.w[1], w[3 * i + 2] = c.w[2];
        v3_store(point, i, c.point);
    }
}

int REF(dem_patch_keep)(int i, int n, const int *id, const int *tri, const int *kind, const real *d2)
{
    return patch_keep(i, n, id, tri, kind, d2);
}

/* The overlap of a sphere of radius r at p on triangle tri_x, in a contact with flags `flags` (PATCH_* of
 * dem_layout.h), as patch_forces computes it (common/patch_contacts.h); 0 where it does not touch. For the energy
 * (host/physics/energy.c). */
real REF(dem_patch_overlap)(const real *p, const real *tri_x, unsigned flags, real r)
{
    static const int tri[3] = {0, 1, 2}; /* vertices 0, 1, 2, stored at 0, 1, 2 */
    static const int none[3] = {-1, -1, -1};
    patch_geom g = patch_geometry(v3_load(p, 0), r, flags, v3_zero(), none, tri_x, tri, tri, 0);
    if (!g.touch)
        return (real)0;
    return g.crossed ? r - g.h / dem_sqrt(v3_dot(g.nrm, g.nrm)) : r - dem_sqrt(g.e2);
}

/* The overlap the Hertz law of a patch contact is given for an overlap d (patch_law_overlap), for the energy */
real REF(dem_patch_law)(real d, real r) { return patch_law_overlap(d, r); }
