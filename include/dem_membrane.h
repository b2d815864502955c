/* dem_membrane.h - membranes in libdem (seed 001): springs, triangles under a pressure, hinges, meshes made or read
 * from files and added as membranes, triangles as patches that particles touch, and particles riding on walls.
 * Installed with dem.h, which includes it; the error rule at the top of dem.h holds here too.
 */
#ifndef DEM_MEMBRANE_H
#define DEM_MEMBRANE_H
#include "dem.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A damped linear spring between particles i and j (seed 001 Eq. 6-7, the membrane's stretching): particle i feels
 * F_i = -rho_hat [k (rho - rest) + 2 gamma sqrt(k m_eff) rho_hat . rho_dot], rho = x_i - x_j, m_eff = m_i m_j /
 * (m_i + m_j), and j the exact negation. k > 0 [N/m]; rest >= 0 [m], or < 0 for the distance at dem_start; gamma >=
 * 0 the damping ratio. Turns on DEM_EFFECT_SPRINGS. Each particle's spring forces are added in spring order after
 * its contact forces (a channel of records gathered per particle: no atomics). Returns the spring's index, or a
 * negative dem_status. */
DEM_API int dem_add_spring(dem_sim *s, int i, int j, double k, double rest, double gamma);
DEM_API int dem_spring_count(const dem_sim *s);
/* A triangle of particles a, b, c (a membrane patch). Under a pressure sigma (dem_set_pressure) it is loaded with
 * F = sigma A n_hat (seed 001 Eq. 18), A and n_hat its current area and unit normal along (x_b - x_a) x (x_c - x_a):
 * order the vertices so that this points where the pressure pushes (into the enclosed granulate); each vertex gets
 * F / 3, added in triangle order after its spring forces (the contribution channel). Returns the triangle's index, or a
 * negative dem_status. */
DEM_API int dem_add_triangle(dem_sim *s, int a, int b, int c);
DEM_API int dem_triangle_count(const dem_sim *s);
/* The triangles' particles, 3 per triangle in triangle order, into tri[3 dem_triangle_count] */
DEM_API void dem_triangles_get(const dem_sim *s, int *tri);
/* Triangles first .. first+count-1 become patches: surfaces that the other particles touch (seed 001 section 2.5,
 * common/patch_contacts.h), with the Hertz-Mindlin law of the particle's and the triangle's first vertex's materials;
 * their vertices then touch no particle as spheres (walls still, with their radius). Turns on DEM_EFFECT_PATCHES. */
DEM_API int dem_add_patches(dem_sim *s, int first, int count);
/* The pressure [Pa] on every triangle; turns on DEM_EFFECT_PRESSURE. */
DEM_API int dem_set_pressure(dem_sim *s, double sigma);
/* A pressure schedule (before dem_start): stage k takes the pressure linearly from where the previous stage ended
 * (the first: dem_set_pressure's value, 0 by default) to `pressure` over `duration` [s] (0: a jump); after the last
 * stage it holds. Evaluated on the host at the time of each force computation, so every backend gets the same value.
 * At most DEM_MAX_STAGES stages; turns on DEM_EFFECT_PRESSURE. */
typedef struct {
    double duration; /* [s] */
    double pressure; /* [Pa] at the stage's end */
} dem_pressure_stage;
DEM_API int dem_set_pressure_stages(dem_sim *s, int nstages, const dem_pressure_stage *stages);
DEM_API double dem_pressure(const dem_sim *s); /* the pressure of the last force computation [Pa] (before dem_start: 0) */
/* A hinge: the triangles (p1, p3, p4) and (p2, p4, p3) sharing the edge p3-p4 resist bending (seed 001 Eq. 8-16,
 * Bridson et al. 2003; common/bending.h has the derivation): elastic constant kel [N m], dissipative kdiss [N s],
 * rest angle theta0 [rad] (NAN: the angle of the initial positions). Turns on DEM_EFFECT_BENDING. Returns its index,
 * or a negative dem_status. */
DEM_API int dem_add_hinge(dem_sim *s, int p1, int p2, int p3, int p4, double kel, double kdiss, double theta0);
DEM_API int dem_hinge_count(const dem_sim *s);

/* Membranes (seed 001 section 2.2). A triangulated surface: nv vertices (x[3 nv], m) and nt triangles (tri[3 nt])
 * ordered so that (x_b - x_a) x (x_c - x_a) points where a pressure pushes (dem_add_triangle). */
typedef struct {
    int nv, nt;
    double *x;
    int *tri;
} dem_mesh;
typedef enum { DEM_MESH_SHEET = 0, DEM_MESH_TUBE = 1, DEM_MESH_SPHERE = 2 } dem_mesh_kind;
/* A generated mesh (host/mesh/mesh.c): a sheet in the plane z = center[2], a x b [m] along x and y, pushed along -z
 * (equilateral: a kept and cut into whole edges, the rows as many as come nearest to b); a
 * tube around the axis through center along z, radius a, height b, pushed inward (open ends); a sphere of radius a
 * about center, pushed inward (the icosahedron split until its edges are nearest `edge`, smoothed). Near-equilateral
 * triangles with edges near `edge` [m]. */
typedef struct {
    dem_mesh_kind kind;
    double center[3];
    double a, b;
    double edge;
} dem_mesh_spec;
/* Fills m (free it with dem_mesh_free); 0, or DEM_ERR_ARG (a spec it refuses) or DEM_ERR_NOMEM with the reason in err
 * (m then holds nothing). */
DEM_API int dem_mesh_make(const dem_mesh_spec *spec, dem_mesh *m, char *err, size_t errlen);
/* The vertices dem_mesh_make would make of spec, counted in double before anything is made (a caller's cap on a
 * mesh's size, which must see huge counts as huge); NAN for an edge or sizes it refuses (not > 0 and finite). */
DEM_API double dem_mesh_vertices(const dem_mesh_spec *spec);
/* The grid of a generated sheet or tube, in double: n1 vertices along a row (a tube's rings), n2 rows, dx the spacing
 * along a row (a tube's chord), dy between rows (a sheet's equilateral: dx sqrt(3)/2). 0, or DEM_ERR_ARG for
 * other kinds. */
DEM_API int dem_mesh_grid(const dem_mesh_spec *spec, double *n1, double *n2, double *dx, double *dy);
DEM_API void dem_mesh_free(dem_mesh *m);
/* Reads a mesh from a Wavefront OBJ (v and triangular f) or an STL file (ASCII or binary; equal coordinates become one
 * vertex), strictly: anything it cannot take is refused with "path:line: reason" in err (host/mesh/mesh_file.c). The
 * triangles keep the file's order and orientation. Free with dem_mesh_free. 0, or DEM_ERR_ARG (a file it cannot
 * open or take) or DEM_ERR_NOMEM, the reason in err. */
DEM_API int dem_mesh_read(const char *path, dem_mesh *m, char *err, size_t errlen);
/* A mesh's edges (each once, edge[2 ne], in the order of their (lower, higher) vertex) and hinges (one per edge
 * shared by two triangles, hinge[4 nhinges] as dem_add_hinge takes them); nboundary edges belong to one triangle.
 * Refuses an edge of more than two triangles and two triangles turned opposite ways. 0, or DEM_ERR_ARG (refused) or
 * DEM_ERR_NOMEM with the reason in err; free t with dem_mesh_topo_free. */
typedef struct {
    int ne, nhinges, nboundary;
    int *edge, *hinge;
} dem_mesh_topo;
DEM_API int dem_mesh_topology(const dem_mesh *m, dem_mesh_topo *t, char *err, size_t errlen);
DEM_API void dem_mesh_topo_free(dem_mesh_topo *t);
/* A membrane's material (seed 001 section 2.2 and Table 2). The springs on its edges get k = (sqrt(3)/2) young
 * thickness (the stiffness at which a lattice of equilateral triangles has the 2D Young's modulus young x thickness;
 * its Poisson's ratio is then 1/3 whatever `poisson` is: tests/test_springs.c), damping ratio `damping`, rest length
 * the initial one; its hinges k_el, k_diss and the initial angle; a vertex the mass density x thickness x a third of
 * its triangles' area. The vertices are particles of radius vertex_radius that touch other particles as spheres with
 * the membrane's young, poisson, restitution and friction (seed 001's MSS_particle model). A membrane's vertices do not
 * touch each other, so their spheres may overlap: vertex_radius is at most the shortest edge. */
typedef struct {
    double young, poisson, thickness, density, restitution, friction;
    double damping;          /* damping ratio gamma of the edge springs */
    double kel, kdiss;       /* hinges [N m], [N s]; 0 and 0: no hinges */
    double vertex_radius;    /* [m] */
    int model;               /* DEM_MEMBRANE_PARTICLE (0): particles touch the vertices as spheres; DEM_MEMBRANE_PATCH:
                                they touch the triangles (dem_add_patches) */
} dem_membrane;
enum { DEM_MEMBRANE_PARTICLE = 0, DEM_MEMBRANE_PATCH = 1 };
typedef struct {
    int first_particle, nvertices, first_spring, nsprings, first_triangle, ntriangles, first_hinge, nhinges;
    double area, mass;       /* at rest [m^2], [kg] */
} dem_membrane_info;
/* Adds the mesh m as a membrane: its vertices as particles (first_particle onwards, in mesh order), its edges as
 * springs, its triangles (in mesh order, for dem_set_pressure) and its hinges; info (may be NULL) says where they
 * went. Everything is checked before anything is added: on an error nothing is. Returns 0 or a negative dem_status. */
DEM_API int dem_add_membrane(dem_sim *s, const dem_mesh *m, const dem_membrane *mm, dem_membrane_info *info);

/* Particle `particle` rides on wall `wall` (added before): it becomes fixed (DEM_PARTICLE_FIXED) and moves with the
 * wall's velocity at every step, its own given velocity replaced - a membrane's end ring on a platen. It does not
 * touch that wall (the platen's force is the granulate's alone). Turns on DEM_EFFECT_RIDERS. */
DEM_API int dem_attach_to_wall(dem_sim *s, int particle, int wall);

#ifdef __cplusplus
}
#endif
#endif /* DEM_MEMBRANE_H */
