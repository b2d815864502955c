/* mpi_util.h - what the MPI layer's tests share (tests/test_mpi_*.c, run by tests/mpi_check.sh): this rank and the
 * rank count, a verdict agreed by all ranks, and main's MPI frame around cmocka. */
#ifndef DEM_TEST_MPI_UTIL_H
#define DEM_TEST_MPI_UTIL_H
#include "test_util.h"
#include "dem_mpi.h"
#include <stdio.h>

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
