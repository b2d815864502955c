/* test_particle_order.c - where the particles are stored does not change a run's bits.
 *
 * Every sum follows the particles' stable ids (their ids at dem_start: common/neighbor.h), not the places they are
 * stored at, so a run whose particles are stored anew along a Morton curve at its rebuilds (dem_config.reorder) is
 * bit for bit the run that never moves them. Checked on the polydisperse frictional packing of test_util (lattice
 * order, which the Morton order moves almost entirely) under every contact model, in fp32 and fp64, on the
 * reference and on PoCL: after 300 steps with a moving lid (several rebuilds) each particle's position, velocity,
 * spin, force and torque, each wall's force, the energies, a sampled series, the contact network and the saved
 * contact memory are the same bits, particle by particle. And a saved state is the same whether or when the run was
 * reordered, and continues bit for bit in a run stored either way. A membrane's run (springs, pressure, hinges, patches
 * touched by grains, riders on walls, a held velocity: tables that name particles by stable id) is reordered like any
 * other, with the same bits. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STEPS 300

typedef struct {
    const char *name;
    unsigned mc;
    double beta, gamma;
    int iterations;
    int contacts; /* dem_config.contacts: the wall forces kept per particle (the other wall-sum path) */
} model;

static const model models[] = {
    {"classical", 0, 0, 0, 0, 0},
    {"classical, contact network", 0, 0, 0, 0, 1},
    {"MC-stress", DEM_EFFECT_MC_STRESS, 1.65, 0, 0, 0},
    {"MC-strain lagged", DEM_EFFECT_MC_STRAIN, 0, 1.12, 0, 0},
    {"MC-strain iterated", DEM_EFFECT_MC_STRAIN, 0, 1.12, 8, 1},
};

static packing_opts opts_of(const model *m)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 6; /* 216 + 125 = 341 spheres */
    o.lid_speed = 2.0;
    o.speed = 0.3;
    o.effects = DEM_EFFECT_CLASSICAL | m->mc;
    o.mc_beta = m->beta;
    o.mc_gamma = m->gamma;
    o.mc_iterations = m->iterations;
    return o;
}

/* a per-particle field of both runs, particle by particle (by the ids of dem_start, however b is stored) */
static void same_field(dem_sim *a, dem_sim *b, dem_field f, int width, const char *what, const char *where)
{
    int n = dem_count(a);
    double *fa = malloc(sizeof(double) * (size_t)(width * n)), *fb = malloc(sizeof(double) * (size_t)(width * n));
    assert_non_null(fa);
    assert_non_null(fb);
    assert_int_equal(dem_get_field(a, f, fa), 0);
    assert_int_equal(dem_get_field(b, f, fb), 0);
    for (int i = 0; i < n; i++)
        if (memcmp(fb + width * i, fa + width * i, sizeof(double) * (size_t)width))
            fail_msg("%s: %s of particle %d: %.17g against %.17g", where, what, i, fa[width * i], fb[width * i]);
    free(fa), free(fb);
}

/* Every particle's position, velocity, spin, force and torque, and the force on each of the first nwalls walls, the
 * same bits in a and b */
static void same_motion(dem_sim *a, dem_sim *b, int nwalls, const char *where)
{
    same_field(a, b, DEM_FIELD_X, 3, "position", where);
    same_field(a, b, DEM_FIELD_V, 3, "velocity", where);
    same_field(a, b, DEM_FIELD_W, 3, "spin", where);
    same_field(a, b, DEM_FIELD_FORCE, 3, "force", where);
    same_field(a, b, DEM_FIELD_TORQUE, 3, "torque", where);
    double fa[3], fb[3];
    for (int k = 0; k < nwalls; k++) {
        assert_int_equal(dem_wall_force(a, k, fa), 0);
        assert_int_equal(dem_wall_force(b, k, fb), 0);
        if (memcmp(fa, fb, sizeof fa))
            fail_msg("%s: the force on wall %d: %.17g against %.17g", where, k, fa[2], fb[2]);
    }
}

typedef struct {
    int a, b; /* ids, a < b */
    const unsigned char *hist, *fn;
} saved_pair;

static int by_places(const void *p, const void *q)
{
    const saved_pair *x = p, *y = q;
    return x->a != y->a ? (x->a > y->a) - (x->a < y->a) : (x->b > y->b) - (x->b < y->b);
}

/* the saved contacts (dem_state_get) as sets of pairs with their memory */
static void same_saved_contacts(dem_sim *a, dem_sim *b, const char *where)
{
    dem_state sa, sb;
    assert_int_equal(dem_state_get(a, &sa), 0);
    assert_int_equal(dem_state_get(b, &sb), 0);
    assert_int_equal(sa.npairs, sb.npairs);
    assert_true(sa.npairs > 100);
    long np = sa.npairs;
    int rs = sa.real_size;
    saved_pair *pa = calloc((size_t)np, sizeof *pa), *pb = calloc((size_t)np, sizeof *pb);
    assert_non_null(pa);
    assert_non_null(pb);
    for (long p = 0; p < np; p++) {
        pa[p] = (saved_pair){sa.pair_i[p], sa.pair_j[p], (unsigned char *)sa.pair_hist + 3 * rs * p,
                             sa.has_mc ? (unsigned char *)sa.pair_mc_fn + rs * p : NULL};
        int i = sb.pair_i[p], j = sb.pair_j[p];
        assert_true(i < j); /* saved by its owner, the lower id */
        pb[p] = (saved_pair){i, j, (unsigned char *)sb.pair_hist + 3 * rs * p,
                             sb.has_mc ? (unsigned char *)sb.pair_mc_fn + rs * p : NULL};
    }
    qsort(pb, (size_t)np, sizeof *pb, by_places); /* a's are in its row order: ascending i, then j */
    for (long p = 0; p < np; p++) {
        if (pa[p].a != pb[p].a || pa[p].b != pb[p].b)
            fail_msg("%s: saved contact %ld: %d-%d against %d-%d", where, p, pa[p].a, pa[p].b, pb[p].a, pb[p].b);
        if (memcmp(pa[p].hist, pb[p].hist, 3 * (size_t)rs) || (pa[p].fn && memcmp(pa[p].fn, pb[p].fn, (size_t)rs)))
            fail_msg("%s: the memory of contact %d-%d differs", where, pa[p].a, pa[p].b);
    }
    free(pa), free(pb);
    dem_state_free(&sa), dem_state_free(&sb);
}

static void *raw(dem_sim *s, dem_field f, size_t *bytes)
{
    *bytes = dem_field_bytes(s, f);
    void *p = malloc(*bytes ? *bytes : 1);
    assert_non_null(p);
    assert_int_equal(dem_get_raw(s, f, p, *bytes), 0);
    return p;
}

/* the neighbour rows as the callers read them (dem_get_raw: packed from NBR_START, partners by id, MC-strain's force
 * per slot), the same in both runs */
static void same_rows(dem_sim *a, dem_sim *b, const char *where)
{
    int n = dem_count(a);
    size_t bytes[2][4];
    static const dem_field f[4] = {DEM_FIELD_NBR_COUNT, DEM_FIELD_NBR_START, DEM_FIELD_NBR_LIST, DEM_FIELD_MC_FORCE};
    void *v[2][4];
    for (int r = 0; r < 2; r++)
        for (int k = 0; k < 4; k++)
            v[r][k] = raw(r ? b : a, f[k], &bytes[r][k]);
    const int *start = v[0][1];
    if (memcmp(v[0][0], v[1][0], sizeof(int) * (size_t)n) || memcmp(v[0][1], v[1][1], sizeof(int) * ((size_t)n + 1)))
        fail_msg("%s: the rows' counts or starts differ", where);
    assert_true(start[n] > 2 * n && sizeof(int) * (size_t)start[n] <= bytes[0][2]);
    if (memcmp(v[0][2], v[1][2], sizeof(int) * (size_t)start[n]))
        fail_msg("%s: the rows' partners differ", where);
    size_t rs = dem_field_bytes(a, DEM_FIELD_X) / (3 * (size_t)n);
    if (bytes[0][3] && memcmp(v[0][3], v[1][3], rs * (size_t)start[n]))
        fail_msg("%s: MC-strain's forces per row slot differ", where);
    for (int r = 0; r < 2; r++)
        for (int k = 0; k < 4; k++)
            free(v[r][k]);
}

static int by_contact(const void *p, const void *q)
{
    const dem_contact *x = p, *y = q;
    return x->i != y->i ? (x->i > y->i) - (x->i < y->i) : (x->j > y->j) - (x->j < y->j);
}

/* the contact network of both runs, as sets */
static void same_network(dem_sim *a, dem_sim *b, const char *where)
{
    dem_contact *ca, *cb;
    long na, nb, pa, pb;
    assert_int_equal(dem_contacts_get(a, &ca, &na, &pa), 0);
    assert_int_equal(dem_contacts_get(b, &cb, &nb, &pb), 0);
    assert_int_equal(na, nb);
    assert_int_equal(pa, pb);
    assert_true(pa > 100 && na > pa);
    for (long k = 0; k < nb; k++)
        assert_true(cb[k].j < 0 || cb[k].i < cb[k].j);
    qsort(cb, (size_t)pb, sizeof *cb, by_contact);
    qsort(cb + pb, (size_t)(nb - pb), sizeof *cb, by_contact);
    qsort(ca + pa, (size_t)(na - pa), sizeof *ca, by_contact);
    for (long k = 0; k < na; k++)
        if (memcmp(&ca[k], &cb[k], sizeof *ca))
            fail_msg("%s: contact %ld (%d-%d) differs", where, k, ca[k].i, ca[k].j);
    free(ca), free(cb);
}

/* How run b is stored against run a: both sorted before the start or not (dem_sort_particles: ids renumbered, and
 * so the sums' order), b stored anew at every `reorder`-th rebuild (dem_config.reorder: ids kept) */
typedef struct {
    const char *name;
    int sort, reorder;
} storage;
static const storage storages[] = {{"stored anew at every rebuild", 0, 1},
                                   {"both sorted at load, stored anew at every 3rd rebuild", 1, 3}};

static void one_case(const backend_case *bc, const model *m, const storage *st)
{
    char where[300];
    snprintf(where, sizeof where, "%s, %s, %s", bc->name, m->name, st->name);
    packing_opts o = opts_of(m);
    dem_sim *a = packing_build(&o), *b = packing_build(&o);
    if (st->sort) {
        assert_int_equal(dem_sort_particles(a), 0);
        assert_int_equal(dem_sort_particles(b), 0);
    }
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.contacts = m->contacts;
    start_or_fail(a, &c);
    c.reorder = st->reorder;
    c.reorder_gain = 1; /* whenever the order changes: as often as possible */
    start_or_fail(b, &c);
    step_or_fail(a, STEPS);
    step_or_fail(b, STEPS);
    /* a sampled stretch: the series' sums over particles and over the walls' blocks */
    enum { ROWS = 4 };
    unsigned char want[ROWS] = {1, 0, 1, 1};
    dem_sample ra[ROWS], rb[ROWS];
    assert_int_equal(dem_step_sampled(a, ROWS, want, ra), 0);
    assert_int_equal(dem_step_sampled(b, ROWS, want, rb), 0);
    same_motion(a, b, 6, where);
    for (int r = 0; r < 3; r++) /* the sampled rows */
        if (memcmp(&ra[r].energy, &rb[r].energy, sizeof ra[r].energy) ||
            memcmp(ra[r].wall_force, rb[r].wall_force, sizeof ra[r].wall_force))
            fail_msg("%s: sampled row %d differs (kinetic energy %.17g against %.17g)", where, r, ra[r].energy.kinetic,
                     rb[r].energy.kinetic);
    dem_energy_t ea, eb;
    assert_int_equal(dem_energy(a, &ea), 0);
    assert_int_equal(dem_energy(b, &eb), 0);
    assert_true(ea.contacts > 100);
    if (memcmp(&ea, &eb, sizeof ea))
        fail_msg("%s: energies differ (elastic %.17g against %.17g)", where, ea.elastic, eb.elastic);
    same_saved_contacts(a, b, where);
    same_rows(a, b, where);
    assert_true(dem_rebuild_count(a) > 3);
    if (dem_rebuild_count(a) != dem_rebuild_count(b))
        fail_msg("%s: %ld rebuilds against %ld", where, dem_rebuild_count(a), dem_rebuild_count(b));
    if (st->reorder) { /* at every reorder-th rebuild, the first at the start, when the order changed */
        long due = (dem_rebuild_count(b) + st->reorder - 1) / st->reorder, done = dem_reorder_count(b);
        if (!(done > 1 && done <= due))
            fail_msg("%s: stored anew %ld times at %ld rebuilds", where, done, dem_rebuild_count(b));
    }
    assert_int_equal(dem_reorder_count(a), 0);
    if (m->contacts)
        same_network(a, b, where);
    dem_destroy(a);
    dem_destroy(b);
}

static void test_storage_order_keeps_bits(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++)
        for (size_t q = 0; q < sizeof storages / sizeof storages[0]; q++)
            one_case(bc, &models[k], &storages[q]);
}

/* plain started with c as it is, anew with c stored anew whenever the order changes (c keeps that), both stepped */
static void start_twins(dem_sim *plain, dem_sim *anew, dem_config *c, long steps)
{
    start_or_fail(plain, c);
    c->reorder = 1;
    c->reorder_gain = 1;
    start_or_fail(anew, c);
    step_or_fail(plain, steps);
    step_or_fail(anew, steps);
}

/* The saved state of a run stored anew is the saved state of the run that was not, byte for byte (particles by their
 * ids, contacts in the same order), and it continues bit for bit in a run stored either way. */
static void same_state_bytes(const dem_state *x, const dem_state *y, const char *where)
{
    assert_int_equal(x->npairs, y->npairs);
    assert_int_equal(x->narrays, y->narrays);
    assert_non_null(dem_state_find(x, "x")); /* x, v, w, force, torque, the walls' forces and memory, ... */
    for (int k = 0; k < x->narrays; k++) {
        const dem_state_array *a = &x->arrays[k], *b = &y->arrays[k];
        size_t bytes = a->count * (a->elem == DEM_STATE_REAL ? (size_t)x->real_size : sizeof(int));
        if (strcmp(a->name, b->name) || a->count != b->count || memcmp(a->data, b->data, bytes))
            fail_msg("%s: the saved particles' %s differ", where, a->name);
    }
    if (memcmp(x->pair_i, y->pair_i, sizeof(int) * (size_t)x->npairs) ||
        memcmp(x->pair_j, y->pair_j, sizeof(int) * (size_t)x->npairs) ||
        memcmp(x->pair_hist, y->pair_hist, 3 * (size_t)x->real_size * (size_t)x->npairs))
        fail_msg("%s: the saved contacts differ", where);
}

static void test_saved_state(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        packing_opts o = opts_of(&models[0]);
        dem_sim *plain = packing_build(&o), *anew = packing_build(&o);
        dem_config c = cfg_of(bc->backend, bc->precision);
        start_twins(plain, anew, &c, STEPS / 2);
        dem_state sp, sa;
        assert_int_equal(dem_state_get(plain, &sp), 0);
        assert_int_equal(dem_state_get(anew, &sa), 0);
        assert_true(dem_reorder_count(anew) > 1);
        same_state_bytes(&sp, &sa, bc->name);
        /* the saved state of the reordered run, continued in a run stored in id order and in one stored anew */
        for (int reorder = 0; reorder <= 2; reorder += 2) {
            dem_sim *r = packing_build(&o);
            c.reorder = reorder;
            start_or_fail(r, &c);
            assert_int_equal(dem_state_set(r, &sa), 0);
            step_or_fail(r, STEPS / 2);
            if (reorder == 0) {
                step_or_fail(plain, STEPS / 2);
                step_or_fail(anew, STEPS / 2);
            }
            char where[200];
            snprintf(where, sizeof where, "%s, restored into a run with reorder %d", bc->name, reorder);
            same_field(plain, r, DEM_FIELD_X, 3, "position", where);
            same_field(plain, r, DEM_FIELD_V, 3, "velocity", where);
            same_field(anew, r, DEM_FIELD_FORCE, 3, "force", where);
            dem_destroy(r);
        }
        /* a state that does not fit (a contact between particles far apart in its positions, found only after the
         * rows of those positions are built) changes nothing: the run goes on as its twin. (Were only
         * the positions put back, the contacts the saved positions' rows did not list would lose their memory.) */
        double *x = dem_state_find(&sa, "x")->data, *y = x + 3;
        int far = -1, rs = sa.real_size;
        for (int j = 1; rs == 8 && j < sa.n && far < 0; j++, y += 3)
            if ((y[0] - x[0]) * (y[0] - x[0]) + (y[1] - x[1]) * (y[1] - x[1]) + (y[2] - x[2]) * (y[2] - x[2]) > 4e-6)
                far = j;
        if (rs == 8) {
            assert_true(far > 0);
            sa.pair_i[0] = 0, sa.pair_j[0] = far;
            assert_int_equal(dem_state_set(anew, &sa), DEM_ERR_ARG);
            assert_non_null(strstr(dem_error(anew), "is not a neighbour pair of the saved positions"));
            step_or_fail(plain, STEPS / 3);
            step_or_fail(anew, STEPS / 3);
            same_field(plain, anew, DEM_FIELD_X, 3, "position", "after a refused state");
            same_field(plain, anew, DEM_FIELD_W, 3, "spin", "after a refused state");
        }
        dem_state_free(&sp), dem_state_free(&sa);
        dem_destroy(plain), dem_destroy(anew);
    }
}

/* ---- a membrane: the tables that name particles (springs, triangles, hinges, patches, riders) by stable id ---- */
#define TUBE_DT 2e-6
#define TUBE_STEPS 400
#define GRAIN_R 0.0025

/* A patched tube membrane (seed 001's rubber: springs, hinges, patches) between two plane walls its end rings ride on,
 * the top wall moving down, a pressure on its triangles, and grains inside it: an outer ring of each layer thrown
 * outwards onto the patches, an inner ring, one of them held in z; the layers thrown onto each other in pairs. Its vertices come first, the grains after them:
 * the Morton order interleaves them at the first rebuild. */
static dem_sim *tube_build(void)
{
    dem_sim *s = dem_create();
    dem_mesh m;
    char err[256];
    dem_mesh_spec sp = {DEM_MESH_TUBE, {0, 0, 0.05}, 0.02, 0.06, 0.006};
    if (dem_mesh_make(&sp, &m, err, sizeof err))
        fail_msg("%s", err);
    dem_membrane rubber = {1.25e6, 1.0 / 3, 3e-4, 1000, 0.5, 1.2, 0.3, 1e-4, 1e-6, 0.001, DEM_MEMBRANE_PATCH};
    dem_membrane_info info;
    if (dem_add_membrane(s, &m, &rubber, &info))
        fail_msg("%s", dem_error(s));
    assert_true(info.nsprings > 0 && info.ntriangles > 0 && info.nhinges > 0);
    int steel = dem_add_material(s, &(dem_material){7800, INFINITY, 0.3, 0.5, 0.3});
    int glass = dem_add_material(s, &(dem_material){2500, 5e6, 0.3, 0.5, 0.5, 0, 0});
    dem_wall lo = {DEM_WALL_PLANE, steel, {0, 0, 0.02}, {0, 0, 1}, 0, 0, {{0}}};
    dem_wall hi = {DEM_WALL_PLANE, steel, {0, 0, 0.08}, {0, 0, -1}, 0, 1, {{1.0, {0, 0, -0.5}}}};
    int wl = dem_add_wall(s, &lo), wh = dem_add_wall(s, &hi);
    for (int i = 0; i < m.nv; i++) {
        double z = m.x[3 * i + 2];
        if (fabs(z - 0.02) < 1e-12 || fabs(z - 0.08) < 1e-12)
            assert_int_equal(dem_attach_to_wall(s, i, z < 0.05 ? wl : wh), 0);
    }
    dem_mesh_free(&m);
    for (int layer = 0; layer < 9; layer++) {
        double z = 0.028 + 0.0055 * layer;
        for (int ring = 0; ring < 2; ring++) {
            double rr = ring ? 0.0105 : 0.0172, speed = ring ? 0.2 : 1.0;
            int count = ring ? 11 : 19;
            for (int k = 0; k < count; k++) {
                double a = 2 * M_PI * k / count, c = cos(a), sn = sin(a);
                double x[3] = {rr * c, rr * sn, z}, v[3] = {speed * c, speed * sn, layer % 2 ? -0.6 : 0.6};
                int id = dem_add_particle(s, x, v, GRAIN_R, glass);
                assert_true(id >= 0);
                if (layer == 4 && ring == 1 && k == 0)
                    assert_int_equal(dem_set_particle_flags(s, id, DEM_PARTICLE_HOLD_VZ), 0);
            }
        }
    }
    assert_int_equal(dem_set_pressure(s, 2000), 0);
    dem_set_domain(s, (double[3]){-0.05, -0.05, 0}, (double[3]){0.05, 0.05, 0.1});
    dem_set_dt(s, TUBE_DT);
    return s;
}

/* the touching patch contacts and the wall forces of two runs' saved states, by the particles' ids */
static void same_patch_contacts(dem_sim *a, dem_sim *b, const char *where)
{
    dem_state sa, sb;
    assert_int_equal(dem_state_get(a, &sa), 0);
    assert_int_equal(dem_state_get(b, &sb), 0);
    if (sa.npatch != sb.npatch || sa.npatch < 10)
        fail_msg("%s: %ld saved patch contacts against %ld", where, sa.npatch, sb.npatch);
    size_t ni = sizeof(int) * (size_t)sa.npatch;
    if (memcmp(sa.patch_i, sb.patch_i, ni) || memcmp(sa.patch_t, sb.patch_t, ni) ||
        memcmp(sa.patch_side, sb.patch_side, ni) ||
        memcmp(sa.patch_hist, sb.patch_hist, 3 * (size_t)sa.real_size * (size_t)sa.npatch))
        fail_msg("%s: the saved patch contacts differ", where);
    same_state_bytes(&sa, &sb, where);
    dem_state_free(&sa), dem_state_free(&sb);
}

/* The membrane's run stored anew at every rebuild is the run never stored anew, bit for bit: every particle's state,
 * the walls' forces, the energies (springs' and patches' included) and the saved patch contacts. */
static void test_membrane_reordered(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        dem_sim *a = tube_build(), *b = tube_build();
        dem_config c = cfg_of(bc->backend, bc->precision);
        c.skin = 0.2 * GRAIN_R; /* rebuilds every few tens of steps: reorders among them */
        start_twins(a, b, &c, TUBE_STEPS);
        char where[200];
        snprintf(where, sizeof where, "%s, a membrane", bc->name);
        same_motion(a, b, 2, where);
        dem_energy_t ea, eb;
        assert_int_equal(dem_energy(a, &ea), 0);
        assert_int_equal(dem_energy(b, &eb), 0);
        if (memcmp(&ea, &eb, sizeof ea))
            fail_msg("%s: energies differ (elastic %.17g against %.17g)", where, ea.elastic, eb.elastic);
        same_patch_contacts(a, b, where);
        dem_time_scales ta, tb; /* the springs' and hinges' periods: their tables by id, the host's arrays stored */
        assert_int_equal(dem_time_scales_get(a, 0, &ta), 0);
        assert_int_equal(dem_time_scales_get(b, 0, &tb), 0);
        if (memcmp(&ta.spring_period, &tb.spring_period, sizeof(double)) ||
            memcmp(&ta.hinge_period, &tb.hinge_period, sizeof(double)))
            fail_msg("%s: spring period %.17g against %.17g, hinge period %.17g against %.17g", where,
                     ta.spring_period, tb.spring_period, ta.hinge_period, tb.hinge_period);
        if (dem_rebuild_count(a) != dem_rebuild_count(b))
            fail_msg("%s: %ld rebuilds against %ld", where, dem_rebuild_count(a), dem_rebuild_count(b));
        printf("  %s: %ld rebuilds, stored anew %ld times, %ld patch contacts, %ld contacts\n", where,
               dem_rebuild_count(b), dem_reorder_count(b), eb.patch_contacts, eb.contacts);
        assert_true(dem_reorder_count(b) > 2);
        assert_int_equal(dem_reorder_count(a), 0);
        assert_true(eb.patch_contacts > 10 && eb.contacts > 10);
        dem_destroy(a), dem_destroy(b);
    }
}

/* A negative reorder or reorder_gain is refused by dem_start. */
static void test_bad_reorder(void **st)
{
    (void)st;
    packing_opts o = opts_of(&models[0]);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    dem_sim *bad = packing_build(&o);
    c.reorder = -1;
    assert_int_equal(dem_start(bad, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(bad), "reorder must be >= 0 rebuilds (got -1)"));
    dem_destroy(bad);
    bad = packing_build(&o);
    c.reorder = 1;
    c.reorder_gain = -2;
    assert_int_equal(dem_start(bad, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(bad), "reorder_gain must be >= 0 (got -2)"));
    dem_destroy(bad);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_storage_order_keeps_bits),
                                       cmocka_unit_test(test_saved_state), cmocka_unit_test(test_membrane_reordered),
                                       cmocka_unit_test(test_bad_reorder)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
