/* dem.h - public interface of libdem: deterministic Hertz-Mindlin DEM on OpenCL devices with a bit-identical
 * plain C reference.
 *
 * Units are SI: m, kg, s, Pa, N. Typical use:
 *   dem_sim *s = dem_create();
 *   int glass = dem_add_material(s, &(dem_material){2500, 65e9, 0.24, 0.98, 0.2});
 *   dem_add_particle(s, x, v, 0.002, glass); ... dem_add_wall(s, &wall); dem_set_dt(s, 1e-7);
 *   dem_config c; dem_config_default(&c); c.backend = DEM_BACKEND_OPENCL;
 *   if (dem_start(s, &c) || dem_step(s, 1000)) fprintf(stderr, "%s\n", dem_error(s));
 *   dem_destroy(s);
 * Every function returning int returns 0 (DEM_OK) on success or a dem_status; dem_error() then says why.
 * The library never exits and never prints.
 */
#ifndef DEM_H
#define DEM_H
#include <stddef.h>
#include "dem_effects.h" /* DEM_EFFECT_* bits */

#define DEM_VERSION "0.1.0"

typedef enum {
    DEM_OK = 0,
    DEM_ERR_ARG = 1,      /* invalid argument or parameter */
    DEM_ERR_NOMEM = 2,    /* out of host memory */
    DEM_ERR_DEVICE = 3,   /* OpenCL device, kernel build or launch failure */
    DEM_ERR_DOMAIN = 4,   /* a particle left the binning domain or became non-finite */
    DEM_ERR_DT = 5,       /* time step above the stability bound (see dem_time_scales) */
    DEM_ERR_STATE = 6     /* call out of order (e.g. adding particles after dem_start) */
} dem_status;

typedef enum { DEM_FP32 = 4, DEM_FP64 = 8 } dem_precision;
typedef enum { DEM_BACKEND_REFERENCE = 0, DEM_BACKEND_OPENCL = 1 } dem_backend_kind;

/* A material with young = INFINITY is rigid, for walls only: a contact's E* and G* come from the particle alone
 * (seed 000 Eq. 3 and 5 with the wall's terms exactly zero) and its density is not used. */
typedef struct {
    double density;     /* [kg/m^3] */
    double young;       /* Young's modulus E [Pa] */
    double poisson;     /* Poisson's ratio nu, in (-1, 0.5] */
    double restitution; /* coefficient of restitution e, in (0, 1] */
    double friction;    /* Coulomb friction coefficient mu >= 0 */
    double mc_beta;     /* MC-stress prefactor beta >= 0 (seed 000 Eq. 10; used with DEM_EFFECT_MC_STRESS) */
    double mc_gamma;    /* MC-strain prefactor gamma >= 0 (seed 000 Eq. 7; used with DEM_EFFECT_MC_STRAIN) */
} dem_material;

/* Most motion stages of one wall (a scene's settling pause counts as one; `repeat` multiplies a list): enough for
 * a hundred load-unload cycles. */
#define DEM_MAX_STAGES 256
/* Most walls in a run: each particle keeps a 32-bit mask of the walls it touches (common/dem_layout.h). */
#define DEM_MAX_WALLS 32
typedef struct {
    double duration;    /* [s] */
    double velocity[3]; /* [m/s] */
    /* A servo stage (force > 0, plane walls): instead of `velocity` the wall moves along its normal at
     * gain x (force - F) [m/s], within +-max_speed, F the normal force the particles exerted on it in the previous
     * step (pushing it back along -normal counts positive): a platen held at a stress. Evaluated on the host from
     * the device's wall force, so every backend moves the wall alike. */
    double force;       /* [N] */
    double gain;        /* [m/s per N] */
    double max_speed;   /* [m/s] */
    /* A stage may end before its duration (0: not this way; `duration` stays its longest): after the first step in
     * which the normal force the particles exerted on the wall reached until_force [N] (plane walls; a press stage
     * "down until 5 kN"), or in which the wall got until_distance [m] or farther from where the stage began, or
     * after which the relative density reached until_density (in [0, 1], 0 off): the particles' volume (4/3 pi r^3 each, overlaps
     * counted twice, as a press reports it) over the die's bore between this wall and the one facing it, plus the
     * volumes of their cups (dem_wall.cup_radius: pi c (3 r^2 + c^2) / 6 each; a cup lies within the bore). For that
     * the wall is a plane (a punch), the die the first cylinder wall whose axis is parallel to its normal, and the
     * other punch the nearest plane wall facing it along that axis, on the particles' side (dem_start refuses a
     * set-up without them). The next stage begins with the next step. Checked on the host, from the device's wall
     * force and the host's wall positions, so every backend ends a stage at the same step; the stage state is part
     * of dem_state. */
    double until_force;
    double until_distance;
    double until_density;
} dem_stage;

typedef enum { DEM_WALL_PLANE = 0, DEM_WALL_CYLINDER = 1 } dem_wall_kind;
typedef struct {
    dem_wall_kind kind;
    int material;
    double point[3];  /* plane: a point on it; cylinder: a point on its axis [m] */
    double normal[3]; /* plane: normal towards the particles; cylinder: axis direction (normalised for you) */
    double radius;    /* cylinder: inner radius [m]; particles live inside */
    int nstages;      /* motion: stages run one after the other; the wall rests after the last */
    dem_stage stages[DEM_MAX_STAGES];
    double height;    /* cylinder: its length from `point` along the axis [m]: a die, a block with a bore a tablet can
                         leave at the top. In the bore beyond either end a sphere touches the rim (the end circle) as
                         an edge; outside the bore, the die's end faces (the die table). 0: endless */
    double cup_radius; /* plane: a concave face (a punch's cup): a spherical cap about the normal through `point`,
                          recessed away from the particles, this radius where it meets the plane [m]; 0: flat */
    double cup_depth;  /* plane: the cup's depth at its centre [m], 0 < depth <= cup_radius (at most a hemisphere);
                          the plane beyond the cup is the land, the circle where they meet an edge */
} dem_wall;

enum { DEM_PARTICLE_NO_ROTATION = 1, /* infinite moment of inertia */
       DEM_PARTICLE_FIXED = 2,       /* infinite mass and inertia: moves at its set velocity */
       /* keeps its set velocity along x, y or z (a motion prescribed along that axis, e.g. a sphere pushed across a
        * surface), integrates the other components; turns on DEM_EFFECT_CONSTRAINTS */
       DEM_PARTICLE_HOLD_VX = 4, DEM_PARTICLE_HOLD_VY = 8, DEM_PARTICLE_HOLD_VZ = 16 };
#define DEM_PARTICLE_HOLD_V (DEM_PARTICLE_HOLD_VX | DEM_PARTICLE_HOLD_VY | DEM_PARTICLE_HOLD_VZ)

typedef struct {
    dem_backend_kind backend;
    dem_precision precision;
    int device;          /* OpenCL device index over all platforms (see dem_device_count); default $DEM_DEVICE or 0 */
    size_t local_size;   /* work-group size; default 128; 0 = the runtime's choice */
    double skin;         /* neighbour-list skin [m]; 0 = automatic: chosen at each rebuild between 0.05 and 0.3 x
                            the smallest radius from how far the particles moved (dem_neighbor_skin; the bits do
                            not depend on it) */
    double cell_size;    /* binning cell edge [m]; 0 or less than 1.01 (2 r_max + skin) = that minimum (the
                            automatic skin: its largest, 0.3 x the smallest radius) */
    int force_dt;        /* 1: accept a time step above the stability bound */
    const char *source_dir; /* folder with kernels/ and common/; NULL = $DEM_SOURCE_DIR or the build's */
    int contacts;        /* 1: the run reads the contact network (dem_contacts_get), so the device keeps the force from
                            every wall on every particle (3 reals per particle and wall); 0 (default): only a run with a
                            servo wall keeps them (its every-step sums read them), and dem_contacts_get refuses a run
                            with walls that does not */
    long sample_every;   /* steps between the samples the caller will take (dem_step_sampled), 0 = rarely or never: at
                            DEM_SAMPLE_KEEP or fewer the device keeps the wall forces as for `contacts`, so each sample's
                            wall sums add them up instead of evaluating the wall contacts again, and a sampled step's
                            pair energies (1 real per pair, from the force law's own elastic force) */
    int reorder;         /* N > 0: at every N-th neighbour rebuild (the first at dem_start) the particles are stored
                            anew along a Morton curve through their current positions when their storage has
                            become scattered (reorder_gain), so that neighbours in space stay neighbours in memory as
                            the packing flows (host/core/reorder.c); 0 (default): they stay where they are. The bits do
                            not depend on it (every sum follows the particle ids), and every particle id the library
                            takes or returns stays that of dem_start, membranes, patches and attachments included. */
    double reorder_gain; /* stored anew when the mean distance between particles stored next to each other has grown
                            this many times since the last look and is this many times the new order's; 0 =
                            DEM_REORDER_GAIN (2); at most 1: whenever the order changes */
} dem_config;
/* The dem_config.reorder dem run uses with particle_order: spatial (docs/design.md "Every sum follows the particle
 * ids") */
#define DEM_REORDER_PERIOD 8
#define DEM_REORDER_GAIN 2.0 /* dem_config.reorder_gain 0 */
#define DEM_SAMPLE_KEEP 10

/* Fields that can be read back (dem_get_raw, dem_get_field). */
typedef enum {
    DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W,  /* position [m], velocity [m/s], angular velocity [rad/s]: real[3n] */
    DEM_FIELD_FORCE, DEM_FIELD_TORQUE,  /* [N], [N m]: real[3n] */
    DEM_FIELD_X_BUILD,              /* positions at the last neighbour build: real[3n] */
    DEM_FIELD_NBR_COUNT,            /* int[n] */
    DEM_FIELD_NBR_LIST,             /* int[slots]: the rows packed one after the other, row i at
                                       [start[i], start[i] + count[i]) (DEM_FIELD_NBR_START), sorted by partner id
                                       (ids of dem_start); slots (dem_neighbor_capacity) >= start[n] */
    DEM_FIELD_HIST,                 /* real[3*pairs]: elastic tangential force per listed pair [N], pairs numbered in the
                                       order of the particles' storage (each pair by the one stored first, in its row
                                       order: host/core/reorder.c; the ids' order unless dem_config.reorder moved them);
                                       empty without friction */
    DEM_FIELD_WALL_HIST,            /* real[3*n*nwalls]; empty without friction */
    DEM_FIELD_WALL_FORCE,           /* real[3*nwalls]: force each wall receives [N] */
    DEM_FIELD_CELL_START,           /* int[dem_cell_count() + 1] (the buffer may hold more, which mean nothing) */
    DEM_FIELD_CELL_PARTICLES,       /* int[n] */
    DEM_FIELD_FLAGS,                /* int[FLAG_COUNT] (common/dem_layout.h) */
    DEM_FIELD_WALL_REAL,            /* real[11*nwalls] (common/dem_layout.h W_*) */
    DEM_FIELD_TOUCH,                /* unsigned char[pairs]: 1 where the pair touched in the last step, one byte per
                                       listed pair, numbered like PAIR_RECORDS and HIST */
    DEM_FIELD_WALL_MASK,            /* unsigned[n]: bit k set where the particle touched wall k in the last step */
    DEM_FIELD_STRESS,               /* real[6n]: stress tensor xx,yy,zz,xy,xz,yz of each particle [Pa] (seed 000 Eq. 9,
                                   elastic normal forces; negative in compression), computed when read */
    DEM_FIELD_STRESS_TRACE,         /* real[n]: the trace MC-stress used in the last step [Pa]; empty without mc_stress */
    DEM_FIELD_MC_FORCE,             /* real[slots]: MC-strain elastic normal force per row slot (indexed like
                                       NBR_LIST; the device keeps one per pair, spread over both slots when read)
                                       [N]; mc_strain only */
    DEM_FIELD_MC_WALL_FORCE,        /* real[n*nwalls]: the same per particle-wall slot [N]; mc_strain only */
    DEM_FIELD_MC_DISP,              /* real[>= slots]: MC-strain displacement induced at each row slot's contact [m] */
    DEM_FIELD_MC_WALL_DISP,         /* real[n*nwalls]: the same per particle-wall slot [m] */
    DEM_FIELD_PAIR_RECORDS,         /* real[7*pairs]: each touching pair's force on its lower id (common/dem_layout.h
                                       PR_*), one record per listed pair, numbered like HIST (dem_contacts_get
                                       reads them) */
    DEM_FIELD_IN_START,             /* int[n+1]: where each particle's incoming pairs (partners stored before it) start
                                       in DEM_FIELD_IN_PAIR */
    DEM_FIELD_WALL_PF,              /* real[3*n*nwalls]: the force wall k exerts on particle i at [k*n + i] [N];
                                       kept only by runs with dem_config.contacts or a servo wall, else empty */
    DEM_FIELD_IN_PAIR,              /* int[pairs]: the pair record of each incoming pair: in_start[i] + g for the g-th
                                       partner stored before i in its row. IN_START and the pair-sized fields are in
                                       storage order (the ids' unless dem_config.reorder moved the particles).
                                       The pair-sized fields (HIST, TOUCH, PAIR_RECORDS, IN_PAIR) hold the pairs allocated, which
                                       grow at rebuilds: take dem_field_bytes just before each read; entries beyond the
                                       pairs listed (in_start[n]) hold nothing meaningful */
    DEM_FIELD_WALL_NORMAL_FORCE,    /* real[nwalls]: each wall's normal force, the sum of the particles' force components
                                       along their contact normals [N] (a die's radial force; a plane's normal force) */
    DEM_FIELD_NBR_START,            /* int[n+1]: where each particle's row starts in NBR_LIST (the exclusive prefix sum
                                       of NBR_COUNT; start[n] the slots in use) */
    DEM_FIELD__COUNT
} dem_field;

typedef struct {
    double rayleigh_time;  /* smallest Rayleigh time over the particles [s] */
    double recommended_dt; /* 0.2 x rayleigh_time [s] */
    double max_dt;         /* stability bound: 0.5 x rayleigh_time [s] */
    double hertz_time;     /* Hertz contact time of the two smallest like particles at the given speed [s] */
    double spring_period;  /* shortest undamped period 2 pi sqrt(m_eff / k) of the springs [s] (INFINITY: none); the
                              bounds above then also hold 50 steps (recommended) and 10 steps (bound) per period */
    double hinge_period;   /* shortest period of a hinge's fold at the initial positions, linearised (reference/
                              bending.c) [s] (INFINITY: none); held like spring_period */
    double hinge_damping_time; /* 1 / lambda, lambda the largest decay rate of the hinges' k_diss term over all the
                              membranes' vertices together (power iteration, reference/bending.c) [s] (INFINITY:
                              none); an explicit step needs lambda dt < 2: the bound holds lambda dt <= 1, the
                              recommendation 0.5 */
} dem_time_scales;
/* What sets max_dt, in words ("0.5 x Rayleigh time 2.9e-06 s", "the hinges' damping time ..."), for messages */
void dem_time_scales_limit(const dem_time_scales *ts, char *buf, size_t len);

typedef struct {
    double kinetic;    /* translational + rotational [J] */
    double elastic;    /* Hertz normal elastic energy of all contacts, walls and membrane patches included, and the
                          springs' k (l - l0)^2 / 2 (not the hinges') [J] */
    double potential;  /* -m g.x [J] */
    double total;
    long contacts;      /* touching particle pairs */
    long wall_contacts; /* touching particle-wall pairs */
    long patch_contacts; /* touching sphere-patch pairs (dem_add_patches) */
} dem_energy_t;

typedef struct dem_sim dem_sim;

dem_sim *dem_create(void);
void dem_destroy(dem_sim *s);
const char *dem_error(const dem_sim *s);
/* The particle (caller's id) that a step's DEM_ERR_DOMAIN error named - outside the binning domain or not finite -
 * or -1 (issue 39: `dem run` then says which closed membrane a grain left through). */
int dem_error_particle(const dem_sim *s);
void dem_config_default(dem_config *c);

int dem_add_material(dem_sim *s, const dem_material *m); /* returns the material id, or -1 (see dem_error) */
int dem_add_particle(dem_sim *s, const double x[3], const double v[3], double radius, int material); /* id or -1 */
int dem_set_particle_flags(dem_sim *s, int id, unsigned flags);
/* A body's mass [kg] and moment of inertia [kg m^2] (isotropic; 0 = 2/5 m r^2), apart from its contact radius: by
 * default a particle is a solid sphere of its material (density x volume). For bodies whose mass is not that of
 * their contact sphere, e.g. the vertices of a membrane. The contact law still uses the material's E and nu. */
int dem_set_particle_mass(dem_sim *s, int id, double mass, double inertia);
/* A damped linear spring between particles i and j (seed 001 Eq. 6-7, the membrane's stretching): particle i feels
 * F_i = -rho_hat [k (rho - rest) + 2 gamma sqrt(k m_eff) rho_hat . rho_dot], rho = x_i - x_j, m_eff = m_i m_j /
 * (m_i + m_j), and j the exact negation. k > 0 [N/m]; rest >= 0 [m], or < 0 for the distance at dem_start; gamma >=
 * 0 the damping ratio. Turns on DEM_EFFECT_SPRINGS. Each particle's spring forces are added in spring order after
 * its contact forces (a channel of records gathered per particle: no atomics). Returns the spring's index. */
int dem_add_spring(dem_sim *s, int i, int j, double k, double rest, double gamma);
int dem_spring_count(const dem_sim *s);
/* A triangle of particles a, b, c (a membrane patch). Under a pressure sigma (dem_set_pressure) it is loaded with
 * F = sigma A n_hat (seed 001 Eq. 18), A and n_hat its current area and unit normal along (x_b - x_a) x (x_c - x_a):
 * order the vertices so that this points where the pressure pushes (into the enclosed granulate); each vertex gets
 * F / 3, added in triangle order after its spring forces (the contribution channel). Returns the triangle's index. */
int dem_add_triangle(dem_sim *s, int a, int b, int c);
int dem_triangle_count(const dem_sim *s);
/* The triangles' particles, 3 per triangle in triangle order, into tri[3 dem_triangle_count] */
void dem_triangles_get(const dem_sim *s, int *tri);
/* Triangles first .. first+count-1 become patches: surfaces that the other particles touch (seed 001 section 2.5,
 * common/patch_contacts.h), with the Hertz-Mindlin law of the particle's and the triangle's first vertex's materials;
 * their vertices then touch no particle as spheres (walls still, with their radius). Turns on DEM_EFFECT_PATCHES. */
int dem_add_patches(dem_sim *s, int first, int count);
/* The pressure [Pa] on every triangle; turns on DEM_EFFECT_PRESSURE. */
int dem_set_pressure(dem_sim *s, double sigma);
/* A pressure schedule (before dem_start): stage k takes the pressure linearly from where the previous stage ended
 * (the first: dem_set_pressure's value, 0 by default) to `pressure` over `duration` [s] (0: a jump); after the last
 * stage it holds. Evaluated on the host at the time of each force computation, so every backend gets the same value.
 * At most DEM_MAX_STAGES stages; turns on DEM_EFFECT_PRESSURE. */
typedef struct {
    double duration; /* [s] */
    double pressure; /* [Pa] at the stage's end */
} dem_pressure_stage;
int dem_set_pressure_stages(dem_sim *s, int nstages, const dem_pressure_stage *stages);
double dem_pressure(const dem_sim *s); /* the pressure of the last force computation [Pa] (before dem_start: 0) */
/* A hinge: the triangles (p1, p3, p4) and (p2, p4, p3) sharing the edge p3-p4 resist bending (seed 001 Eq. 8-16,
 * Bridson et al. 2003; common/bending.h has the derivation): elastic constant kel [N m], dissipative kdiss [N s],
 * rest angle theta0 [rad] (NAN: the angle of the initial positions). Turns on DEM_EFFECT_BENDING. Returns its index. */
int dem_add_hinge(dem_sim *s, int p1, int p2, int p3, int p4, double kel, double kdiss, double theta0);
int dem_hinge_count(const dem_sim *s);

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
/* Fills m (free it with dem_mesh_free); 0, or -1 with the reason in err. */
int dem_mesh_make(const dem_mesh_spec *spec, dem_mesh *m, char *err, size_t errlen);
/* The vertices dem_mesh_make would make of spec, counted in double before anything is made (a caller's cap on a
 * mesh's size, which must see huge counts as huge); NAN for an edge or sizes it refuses (not > 0 and finite). */
double dem_mesh_vertices(const dem_mesh_spec *spec);
/* The grid of a generated sheet or tube, in double: n1 vertices along a row (a tube's rings), n2 rows, dx the spacing
 * along a row (a tube's chord), dy between rows (a sheet's equilateral: dx sqrt(3)/2). 0, or -1 for other kinds. */
int dem_mesh_grid(const dem_mesh_spec *spec, double *n1, double *n2, double *dx, double *dy);
void dem_mesh_free(dem_mesh *m);
/* Reads a mesh from a Wavefront OBJ (v and triangular f) or an STL file (ASCII or binary; equal coordinates become one
 * vertex), strictly: anything it cannot take is refused with "path:line: reason" in err (host/mesh/mesh_file.c). The
 * triangles keep the file's order and orientation. Free with dem_mesh_free. 0, or -1. */
int dem_mesh_read(const char *path, dem_mesh *m, char *err, size_t errlen);
/* A mesh's edges (each once, edge[2 ne], in the order of their (lower, higher) vertex) and hinges (one per edge
 * shared by two triangles, hinge[4 nhinges] as dem_add_hinge takes them); nboundary edges belong to one triangle.
 * Refuses an edge of more than two triangles and two triangles turned opposite ways. */
typedef struct {
    int ne, nhinges, nboundary;
    int *edge, *hinge;
} dem_mesh_topo;
int dem_mesh_topology(const dem_mesh *m, dem_mesh_topo *t, char *err, size_t errlen);
void dem_mesh_topo_free(dem_mesh_topo *t);
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
 * went. Everything is checked before anything is added: on an error nothing is. Returns 0, or -1 (dem_error). */
int dem_add_membrane(dem_sim *s, const dem_mesh *m, const dem_membrane *mm, dem_membrane_info *info);
int dem_set_particle_omega(dem_sim *s, int id, const double w[3]);
/* Orders all particles added so far along a Morton (Z-order) curve through their positions, for memory locality
 * (host/core/particle_order.c: a bed of 1e5 spheres in random order ran 2.4x faster sorted). Before dem_start and before
 * any spring, triangle, hinge, patch or attachment refers to particles. Particle ids change: dem_particle_source(s,
 * i) is the id particle i had when it was added (i itself when nothing was sorted). Returns 0 or a dem_status. */
int dem_sort_particles(dem_sim *s);
int dem_particle_source(const dem_sim *s, int i);
/* How scattered the particles' order is in space: the median over consecutive particles of their distance over the
 * sum of their radii (about 1 for a lattice or a sorted packing, tens for one generated at random; dem run suggests
 * particle_order: spatial above DEM_ORDER_SCATTERED). 0 for fewer than 2 particles. */
double dem_order_scatter(const dem_sim *s);
#define DEM_ORDER_SCATTERED 4.0
/* How finely precision p resolves positions where the set-up lies: the spacing of representable numbers at the largest
 * coordinate magnitude of the particles' initial positions and the walls' points (*largest, may be NULL). fp32 far
 * from the origin resolves overlaps coarsely: dem check and dem run warn above DEM_RESOLUTION_WARN of the smallest
 * radius. */
double dem_position_resolution(const dem_sim *s, dem_precision p, double *largest);
#define DEM_RESOLUTION_WARN 1e-4
int dem_add_wall(dem_sim *s, const dem_wall *w); /* returns the wall id, or -1 */
/* Six planes enclosing [lo, hi] from inside, in the order x-, x+, y-, y+, z-, z+; returns the first wall id. */
int dem_add_box(dem_sim *s, const double lo[3], const double hi[3], int material);
/* The overlap of a sphere (centre x, radius r) with wall w when the wall is at `point` (w->point, or its current
 * position: dem_wall_position), by the kernels' own geometry (common/contact_geometry.h) in double: > 0 when they
 * touch, <= 0 when apart; n (may be NULL) gets the unit normal from the wall towards the centre. w->normal must be a
 * unit vector (dem_add_wall normalises the walls it keeps). */
double dem_wall_overlap(const dem_wall *w, const double point[3], const double x[3], double r, double n[3]);
/* Particle `particle` rides on wall `wall` (added before): it becomes fixed (DEM_PARTICLE_FIXED) and moves with the
 * wall's velocity at every step, its own given velocity replaced - a membrane's end ring on a platen. It does not
 * touch that wall (the platen's force is the granulate's alone). Turns on DEM_EFFECT_RIDERS. */
int dem_attach_to_wall(dem_sim *s, int particle, int wall);
/* Replaces the motion stages of a wall (before dem_start). */
int dem_set_wall_motion(dem_sim *s, int wall, int nstages, const dem_stage *stages);
int dem_set_gravity(dem_sim *s, const double g[3]);
int dem_set_domain(dem_sim *s, const double lo[3], const double hi[3]);
int dem_set_dt(dem_sim *s, double dt);
/* Which physics to simulate: a mask of DEM_EFFECT_* (dem_effects.h), DEM_EFFECT_CLASSICAL by default. Code of an
 * effect that is off is not compiled into the kernels, its buffers are not allocated and its stages not launched. */
int dem_set_effects(dem_sim *s, unsigned effects);
unsigned dem_effects(const dem_sim *s);
const char *dem_effect_name(int bit); /* "hertz", "damping", ... for bit 0, 1, ...; NULL past the last */
int dem_effect_bit(const char *name); /* inverse of dem_effect_name; -1 for an unknown name */
void dem_effects_string(unsigned effects, char *buf, size_t len); /* "hertz+damping+..." */
/* MC-stress pressure convention: DEM_MCS_* bits of dem_effects.h (DEM_MCS_DEFAULT unless set; docs/multicontact.md).
 * Compiled into the kernels with the effects; used only with DEM_EFFECT_MC_STRESS. */
int dem_set_mc_stress_convention(dem_sim *s, unsigned convention);
unsigned dem_mc_stress_convention(const dem_sim *s);
/* "own_contact in, lever centres, scale mean_trace": the scene key's words */
void dem_mc_stress_convention_string(unsigned convention, char *buf, size_t len);

/* MC-strain scheme: max_iterations 0 (default) is the published lagged scheme (the induced displacements use the
 * forces of the previous step, one pass); N > 0 iterates displacements and forces within each step until no contact
 * force changes by more than tolerance (relative) or N iterations have run. */
int dem_set_mc_strain(dem_sim *s, int max_iterations, double tolerance);
/* MC-strain contact distance factor F in [1, 2] (default 1: only geometric overlaps, as published): neighbours whose
 * centres are closer than F (r_i + r_j) become contacts when the induced displacements close their gap (LIGGGHTS'
 * option; mc_strain.h). Neighbour rows then reach 2 (F - 1) r_max further; results stay independent of the skin. */
int dem_set_mc_strain_reach(dem_sim *s, double factor);
typedef struct {
    long last;        /* iterations in the last step */
    long max;         /* most iterations of any step */
    long total;       /* all iterations so far */
    long unconverged; /* steps that hit the iteration cap */
    /* The first and the last step that hit the cap in this process (from dem_start; -1: none): not part of the
     * state (dem_state_set keeps them), so that a failing run can say where its capped steps began. The force
     * evaluation of dem_start is not a step: it counts in none of these (only in last). */
    long first_capped, last_capped;
} dem_mc_stats;
void dem_mc_stats_get(const dem_sim *s, dem_mc_stats *st);
/* How wall k's latest servo stage went (a P controller: it settles when gain x the stiffness of the wall's contacts
 * x dt is below 1; above it the force chatters about the target, the wall touching and leaving the particles in
 * turn, and the mean force it holds is off). Counted by this process from dem_start (a restored run counts anew). */
typedef struct {
    int stage;     /* the stage's index, -1 if none has run */
    double force;  /* its target [N] */
    long steps;    /* its steps run */
    long tail;     /* of them, the steps in its last tenth */
    double held;   /* the mean normal force the wall received over those [N] (NAN: none yet) */
    long chatter;  /* steps whose force error changed sign from the step before, both beyond 10 % of the target */
} dem_servo_stats;
int dem_servo_stats_get(const dem_sim *s, int wall, dem_servo_stats *st);

/* Time scales of the current particles and materials; hertz_velocity is the impact speed for hertz_time. */
int dem_time_scales_get(dem_sim *s, double hertz_velocity, dem_time_scales *ts);
/* The shortest contact the scene can make, for choosing dt: Hertz contact times (closed form, undamped) at the
 * fastest approach the set-up gives - particle pairs at twice the largest initial particle speed, particle-wall
 * contacts at that speed plus the wall's fastest stage - for every particle's size and material. Gravity is left
 * out (a settled bed does not fall; a pour hits at sqrt(2 g h) of its drop height). steps = contact time / dt (the run's
 * dt, 0 when not set). Fewer than DEM_MIN_STEPS_PER_CONTACT steps per contact resolve a collision badly: a
 * restitution of 0.7 comes out 0.5 % high at 20 steps, 1.1 % at 10, 5.8 % at 5 (velocity Verlet, measured on
 * scenes/two_spheres.yaml; docs/design.md). */
#define DEM_MIN_STEPS_PER_CONTACT 20
typedef struct {
    double pair_speed, wall_speed;   /* fastest approach [m/s] */
    double pair_time, wall_time;     /* shortest contact time [s] (INFINITY: no such contact) */
    double contact_time, steps;      /* the shorter of the two [s], and the steps of dt it spans */
    int wall;                        /* the wall of wall_time (-1: none) */
} dem_contact_advice;
int dem_contact_advice_get(dem_sim *s, dem_contact_advice *a);
/* How close dt is to the explicit step's stability bound at the current overlaps (host/physics/stability.c): a Hertz contact
 * stiffens as sqrt(overlap), so a packing pressed hard can outgrow a dt chosen by the Rayleigh time (a 50 MPa
 * compact heated up at 0.2 Rayleigh times: docs/design.md "The time step under compaction"). Per particle, each
 * contact's normal and tangential-rotational two-body frequencies at the law's stiffness at its overlap, summed over
 * the particle's contacts and walls; ratio = the largest omega dt over the damped bound 2 (sqrt(1 + zeta^2) - zeta),
 * 1 at the bound if the estimate were exact. Measured on a 50 MPa compact and a pressed lattice (docs/design.md): at
 * restitution 0.1 stirred - the kinetic energy not decaying - from 1.2, creeping up at 1, at rest at 0.7; at 0.5
 * stirred from 1.35; at 0.7 and 0.9 at rest up to 1.17 and 1.5. Hence the warning above DEM_STABILITY_LIMIT, and
 * dt_advice for DEM_STABILITY_TARGET. Springs, patches and membranes are not counted. */
#define DEM_STABILITY_LIMIT 1.2
#define DEM_STABILITY_TARGET 0.7
typedef struct {
    double ratio;     /* the largest omega dt / damped bound over the particles (0: no contact) */
    double omega_dt;  /* omega dt of that particle's mode (the undamped bound is 2) */
    double zeta;      /* the damping ratio the bound took there */
    int tangential;   /* 1: its tangential-rotational mode, 0: its normal one */
    int particle;     /* its id (-1: no contact) */
    int contacts;     /* its contacts, walls included */
    double dt_advice; /* the dt at which the ratio would be DEM_STABILITY_TARGET [s] (INFINITY: no contact) */
} dem_stability;
int dem_stability_get(dem_sim *s, dem_stability *st);
/* Closed forms of the undamped Hertz collision (relative speed v): duration and largest overlap. */
double dem_hertz_contact_time(double mstar, double rstar, double estar, double v);
double dem_hertz_max_overlap(double mstar, double rstar, double estar, double v);
/* The damping factor c of hertz_mindlin.h that makes a Hertz collision rebound with restitution e. */
double dem_damping_for_restitution(double e);
double dem_restitution_for_damping(double c);

/* Validates everything, builds the backend and computes the initial forces. */
int dem_start(dem_sim *s, const dem_config *c);
/* Advances nsteps steps. The force each wall received (DEM_FIELD_WALL_FORCE, dem_wall_force) is summed on the last
 * of them (on every one under a servo stage): after a call that failed, it is that of an earlier call. */
int dem_step(dem_sim *s, long nsteps);

int dem_count(const dem_sim *s);
double dem_particle_radius(const dem_sim *s, int i); /* [m], as given */
int dem_particle_material(const dem_sim *s, int i);   /* material id, -1 for no such particle */
double dem_particle_mass(const dem_sim *s, int i);     /* [kg]: set apart or the material's; NAN for no such particle */
int dem_wall_count(const dem_sim *s);
long dem_step_index(const dem_sim *s);
double dem_time(const dem_sim *s);
double dem_dt(const dem_sim *s);
int dem_neighbor_capacity(const dem_sim *s);  /* slots held by the current rows, all rows together (NBR_LIST) */
double dem_neighbor_skin(const dem_sim *s);   /* the skin of the current rows [m] (dem_config.skin); with MC-strain's
                                                 contact distance the rows reach 2 (F - 1) r_max further */
long dem_rebuild_count(const dem_sim *s);
long dem_reorder_count(const dem_sim *s); /* times the particles were stored anew (dem_config.reorder) */
/* Cells the last binning used (DEM_FIELD_CELL_START holds one more entry); before dem_start, those the particles'
 * positions hold. */
int dem_cell_count(const dem_sim *s);
/* The binning grid of a started run: its lower corner [m], 1 / cell size [1/m] (as the kernels get it, before the
 * cast to the run's precision) and the domain's cells per axis. Cell of a position x along an axis:
 * floor((x - lo) * inv_cell), in the run's precision. */
int dem_grid_get(const dem_sim *s, double lo[3], double *inv_cell, int ncell[3]);
/* The cells the last binning used: along each axis count[d] cells of that grid from first[d] on, the particles'
 * bounding box (common/binning.h); cell (cx, cy, cz) of the grid is cell index
 * ((cz - first[2]) * count[1] + cy - first[1]) * count[0] + cx - first[0] of DEM_FIELD_CELL_START. */
int dem_grid_cells(const dem_sim *s, int first[3], int count[3]);
const char *dem_describe(dem_sim *s);   /* backend, device and active effects */

/* Raw bytes of a field in the run's precision (bit comparisons); bytes must not exceed the field's size. */
int dem_get_raw(dem_sim *s, dem_field f, void *dst, size_t bytes);
size_t dem_field_bytes(const dem_sim *s, dem_field f);
/* A real-valued field converted to double. */
int dem_get_field(dem_sim *s, dem_field f, double *dst);
int dem_wall_force(dem_sim *s, int wall, double f[3]);     /* force the wall received in the last step [N] */
/* The wall's normal force in the last step: the sum of the particles' force components along their contact normals
 * [N], summed with the force; for a die (cylinder) its radial force, whose vector sum cancels. */
int dem_wall_normal_force(dem_sim *s, int wall, double *fn);
int dem_wall_position(const dem_sim *s, int wall, double p[3]);
int dem_wall_get(const dem_sim *s, int wall, dem_wall *w); /* the wall as added (its normal or axis normalised) */
/* For a punch (plane wall): the die (the first cylinder wall whose axis is parallel to its normal) and the punch facing
 * it (the nearest plane wall with the opposite normal, on the particles' side) that dem_stage.until_density measures
 * between; -1 where there is none (then DEM_ERR_ARG). Valid as soon as the walls are added. */
int dem_density_walls(const dem_sim *s, int wall, int *die, int *other);
/* Whether punch `wall`'s cup (dem_wall.cup_radius) lies within die `die`'s bore - the offset of the punch's point from
 * the die's axis plus the cup's radius at most the bore's radius - as the relative density, which counts the cup's
 * volume as the bore's, assumes: 1 (and 1 for a flat punch), else 0. */
int dem_cup_in_bore(const dem_sim *s, int wall, int die);
/* The relative density punch `wall` sees now (before dem_start: where the walls were added), as until_density
 * measures it; DEM_ERR_ARG without a die and a facing punch, or when a punch's cup does not lie within the bore. */
int dem_relative_density(const dem_sim *s, int wall, double *rho);
int dem_energy(dem_sim *s, dem_energy_t *e); /* energies and contact counts, on the host in double */
/* What a time-series row needs: the energies and contact counts (as dem_energy defines them) and every wall's force
 * and position, with the step, its time and the MC-strain iteration counts, all as they were after that step. */
typedef struct {
    dem_energy_t energy;
    double wall_force[3 * DEM_MAX_WALLS]; /* [N] */
    double wall_pos[3 * DEM_MAX_WALLS];   /* [m] */
    double wall_normal[DEM_MAX_WALLS];    /* each wall's normal force (DEM_FIELD_WALL_NORMAL_FORCE) [N] */
    long step;
    double time;     /* [s] */
    dem_mc_stats mc; /* dem_mc_stats_get after the step */
} dem_sample;
/* The current state's sample, computed on the host in double like dem_energy (one synchronisation). */
int dem_sample_get(dem_sim *s, dem_sample *out);
/* Advances nsteps steps like dem_step and samples the steps k (0 <= k < nsteps, of this call) with want[k] != 0:
 * rows receives one sample per such step, in order (want NULL: none). The kernels of a sampled step write each
 * particle's terms in the run's precision to a ring of rows on the device (common/series.h), which the host reads
 * when it is full or the call ends and adds up in double: no synchronisation and no kernel launch per row. The same
 * bits on every backend, and within rounding of dem_sample_get (fp64: a few roundoffs; fp32: the overlaps' own
 * precision). A run with a membrane (springs, patches) is sampled on the host, one synchronisation per row. As after
 * dem_step, DEM_FIELD_WALL_FORCE holds the last step's wall forces; each row holds its own step's. */
int dem_step_sampled(dem_sim *s, long nsteps, const unsigned char *want, dem_sample *rows);

/* The contact network of the current state: every touching particle pair (by i < j, ascending) and then every
 * touching particle-wall pair (by particle, then wall), with the force the step computed on particle i split along
 * the contact normal and across it, the overlap and the contact point (host/physics/contacts.c). */
typedef struct {
    int i, j;            /* particles, i < j; for a wall contact j = -1 - wall */
    double overlap;      /* [m] */
    double fn[3], ft[3]; /* normal and tangential parts of the force on particle i [N] */
    double point[3];     /* contact point [m] */
    double extra[2];     /* the law's own terms: MC-stress, the traces T_i, T_j [Pa] (P = -(T_i + T_j) / K);
                            MC-strain, the induced displacements D at i's and at j's end [m]; otherwise 0 */
} dem_contact;
/* Allocates *out (free() it): count contacts, the first npairs of them particle pairs. */
int dem_contacts_get(dem_sim *s, dem_contact **out, long *count, long *npairs);
/* Per-kernel seconds when the environment has DEM_PROFILE set (OpenCL only); count 0 otherwise. */
int dem_kernel_times(dem_sim *s, const char ***names, const double **seconds, int *count);
/* The bytes of every buffer kernel k (an index of dem_kernel_times' names) is given, as now allocated: what one launch
 * would move if it touched each byte once (make bench divides it by the kernel's time: a bandwidth to set against
 * the device's copy rate). */
double dem_kernel_bytes(const dem_sim *s, int k);
/* The kernels the last step launched, in order, without a rebuild's (rebuild = 0), or those of the last neighbour
 * rebuild (rebuild = 1), as "name, name, N x (name, name), ..." (an iteration's pair once, with its count).
 * Returns the number of launches (0 before the first step). */
int dem_kernel_sequence(const dem_sim *s, int rebuild, char *buf, size_t len);
/* Provenance of a started run's arithmetic: the library version, the compiler and numeric flags of the host code and
 * the reference, and for OpenCL the device, driver and the program's build options (with the source hash). */
const char *dem_build_info(dem_sim *s);
/* Bytes the backend holds now for the run (every buffer of the registry, both neighbour-row sets). */
size_t dem_device_bytes(const dem_sim *s);
/* What the device's bytes hold (common/dem_buffers.h names each buffer's part): per-particle state and pair indices
 * (PARTICLES), the pair records with their history, flags, MC-strain forces and the flags' copy (PAIRS), both neighbour-row sets (ROWS), the
 * walls' records, per-particle wall contacts and sums (WALLS), the cell grid (CELLS), the sampled series' rows of
 * particles and walls and the output stress tensor (OUTPUT), membranes, patches and riders (MESH). */
typedef enum {
    DEM_MEM_PARTICLES,
    DEM_MEM_PAIRS,
    DEM_MEM_ROWS,
    DEM_MEM_WALLS,
    DEM_MEM_CELLS,
    DEM_MEM_OUTPUT,
    DEM_MEM_MESH,
    DEM_MEM__COUNT
} dem_memory_part;
/* Bytes held now in one part (their sum over the parts is dem_device_bytes), and its name ("pairs", ...). */
size_t dem_device_bytes_part(const dem_sim *s, dem_memory_part part);
const char *dem_memory_part_name(dem_memory_part part);
/* Before dem_start: the bytes the run would hold on the device at the start, from the same registry (rows at their
 * initial capacity, three pair records per particle; rows grow when a packing needs more). Validates and packs
 * the description as dem_start does. */
int dem_memory_estimate(dem_sim *s, const dem_config *c, size_t *bytes);

/* The dynamic state of a run, enough to continue it bit for bit (a checkpoint). Real arrays are raw bytes in the
 * run's precision (real_size 4 or 8). Contacts: the touching pairs (i < j) and, with friction, their tangential
 * spring; walls: the touch mask per particle and the springs. Neighbour rows are rebuilt on restore. */
#define DEM_PAIR_RECORD_REALS 7 /* reals per pair record (DEM_FIELD_PAIR_RECORDS, dem_state.pair_rec) */
typedef struct {
    long step, rebuilds;
    int n, nwalls, real_size;
    void *x, *v, *w, *force, *torque; /* real[3n] */
    void *wall_force;                 /* real[3 nwalls] */
    void *wall_nforce;                /* real[nwalls]: DEM_FIELD_WALL_NORMAL_FORCE (NULL: zero) */
    double wall_pos[DEM_MAX_WALLS][3]; /* [m] */
    int has_stages;                       /* 1: the three below hold (0: derive them from the step) */
    int wall_stage[DEM_MAX_WALLS];        /* each wall's motion stage (nstages: past the last) */
    long wall_stage_first[DEM_MAX_WALLS]; /* the step it began */
    double wall_stage_from[DEM_MAX_WALLS][3]; /* where the wall was then [m] (dem_stage.until_distance) */
    long npairs;
    int *pair_i, *pair_j;
    void *pair_hist;                  /* real[3 npairs] */
    void *pair_rec;                   /* real[DEM_PAIR_RECORD_REALS npairs]: each pair's force record of the last step (dem_layout.h
                                         PR_*: the contact network's forces); NULL: not known (a checkpoint from
                                         before 2026-12-03), zero until the next step */
    int has_hist;                     /* 1 when the run has friction */
    void *wall_hist;                  /* real[3 n nwalls] with friction, else empty */
    size_t wall_hist_bytes;
    void *wall_pf;                    /* real[3 n nwalls]: each wall's force on each particle in the last step, as
                                         DEM_FIELD_WALL_PF (runs that keep them: dem_config.contacts, servos), else
                                         empty; NULL: not known (a checkpoint from before 2026-12-03) */
    size_t wall_pf_bytes;
    unsigned *wall_mask;              /* [n] */
    int has_mc;                       /* 1 when the run has MC-strain: its stored forces follow */
    void *pair_mc_fn;                 /* real[npairs]: MC-strain force of each touching pair */
    void *wall_mc_fn;                 /* real[n nwalls] with MC-strain, else empty */
    size_t wall_mc_fn_bytes;
    void *pair_mc_disp;               /* real[2 npairs] with MC-strain: the induced displacement at i's and at j's
                                         end in the last step (the contact network's extra); NULL: not known */
    void *wall_mc_disp;               /* real[n nwalls] with MC-strain: the same at each particle's wall contacts */
    size_t wall_mc_disp_bytes;
    dem_mc_stats mc;                  /* iteration counts so far */
    long npatch;                      /* sphere-patch row slots with flags: the touching contacts, and the spheres
                                         touching a patch whose side is remembered (common/patch_contacts.h), by
                                         sphere then triangle */
    int *patch_i, *patch_t;           /* the sphere, the triangle */
    void *patch_hist;                 /* real[3 npatch]: their tangential springs (zero without friction) */
    int *patch_side;                  /* [npatch]: their flags, PATCH_SAVED bits of common/dem_layout.h (1: a contact,
                                         4: the sphere is below the triangle's normal (x_b - x_a) x (x_c - x_a), 8: the
                                         side is known, 16: the centre has crossed the patch's plane); NULL: not known
                                         (a checkpoint from before 2026-12-04: contacts, each side taken anew) */
} dem_state;
int dem_state_get(dem_sim *s, dem_state *st); /* allocates; free with dem_state_free */
/* After dem_start of the same set-up: continue from st (replaces positions, velocities, contacts, step). */
int dem_state_set(dem_sim *s, const dem_state *st);
void dem_state_free(dem_state *st);

/* OpenCL devices over all platforms; name of device k. */
int dem_device_count(void);
int dem_device_name(int k, char *buf, size_t len);
#endif /* DEM_H */
