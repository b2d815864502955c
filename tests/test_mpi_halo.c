/* test_mpi_halo.c - a run split by space over the ranks (tests/mpi_check.sh: 1, 2 and 3), each rank holding its slab's
 * particles and a halo of ghosts kept equal to their owners after each step (host/mpi/dem_mpi.h): after 600 steps
 * every particle's position, velocity, spin, force and torque, on the rank that owns it, has the bits of the same
 * particle in the whole scene run in one process; and the force each wall receives, summed exactly over each rank's
 * own particles and merged across the ranks, has the whole run's bits. The scene: 855 polydisperse spheres
 * (Hertz-Mindlin with friction, damping, gravity) released with random velocities in a box of six walls whose lid
 * comes down; the slabs cut across x, so contacts and their tangential histories cross the cuts. The halo is fixed
 * (no migration yet): the test checks that no particle moved by half its margin (every 50 steps), else its premise would not hold.
 * Reference and PoCL, fp64 and fp32. Every check is agreed by all ranks before it is asserted. */
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

static void make_particles(void)
{
    unsigned long long z = 12345;
    int k = 0;
    for (int layer = 0; layer < 2; layer++) {
        int m = SIDE - layer;
        for (int i = 0; i < m * m * m; i++, k++) {
            double off = layer ? 1.0 : 0.5;
            px[k][0] = (i % m + off) * 2 * RMAX, px[k][1] = ((i / m) % m + off) * 2 * RMAX;
            px[k][2] = (i / (m * m) + off) * 2 * RMAX;
            for (int d = 0; d < 4; d++) {
                z = z * 6364136223846793005ull + 1442695040888963407ull;
                double u = (double)(z >> 11) / 9007199254740992.0;
                if (d < 3)
                    pv[k][d] = 0.2 * (2 * u - 1);
                else
                    pr[k] = RMAX * (layer ? 0.45 + 0.05 * u : 0.9 + 0.1 * u);
            }
        }
    }
}

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
        fail_msg("%s", dem_error(s));
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
        start_or_fail(whole, &c);
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
        start_or_fail(part, &c);
        dem_mpi_halo h;
        assert_int_equal(dem_mpi_halo_init(&h, MPI_COMM_WORLD, part, n, gid, owner), 0);
        static double fw[3 * NTOT], fp[3 * NTOT];
        double moved = 0; /* the largest distance of a particle from where it started, every 50 steps */
        for (long t = 0; t < steps; t += 50) {
            step_or_fail(whole, 50);
            assert_int_equal(dem_get_field(whole, DEM_FIELD_X, fw), 0);
            for (int k = 0; k < NTOT; k++)
                for (int d = 0; d < 3; d++)
                    moved = fmax(moved, fabs(fw[3 * k + d] - px[k][d]));
        }
        for (long t = 0; t < steps; t++) {
            step_or_fail(part, 1);
            assert_int_equal(dem_mpi_halo_exchange(&h), 0);
        }
        /* own particles against the whole run, field by field */
        static const dem_field fields[] = {DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W, DEM_FIELD_FORCE, DEM_FIELD_TORQUE};
        int ok = 1, own = 0;
        for (int f = 0; f < 5; f++) {
            assert_int_equal(dem_get_field(whole, fields[f], fw), 0);
            assert_int_equal(dem_get_field(part, fields[f], fp), 0);
            for (int i = 0; i < n; i++)
                if (owner[i] == rank) {
                    ok &= !memcmp(fw + 3 * gid[i], fp + 3 * i, sizeof(double) * 3);
                    own += f == 0;
                }
        }
        /* touching pairs across the cut: one own particle, one ghost */
        dem_contact *cs;
        long count, npairs, across = 0;
        assert_int_equal(dem_contacts_get(part, &cs, &count, &npairs), 0);
        for (long k = 0; k < npairs; k++)
            across += (owner[cs[k].i] == rank) != (owner[cs[k].j] == rank);
        free(cs);
        /* the walls: each rank's own particles' kept wall forces, exactly; merged; rounded once */
        int nw = dem_wall_count(part);
        static double pf[3 * 6 * NTOT];
        static unsigned mask[NTOT];
        assert_int_equal(dem_get_field(part, DEM_FIELD_WALL_PF, pf), 0);
        assert_int_equal(dem_get_raw(part, DEM_FIELD_WALL_MASK, mask, sizeof(unsigned) * (size_t)n), 0);
        exact_acc a[3 * 6];
        for (int q = 0; q < 3 * nw; q++)
            exact_clear(&a[q]);
        for (int w = 0; w < nw; w++)
            for (int i = 0; i < n; i++)
                if (owner[i] == rank && ((mask[i] >> w) & 1u))
                    for (int d = 0; d < 3; d++)
                        exact_add_double(&a[3 * w + d], -pf[3 * ((size_t)w * n + i) + d]);
        assert_int_equal(dem_mpi_exact_allreduce(MPI_COMM_WORLD, a, 3 * nw), MPI_SUCCESS);
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

MPI_TEST_MAIN(cmocka_unit_test(test_split_run))
