/* scene.h - a scene file (YAML) as C data, and what the `dem` command builds from it.
 *
 * scene_schema.c maps the YAML onto these structs with libcyaml (the schema is the one description of the file
 * format; docs/scenes.md explains every key). scene_locate.c remembers where every key sits in the file, so any
 * error can name file, line and field. scene_build.c checks the values and builds a dem_sim.
 * Units are SI throughout (m, kg, s, Pa, N).
 */
#ifndef DEM_SCENE_H
#define DEM_SCENE_H
#include <stdbool.h>
#include "dem.h"
#include <stdio.h>
#include <stddef.h>

/* material_pairs: a pair of materials with its own friction or restitution (dem_set_material_pair) */
typedef struct {
    char **materials; /* the two names */
    unsigned materials_count;
    double friction, restitution, rolling_friction, bond_strength, surface_energy; /* each only where given */
} scene_material_pair;

typedef struct {
    char *name;
    double density, young, poisson, restitution, friction;
    double beta, gamma;           /* multi-contact prefactors (mc_stress, mc_strain) */
    double yield_stress;          /* limiting contact pressure of thornton_ning [Pa]; 0: does not yield */
    double rolling_friction;      /* rolling resistance coefficient (effect rolling) */
    double bond_strength;         /* strength of a yielded contact's solid bridge (thornton_ning, mdr) [Pa]; 0: none */
    double rolling_damping;       /* viscous damping ratio of the rolling spring (effect rolling_spring) */
    double surface_energy;        /* the mdr law's surface energy, thornton_ning's work of adhesion with the effect
                                     adhesion [J/m^2] */
    double bulk_fraction;         /* the mdr law's psi_b (required with it) */
    double mdr_damping;           /* the mdr law's damping coefficient eta_d */
} scene_material;

typedef struct {
    double x[3], v[3], w[3];
    double radius;
} scene_sphere;

typedef struct {
    double lo[3], hi[3];          /* box */
    double base[3], axis[3];      /* cylinder: centre of the base disc, axis direction */
    double radius, height;        /* cylinder */
} scene_region;

typedef struct {
    double median, sigma;         /* lognormal radii: median [m], standard deviation of ln r */
} scene_lognormal;

typedef struct {
    double radius, fraction;      /* one size of a listed distribution [m], its share (by number or volume) */
} scene_size;

typedef struct {
    char *kind;                   /* "random" (random sequential addition, no overlaps) or "lattice" (cubic) */
    char *shape;                  /* "box" or "cylinder" */
    scene_region region;
    unsigned count;               /* number of spheres (random; lattice: at most this many, 0 = fill) */
    double radius;                /* every sphere, or: */
    double radius_min, radius_max; /* radii uniform in [min, max], or the bounds of a lognormal */
    scene_lognormal *lognormal;   /* random: lognormal radii, truncated to [radius_min, radius_max] */
    scene_size *sizes;            /* random: listed radii, shares summing to 1 */
    unsigned sizes_count;
    char *fractions;              /* the shares of sizes: "number" (default) or "volume" */
    double spacing;               /* lattice: centre distance (default 2 radius_max) */
    double speed;                 /* random initial velocity, each component uniform in [-speed, speed] */
    unsigned seed;
} scene_generate;

typedef struct {
    char *material;
    scene_sphere *spheres;        /* explicit list, or */
    unsigned spheres_count;
    char *csv;                    /* a CSV file (path relative to the scene file), or */
    char *csv_density;            /* "check" (default: a density column must match the material) or "ignore" */
    scene_generate *generate;     /* generated */
    char **hold;                  /* velocity components every sphere of the group keeps: "x", "y", "z" */
    unsigned hold_count;
    bool fixed_rotation;          /* the group's spheres do not rotate */
} scene_particles;

typedef struct {
    double velocity[3];           /* [m/s] */
    double duration;              /* [s], or */
    double distance;              /* [m] travelled at |velocity|, or */
    double strain, length;        /* distance = strain x length */
    double force;                 /* servo stage: the normal force the wall should receive [N], or */
    double stress, area;          /* stress [Pa] x area [m^2] */
    double gain, max_speed;       /* [m/s per N], [m/s] */
    double until_force;           /* the stage ends early once the wall receives this normal force [N], or */
    double until_stress;          /* this stress [Pa] x area, and/or */
    double until_distance;        /* once it has moved this far [m] */
    double until_density;         /* once the relative density in the die reached this (dem_stage.until_density) */
    double ramp;                  /* [s]: the velocity ramps from the previous stage's (dem_stage.ramp) */
    char *after;                  /* the stage waits until this wall has run all its stages (dem_stage.after_wall) */
} scene_stage;

typedef struct {
    double radius, depth;         /* a concave punch face's cup: radius at the face, depth at its centre [m] */
} scene_cup;

typedef struct {
    char *name;
    char *material;
    double point[3], normal[3];   /* plane (normal towards the particles) */
    double axis[3], radius;       /* cylinder: point on its axis, axis direction, inner radius */
    double height;                /* cylinder: length from the point along the axis (0: endless) */
    double lo[3], hi[3];          /* box: six planes from inside */
    char *type;                   /* "plane", "cylinder" or "box" */
    scene_stage *motion;
    unsigned motion_count;
    bool rigid;                   /* infinitely stiff: E* of a contact from the particle alone (dem.h) */
    unsigned repeat;              /* the motion list this many times (0 = given: once) */
    scene_cup *cup;               /* plane: a concave face (dem_wall.cup_radius, cup_depth) */
} scene_wall;

/* membranes: [{name, mesh: {kind, center, radius, height, size, edge}, material: {...}, model, pressure,
 * pressure_stages, attach: [{wall, within}]}] (seed 001; docs/scenes.md) */
typedef struct {
    char *kind;                   /* "tube", "sheet", "sphere" or "file" */
    double center[3];             /* tube, sheet, sphere: centre [m] */
    double radius, height;        /* tube, sphere (radius) [m] */
    double size[2];               /* sheet: along x and y [m] */
    double edge;                  /* target edge length [m] (generated meshes) */
    char *path;                   /* file: .obj or .stl, relative to the scene file */
    double scale;                 /* file: coordinates x scale [m per file unit] (default 1) ... */
    double translate[3];          /* ... + translate [m] */
    bool flip;                    /* file: reverse every triangle (the pressure then pushes the other way) */
} scene_mesh;

typedef struct {
    double young, poisson, thickness, density, restitution, friction;
    double damping;               /* damping ratio of the edge springs */
    double kel, kdiss;            /* bending [N m], [N s] */
    double vertex_radius;         /* [m] */
} scene_membrane_material;

typedef struct {
    char *wall;                   /* a plane wall's name */
    double within;                /* vertices closer to the plane than this ride on the wall [m] */
} scene_attach;

typedef struct {
    double duration, pressure;    /* [s], [Pa] at the stage's end */
} scene_pressure_stage;

typedef struct {
    char *name;
    scene_mesh mesh;
    scene_membrane_material material;
    char *model;                  /* "patch" (default) or "particle" */
    double pressure;              /* [Pa] pushing towards the inside (tube, sphere) or along -z (sheet) */
    scene_pressure_stage *pressure_stages;
    unsigned pressure_stages_count;
    scene_attach *attach;
    unsigned attach_count;
    bool fixed;                   /* every vertex fixed (a membrane on a rigid support) */
} scene_membrane;

typedef struct {
    double dt;                    /* [s], or */
    double dt_rayleigh;           /* fraction of the Rayleigh time */
    double duration;              /* [s] */
    double settle;                /* [s] at the start during which walls hold still (their stages start after) */
    double mass_scale;            /* every mass x this (>= 1; 1 when absent): scene_mass_scale, docs/scenes.md */
    char *mass_scale_keeps;       /* "weight" (default: gravity / mass_scale) or "acceleration" (gravity as given) */
} scene_time;

typedef struct {
    double frame_every;           /* [s] between particle frames */
    double series_every;          /* [s] between time-series rows */
    double checkpoint_every;      /* [s] between checkpoints (0: only at the end) */
    unsigned series_average;      /* each series row the mean over this many steps ending at it (0, 1: no mean) */
    char **fields;
    unsigned fields_count;
} scene_output;

typedef struct {
    char *piston;                 /* name of the wall that compresses the sample */
    double height;                /* initial sample height [m] (0: piston to the lowest particle bottom) */
    double area;                  /* cross-section [m^2] (0: from a box or cylinder wall around the sample) */
    double contact_travel;        /* piston travel [m] at which the sample starts being strained (default 0) */
} scene_sample;

/* mc_stress_convention: {own_contact: in|out, lever: centres|contact_point, scale: mean_trace|text|mean_pressure};
 * an absent key keeps DEM_MCS_DEFAULT's choice (docs/scenes.md, docs/multicontact.md). */
typedef struct {
    char *own_contact;
    char *lever;
    char *scale;
} scene_mcs_convention;

typedef struct {
    char *name;
    char *description;
    char *precision;              /* "fp32" or "fp64" */
    int device;
    char *backend;                /* "opencl" (default) or "reference" */
    char *particle_order;         /* "spatial" (dem_sort_particles; the default: scene_particle_order) or "input" */
    char **effects;
    unsigned effects_count;
    scene_material *materials;
    unsigned materials_count;
    scene_material_pair *material_pairs;
    unsigned material_pairs_count;
    scene_particles *particles;
    unsigned particles_count;
    scene_wall *walls;
    unsigned walls_count;
    scene_membrane *membranes;
    unsigned membranes_count;
    double gravity[3];
    double domain_lo[3], domain_hi[3];
    double overlap_tolerance;     /* largest initial overlap accepted, fraction of the smaller radius */
    scene_time time;
    scene_output output;
    scene_sample *sample;         /* optional: report engineering strain and stress of a compressed sample */
    int mc_iterations;            /* MC-strain: 0 lagged (published scheme), N > 0 iterate up to N times */
    double mc_tolerance;          /* MC-strain iteration: relative force change accepted (default 1e-6) */
    scene_mcs_convention *mc_stress_convention; /* optional: how MC-stress builds its pressure (dem_effects.h) */
    double mc_contact_distance;   /* MC-strain contact distance factor in [1, 2] (absent: 1, geometric contacts) */
} scene_file;

typedef struct scene_locator scene_locator; /* scene_locate.c */

/* A loaded scene: the data, the file text, and where each key is. */
typedef struct {
    char *path;      /* as given */
    char *dir;       /* its folder, for relative paths in it */
    char *text;      /* the file's bytes (stored in the output) */
    size_t text_len;
    scene_file *f;
    scene_locator *loc;
    const char *order_default; /* particle_order where the text gives none: NULL = "spatial"; "input" for a
                                  checkpoint written before spatial became the default (its own order) */
} scene;

/* Output fields a scene may ask for. */
enum { OUT_POSITION = 1, OUT_VELOCITY = 2, OUT_ANGULAR_VELOCITY = 4, OUT_RADIUS = 8, OUT_FORCE = 16,
       OUT_TORQUE = 32, OUT_MATERIAL = 64, OUT_STRESS = 128, OUT_CONTACTS = 256,
       OUT_APPARENT_RADIUS = 512 /* not a scene's key: output.c adds it to `radius` under mdr */ };

/* What scene_build derives. */
typedef struct {
    unsigned effects;
    dem_config cfg;
    double dt;
    long steps, frame_every, series_every, checkpoint_every; /* in steps */
    long series_average;          /* steps each series row averages (1: the row's own step) */
    unsigned fields;        /* OUT_* */
    int piston;             /* wall whose position and force define the sample's strain and stress, -1 none */
    double sample_height;   /* initial piston-to-opposite-wall distance [m] (strain reference) */
    double sample_area;     /* cross-section the piston force acts on [m^2] */
    double piston_point[3], piston_normal[3]; /* initial point and unit normal (towards the particles) */
    double contact_travel;  /* [m] */
    dem_time_scales ts;
    char note[1024];        /* remarks for `dem check` (ignored parameters ...) */
    char fill[2048];        /* the random groups' placement: count, volume share, time (dem check) */
    char model[32];         /* normal law chosen on the command line (dem run --model), "" = the scene's */
    unsigned mcs_conv;      /* DEM_MCS_* bits (used when MC-stress runs) */
    int mc_cap;             /* MC-strain iteration cap in force (0: lagged) and its tolerance */
    double mc_tol;
    dem_membrane_info membrane[16]; /* where each of the scene's membranes went (scene_add_membranes) */
    long particles;         /* particles in the run (the series' coordination number) */
} scene_run;

/* Loads and parses; on failure returns NULL and writes "file:line: field: reason" into err. */
scene *scene_load(const char *path, char *err, size_t errlen);
scene *scene_load_text(const char *path, const char *text, size_t len, char *err, size_t errlen);
void scene_free(scene *sc);
/* A file the scene names (a CSV, a mesh): an absolute path as it is, else relative to the scene file's folder */
void scene_file_path(const scene *sc, const char *name, char *buf, size_t len);
/* path opened for reading ("rb") when it is a regular file; else NULL with the reason in why (strerror, or "not a
 * regular file ..."): a named pipe would block the open and the read forever, a device (/dev/zero) be read without
 * end. The scene, its CSV files and its mesh files are opened this way. */
FILE *scene_open_regular(const char *path, char *why, size_t len);
/* " (did you mean 'x'?)" in buf when one of the n candidates is near word - an edit distance (insertions, deletions,
 * substitutions, and swaps of two neighbours) of at most 1 for words up to 4 characters, 2 up to 8, 3 beyond - the
 * nearest, the first of equals; else "". For a misspelt key, wall, material or effect name. Returns buf. */
const char *scene_did_you_mean(const char *word, const char *const *cands, int n, char *buf, size_t len);
/* The same over the names of the scene's walls (plane walls only when planes_only) and over its materials' names */
const char *scene_wall_hint(const scene *sc, const char *word, int planes_only, char *buf, size_t len);
const char *scene_material_hint(const scene *sc, const char *word, char *buf, size_t len);
/* Library wall k's name, as the output's wall_names lists it (a box's faces "NAME x-" ...) */
void scene_wall_label(const scene *sc, int k, char *buf, size_t len);
/* The library id of the first wall scene wall k adds (a box adds six planes, any other wall one) */
int scene_first_wall(const scene *sc, unsigned k);
/* Checks every value and builds the simulation (not started). Returns NULL with err set on failure. */
dem_sim *scene_build(const scene *sc, scene_run *run, char *err, size_t errlen);
/* time.mass_scale, or 1 where the scene gives none (scene_build has checked it: finite, >= 1) */
double scene_mass_scale(const scene *sc);
/* particle_order: "spatial" where the scene gives none (the spheres sorted along a Morton curve at load: a packing
 * in another code's order, or generated at random, then runs in the fast order without the user knowing the key;
 * docs/scenes.md), else as given (scene_particles.c checks it) */
const char *scene_particle_order(const scene *sc);
/* 1 when gravity is kept as given under mass scaling (time.mass_scale_keeps: acceleration), 0: divided by it */
int scene_keeps_acceleration(const scene *sc);
/* Replaces the scene's normal law (after scene_build, before dem_start): "classical", "mc_stress", "mc_strain"
 * (lagged) or "mc_strain_iterated" (the scene's mc_iterations, or 20). Records it in run->model. */
int scene_apply_model(const scene *sc, dem_sim *s, scene_run *run, const char *model, char *err, size_t errlen);

/* scene_locate.c: line of a field path such as "walls[1].motion[0].velocity" (0 if absent). */
scene_locator *scene_locate(const char *text, size_t len);
void scene_locator_free(scene_locator *l);
int scene_line(const scene_locator *l, const char *path);
int scene_has(const scene_locator *l, const char *path);
/* Entry k of the located paths in document order: its path, the scalar value's text (NULL for a collection) and line;
 * 0 past the end. */
int scene_scalar(const scene_locator *l, size_t k, const char **path, const char **value, int *line);
/* The first key given twice in one mapping: returns its second line (0 if none), with its path and first line. */
int scene_duplicate(const scene_locator *l, const char **path, int *first);
/* A YAML syntax error: libyaml's reason and the line where it stopped (the last line when it ran off the end), or
 * NULL when the text parsed. */
const char *scene_syntax_error(const scene_locator *l, int *line);
#endif
