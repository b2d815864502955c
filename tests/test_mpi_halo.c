/* test_mpi_halo.c - a run split by space over the ranks (tests/mpi_check.sh: 1, 2 and 3), each rank holding its slab's
 * particles and a halo of ghosts kept equal to their owners after each step (host/mpi/mpi_layer.h): after 600 steps
 * every particle's position, velocity, spin, force and torque, on the rank that owns it, has the bits of the same
 * particle in the whole scene run in one process; and the force each wall receives, summed exactly over each rank's
 * own particles and merged across the ranks, has the whole run's bits. The scene: 855 polydisperse spheres
 * (Hertz-Mindlin with friction, damping, gravity) released with random velocities in a box of six walls whose lid
 * comes down; the slabs cut across x, so contacts and their tangential histories cross the cuts. The halo is fixed
 * here: the test checks that no particle moved by half its margin (every 50 steps), else its premise would not hold;
 * test_split_anew splits the run anew twice, particles and contacts migrating (moved from each rank's state,
 * dem_mpi_state_move, against the whole state cut, from every rank and from rank 0 alone holding it; the last part
 * a copy of an unstarted whole run, sim_part_copy);
 * test_refusals, what the halo refuses.
 * Reference and PoCL, fp64 and fp32. Every verdict is agreed by all ranks before it is asserted; a rank's own failing
 * call ends all ranks (tests/mpi_util.h). */
#include "mpi_util.h"
#include "sim.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#define SIDE 8 /* large spheres on SIDE^3 lattice points, small ones in the (SIDE-1)^3 centres */
#define NTOT (SIDE * SIDE * SIDE + (SIDE - 1) * (SIDE - 1) * (SIDE - 1))
#define RMAX 0.001
#define L (SIDE * 2 * RMAX)
static double px[NTOT][3], pv[NTOT][3], pr[NTOT];

static void make_particles(void) { mixed_lattice(SIDE, RMAX, 0.2, 12345, px, pv, pr); }

/* the scene with the particles k where keep[k] (NULL: all), in ascending k; dt given (0: the recommended one) */
static dem_sim *build(const unsigned char *keep, double *dt)
{
    dem_sim *s = dem_create();
    int mat = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.5});
    int wmat = dem_add_material(s, &(dem_material){7800, 2e8, 0.3, 0.5, 0.5});
    for (int k = 0; k < NTOT; k++)
        if (!keep || keep[k])
            dem_add_particle(s, px[k], pv[k], pr[k], mat);
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, wmat);
    dem_stage lid = {0.01, {0, 0, -0.2}};
    dem_set_wall_motion(s, 5, 1, &lid);
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    dem_set_domain(s, (double[3]){-0.5 * L, -0.5 * L, -0.5 * L}, (double[3]){1.5 * L, 1.5 * L, 1.5 * L});
    if (dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION | DEM_EFFECT_GRAVITY |
                               DEM_EFFECT_WALLS))
        rank_fails(__FILE__, __LINE__, "dem_set_effects", dem_error(s));
    if (*dt == 0) {
        dem_time_scales ts;
        dem_time_scales_get(s, 0, &ts);
        *dt = ts.recommended_dt;
    }
    dem_set_dt(s, *dt);
    return s;
}

static void test_split_run(void **st)
{
    (void)st;
    make_particles();
    const double margin = 3 * RMAX, layer = 2 * RMAX + margin; /* the halo: what can touch within the margin */
    const long steps = 600;
    FOR_EACH_BACKEND(bc)
    {
        dem_config c = cfg_of(bc->backend, bc->precision);
        c.contacts = 1; /* each particle's wall forces kept (the walls' sums over own particles) */
        double dt = 0;
        dem_sim *whole = build(NULL, &dt);
        REQUIRE_SIM(whole, dem_start(whole, &c));
        /* slabs across x by the starting positions; the halo of this rank's slab */
        static unsigned char keep[NTOT];
        static int owner_of[NTOT];
        long gid[NTOT];
        int owner[NTOT], n = 0;
        double lo = L * rank / size, hi = L * (rank + 1) / size;
        for (int k = 0; k < NTOT; k++) {
            int q = (int)(px[k][0] / L * size);
            owner_of[k] = q < 0 ? 0 : q >= size ? size - 1 : q;
            keep[k] = owner_of[k] == rank || (px[k][0] > lo - layer && px[k][0] < hi + layer);
            if (keep[k])
                gid[n] = k, owner[n++] = owner_of[k];
        }
        dem_sim *part = build(keep, &dt);
        REQUIRE_SIM(part, dem_start(part, &c));
        dem_mpi_halo h;
        REQUIRE0(dem_mpi_halo_init(&h, MPI_COMM_WORLD, part, n, gid, owner));
        static double fw[3 * NTOT], fp[3 * NTOT];
        double moved = 0; /* the largest distance of a particle from where it started, every 50 steps */
        for (long t = 0; t < steps; t += 50) {
            REQUIRE_SIM(whole, dem_step(whole, 50));
            REQUIRE0(dem_get_field(whole, DEM_FIELD_X, fw));
            for (int k = 0; k < NTOT; k++)
                for (int d = 0; d < 3; d++)
                    moved = fmax(moved, fabs(fw[3 * k + d] - px[k][d]));
        }
        for (long t = 0; t < steps; t++) {
            REQUIRE_SIM(part, dem_step(part, 1));
            REQUIRE0(dem_mpi_halo_exchange(&h));
        }
        /* own particles against the whole run, field by field */
        static const dem_field fields[] = {DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W, DEM_FIELD_FORCE, DEM_FIELD_TORQUE};
        int ok = 1, own = 0;
        for (int f = 0; f < 5; f++) {
            REQUIRE0(dem_get_field(whole, fields[f], fw));
            REQUIRE0(dem_get_field(part, fields[f], fp));
            for (int i = 0; i < n; i++)
                if (owner[i] == rank) {
                    ok &= !memcmp(fw + 3 * gid[i], fp + 3 * i, sizeof(double) * 3);
                    own += f == 0;
                }
        }
        /* touching pairs across the cut: one own particle, one ghost */
        dem_contact *cs;
        long count, npairs, across = 0;
        REQUIRE0(dem_contacts_get(part, &cs, &count, &npairs));
        for (long k = 0; k < npairs; k++)
            across += (owner[cs[k].i] == rank) != (owner[cs[k].j] == rank);
        free(cs);
        /* the walls: each rank's own particles' kept wall forces, exactly; merged; rounded once */
        int nw = dem_wall_count(part);
        static double pf[3 * 6 * NTOT];
        static unsigned mask[NTOT];
        REQUIRE0(dem_get_field(part, DEM_FIELD_WALL_PF, pf));
        REQUIRE0(dem_get_raw(part, DEM_FIELD_WALL_MASK, mask, sizeof(unsigned) * (size_t)n));
        exact_acc a[3 * 6];
        for (int q = 0; q < 3 * nw; q++)
            exact_clear(&a[q]);
        for (int w = 0; w < nw; w++)
            for (int i = 0; i < n; i++)
                if (owner[i] == rank && ((mask[i] >> w) & 1u))
                    for (int d = 0; d < 3; d++)
                        exact_add_double(&a[3 * w + d], -pf[3 * ((size_t)w * n + i) + d]);
        REQUIRE0(dem_mpi_exact_allreduce(MPI_COMM_WORLD, a, 3 * nw));
        int wall_ok = 1;
        for (int w = 0; w < nw; w++) {
            double f[3];
            dem_wall_force(whole, w, f);
            for (int d = 0; d < 3; d++) {
                double g = bc->precision == DEM_FP64 ? exact_to_double(&a[3 * w + d]) : (double)exact_to_float(&a[3 * w + d]);
                wall_ok &= !memcmp(&g, &f[d], sizeof g);
            }
        }
        int own_all = 0;
        long across_all = 0;
        MPI_Allreduce(&own, &own_all, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        MPI_Allreduce(&across, &across_all, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
        if (rank == 0)
            printf("  %s, %d ranks: %d particles owned in all (of %d), %ld own-ghost contacts, largest move %.3g of "
                   "the margin's half %.3g m; particles %s, walls %s\n",
                   bc->name, size, own_all, NTOT, across_all, moved, margin / 2, ok ? "equal" : "DIFFER",
                   wall_ok ? "equal" : "DIFFER");
        assert_true(all_ok(moved < margin / 2 && own_all == NTOT));
        assert_true(all_ok(size == 1 || across_all > 0));
        assert_true(all_ok(ok));
        assert_true(all_ok(wall_ok));
        dem_mpi_halo_free(&h);
        dem_destroy(whole);
        dem_destroy(part);
    }
}

/* The particles of ranks' runs split anew twice (migration): 3 phases of 300 steps, the slabs cut across x, then
 * across y, then across x half a slab further on, by the positions at each split. At a split the whole state is
 * gathered from the ranks' own particles (dem_mpi_state_gather), cut to each rank's new particles and halo
 * (dem_mpi_state_part) and set into a new run of them (dem_state_set): particles, their per-particle and per-wall
 * arrays and their contacts' histories move between ranks. After the 900 steps every own particle has the whole
 * run's bits, and the gathered state has the whole run's state's: every per-particle and per-wall array and every
 * contact with its history and force record (the walls' sums aside: rank 0's). The reference in fp64 and PoCL in fp32. */

/* the slabs of a phase of test_split_anew: who keeps what (dem_mpi_state_move's question) */
typedef struct {
    const double (*pos)[3];
    int axis;
    double shift, layer;
} slabs;
static int slab_of(const slabs *sl, long k)
{
    int q = (int)floor((sl->pos[k][sl->axis] - sl->shift) / L * size);
    return q < 0 ? 0 : q >= size ? size - 1 : q;
}
static int slab_keeps(void *arg, long k, int r)
{
    const slabs *sl = arg;
    double lo = L * r / size + sl->shift, hi = L * (r + 1) / size + sl->shift, v = sl->pos[k][sl->axis];
    return slab_of(sl, k) == r || (v > lo - sl->layer && v < hi + sl->layer);
}

static void test_split_anew(void **st)
{
    (void)st;
    make_particles();
    const double margin = 3 * RMAX, layer = 2 * RMAX + margin;
    const long phase_steps = 300;
    FOR_EACH_BACKEND(bc)
    {
        /* two of the four cases (the state's travel is the host's, the same for every backend; test_split_run runs
         * all four): make test's time */
        if ((bc->backend == DEM_BACKEND_REFERENCE) != (bc->precision == DEM_FP64))
            continue;
        dem_config c = cfg_of(bc->backend, bc->precision);
        double dt = 0;
        dem_sim *whole = build(NULL, &dt), *part = NULL, *tmpl = build(NULL, &dt);
        REQUIRE_SIM(whole, dem_start(whole, &c));
        static double pos[NTOT][3], xw[3 * NTOT];
        memcpy(pos, px, sizeof pos);
        static unsigned char keep[NTOT];
        static long gid[NTOT];
        static int owner[NTOT];
        int n = 0, moved_ok = 1;
        long migrated = 0;
        dem_mpi_halo h = {0};
        dem_state g = {0};
        for (int phase = 0; phase < 3; phase++) {
            int axis = phase == 1 ? 1 : 0;
            double shift = phase == 2 ? 0.5 * L / size : 0, lo = L * rank / size + shift, hi = L * (rank + 1) / size + shift;
            int prev_owner[NTOT];
            for (int k = 0; k < NTOT; k++)
                prev_owner[k] = -1;
            for (int i = 0; i < n; i++)
                prev_owner[gid[i]] = owner[i];
            static long prev_gid[NTOT];
            static int prev_own[NTOT];
            memcpy(prev_gid, gid, sizeof prev_gid), memcpy(prev_own, owner, sizeof prev_own);
            slabs sl = {(const double(*)[3])pos, axis, shift, layer};
            int prev_n = n;
            n = 0;
            for (int k = 0; k < NTOT; k++) {
                int q = slab_of(&sl, k);
                keep[k] = q == rank || (pos[k][axis] > lo - layer && pos[k][axis] < hi + layer);
                assert_int_equal(keep[k], slab_keeps(&sl, k, rank));
                if (keep[k]) {
                    migrated += q == rank && phase > 0 && prev_owner[k] != rank;
                    gid[n] = k, owner[n++] = q;
                }
            }
            /* the last part copied from an unstarted whole run of the scene (what a split anew of dem run does:
             * sim_part_copy), the others built with their particles alone */
            char why[256];
            dem_sim *next = phase == 2 ? sim_part_copy(tmpl, keep, why, sizeof why) : build(keep, &dt);
            if (!next)
                rank_fails(__FILE__, __LINE__, "sim_part_copy", why);
            REQUIRE_SIM(next, dem_start(next, &c));
            if (phase > 0) { /* the whole state, cut to this rank's particles */
                dem_state ps, pm, loc;
                REQUIRE0(dem_mpi_state_part(next, &g, keep, &ps));
                /* the same part moved from each rank's own state, no rank holding the whole: bit for bit */
                REQUIRE_SIM(part, dem_state_get(part, &loc));
                assert_int_equal(loc.n, prev_n);
                REQUIRE0(dem_mpi_state_move(MPI_COMM_WORLD, next, &loc, prev_gid, prev_own, slab_keeps, &sl, n, gid,
                                            &pm));
                int same = states_equal(&pm, &ps);
                if (rank == 0)
                    printf("  %s, %d ranks, split %d: the part moved from the ranks' own states (%d particles, %ld "
                           "contacts) %s the part cut from the whole\n", bc->name, size, phase, pm.n, pm.npairs,
                           same ? "equals" : "DIFFERS from");
                assert_true(all_ok(same && pm.npairs > 0));
                /* and moved from rank 0 alone holding the whole state, the others none (dem run's start) */
                static long ident[NTOT];
                static int all0[NTOT];
                for (int k = 0; k < NTOT; k++)
                    ident[k] = k, all0[k] = 0;
                dem_state p0;
                REQUIRE0(dem_mpi_state_move(MPI_COMM_WORLD, next, rank == 0 ? &g : NULL, ident, all0, slab_keeps, &sl,
                                            n, gid, &p0));
                int same0 = states_equal(&p0, &ps);
                if (rank == 0)
                    printf("  %s, %d ranks, split %d: moved from rank 0's whole state, the part %s the part cut\n",
                           bc->name, size, phase, same0 ? "equals" : "DIFFERS from");
                assert_true(all_ok(same0));
                dem_state_free(&p0);
                REQUIRE_SIM(next, dem_state_set(next, &pm));
                dem_state_free(&ps), dem_state_free(&pm), dem_state_free(&loc), dem_state_free(&g);
                dem_mpi_halo_free(&h);
                dem_destroy(part);
            }
            part = next;
            REQUIRE0(dem_mpi_halo_init(&h, MPI_COMM_WORLD, part, n, gid, owner));
            for (long t = 0; t < phase_steps; t++) {
                REQUIRE_SIM(part, dem_step(part, 1));
                REQUIRE0(dem_mpi_halo_exchange(&h));
            }
            for (long t = 0; t < phase_steps; t += 50) { /* the whole run; no particle may move half the margin */
                REQUIRE_SIM(whole, dem_step(whole, 50));
                REQUIRE0(dem_get_field(whole, DEM_FIELD_X, xw));
                for (int k = 0; k < NTOT; k++)
                    for (int d = 0; d < 3; d++)
                        moved_ok &= fabs(xw[3 * k + d] - pos[k][d]) < margin / 2;
            }
            REQUIRE0(dem_mpi_state_gather(&h, gid, owner, NTOT, &g));
            { /* the gather on rank 0 alone: its copy the same, the others hold no arrays or contacts */
                dem_state g0;
                REQUIRE0(dem_mpi_state_gather_at(&h, gid, owner, NTOT, 0, &g0));
                int same = rank == 0 ? states_equal(&g0, &g) : g0.narrays == 0 && g0.npairs == 0 && g0.n == NTOT;
                assert_true(all_ok(same));
                dem_state_free(&g0);
            }
            { /* the same state on rank 0 slab by slab of 97 ids (a checkpoint's, app/run_mpi.c): each slab's arrays
                 * the whole's rows of its particles, its contacts the whole's whose lower id is in it, in order */
                dem_state loc, sl;
                REQUIRE_SIM(part, dem_state_get(part, &loc));
                long pairs = 0;
                int same = 1;
                size_t rs = (size_t)g.real_size;
                for (long a = 0; a < NTOT; a += 97) {
                    long b = a + 97 < NTOT ? a + 97 : NTOT, m = b - a;
                    REQUIRE0(dem_mpi_state_slab(&h, gid, owner, NTOT, &loc, a, b, 0, &sl));
                    same &= rank != 0 || (sl.n == m && sl.narrays == g.narrays);
                    for (int k = 0; rank == 0 && same && k < g.narrays; k++) {
                        const dem_state_array *ga = &g.arrays[k], *sa = &sl.arrays[k];
                        int per, kind = sim_state_array_layout(part, ga->name, &per);
                        size_t es = ga->elem == DEM_STATE_REAL ? rs : sizeof(int), row = (size_t)per * es;
                        size_t groups = per ? ga->count / ((size_t)NTOT * per) : 0;
                        if (kind == DEM_MOVE_STAY || !ga->count)
                            continue;
                        for (size_t q = 0; same && q < groups; q++) /* one group (DEM_MOVE_P), one per wall (G) */
                            same = sa->count == groups * (size_t)m * per &&
                                   !memcmp((char *)sa->data + q * (size_t)m * row,
                                           (char *)ga->data + (q * NTOT + (size_t)a) * row, (size_t)m * row);
                    }
                    for (long p = 0; rank == 0 && same && p < sl.npairs; p++, pairs++)
                        same = pairs < g.npairs && sl.pair_i[p] == g.pair_i[pairs] && sl.pair_j[p] == g.pair_j[pairs] &&
                               sl.pair_i[p] >= a && sl.pair_i[p] < b &&
                               !memcmp((char *)sl.pair_hist + p * 3 * rs, (char *)g.pair_hist + pairs * 3 * rs, 3 * rs);
                    same &= rank == 0 || (sl.narrays == 0 && sl.npairs == 0);
                    dem_state_free(&sl);
                }
                same &= rank != 0 || pairs == g.npairs;
                if (rank == 0)
                    printf("  %s, %d ranks: the state gathered in slabs of 97 ids (%ld contacts) %s the whole gather\n",
                           bc->name, size, pairs, same ? "equals" : "DIFFERS from");
                assert_true(all_ok(same));
                dem_state_free(&loc);
            }
            const dem_state_array *x = dem_state_find(&g, "x");
            for (int k = 0; k < NTOT; k++) /* the positions the next split cuts by */
                for (int d = 0; d < 3; d++)
                    pos[k][d] = bc->precision == DEM_FP64 ? ((double *)x->data)[3 * k + d]
                                                          : ((float *)x->data)[3 * k + d];
        }
        /* the gathered state against the whole run's */
        dem_state ws;
        REQUIRE0(dem_state_get(whole, &ws));
        int ok = ws.npairs == g.npairs && ws.narrays == g.narrays && ws.step == g.step, arrays = 0;
        size_t rs = (size_t)g.real_size;
        for (int a = 0; ok && a < ws.narrays; a++) {
            const dem_state_array *wa = &ws.arrays[a], *ga = dem_state_find(&g, wa->name);
            int per;
            if (sim_state_array_layout(whole, wa->name, &per) == DEM_MOVE_STAY)
                continue;
            size_t es = wa->elem == DEM_STATE_REAL ? rs : sizeof(int);
            ok &= ga && ga->count == wa->count && (!wa->count || !memcmp(ga->data, wa->data, wa->count * es));
            arrays++;
        }
        for (long p = 0; ok && p < ws.npairs; p++)
            ok &= ws.pair_i[p] == g.pair_i[p] && ws.pair_j[p] == g.pair_j[p] &&
                  !memcmp((char *)ws.pair_hist + p * 3 * rs, (char *)g.pair_hist + p * 3 * rs, 3 * rs) &&
                  !memcmp((char *)ws.pair_rec + p * DEM_PAIR_RECORD_REALS * rs,
                          (char *)g.pair_rec + p * DEM_PAIR_RECORD_REALS * rs, DEM_PAIR_RECORD_REALS * rs);
        long migrated_all = 0;
        MPI_Allreduce(&migrated, &migrated_all, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
        if (rank == 0)
            printf("  %s, %d ranks: %ld particles changed rank at the two splits; after %ld steps the gathered state "
                   "(%d arrays, %ld contacts) %s the whole run's\n",
                   bc->name, size, migrated_all, 3 * phase_steps, arrays, g.npairs, ok ? "equals" : "DIFFERS from");
        assert_true(all_ok(moved_ok));
        assert_true(all_ok(size == 1 || migrated_all > 100));
        assert_true(all_ok(ok));
        dem_state_free(&ws), dem_state_free(&g);
        dem_mpi_halo_free(&h);
        dem_destroy(part);
        dem_destroy(whole);
        dem_destroy(tmpl);
    }
}

/* What the halo takes and refuses, the same on every rank and without a hang: a run whose lid stops at a force
 * (until_force: the walls' sums merged after each step) is taken; on more than one rank, a run with a spring (a
 * membrane's, whose tables name particles by index) is refused, naming it; and a halo whose ranks disagree on an
 * owner (the last rank says one of its particles, far from rank 0's slab, belongs to rank 0, which does not hold
 * it): DEM_ERR_ARG on every rank. */
static void test_refusals(void **st)
{
    (void)st;
    make_particles();
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    static unsigned char keep[NTOT];
    static long gid[NTOT];
    static int owner[NTOT];
    const double layer = 5 * RMAX;
    int n = 0, far = -1;
    double lo = L * rank / size, hi = L * (rank + 1) / size;
    for (int k = 0; k < NTOT; k++) {
        int q = (int)(px[k][0] / L * size);
        q = q < 0 ? 0 : q >= size ? size - 1 : q;
        keep[k] = q == rank || (px[k][0] > lo - layer && px[k][0] < hi + layer);
        if (keep[k]) {
            if (q == rank && px[k][0] > L / size + layer && far < 0)
                far = n; /* an own particle no other rank holds as a ghost of rank 0's */
            gid[n] = k, owner[n++] = q;
        }
    }
    double dt = 0;
    dem_sim *s = build(keep, &dt);
    dem_stage lid = {0.01, {0, 0, -0.2}, .until_force = 1.0};
    REQUIRE0(dem_set_wall_motion(s, 5, 1, &lid));
    REQUIRE_SIM(s, dem_start(s, &c));
    dem_mpi_halo h;
    int e = dem_mpi_halo_init(&h, MPI_COMM_WORLD, s, n, gid, owner);
    if (rank == 0)
        printf("  %d ranks, a lid stopped by until_force: %d (%s)\n", size, e, e ? dem_error(s) : "taken");
    assert_true(all_ok(e == 0 && h.steer == (size > 1)));
    if (!e)
        dem_mpi_halo_free(&h);
    dem_destroy(s);
    s = build(keep, &dt);
    REQUIRE0(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION | DEM_EFFECT_GRAVITY |
                                    DEM_EFFECT_WALLS | DEM_EFFECT_SPRINGS));
    REQUIRE(dem_add_spring(s, 0, 1, 1.0, 0.01, 0) >= 0);
    REQUIRE_SIM(s, dem_start(s, &c));
    e = dem_mpi_halo_init(&h, MPI_COMM_WORLD, s, n, gid, owner);
    if (rank == 0)
        printf("  %d ranks, a spring: %d (%s)\n", size, e, e ? dem_error(s) : "taken");
    assert_true(all_ok(size == 1 ? e == 0 : e == DEM_ERR_ARG && strstr(dem_error(s), "springs") != NULL));
    if (!e)
        dem_mpi_halo_free(&h);
    dem_destroy(s);
    if (size < 2)
        return;
    s = build(keep, &dt);
    REQUIRE_SIM(s, dem_start(s, &c));
    if (rank == size - 1) {
        REQUIRE(far >= 0);
        owner[far] = 0;
    }
    e = dem_mpi_halo_init(&h, MPI_COMM_WORLD, s, n, gid, owner);
    if (rank == 0)
        printf("  %d ranks, an owner the ranks disagree on: %d\n", size, e);
    assert_true(all_ok(e == DEM_ERR_ARG));
    dem_destroy(s);
}

MPI_TEST_MAIN(cmocka_unit_test(test_split_run), cmocka_unit_test(test_split_anew), cmocka_unit_test(test_refusals))
