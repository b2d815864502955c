/* mpi_util.h - what the MPI layer's tests share (tests/test_mpi_*.c, run by tests/mpi_check.sh): this rank and the
 * rank count, a verdict agreed by all ranks, and main's MPI frame around cmocka. */
#ifndef DEM_TEST_MPI_UTIL_H
#define DEM_TEST_MPI_UTIL_H
#include "test_util.h"
#include "mpi_layer.h"
#include <stdio.h>
#include <string.h>

static int rank, size;

/* 1 when ok holds on every rank: a check agreed before it is asserted, so that one rank's failure fails them all
 * instead of leaving the others waiting in a collective */
static int all_ok(int ok)
{
    int all = 0;
    assert_int_equal(MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), MPI_SUCCESS);
    return all;
}

/* A failure of this rank's own call (not a verdict all ranks agreed on): ends every rank at once with its message
 * (MPI_Abort: mpirun then exits non-zero), since the other ranks may be waiting in a collective this one would never
 * reach */
static void rank_fails(const char *file, int line, const char *what, const char *msg)
{
    fprintf(stderr, "rank %d of %d: %s:%d: %s failed%s%s\n", rank, size, file, line, what, msg ? ": " : "",
            msg ? msg : "");
    fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
}
#define REQUIRE(cond) ((cond) ? (void)0 : rank_fails(__FILE__, __LINE__, #cond, NULL))
#define REQUIRE0(call) ((call) == 0 ? (void)0 : rank_fails(__FILE__, __LINE__, #call, NULL))
/* a library call on run s: its message too */
#define REQUIRE_SIM(s, call) ((call) == 0 ? (void)0 : rank_fails(__FILE__, __LINE__, #call, dem_error(s)))

/* whether two states hold the same particles, arrays, walls' places and contacts, bit for bit (an empty array's
 * data pointer aside); the name of an array that differs said by rank 0 */
static inline int states_equal(const dem_state *a, const dem_state *b)
{
    size_t rs = (size_t)a->real_size;
    int ok = a->n == b->n && a->narrays == b->narrays && a->npairs == b->npairs && a->step == b->step &&
             a->rebuilds == b->rebuilds && a->real_size == b->real_size && a->has_hist == b->has_hist &&
             a->has_mc == b->has_mc && a->has_law == b->has_law && a->has_rspring == b->has_rspring && a->nwalls == b->nwalls &&
             !memcmp(a->wall_pos, b->wall_pos, sizeof a->wall_pos);
    for (int k = 0; ok && k < a->narrays; k++) {
        const dem_state_array *x = &a->arrays[k], *y = &b->arrays[k];
        size_t es = x->elem == DEM_STATE_REAL ? rs : sizeof(int);
        ok = !strcmp(x->name, y->name) && x->count == y->count && /* (an empty one's data: either) */
             (!x->count || (x->data && y->data && !memcmp(x->data, y->data, x->count * es)));
        if (!ok && rank == 0)
            fprintf(stderr, "array %s differs\n", x->name);
    }
    size_t m = (size_t)a->npairs;
    ok = ok && (!m || (!memcmp(a->pair_i, b->pair_i, m * sizeof(int)) && !memcmp(a->pair_j, b->pair_j, m * sizeof(int))));
    const void *pa[6] = {a->pair_hist, a->pair_rec, a->pair_mc_fn, a->pair_mc_disp, a->pair_law, a->pair_rspring};
    const void *pb[6] = {b->pair_hist, b->pair_rec, b->pair_mc_fn, b->pair_mc_disp, b->pair_law, b->pair_rspring};
    size_t w[6] = {3, DEM_PAIR_RECORD_REALS, 1, 2, (size_t)a->has_law, a->has_rspring ? 3 : 0};
    for (int q = 0; ok && m && q < 6; q++)
        ok = !pa[q] == !pb[q] && (!pa[q] || !w[q] || !memcmp(pa[q], pb[q], m * w[q] * rs));
    return ok;
}

/* Polydisperse spheres on two interleaved lattices: large ones (radius 0.9-1 rmax) on side^3 points 2 rmax apart,
 * small ones (0.45-0.5 rmax) in the (side-1)^3 centres, each with a random velocity of up to vmax per component;
 * the numbers from a fixed seed (the same on every rank). x, v, r: side^3 + (side-1)^3 of them. */
static inline void mixed_lattice(int side, double rmax, double vmax, unsigned long long z, double (*x)[3],
                                 double (*v)[3], double *r)
{
    int k = 0;
    for (int layer = 0; layer < 2; layer++) {
        int m = side - layer;
        for (int i = 0; i < m * m * m; i++, k++) {
            double off = layer ? 1.0 : 0.5;
            x[k][0] = (i % m + off) * 2 * rmax, x[k][1] = ((i / m) % m + off) * 2 * rmax;
            x[k][2] = (i / (m * m) + off) * 2 * rmax;
            for (int d = 0; d < 4; d++) {
                z = z * 6364136223846793005ull + 1442695040888963407ull;
                double u = (double)(z >> 11) / 9007199254740992.0;
                if (d < 3)
                    v[k][d] = vmax * (2 * u - 1);
                else
                    r[k] = rmax * (layer ? 0.45 + 0.05 * u : 0.9 + 0.1 * u);
            }
        }
    }
}

/* MPI_Init, the group of tests on every rank, MPI_Finalize; the number of tests that failed on this rank */
#define MPI_TEST_MAIN(...)                                                                                              \
    int main(int argc, char **argv)                                                                                     \
    {                                                                                                                   \
        MPI_Init(&argc, &argv);                                                                                         \
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);                                                                           \
        MPI_Comm_size(MPI_COMM_WORLD, &size);                                                                           \
        const struct CMUnitTest tests[] = {__VA_ARGS__};                                                                \
        int failed = cmocka_run_group_tests(tests, NULL, NULL);                                                         \
        MPI_Finalize();                                                                                                 \
        return failed;                                                                                                  \
    }
#endif
