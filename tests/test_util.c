/* test_util.c - see test_util.h */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

int test_tmpdir_make(char *dir, size_t len, const char *prefix)
{
    snprintf(dir, len, "/tmp/%s-XXXXXX", prefix);
    return mkdtemp(dir) ? 0 : -1;
}

int test_tmpdir_remove(const char *dir)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

int test_sh(const char *dir, char *err, size_t len, const char *fmt, ...)
{
    char cmd[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    char full[4600];
    snprintf(full, sizeof full, "%s 2>%s/stderr.txt", cmd, dir);
    int st = system(full);
    char p[600];
    snprintf(p, sizeof p, "%s/stderr.txt", dir);
    FILE *fp = fopen(p, "r");
    size_t n = fp ? fread(err, 1, len - 1, fp) : 0;
    err[n] = 0;
    if (fp)
        fclose(fp);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* scripts/find_python.sh MODULES, once per module set: its path, or fails the test with its message */
static const char *python_with(int k, const char *modules)
{
    static char path[2][1024], msg[2][2048];
    static int looked[2];
    if (!looked[k]) {
        looked[k] = 1;
        char cmd[1200];
        snprintf(cmd, sizeof cmd, "/bin/sh '%s/scripts/find_python.sh' %s 2>&1", DEM_DEFAULT_SOURCE_DIR, modules);
        FILE *p = popen(cmd, "r");
        size_t n = p ? fread(msg[k], 1, sizeof msg[k] - 1, p) : 0;
        msg[k][n] = 0;
        int st = p ? pclose(p) : -1;
        while (n > 0 && (msg[k][n - 1] == '\n' || msg[k][n - 1] == ' '))
            msg[k][--n] = 0;
        if (st == 0 && n > 0 && n < sizeof path[k]) {
            const char *last = strrchr(msg[k], '\n'); /* its last line: the path */
            snprintf(path[k], sizeof path[k], "%s", last ? last + 1 : msg[k]);
        } else if (!n) {
            snprintf(msg[k], sizeof msg[k], "%s/scripts/find_python.sh did not run (status %d)",
                     DEM_DEFAULT_SOURCE_DIR, st);
        }
    }
    if (!path[k][0])
        fail_msg("%s", msg[k]);
    return path[k];
}

const char *test_python(void)
{
    return python_with(0, "h5py numpy");
}

const char *test_python_plots(void)
{
    return python_with(1, "h5py numpy matplotlib");
}

double uniform01(unsigned *st)
{
    *st = *st * 1664525u + 1013904223u;
    return (double)(*st >> 8) / 16777216.0;
}

void packing_defaults(packing_opts *o)
{
    memset(o, 0, sizeof *o);
    o->side = 11; /* 1331 + 1000 = 2331 particles */
    o->rmax = 1e-3;
    o->speed = 0.5;
    o->lid_speed = 0.2;
    o->friction = 0.4;
    o->restitution = 0.6;
    o->young = 1e7;
    o->density = 2500;
    o->poisson = 0.3;
    o->gravity = 1;
    o->seed = 12345;
    o->mcs_conv = DEM_MCS_DEFAULT;
}

unsigned mcs_convention(int k)
{
    static const unsigned scale[3] = {DEM_MCS_SCALE_TRACE, DEM_MCS_SCALE_TEXT, 0};
    return (k / 6 ? 0u : (unsigned)DEM_MCS_OWN_IN) | ((k / 3) % 2 ? 0u : (unsigned)DEM_MCS_LEVER_CENTRES) |
           scale[k % 3];
}

const char *mcs_convention_name(unsigned c, char *buf, size_t len)
{
    dem_mc_stress_convention_string(c, buf, len);
    return buf;
}

dem_sim *head_on_build(const dem_material *m, const dem_material *wall_m, double r, double v, unsigned effects,
                       double dt)
{
    dem_sim *s = dem_create();
    int id = dem_add_material(s, m);
    if (wall_m) {
        dem_wall w;
        memset(&w, 0, sizeof w);
        w.kind = DEM_WALL_PLANE;
        w.material = dem_add_material(s, wall_m);
        w.normal[0] = 1;
        assert_true(dem_add_wall(s, &w) >= 0);
        dem_add_particle(s, (double[3]){r, 0, 0}, (double[3]){-v, 0, 0}, r, id);
    } else {
        dem_add_particle(s, (double[3]){-r, 0, 0}, (double[3]){0.5 * v, 0, 0}, r, id);
        dem_add_particle(s, (double[3]){r, 0, 0}, (double[3]){-0.5 * v, 0, 0}, r, id);
    }
    double L = 8 * r;
    dem_set_domain(s, (double[3]){-L, -L, -L}, (double[3]){L, L, L});
    if (dem_set_effects(s, effects))
        fail_msg("%s", dem_error(s));
    dem_set_dt(s, dt);
    return s;
}

dem_sim *packing_build(const packing_opts *o)
{
    dem_sim *s = dem_create();
    dem_material m = {o->density,  o->young,    o->poisson,     o->restitution,
                      o->friction, o->mc_beta, o->mc_gamma, o->yield_stress, o->rolling_friction, o->bond_strength,
                      o->rolling_damping, o->surface_energy, o->bulk_fraction, o->mdr_damping};
    int mat = dem_add_material(s, &m);
    dem_material wm = {7800, 2e8, 0.3, o->restitution, o->friction};
    int wmat = dem_add_material(s, &wm);
    int side = o->side;
    double a = 2 * o->rmax, L = side * a;
    unsigned st = o->seed;
    for (int layer = 0; layer < 2; layer++) {
        int m = side - layer;
        for (int i = 0; i < m * m * m; i++) {
            int ix = i % m, iy = (i / m) % m, iz = i / (m * m);
            double off = layer ? 1.0 : 0.5;
            double x[3] = {(ix + off) * a, (iy + off) * a, (iz + off) * a};
            double v[3];
            for (int d = 0; d < 3; d++)
                v[d] = o->speed * (2 * uniform01(&st) - 1);
            double r = o->rmax * (layer ? 0.45 + 0.05 * uniform01(&st) : 0.9 + 0.1 * uniform01(&st));
            dem_add_particle(s, x, v, r, mat);
        }
    }
    /* box [0,L]^3: x-, x+, y-, y+, floor, lid (wall 5) */
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, wmat);
    if (o->lid_speed > 0) {
        dem_stage lid[2] = {{0.006, {0, 0, -o->lid_speed}}, {0.006, {0, 0, o->lid_speed}}};
        dem_set_wall_motion(s, 5, 2, lid);
    }
    if (o->gravity)
        dem_set_gravity(s, (double[3]){0, 0, -9.81});
    double lo[3] = {-0.5 * L, -0.5 * L, -0.5 * L}, hi[3] = {1.5 * L, 1.5 * L, 1.5 * L};
    dem_set_domain(s, lo, hi);
    if (o->effects & DEM_EFFECT_MDR) /* MDR's stiffness bound is its own (laws/mdr.h): dt from it */
        dem_set_effects(s, o->effects);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    if (o->effects)
        dem_set_effects(s, o->effects);
    if (o->mc_iterations)
        dem_set_mc_strain(s, o->mc_iterations, 1e-6);
    dem_set_mc_stress_convention(s, o->mcs_conv);
    if (o->mc_reach > 1)
        dem_set_mc_strain_reach(s, o->mc_reach);
    return s;
}

dem_config cfg_of(dem_backend_kind b, dem_precision p)
{
    dem_config c;
    dem_config_default(&c);
    c.backend = b;
    c.precision = p;
    return c;
}

const backend_case backend_cases[BACKEND_CASES] = {
    {"reference fp64", DEM_BACKEND_REFERENCE, DEM_FP64, 0x1p-53},
    {"reference fp32", DEM_BACKEND_REFERENCE, DEM_FP32, 0x1p-24},
    {"OpenCL fp64", DEM_BACKEND_OPENCL, DEM_FP64, 0x1p-53},
    {"OpenCL fp32", DEM_BACKEND_OPENCL, DEM_FP32, 0x1p-24},
};

void backend_run(const backend_case *bc, dem_sim *(*build)(void *ctx), long steps,
                 void (*check)(dem_sim *s, const backend_case *bc, void *ctx), void *ctx)
{
    dem_sim *s = build(ctx);
    dem_config c = cfg_of(bc->backend, bc->precision);
    start_or_fail(s, &c);
    if (steps)
        step_or_fail(s, steps);
    check(s, bc, ctx);
    if (bc->backend == DEM_BACKEND_OPENCL) { /* the reference, to the step the check left the case at */
        dem_sim *r = build(ctx);
        dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, bc->precision);
        start_or_fail(r, &rc);
        if (dem_step_index(s) > 0)
            step_or_fail(r, dem_step_index(s));
        char msg[512];
        if (state_diff(s, r, msg, sizeof msg))
            fail_msg("%s against the reference: %s", bc->name, msg);
        dem_destroy(r);
    }
    dem_destroy(s);
}

void packing_pair(const packing_opts *o, const dem_config *rc, const dem_config *c, long steps, dem_sim **ref,
                  dem_sim **cl)
{
    *ref = packing_build(o);
    *cl = packing_build(o);
    start_or_fail(*ref, rc);
    start_or_fail(*cl, c);
    step_or_fail(*ref, steps);
    step_or_fail(*cl, steps);
}

void start_or_fail(dem_sim *s, const dem_config *c)
{
    if (dem_start(s, c) != DEM_OK)
        fail_msg("dem_start: %s", dem_error(s));
}

void test_pocl_threads(void)
{
    const char *v = getenv("POCL_MAX_PTHREAD_COUNT");
    if (!v || atoi(v) < 2)
        setenv("POCL_MAX_PTHREAD_COUNT", "2", 1);
}

void step_or_fail(dem_sim *s, long n)
{
    if (dem_step(s, n) != DEM_OK)
        fail_msg("dem_step at step %ld: %s", dem_step_index(s), dem_error(s));
}

static void *get(dem_sim *s, dem_field f, size_t *bytes)
{
    *bytes = dem_field_bytes(s, f);
    void *p = malloc(*bytes ? *bytes : 1);
    if (!p || dem_get_raw(s, f, p, *bytes))
        fail_msg("reading field %d: %s", (int)f, dem_error(s));
    return p;
}

void restart_check(dem_sim *a, dem_sim *b, const dem_config *c, long before, long after, const char *what)
{
    start_or_fail(a, c);
    start_or_fail(b, c);
    step_or_fail(a, before);
    dem_state saved;
    if (dem_state_get(a, &saved) || dem_state_set(b, &saved))
        fail_msg("%s: %s", what, dem_error(a)[0] ? dem_error(a) : dem_error(b));
    step_or_fail(a, after);
    step_or_fail(b, after);
    char msg[512];
    if (state_diff(a, b, msg, sizeof msg))
        fail_msg("%s: the restored run differs: %s", what, msg);
    dem_state_free(&saved);
}

void skins_and_order_check(const packing_opts *o, const dem_config *c, long steps, const char *what, dem_sim **s1,
                           dem_sim **s3)
{
    dem_config c1 = *c, c2 = *c;
    c1.skin = 0.05 * o->rmax, c2.skin = 0.3 * o->rmax;
    dem_sim *a = packing_build(o), *b = packing_build(o);
    start_or_fail(a, &c1);
    start_or_fail(b, &c2);
    char name[300];
    snprintf(name, sizeof name, "%s: skins 0.05 and 0.3 x the largest radius", what);
    twins_step(a, b, steps, name);
    dem_destroy(b);
    dem_config c3 = c1; /* stored anew at every rebuild: what a pair or particle keeps moves with it (gain 1: whenever
                         * the curve's order changed, not only once it has scattered) */
    c3.reorder = 1;
    c3.reorder_gain = 1;
    dem_sim *r = packing_build(o);
    start_or_fail(r, &c3);
    step_or_fail(r, steps);
    char msg[512];
    if (state_diff(a, r, msg, sizeof msg))
        fail_msg("%s: stored anew, the run differs: %s", what, msg);
    *s1 = a, *s3 = r;
}

void packing_restart_state(const packing_opts *o, const dem_config *c, const char *what, dem_state *st)
{
    dem_sim *a = packing_build(o), *b = packing_build(o);
    restart_check(a, b, c, 300, 300, what);
    if (dem_state_get(a, st))
        fail_msg("%s: dem_state_get: %s", what, dem_error(a));
    dem_destroy(a);
    dem_destroy(b);
}

void skins_order_and_reference_check(const packing_opts *o, const dem_config *c, long steps, const char *what)
{
    dem_sim *s1, *s3;
    skins_and_order_check(o, c, steps, what, &s1, &s3);
    dem_destroy(s3);
    if (c->backend == DEM_BACKEND_OPENCL) { /* and the reference's bits, at the first run's skin */
        dem_config r = cfg_of(DEM_BACKEND_REFERENCE, c->precision);
        dem_sim *ref = packing_build(o);
        r.skin = 0.05 * o->rmax;
        start_or_fail(ref, &r);
        step_or_fail(ref, steps);
        char msg[512];
        if (state_diff(s1, ref, msg, sizeof msg))
            fail_msg("%s: the reference differs: %s", what, msg);
        dem_destroy(ref);
    }
    dem_destroy(s1);
}

void twins_step(dem_sim *a, dem_sim *b, long n, const char *what)
{
    step_or_fail(a, n);
    step_or_fail(b, n);
    char msg[512];
    if (state_diff(a, b, msg, sizeof msg))
        fail_msg("%s, step %ld: %s", what, dem_step_index(a), msg);
}

void mesh_write_obj(const dem_mesh *m, const char *path)
{
    FILE *fp = fopen(path, "w");
    if (!fp)
        fail_msg("cannot write %s", path);
    for (int i = 0; i < m->nv; i++)
        fprintf(fp, "v %.17g %.17g %.17g\n", m->x[3 * i], m->x[3 * i + 1], m->x[3 * i + 2]);
    for (int t = 0; t < m->nt; t++)
        fprintf(fp, "f %d %d %d\n", m->tri[3 * t] + 1, m->tri[3 * t + 1] + 1, m->tri[3 * t + 2] + 1);
    fclose(fp);
}

/* What state_diff compares of one run, read once: the fields below (those of a model the run has not, from
 * DEM_FIELD_STRESS_TRACE on, empty) and dem_state_get's pairs with what each keeps */
enum { SNAP_FIELDS = 12 };
static const dem_field snap_fields[SNAP_FIELDS] = {
    DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W, DEM_FIELD_FORCE, DEM_FIELD_TORQUE, DEM_FIELD_WALL_FORCE, DEM_FIELD_WALL_HIST,
    DEM_FIELD_STRESS, DEM_FIELD_STRESS_TRACE, DEM_FIELD_MC_FORCE, DEM_FIELD_MC_WALL_FORCE, DEM_FIELD_RADIUS};
static const char *snap_names[SNAP_FIELDS] = {"position", "velocity", "angular velocity", "force", "torque", "wall force",
                                               "wall history", "stress tensor", "stress trace", "MC-strain force",
                                               "MC-strain wall force", "radius"};
typedef struct {
    unsigned char *field[SNAP_FIELDS];
    size_t bytes[SNAP_FIELDS];
    int has[SNAP_FIELDS]; /* the run has the field (a multi-contact model's only under that model) */
    size_t rs;            /* bytes of a real */
    dem_state st;
} snapshot;

static void snap_take(dem_sim *s, snapshot *p)
{
    p->rs = dem_field_bytes(s, DEM_FIELD_X) / (3 * (size_t)dem_count(s));
    for (int k = 0; k < SNAP_FIELDS; k++) {
        p->has[k] = snap_fields[k] < DEM_FIELD_STRESS_TRACE || dem_field_bytes(s, snap_fields[k]) != 0;
        p->field[k] = p->has[k] ? get(s, snap_fields[k], &p->bytes[k]) : NULL;
    }
    if (dem_state_get(s, &p->st))
        fail_msg("dem_state_get: %s", dem_error(s));
}

static void snap_free(snapshot *p)
{
    for (int k = 0; k < SNAP_FIELDS; k++)
        free(p->field[k]);
    dem_state_free(&p->st);
}

/* The touching pairs of a and b in the callers' ids (dem_state_get) and what each keeps: the same pairs, the same
 * bits; with MDR also every particle's and wall slot's row (laws/mdr.h) */
static int pairs_state_diff(const dem_state *sa, const dem_state *sb, char *msg, size_t len)
{
    int bad = 0;
    size_t rs = (size_t)sa->real_size, np = (size_t)sa->npairs;
    if (sa->npairs != sb->npairs || memcmp(sa->pair_i, sb->pair_i, sizeof(int) * np) ||
        memcmp(sa->pair_j, sb->pair_j, sizeof(int) * np))
        bad = 1, snprintf(msg, len, "the touching pairs differ (%ld and %ld of them)", sa->npairs, sb->npairs);
    const struct {
        const char *what;
        void *pa, *pb;
        size_t reals;
    } kept[] = {{"tangential history", sa->has_hist ? sa->pair_hist : NULL, sb->has_hist ? sb->pair_hist : NULL, 3},
                {"MC-strain force", sa->has_mc ? sa->pair_mc_fn : NULL, sb->has_mc ? sb->pair_mc_fn : NULL, 1},
                {"contact law state", sa->pair_law, sb->pair_law, (size_t)sa->has_law},
                {"rolling spring", sa->pair_rspring, sb->pair_rspring, 3}};
    for (size_t k = 0; k < sizeof kept / sizeof kept[0] && !bad; k++) {
        /* the history in both or neither; what a model keeps of its own (MC-strain, a law, a rolling spring) only where
         * both runs have it, as the fields above */
        if (k == 0 && !kept[k].pa != !kept[k].pb)
            bad = 1, snprintf(msg, len, "one run keeps the pairs' %s and the other not", kept[k].what);
        else if (kept[k].pa && kept[k].pb && np && (k != 2 || sa->has_law == sb->has_law) &&
                 memcmp(kept[k].pa, kept[k].pb, np * kept[k].reals * rs)) {
            size_t at = 0;
            while (!memcmp((char *)kept[k].pa + at * kept[k].reals * rs, (char *)kept[k].pb + at * kept[k].reals * rs,
                           kept[k].reals * rs))
                at++;
            bad = 1, snprintf(msg, len, "%s of the pair %d-%d differs", kept[k].what, sa->pair_i[at], sa->pair_j[at]);
        }
    }
    const char *rows[] = {"mdr_particle", "wall_law"};
    for (int k = 0; k < 2 && !bad && sa->has_law == DEM_MDR_LAW_REALS && sb->has_law == DEM_MDR_LAW_REALS; k++) {
        dem_state_array *x = dem_state_find((dem_state *)sa, rows[k]), *y = dem_state_find((dem_state *)sb, rows[k]);
        bad = !x || !y || x->count != y->count || memcmp(x->data, y->data, x->count * rs);
        if (bad)
            snprintf(msg, len, "MDR's %s differs", rows[k]);
    }
    return bad;
}

static int snap_diff(const snapshot *a, const snapshot *b, char *msg, size_t len)
{
    size_t rs = a->rs;
    for (int k = 0; k < SNAP_FIELDS; k++) {
        /* fields of a model one run does not have (multi-contact) are compared only when both have them */
        if (!a->has[k] || !b->has[k])
            continue;
        const unsigned char *pa = a->field[k], *pb = b->field[k];
        size_t na = a->bytes[k], nb = b->bytes[k];
        if (na != nb || memcmp(pa, pb, na) != 0) {
            size_t at = 0;
            while (at < na && at < nb && pa[at] == pb[at])
                at++;
            size_t idx = at / rs;
            double va = rs == 8 ? ((const double *)pa)[idx] : ((const float *)pa)[idx];
            double vb = rs == 8 ? ((const double *)pb)[idx] : ((const float *)pb)[idx];
            snprintf(msg, len, "%s differs at component %zu (item %zu): %.17g vs %.17g", snap_names[k], idx, idx / 3, va,
                     vb);
            return 1;
        }
    }
    /* what every touching pair keeps (tangential history, MC-strain's force, a law's state, a rolling spring), pair by
     * pair as dem_state_get lists them: by the callers' ids, whatever the storage order and the rows */
    return pairs_state_diff(&a->st, &b->st, msg, len);
}


int state_diff_each(dem_sim *a, dem_sim *const *b, int nb, char *msg, size_t len)
{
    snapshot sa;
    snap_take(a, &sa);
    int bad = -1;
    for (int k = 0; k < nb && bad < 0; k++) {
        snapshot sb;
        snap_take(b[k], &sb);
        if (snap_diff(&sa, &sb, msg, len))
            bad = k;
        snap_free(&sb);
    }
    snap_free(&sa);
    return bad;
}

int state_diff(dem_sim *a, dem_sim *b, char *msg, size_t len) { return state_diff_each(a, &b, 1, msg, len) >= 0; }

uint64_t state_hash(dem_sim *s)
{
    static const dem_field fields[] = {DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W, DEM_FIELD_FORCE, DEM_FIELD_TORQUE, DEM_FIELD_WALL_FORCE};
    uint64_t h = 1469598103934665603ull;
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
        size_t n;
        unsigned char *p = get(s, fields[k], &n);
        for (size_t i = 0; i < n; i++)
            h = (h ^ p[i]) * 1099511628211ull;
        free(p);
    }
    return h;
}

dem_sim *pair_build(const dem_material *m, double r1, double r2, double v, double dt_frac)
{
    dem_sim *s = dem_create();
    int id = dem_add_material(s, m);
    dem_add_particle(s, (double[3]){-r1, 0, 0}, (double[3]){0.5 * v, 0, 0}, r1, id);
    dem_add_particle(s, (double[3]){r2, 0, 0}, (double[3]){-0.5 * v, 0, 0}, r2, id);
    double L = 4 * (r1 + r2);
    dem_set_domain(s, (double[3]){-L, -L, -L}, (double[3]){L, L, L});
    double es = 1 / (2 * (1 - m->poisson * m->poisson) / m->young);
    double m1 = m->density * 4.0 / 3.0 * M_PI * r1 * r1 * r1, m2 = m->density * 4.0 / 3.0 * M_PI * r2 * r2 * r2;
    double tc = dem_hertz_contact_time(m1 * m2 / (m1 + m2), r1 * r2 / (r1 + r2), es, v);
    dem_set_dt(s, tc * dt_frac);
    return s;
}

double pair_distance(dem_sim *s)
{
    double x[6];
    if (dem_get_field(s, DEM_FIELD_X, x))
        fail_msg("%s", dem_error(s));
    double d = sqrt((x[0] - x[3]) * (x[0] - x[3]) + (x[1] - x[4]) * (x[1] - x[4]) + (x[2] - x[5]) * (x[2] - x[5]));
    return d;
}

/* ---- the tests' own probe kernels (test_util.h) ---- */
#include <CL/cl.h>
#include "cl_util.h" /* cl_build_options: the library's build options */

void test_cl_open(test_cl *t, const char *src, const char *name, int rs)
{
    cl_platform_id plats[8];
    cl_uint np = 0;
    assert_int_equal(clGetPlatformIDs(8, plats, &np), CL_SUCCESS);
    const char *env = getenv("DEM_DEVICE");
    int want = env ? atoi(env) : 0, seen = 0;
    cl_device_id dev = NULL;
    for (cl_uint k = 0; k < np && !dev; k++) {
        cl_device_id ds[16];
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[k], CL_DEVICE_TYPE_ALL, 16, ds, &nd) != CL_SUCCESS)
            continue;
        for (cl_uint j = 0; j < nd && !dev; j++, seen++)
            if (seen == want)
                dev = ds[j];
    }
    if (!dev)
        fail_msg("no OpenCL device %d (DEM_DEVICE)", want);
    cl_int e;
    cl_context ctx = clCreateContext(NULL, 1, &dev, NULL, NULL, &e);
    assert_int_equal(e, CL_SUCCESS);
    cl_command_queue q = clCreateCommandQueue(ctx, dev, 0, &e);
    assert_int_equal(e, CL_SUCCESS);
    cl_program prog = clCreateProgramWithSource(ctx, 1, &src, NULL, &e);
    char opts[4096];
    /* the library's own options: without correctly rounded fp32 divide and sqrt NVIDIA's OpenCL gives other fp32
     * bits than the reference */
    assert_true(cl_build_options(opts, sizeof opts, DEM_DEFAULT_SOURCE_DIR, rs) > 0);
    if (clBuildProgram(prog, 1, &dev, opts, NULL, NULL) != CL_SUCCESS) {
        static char log[16384];
        clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, sizeof log, log, NULL);
        fail_msg("the probe kernel %s does not build as OpenCL C: %s", name, log);
    }
    cl_kernel k = clCreateKernel(prog, name, &e);
    assert_int_equal(e, CL_SUCCESS);
    t->ctx = ctx, t->queue = q, t->program = prog, t->kernel = k;
}

void *test_cl_buffer(test_cl *t, size_t bytes, const void *host)
{
    cl_int e;
    cl_mem b = clCreateBuffer((cl_context)t->ctx, CL_MEM_READ_WRITE | (host ? CL_MEM_COPY_HOST_PTR : 0), bytes,
                              (void *)host, &e);
    assert_int_equal(e, CL_SUCCESS);
    return b;
}

void test_cl_close(test_cl *t)
{
    clReleaseKernel((cl_kernel)t->kernel), clReleaseProgram((cl_program)t->program);
    clReleaseCommandQueue((cl_command_queue)t->queue), clReleaseContext((cl_context)t->ctx);
}

/* The correctly rounded sum of x[0..n) in double, by Shewchuk's exact partials (the algorithm of Python's math.fsum,
 * written here from its description, apart from common/exact_sum.h): the partials are non-overlapping doubles whose
 * sum is exact; the result rounds their sum once, with the half-way correction for the partial below. */
double fsum_ref(const double *x, long n)
{
    double p[256];
    int np = 0;
    for (long k = 0; k < n; k++) {
        double v = x[k];
        int j = 0;
        for (int q = 0; q < np; q++) {
            double y = p[q];
            if (fabs(v) < fabs(y)) {
                double t = v;
                v = y, y = t;
            }
            double hi = v + y, lo = y - (hi - v);
            if (lo != 0)
                p[j++] = lo;
            v = hi;
        }
        assert_true(j < 256);
        p[j++] = v;
        np = j;
    }
    double hi = 0, lo = 0;
    if (np > 0) {
        hi = p[--np];
        while (np > 0) {
            double v = hi, y = p[--np];
            hi = v + y;
            lo = y - (hi - v);
            if (lo != 0)
                break;
        }
        if (np > 0 && ((lo < 0 && p[np - 1] < 0) || (lo > 0 && p[np - 1] > 0))) {
            double y = lo * 2, v = hi + y;
            if (y == v - hi)
                hi = v;
        }
    }
    return hi;
}
