/* vec3.h - small 3-vector algebra on `real`, identical in C and OpenCL C.
 * Each operation is written out component by component so that the order of rounding is fixed. */
#ifndef DEM_VEC3_H
#define DEM_VEC3_H
#include "dem_real.h"

typedef struct { real x, y, z; } vec3;

DEM_INLINE vec3 v3(real x, real y, real z) { vec3 r; r.x = x; r.y = y; r.z = z; return r; }
DEM_INLINE vec3 v3_zero(void) { return v3((real)0, (real)0, (real)0); }
DEM_INLINE vec3 v3_add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
DEM_INLINE vec3 v3_sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
DEM_INLINE vec3 v3_scale(vec3 a, real s) { return v3(a.x * s, a.y * s, a.z * s); }
DEM_INLINE vec3 v3_neg(vec3 a) { return v3(-a.x, -a.y, -a.z); }
DEM_INLINE real v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
DEM_INLINE vec3 v3_cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
DEM_INLINE vec3 v3_load(DEM_CONST_GLOBAL real *a, int i) { return v3(a[3 * i], a[3 * i + 1], a[3 * i + 2]); }
DEM_INLINE void v3_store(DEM_GLOBAL real *a, int i, vec3 v)
{
    a[3 * i] = v.x;
    a[3 * i + 1] = v.y;
    a[3 * i + 2] = v.z;
}
#endif /* DEM_VEC3_H */
