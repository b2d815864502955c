/* mpi_util.h - what the MPI layer's tests share (tests/test_mpi_*.c, run by tests/mpi_check.sh): this rank and the
 * rank count, a verdict agreed by all ranks, and main's MPI frame around cmocka. */
#ifndef DEM_TEST_MPI_UTIL_H
#define DEM_TEST_MPI_UTIL_H
#include "test_util.h"
#include "dem_mpi.h"

static int rank, size;

/* 1 when ok holds on every rank: a check agreed before it is asserted, so that one rank's failure fails them all
 * instead of leaving the others waiting in a collective */
static int all_ok(int ok)
{
    int all = 0;
    assert_int_equal(MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), MPI_SUCCESS);
    return all;
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
