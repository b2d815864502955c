/* test_util.h - scene builders and bitwise comparison helpers shared by the tests. */
#ifndef DEM_TEST_UTIL_H
#define DEM_TEST_UTIL_H
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "dem.h"
#include "dem_debug.h" /* the tests read the internals too */

typedef struct {
    int side;           /* large spheres on a side^3 cubic lattice of spacing 2 rmax, small ones in the
                           (side-1)^3 body centres: n = side^3 + (side-1)^3, solid fraction about 0.58 */
    double rmax;        /* largest radius [m]; large radii in [0.9, 1] rmax, small in [0.45, 0.5] rmax */
    double speed;       /* random initial speed scale [m/s] */
    double lid_speed;   /* downward lid speed [m/s] (0: no motion) */
    double friction, restitution, young, density, poisson;
    int gravity;
    unsigned seed;
    unsigned effects;   /* DEM_EFFECT_* mask; 0 = the default (classical) */
    double mc_beta, mc_gamma; /* multi-contact prefactors of the particle material */
    int mc_iterations;  /* MC-strain: 0 lagged, else iterated with tolerance 1e-6 */
    unsigned mcs_conv;  /* MC-stress convention, DEM_MCS_* (DEM_MCS_DEFAULT from packing_defaults) */
    double mc_reach;    /* MC-strain contact distance factor (0 or 1: off) */
    double yield_stress; /* the particle material's limiting contact pressure (DEM_EFFECT_THORNTON_NING) [Pa] */
    double bond_strength; /* the particle material's bond strength sigma_b (DEM_EFFECT_THORNTON_NING) [Pa] */
    double rolling_friction, rolling_damping; /* the particle material's mu_r and eta_r (DEM_EFFECT_ROLLING[_SPRING]) */
    double surface_energy, bulk_fraction, mdr_damping; /* the particle material's MDR gamma, psi_b, eta_d
                                                          (DEM_EFFECT_MDR, with yield_stress its Y) */
} packing_opts;

void packing_defaults(packing_opts *o);
/* The twelve MC-stress conventions, k = 0..11 (own in/out x lever centres/contact point x scale mean trace/text/
 * mean pressure; k = 0 is DEM_MCS_DEFAULT), and a readable name of one. */
#define MCS_CONVENTIONS 12
unsigned mcs_convention(int k);
const char *mcs_convention_name(unsigned c, char *buf, size_t len);
/* Builds the packing into a fresh simulation: a box of 6 plane walls, the top one (wall 5) a moving lid. */
dem_sim *packing_build(const packing_opts *o);

dem_config cfg_of(dem_backend_kind b, dem_precision p);
/* A head-on collision of spheres of radius r and material m along x, touching at t = 0: wall_m NULL, two spheres at
 * -+r approaching at +-v/2; else one sphere at x = r moving at -v onto the plane x = 0 of material wall_m. Domain
 * +-8 r; effects as given (fails the test if refused); dt set. */
dem_sim *head_on_build(const dem_material *m, const dem_material *wall_m, double r, double v, unsigned effects,
                       double dt);

/* The backend x precision matrix every kernel test runs over (HOOMD style): the reference and OpenCL device
 * DEM_DEVICE (default 0), each in fp32 and fp64. A test builds the same scene for each case, checks the physics on
 * it, and checks that the OpenCL case has the reference's bits (backend_same_bits). */
typedef struct {
    const char *name;      /* "reference fp64", ... */
    dem_backend_kind backend;
    dem_precision precision;
    double eps;            /* unit roundoff of the precision (2^-53 or 2^-24) */
} backend_case;
#define BACKEND_CASES 4
extern const backend_case backend_cases[BACKEND_CASES];
#define FOR_EACH_BACKEND(bc) for (const backend_case *bc = backend_cases; bc < backend_cases + BACKEND_CASES; bc++)
/* Runs build() for the case, starts it, steps it, calls check() (which may step it further); when the case is
 * OpenCL, builds the reference of that precision, steps it to the same step and asserts the states bitwise equal. */
void backend_run(const backend_case *bc, dem_sim *(*build)(void *ctx), long steps,
                 void (*check)(dem_sim *s, const backend_case *bc, void *ctx), void *ctx);
/* The same packing on the reference (rc) and on OpenCL (c), both started and advanced by `steps`. */
void packing_pair(const packing_opts *o, const dem_config *rc, const dem_config *c, long steps, dem_sim **ref,
                  dem_sim **cl);
/* dem_start, failing the test with the library's message. */
void start_or_fail(dem_sim *s, const dem_config *c);
void step_or_fail(dem_sim *s, long n);
/* This process's PoCL on at least two threads (POCL_MAX_PTHREAD_COUNT raised to 2 where unset or lower; called
 * first in main, before any OpenCL call reads it). scripts/run-tests.sh gives each program one thread when the
 * programs fill the cores; the programs that call this keep work-groups running on two threads at once, so a race
 * between work-groups can still show as a difference from the reference: test_determinism (classical),
 * test_multicontact (MC-stress, MC-strain), test_patch_contacts (membranes), test_mdr_run (MDR) and test_tn_adhesion
 * (Thornton-Ning, JKR adhesion). Not test_bonds: its small scenes' thousands of launches took 88 s on two threads
 * against 34 s on one (warm kernel cache, beside another program); a bond is a per-pair term of contact_forces, whose
 * loops classical runs on two threads. */
void test_pocl_threads(void);

/* Bitwise comparison of the dynamic state of two simulations (x, v, w, force, torque, wall force and the
 * tangential history of every pair in contact). Returns 0 when identical; else describes the first difference. */
int state_diff(dem_sim *a, dem_sim *b, char *msg, size_t len);
/* state_diff of a against each of b[0..nb-1], a's state read once (runs in lockstep with one reference): -1 when
 * every one is bitwise equal to a, else the index of the first that is not, msg describing its first difference */
int state_diff_each(dem_sim *a, dem_sim *const *b, int nb, char *msg, size_t len);
/* Steps a and b by n each and fails the test (naming what and the step) unless their states are bitwise equal
 * (state_diff): twins on two backends, skins or storage orders */
void twins_step(dem_sim *a, dem_sim *b, long n, const char *what);
/* Writes m as a Wavefront OBJ with every digit of its coordinates (%.17g), for dem_mesh_read to read back */
void mesh_write_obj(const dem_mesh *m, const char *path);
/* The packing o run `steps` with c's backend and precision three ways: skins 0.05 and 0.3 x the largest radius
 * (other rebuild steps) and stored anew at every rebuild (skin 0.05); fails the test (naming `what`) unless all three
 * are bitwise equal. Returns the first run and the one stored anew alive in *s1 and *s3 (dem_destroy them). */
void skins_and_order_check(const packing_opts *o, const dem_config *c, long steps, const char *what, dem_sim **s1,
                           dem_sim **s3);
/* restart_check on two fresh builds of packing o with c (300 steps, restored, 300 more); the first run's state then
 * into *st (dem_state_free it) */
void packing_restart_state(const packing_opts *o, const dem_config *c, const char *what, dem_state *st);
/* skins_and_order_check keeping none of the runs, and on OpenCL also against the reference of c's precision
 * (skin 0.05) */
void skins_order_and_reference_check(const packing_opts *o, const dem_config *c, long steps, const char *what);
/* Restart: starts a and b (the same set-up) with c, steps a by `before`, restores a's state into b, steps both by
 * `after` and fails the test (naming `what`) unless they are bitwise equal. Leaves both alive for further checks. */
void restart_check(dem_sim *a, dem_sim *b, const dem_config *c, long before, long after, const char *what);
/* FNV-1a hash of the same state, for comparing runs in other processes. */
uint64_t state_hash(dem_sim *s);

double uniform01(unsigned *state);

/* A fresh folder /tmp/PREFIX-XXXXXX into dir (0 on success), and its removal with everything in it. */
int test_tmpdir_make(char *dir, size_t len, const char *prefix);
int test_tmpdir_remove(const char *dir);
/* Runs a shell command (printf-style), its stderr captured into err via dir/stderr.txt; returns its exit status. */
int test_sh(const char *dir, char *err, size_t len, const char *fmt, ...);
/* The Python the tests run their scripts with, by scripts/find_python.sh's rule: $PYTHON when set, else the first of
 * the `python3` on PATH and /usr/bin/python3 that imports h5py and numpy; test_python_plots: one that also imports
 * matplotlib (for the tests that draw a PNG). When there is none, fails the test with the script's message (what each
 * interpreter tried lacks): a test that needs Python never passes without running it. Looked up once per program. */
const char *test_python(void);
const char *test_python_plots(void);

/* A probe kernel of the tests' own (a header of common/ driven by a few lines of OpenCL C): its program built from src
 * for device DEM_DEVICE (default 0) with the library's build options for precision rs (4 or 8; cl_build_options), and
 * its kernel `name`; fails the test with the build log when it does not build. test_cl_buffer makes a buffer of
 * bytes bytes (copied from host when not NULL); test_cl_close releases the kernel, program, queue and context. */
typedef struct {
    void *ctx, *queue, *program, *kernel; /* cl_context, cl_command_queue, cl_program, cl_kernel */
} test_cl;
void test_cl_open(test_cl *t, const char *src, const char *name, int rs);
void *test_cl_buffer(test_cl *t, size_t bytes, const void *host);
void test_cl_close(test_cl *t);

/* Two spheres (radius r, material m) approaching head-on along x at relative speed v, touching at t = 0.
 * dt_frac: time step as a fraction of the closed-form Hertz contact time. */
dem_sim *pair_build(const dem_material *m, double r1, double r2, double v, double dt_frac);
/* Distance between the centres of particles 0 and 1 [m] (a two-particle simulation). */
double pair_distance(dem_sim *s);
/* The correctly rounded double sum of x[0..n) (Shewchuk's exact partials, math.fsum's algorithm): a check of the
 * exact sums written apart from common/exact_sum.h */
double fsum_ref(const double *x, long n);
#endif
