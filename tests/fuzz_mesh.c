/* fuzz_mesh.c - libFuzzer harness for the meshes a membrane is made of (make fuzz-mesh): the generated specs
 * (dem_mesh_vertices, dem_mesh_make: sheet, tube, sphere from any 64-bit sizes, nan, inf and denormals included) and
 * the mesh file readers (dem_mesh_read: OBJ, ASCII and binary STL from any bytes).
 *
 * Input: byte 0 chooses. Even: a spec - byte 1 the kind (3 of 4 valid), then centre x, y, z, a, b, edge as 8-byte
 * doubles (missing bytes are 0). Odd: the rest of the input is a file, .obj when byte 0 & 2 is 0, else .stl.
 * Oracles, besides ASan and UBSan: a spec's vertex count is computed without overflow (in integers a tube of radius
 * 1e-30 m and height 5.3e18 m wraps to 2051 vertices); one above the library's cap is refused before anything is
 * made; one made has exactly the count announced, finite vertices and triangles of three different vertices in
 * range; a file read gives the same, or a refusal that names the file. Counts above FUZZ_MESH_MAKE are counted but
 * not made (one input must not take seconds). */
#include "dem.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FUZZ_MESH_MAKE 20000
#define MESH_CAP 2000000 /* host/mesh/mesh.c MESH_MAX_VERTICES */

static void check_mesh(const dem_mesh *m)
{
    if (m->nv < 3 || m->nt < 1 || !m->x || !m->tri)
        __builtin_trap();
    for (int i = 0; i < 3 * m->nv; i++)
        if (!isfinite(m->x[i]))
            __builtin_trap();
    for (int t = 0; t < m->nt; t++) {
        const int *c = m->tri + 3 * t;
        for (int k = 0; k < 3; k++)
            if (c[k] < 0 || c[k] >= m->nv)
                __builtin_trap();
    }
}

static void fuzz_spec(const uint8_t *data, size_t size)
{
    double v[6] = {0};
    for (int k = 0; k < 6 && 2 + 8 * (size_t)k < size; k++) {
        uint8_t b[8] = {0};
        memcpy(b, data + 2 + 8 * k, size - 2 - 8 * (size_t)k < 8 ? size - 2 - 8 * (size_t)k : 8);
        memcpy(&v[k], b, 8);
    }
    dem_mesh_spec sp = {(dem_mesh_kind)(size > 1 ? data[1] % 4 : 0), {v[0], v[1], v[2]}, v[3], v[4], v[5]};
    double count = dem_mesh_vertices(&sp);
    if (count != count) { /* refused sizes: made never */
        dem_mesh m;
        char err[512];
        if (dem_mesh_make(&sp, &m, err, sizeof err) == 0)
            __builtin_trap();
        return;
    }
    if (!(count >= 3) || count > FUZZ_MESH_MAKE && count <= MESH_CAP)
        return;
    dem_mesh m;
    char err[512];
    int rc = dem_mesh_make(&sp, &m, err, sizeof err);
    if (count > MESH_CAP) { /* refused (for its size, or for a centre that is not finite) */
        if (rc == 0)
            __builtin_trap();
        return;
    }
    if (rc == 0) {
        if ((double)m.nv != count)
            __builtin_trap();
        check_mesh(&m);
        dem_mesh_free(&m);
    }
}

static void fuzz_file(const uint8_t *data, size_t size, int stl)
{
    static char path[2][128];
    if (!path[stl][0])
        snprintf(path[stl], sizeof path[stl], "/tmp/fuzz-mesh-%d.%s", (int)getpid(), stl ? "stl" : "obj");
    FILE *fp = fopen(path[stl], "wb");
    if (!fp || fwrite(data, 1, size, fp) != size)
        __builtin_trap(); /* the harness itself is broken */
    fclose(fp);
    dem_mesh m;
    char err[1024];
    if (dem_mesh_read(path[stl], &m, err, sizeof err)) {
        if (!strstr(err, path[stl])) /* a refusal names the file */
            __builtin_trap();
        return;
    }
    check_mesh(&m);
    dem_mesh_free(&m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    if (data[0] % 2 == 0)
        fuzz_spec(data, size);
    else
        fuzz_file(data + 1, size - 1, (data[0] & 2) != 0);
    return 0;
}
