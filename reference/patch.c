/* patch.c - reference twin of the patch geometry (common/patch.h) as tests/test_patch.c probes it, until the patch
 * contact pass (common/patch_contacts.h) runs it in full: the closest feature of point i to triangle i, and which of a list of
 * contacts stay. The test runs the same items in an OpenCL program and compares the bits. */
#include "ref_kernels.h"
#include "patch.h"

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
