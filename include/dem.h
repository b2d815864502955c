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
 *
 * Errors: one rule for every function of the public headers.
 *  - A function that returns int and does something (dem_set_*, dem_start, dem_step, dem_*_get ...) returns a
 *    dem_status: DEM_OK (0) on success, a negative DEM_ERR_* on failure.
 *  - A function that returns an int answer - an id, an index, a count or a yes (1) / no (0) - returns it (>= 0) on
 *    success and a negative DEM_ERR_* on failure (dem_add_particle, dem_count, dem_cup_in_bore ...).
 *  So `< 0` tests any failure of either kind, and the value says which. dem_error(s) then says why, in words, for
 *  the functions given a dem_sim that is not const (those given a const one leave it as it was: their code alone
 *  says); the mesh functions, which take no dem_sim, write the reason to their `err` argument. A double result is
 *  NAN where there is no answer; a size_t result 0; a void function cannot fail. The library never exits and never
 *  prints.
 *
 * The public headers, all installed and all included by this one: dem.h (a simulation's set-up, materials,
 * particles and walls, the run, its fields and state, errors), dem_effects.h (the physics mask, DEM_EFFECT_*),
 * dem_membrane.h (springs, triangles, hinges, meshes, membranes, patches and riders) and dem_press.h (a press: the
 * die and punches, relative density, servo records). libdem.so exports exactly the functions they declare (DEM_API);
 * dem_debug.h, not installed, declares what the tests and tools read of the internals.
 */
#ifndef DEM_H
#define DEM_H
#include <stddef.h>
#include "dem_effects.h" /* DEM_EFFECT_* bits */

/* Marks the functions the shared library exports: it is built with -fvisibility=hidden, so everything else in it
 * (the driver's, the backends' and the reference's own functions) stays inside. */
#ifndef DEM_API
#if defined(__GNUC__) || defined(__clang__)
#define DEM_API __attribute__((visibility("default")))
#else
#define DEM_API
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define DEM_VERSION "0.1.0"

/* What went wrong: 0 or a negative code (the rule above). */
typedef enum {
    DEM_OK = 0,
    DEM_ERR_ARG = -1,    /* invalid argument or parameter, or no such particle, wall, material ... */
    DEM_ERR_NOMEM = -2,  /* out of host memory */
    DEM_ERR_DEVICE = -3, /* OpenCL device, kernel build or launch failure */
    DEM_ERR_DOMAIN = -4, /* a particle left the binning domain or became non-finite */
    DEM_ERR_DT = -5,     /* time step above the stability bound (see dem_time_scales) */
    DEM_ERR_STATE = -6   /* call out of order (e.g. adding particles after dem_start) */
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
    double yield_stress; /* limiting contact pressure p_y [Pa] of the plastic law (DEM_EFFECT_THORNTON_NING); 0: the
                            material does not yield (a wall's steel). A pair yields at the smaller p_y of its two
                            materials that yield */
    double rolling_friction; /* coefficient of rolling resistance mu_r >= 0 (DEM_EFFECT_ROLLING): a contact's torque
                                is at most mu_r r* f_n; a pair takes the mean of its two materials' */
    double bond_strength; /* sigma_b [Pa] >= 0 of the solid bridge a yielded contact forms (DEM_EFFECT_THORNTON_NING,
                             and DEM_EFFECT_MDR over each side's pi a_max^2: docs/laws/mdr.md "Bonds"): the contact
                             then holds a tension up to sigma_b pi a_p^2, a_p its plastic contact radius, and breaks
                             beyond it. A pair takes the smaller of its two materials' (0: no bond, e.g. a tool's
                             steel) */
    double rolling_damping; /* viscous damping ratio eta_r >= 0 of the rolling spring (DEM_EFFECT_ROLLING_SPRING; Ai et
                               al. 2011 model C: the dashpot is eta_r times the critical 2 sqrt(I_r k_r)); a pair takes
                               the mean of its two materials' */
    /* MDR (DEM_EFFECT_MDR; common/laws/mdr.h, docs/laws/mdr.md): a particle material gives yield_stress > 0 (the
     * yield stress Y of MDR's plastic branch, whose mean contact pressure starts at 2.75 Y) and Poisson's ratio < 0.5;
     * every particle material of an MDR run has the same young, poisson, yield_stress, surface_energy, bulk_fraction
     * and mdr_damping (one MDR material, as in the papers and LAMMPS). A material with yield_stress 0 is a wall's:
     * a wall contact takes the particle's properties and the wall material's surface_energy. */
    double surface_energy; /* effective surface energy gamma >= 0 [J/m^2] of MDR's adhesion (0: none) */
    double bulk_fraction;  /* free-surface fraction psi_b in [0, 1) below which MDR's bulk response of a confined
                              sphere starts (0: never; 0.5 in Zunker et al.'s MCC) */
    double mdr_damping;    /* MDR's damping coefficient eta_d >= 0 (dimensionless, docs/laws/mdr.md (M38)) */
} dem_material;

/* What one pair of materials takes instead of the mean of its two materials' values (dem_set_material_pair): a
 * field left NAN keeps the mean. E.g. a lubricated die: friction 0.1 between the powder and the die's steel, while
 * the powder keeps 0.7 against itself. */
typedef struct {
    double friction;    /* Coulomb friction coefficient of the pair, >= 0 */
    double restitution; /* coefficient of restitution of the pair, in (0, 1] (the damping follows from it) */
    double rolling_friction; /* rolling resistance coefficient of the pair, >= 0 (DEM_EFFECT_ROLLING) */
    double bond_strength; /* sigma_b of the pair's bonds [Pa], >= 0 (DEM_EFFECT_THORNTON_NING); NAN: the smaller of
                             the two materials'. Give every field: an initialiser that leaves it out sets 0, no bond */
    double surface_energy; /* the pair's work of adhesion w [J/m^2], >= 0 (DEM_EFFECT_ADHESION); NAN: the geometric
                              mean of the two materials' surface_energy. Left out of an initialiser: 0, no adhesion.
                              Not under DEM_EFFECT_MDR (refused: MDR takes its materials') */
} dem_material_pair;

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
    /* A velocity ramp (0: none, the velocity steps at once): over its first `ramp` seconds the stage's velocity goes
     * linearly from the previous stage's (0 after a servo stage or for the first one) to its own, step by step at
     * each step's midpoint, so the ramp moves the wall by ramp (v_prev + v) / 2. At most the stage's duration; not
     * with a servo stage. */
    double ramp;        /* [s] */
    /* A stage that waits for another wall: it begins (its duration counts) only once wall after_wall has begun its
     * stage after_stage (its nstages: has run them all), and the wall rests while it waits. Both 0 (wall 0's first
     * stage): no wait. */
    int after_wall;
    int after_stage;
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
    int one_pass;        /* 1: on the steps whose pair records nothing reads (every step of a dem_step or
                            dem_step_sampled call but its last, and not a sampled one), the particle contacts take
                            one kernel (each particle evaluates its row's pairs itself; each pair's law runs twice)
                            instead of two passes through the pair records: the same bits, fewer bytes moved per
                            step, more arithmetic; for a device that memory bounds (a GPU), not a CPU (docs/design.md
                            "One pass over the rows"). Taken with the classical law and MC-stress; runs of MC-strain,
                            Thornton-Ning, MDR or the rolling spring keep the two passes. Default 0, or 1 when the
                            environment has DEM_ONE_PASS=1. */
} dem_config;
/* The dem_config.reorder dem run uses with particle_order: spatial (docs/design.md "Every sum follows the particle
 * ids") */
#define DEM_REORDER_PERIOD 8
#define DEM_REORDER_GAIN 2.0 /* dem_config.reorder_gain 0 */
#define DEM_SAMPLE_KEEP 10

/* Fields that can be read back (dem_get_raw, dem_get_field). An int, so that the fields the library keeps for
 * itself (dem_debug.h: neighbour rows, pair records, contact history, cells, flags) share the numbering. */
typedef int dem_field;
enum {
    DEM_FIELD_X = 0, DEM_FIELD_V = 1, DEM_FIELD_W = 2, /* position [m], velocity [m/s], angular velocity [rad/s]:
                                                          real[3n] */
    DEM_FIELD_FORCE = 3, DEM_FIELD_TORQUE = 4,         /* [N], [N m]: real[3n] */
    DEM_FIELD_WALL_FORCE = 10,        /* real[3*nwalls]: force each wall receives [N] */
    DEM_FIELD_STRESS = 17,            /* real[6n]: stress tensor xx,yy,zz,xy,xz,yz of each particle [Pa] (seed 000
                                         Eq. 9, elastic normal forces; negative in compression), computed when read */
    DEM_FIELD_STRESS_TRACE = 18,      /* real[n]: the trace MC-stress used in the last step [Pa]; empty without
                                         mc_stress */
    DEM_FIELD_WALL_NORMAL_FORCE = 27, /* real[nwalls]: each wall's normal force, the sum of the particles' force
                                         components along their contact normals [N] (a die's radial force; a plane's
                                         normal force) */
    DEM_FIELD_RADIUS = 29             /* real[n]: each particle's radius as its contacts see it now [m]: the radius as
                                         given (dem_particle_radius, in the run's precision), or under mdr its
                                         apparent radius, which grows as the sphere is pressed (docs/laws/mdr.md M34) */
};

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
DEM_API void dem_time_scales_limit(const dem_time_scales *ts, char *buf, size_t len);

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

DEM_API dem_sim *dem_create(void);
DEM_API void dem_destroy(dem_sim *s);
DEM_API const char *dem_error(const dem_sim *s);
/* The particle (caller's id) that a step's DEM_ERR_DOMAIN error named - outside the binning domain or not finite -
 * or a negative value when the last error named none (`dem run` then says which closed membrane a grain left
 * through). */
DEM_API int dem_error_particle(const dem_sim *s);
/* MDR (DEM_EFFECT_MDR): the first step of this process (from dem_create; for an MPI rank, among its own particles) at
 * which a particle's apparent radius met the law's cap of 1.5 times its own radius, its growth held there (common/
 * laws/mdr_core.h mdr_particle_begin), and that particle (caller's id) into *particle if not NULL; -1 both when none.
 * Past it the law no longer keeps the sphere's volume and a compact pressed on can leave the law's range (docs/laws/
 * mdr.md "Range"; a step that then fails says so in its error). Not part of the state. */
DEM_API long dem_mdr_capped(const dem_sim *s, long *particle);
DEM_API void dem_config_default(dem_config *c);

/* Returns the new material's id (0, 1, ... in the order added; at most 64), or a negative dem_status. */
DEM_API int dem_add_material(dem_sim *s, const dem_material *m);
/* Returns the new particle's id (0, 1, ... in the order added), or a negative dem_status. v may be NULL (at rest). */
/* The pair of materials a and b (either order; a == b: the material with itself) takes p's values instead of the mean
 * of the two materials' (the default, dem_material). Before dem_start; a later call for the same pair replaces it. */
DEM_API int dem_set_material_pair(dem_sim *s, int a, int b, const dem_material_pair *p);
DEM_API int dem_add_particle(dem_sim *s, const double x[3], const double v[3], double radius, int material);
DEM_API int dem_set_particle_flags(dem_sim *s, int id, unsigned flags);
/* A body's mass [kg] and moment of inertia [kg m^2] (isotropic; 0 = 2/5 m r^2), apart from its contact radius: by
 * default a particle is a solid sphere of its material (density x volume). For bodies whose mass is not that of
 * their contact sphere, e.g. the vertices of a membrane. The contact law still uses the material's E and nu. */
DEM_API int dem_set_particle_mass(dem_sim *s, int id, double mass, double inertia);
DEM_API int dem_set_particle_omega(dem_sim *s, int id, const double w[3]);
/* Orders all particles added so far along a Morton (Z-order) curve through their positions, for memory locality
 * (host/core/particle_order.c: a bed of 1e5 spheres in random order ran 2.4x faster sorted). Before dem_start and before
 * any spring, triangle, hinge, patch or attachment refers to particles. Particle ids change: dem_particle_source(s,
 * i) is the id particle i had when it was added (i itself when nothing was sorted), DEM_ERR_ARG for no particle i. */
DEM_API int dem_sort_particles(dem_sim *s);
DEM_API int dem_particle_source(const dem_sim *s, int i);
/* How scattered the particles' order is in space: the median over consecutive particles of their distance over the
 * sum of their radii (about 1 for a lattice or a sorted packing, tens for one generated at random; dem run suggests
 * particle_order: spatial above DEM_ORDER_SCATTERED). 0 for fewer than 2 particles. */
DEM_API double dem_order_scatter(const dem_sim *s);
#define DEM_ORDER_SCATTERED 4.0
/* How finely precision p resolves positions where the set-up lies: the spacing of representable numbers at the largest
 * coordinate magnitude of the particles' initial positions and the walls' points (*largest, may be NULL). fp32 far
 * from the origin resolves overlaps coarsely: dem check and dem run warn above DEM_RESOLUTION_WARN of the smallest
 * radius. */
DEM_API double dem_position_resolution(const dem_sim *s, dem_precision p, double *largest);
#define DEM_RESOLUTION_WARN 1e-4
/* Returns the new wall's id (0, 1, ... in the order added; at most DEM_MAX_WALLS), or a negative dem_status. */
DEM_API int dem_add_wall(dem_sim *s, const dem_wall *w);
/* Six planes enclosing [lo, hi] from inside, in the order x-, x+, y-, y+, z-, z+; returns the first wall's id, or a
 * negative dem_status (the walls added before the one refused stay). */
DEM_API int dem_add_box(dem_sim *s, const double lo[3], const double hi[3], int material);
/* The overlap of a sphere (centre x, radius r) with wall w when the wall is at `point` (w->point, or its current
 * position: dem_wall_position), by the kernels' own geometry (common/contact_geometry.h) in double: > 0 when they
 * touch, <= 0 when apart; n (may be NULL) gets the unit normal from the wall towards the centre. w->normal must be a
 * unit vector (dem_add_wall normalises the walls it keeps). */
DEM_API double dem_wall_overlap(const dem_wall *w, const double point[3], const double x[3], double r, double n[3]);
/* Replaces the motion stages of a wall (before dem_start). */
DEM_API int dem_set_wall_motion(dem_sim *s, int wall, int nstages, const dem_stage *stages);
/* How far stage st of a motion list moves a wall along the direction u (normalised here): its velocity along u over
 * its duration, less what a ramp from the previous stage's velocity (0 after a servo stage or for the first) leaves
 * out (dem_stage.ramp: the ramp covers ramp (v_prev + v) / 2); 0 for a servo stage, whose motion is found as it
 * runs. Early ends (until_*) and waits are not counted: the most it can move. [m] */
DEM_API double dem_stage_travel(const dem_stage *stages, int st, const double u[3]);
DEM_API int dem_set_gravity(dem_sim *s, const double g[3]);
DEM_API int dem_set_domain(dem_sim *s, const double lo[3], const double hi[3]);
DEM_API int dem_set_dt(dem_sim *s, double dt);
/* Which physics to simulate: a mask of DEM_EFFECT_* (dem_effects.h), DEM_EFFECT_CLASSICAL by default. Code of an
 * effect that is off is not compiled into the kernels, its buffers are not allocated and its stages not launched. */
DEM_API int dem_set_effects(dem_sim *s, unsigned effects);
DEM_API unsigned dem_effects(const dem_sim *s);
DEM_API const char *dem_effect_name(int bit); /* "hertz", "damping", ... for bit 0, 1, ...; NULL past the last */
DEM_API int dem_effect_bit(const char *name); /* inverse of dem_effect_name; DEM_ERR_ARG for an unknown name */
DEM_API void dem_effects_string(unsigned effects, char *buf, size_t len); /* "hertz+damping+..." */
/* MC-stress pressure convention: DEM_MCS_* bits of dem_effects.h (DEM_MCS_DEFAULT unless set; docs/multicontact.md).
 * Compiled into the kernels with the effects; used only with DEM_EFFECT_MC_STRESS. */
DEM_API int dem_set_mc_stress_convention(dem_sim *s, unsigned convention);
DEM_API unsigned dem_mc_stress_convention(const dem_sim *s);
/* "own_contact in, lever centres, scale mean_trace": the scene key's words */
DEM_API void dem_mc_stress_convention_string(unsigned convention, char *buf, size_t len);

/* MC-strain scheme: max_iterations 0 (default) is the published lagged scheme (the induced displacements use the
 * forces of the previous step, one pass); N > 0 iterates displacements and forces within each step until no contact
 * force changes by more than tolerance (relative) or N iterations have run. */
DEM_API int dem_set_mc_strain(dem_sim *s, int max_iterations, double tolerance);
/* MC-strain contact distance factor F in [1, 2] (default 1: only geometric overlaps, as published): neighbours whose
 * centres are closer than F (r_i + r_j) become contacts when the induced displacements close their gap (LIGGGHTS'
 * option; mc_strain.h). Neighbour rows then reach 2 (F - 1) r_max further; results stay independent of the skin. */
DEM_API int dem_set_mc_strain_reach(dem_sim *s, double factor);
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
DEM_API void dem_mc_stats_get(const dem_sim *s, dem_mc_stats *st);

/* Time scales of the current particles and materials; hertz_velocity is the impact speed for hertz_time. */
DEM_API int dem_time_scales_get(dem_sim *s, double hertz_velocity, dem_time_scales *ts);
/* The shortest contact the scene can make, for choosing dt: Hertz contact times (closed form, undamped) at the
 * fastest approach the set-up gives - particle pairs at twice the largest initial particle speed, particle-wall
 * contacts at that speed plus the wall's fastest approach (a plane: its speed along its normal in the stages that
 * reach the particles as placed, a servo's max_speed; a cylinder: its fastest stage) - for every particle's size
 * and material. Gravity is left
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
DEM_API int dem_contact_advice_get(dem_sim *s, dem_contact_advice *a);
/* How close dt is to the explicit step's stability bound at the current overlaps (host/physics/stability.c): a Hertz contact
 * stiffens as sqrt(overlap), so a packing pressed hard can outgrow a dt chosen by the Rayleigh time (a 50 MPa
 * compact heated up at 0.2 Rayleigh times: docs/design.md "The time step under compaction"). Per particle, each
 * contact's normal and tangential-rotational two-body frequencies at the law's stiffness at its overlap, summed over
 * the particle's contacts and walls; ratio = the largest omega dt over the damped bound 2 (sqrt(1 + zeta^2) - zeta),
 * 1 at the bound if the estimate were exact. Measured on a 50 MPa compact and a pressed lattice (docs/design.md): at
 * restitution 0.1 stirred - the kinetic energy not decaying - from 1.2, creeping up at 1, at rest at 0.7; at 0.5
 * stirred from 1.35; at 0.7 and 0.9 at rest up to 1.17 and 1.5. Hence the warning above DEM_STABILITY_LIMIT, and
 * dt_advice for DEM_STABILITY_TARGET. Springs, patches and membranes are not counted. Of particles whose ratios are
 * equal, the lowest id. A rank's part of a split run counts its own particles only (its ghosts are their owners'). */
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
DEM_API int dem_stability_get(dem_sim *s, dem_stability *st);
/* Closed forms of the undamped Hertz collision (relative speed v): duration and largest overlap. */
DEM_API double dem_hertz_contact_time(double mstar, double rstar, double estar, double v);
DEM_API double dem_hertz_max_overlap(double mstar, double rstar, double estar, double v);
/* The damping factor c of hertz_mindlin.h that makes a Hertz collision rebound with restitution e. */
DEM_API double dem_damping_for_restitution(double e);
DEM_API double dem_restitution_for_damping(double c);

/* Validates everything, builds the backend and computes the initial forces. */
DEM_API int dem_start(dem_sim *s, const dem_config *c);
/* Advances nsteps steps. The force each wall received (DEM_FIELD_WALL_FORCE, dem_wall_force) is summed on the last
 * of them (on every one under a servo stage): after a call that failed, it is that of an earlier call. */
DEM_API int dem_step(dem_sim *s, long nsteps);

DEM_API int dem_count(const dem_sim *s);
DEM_API double dem_particle_radius(const dem_sim *s, int i); /* [m], as given */
DEM_API int dem_particle_material(const dem_sim *s, int i);   /* material id; DEM_ERR_ARG for no such particle */
DEM_API double dem_particle_mass(const dem_sim *s, int i);     /* [kg]: set apart or the material's; NAN for no such particle */
DEM_API int dem_wall_count(const dem_sim *s);
DEM_API long dem_step_index(const dem_sim *s);
DEM_API double dem_time(const dem_sim *s);
DEM_API double dem_dt(const dem_sim *s);
DEM_API double dem_neighbor_skin(const dem_sim *s);   /* the skin of the current rows [m] (dem_config.skin); with MC-strain's
                                                 contact distance the rows reach 2 (F - 1) r_max further */
DEM_API long dem_rebuild_count(const dem_sim *s);
DEM_API long dem_reorder_count(const dem_sim *s); /* times the particles were stored anew (dem_config.reorder) */
DEM_API const char *dem_describe(dem_sim *s);   /* backend, device and active effects */

/* Raw bytes of a field in the run's precision (bit comparisons); bytes must not exceed the field's size. */
DEM_API int dem_get_raw(dem_sim *s, dem_field f, void *dst, size_t bytes);
DEM_API size_t dem_field_bytes(const dem_sim *s, dem_field f);
/* A real-valued field converted to double. */
DEM_API int dem_get_field(dem_sim *s, dem_field f, double *dst);
DEM_API int dem_wall_force(dem_sim *s, int wall, double f[3]);     /* force the wall received in the last step [N] */
/* The wall's normal force in the last step: the sum of the particles' force components along their contact normals
 * [N], summed with the force; for a die (cylinder) its radial force, whose vector sum cancels. */
DEM_API int dem_wall_normal_force(dem_sim *s, int wall, double *fn);
DEM_API int dem_wall_position(const dem_sim *s, int wall, double p[3]);
DEM_API int dem_wall_get(const dem_sim *s, int wall, dem_wall *w); /* the wall as added (its normal or axis normalised) */
DEM_API int dem_energy(dem_sim *s, dem_energy_t *e); /* energies and contact counts, on the host in double */
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
DEM_API int dem_sample_get(dem_sim *s, dem_sample *out);
/* Advances nsteps steps like dem_step and samples the steps k (0 <= k < nsteps, of this call) with want[k] != 0:
 * rows receives one sample per such step, in order (want NULL: none). The kernels of a sampled step write each
 * particle's terms in the run's precision to a ring of rows on the device (common/series.h), which the host reads
 * when it is full or the call ends and adds up in double: no synchronisation and no kernel launch per row. The same
 * bits on every backend, and within rounding of dem_sample_get (fp64: a few roundoffs; fp32: the overlaps' own
 * precision). A run with a membrane (springs, patches) is sampled on the host, one synchronisation per row. As after
 * dem_step, DEM_FIELD_WALL_FORCE holds the last step's wall forces; each row holds its own step's. */
DEM_API int dem_step_sampled(dem_sim *s, long nsteps, const unsigned char *want, dem_sample *rows);

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
DEM_API int dem_contacts_get(dem_sim *s, dem_contact **out, long *count, long *npairs);
/* Bytes the backend holds now for the run (every buffer of the registry, both neighbour-row sets). */
DEM_API size_t dem_device_bytes(const dem_sim *s);
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
DEM_API size_t dem_device_bytes_part(const dem_sim *s, dem_memory_part part);
DEM_API const char *dem_memory_part_name(dem_memory_part part);
/* Before dem_start: the bytes the run would hold on the device at the start, from the same registry (rows at their
 * initial capacity, three pair records per particle; rows grow when a packing needs more). Validates and packs
 * the description as dem_start does. */
DEM_API int dem_memory_estimate(dem_sim *s, const dem_config *c, size_t *bytes);

/* The dynamic state of a run, enough to continue it bit for bit (a checkpoint). Real arrays are raw bytes in the
 * run's precision (real_size 4 or 8). Per particle (and per wall): the arrays, each a buffer of the library saved
 * whole, particles by their ids (x, v, w, force, torque, the walls' forces and each particle's wall contact memory:
 * dem_state_arrays lists them). Contacts: the touching pairs (i < j) and, with friction, their tangential spring.
 * Neighbour rows are rebuilt on restore. */
#define DEM_PAIR_RECORD_REALS 7 /* reals per pair record (DEM_FIELD_PAIR_RECORDS, dem_state.pair_rec) */
#define DEM_MDR_LAW_REALS 25 /* reals of state per pair of the mdr law (dem_state.has_law, pair_law) */
typedef enum { DEM_STATE_REAL, DEM_STATE_INT, DEM_STATE_UINT } dem_state_elem;
/* One array of a state: name (a checkpoint's dataset /state/<name>), unit (NULL: none), element type, elements per
 * dataset row (3 for x), whether a state must hold it (else missing: zero until computed), and count elements at
 * data (malloc'd; NULL: missing). */
typedef struct {
    const char *name, *unit;
    dem_state_elem elem;
    int width, required;
    size_t count;
    void *data;
} dem_state_array;
#define DEM_STATE_MAX_ARRAYS 32
typedef struct {
    long step, rebuilds;
    int n, nwalls, real_size;
    int narrays;                       /* the per-particle and per-wall arrays (dem_state_arrays) */
    dem_state_array arrays[DEM_STATE_MAX_ARRAYS];
    double wall_pos[DEM_MAX_WALLS][3]; /* [m] */
    int has_stages;                       /* 1: the three below hold (0: derive them from the step) */
    int wall_stage[DEM_MAX_WALLS];        /* each wall's motion stage (nstages: past the last) */
    long wall_stage_first[DEM_MAX_WALLS]; /* the step it began */
    double wall_stage_from[DEM_MAX_WALLS][3]; /* where the wall was then [m] (dem_stage.until_distance) */
    long npairs;
    int *pair_i, *pair_j;             /* each contact's particles, in ascending i, then j */
    void *pair_hist;                  /* real[3 npairs] */
    void *pair_rec;                   /* real[DEM_PAIR_RECORD_REALS npairs]: each pair's force record of the last step (dem_layout.h
                                         PR_*: the contact network's forces); NULL: not known (an older checkpoint),
                                         zero until the next step */
    int has_hist;                     /* 1 when the run has friction */
    int has_mc;                       /* 1 when the run has MC-strain: its stored forces follow */
    void *pair_mc_fn;                 /* real[npairs]: MC-strain force of each touching pair */
    void *pair_mc_disp;               /* real[2 npairs] with MC-strain: the induced displacement at i's and at j's
                                         end in the last step (the contact network's extra); NULL: not known */
    int has_law;                      /* the reals of state the run's contact law keeps per contact: 0 none, 1
                                         DEM_EFFECT_THORNTON_NING, DEM_MDR_LAW_REALS DEM_EFFECT_MDR (its row, dem_layout.h
                                         MDR_*); pair_law and the array wall_law (13 per slot with MDR) follow */
    void *pair_law;                   /* real[has_law npairs]: that state of each touching pair (Thornton-Ning: the
                                         largest overlap so far [m], negated once the contact's bond broke; with
                                         DEM_EFFECT_ADHESION the largest contact radius so far [m], negated once it
                                         let go; before 2026-12-06 that too was the largest overlap) */
    int has_rspring;                  /* 1 when the run has rolling springs (DEM_EFFECT_ROLLING_SPRING): pair_rspring
                                         and the array wall_rspring follow */
    void *pair_rspring;               /* real[3 npairs]: each touching pair's rolling spring, the torque on its lower
                                         id [N m] */
    dem_mc_stats mc;                  /* iteration counts so far */
    long npatch;                      /* sphere-patch row slots with flags: the touching contacts, and the spheres
                                         touching a patch whose side is remembered (common/patch_contacts.h), by
                                         sphere then triangle */
    int *patch_i, *patch_t;           /* the sphere, the triangle */
    void *patch_hist;                 /* real[3 npatch]: their tangential springs (zero without friction) */
    int *patch_side;                  /* [npatch]: their flags, PATCH_SAVED bits of common/dem_layout.h (1: a contact,
                                         4: the sphere is below the triangle's normal (x_b - x_a) x (x_c - x_a), 8: the
                                         side is known, 16: the centre has crossed the patch's plane); NULL: not known
                                         (an older checkpoint: contacts, each side taken anew) */
} dem_state;
/* The arrays a state of st's n, nwalls, real_size, has_hist, has_mc, has_law and has_rspring holds, without data:
 * names, types, and the count each has (an array whose size only the run knows, e.g. wall_pf: its full size, not
 * required); what a reader of a saved state fills before dem_state_set. Sets st->narrays and returns it. */
DEM_API int dem_state_arrays(dem_state *st);
/* The array called name (NULL: none), e.g. (double *)dem_state_find(&st, "x")->data in an fp64 run */
DEM_API dem_state_array *dem_state_find(const dem_state *st, const char *name);
DEM_API int dem_state_get(dem_sim *s, dem_state *st); /* allocates; free with dem_state_free */
/* After dem_start of the same set-up: continue from st (replaces positions, velocities, contacts, step). */
DEM_API int dem_state_set(dem_sim *s, const dem_state *st);
DEM_API void dem_state_free(dem_state *st);

/* The OpenCL devices over all platforms (0 when there are none); the name of device k, or DEM_ERR_DEVICE with the
 * reason in buf. */
DEM_API int dem_device_count(void);
DEM_API int dem_device_name(int k, char *buf, size_t len);
/* What device k has: compute units, clock, global memory, largest work-group, driver (`dem devices`) */
DEM_API int dem_device_describe(int k, char *buf, size_t len);

#ifdef __cplusplus
}
#endif
/* The rest of the public interface: membranes and the press */
#include "dem_membrane.h"
#include "dem_press.h"
#endif /* DEM_H */
