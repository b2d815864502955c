/* exact_allreduce.c - exact accumulators merged across MPI ranks (mpi_layer.h) */
#include "mpi_layer.h"
#include <limits.h>

/* MPI's user operation: each accumulator of in merged into inout's, exactly */
static void merge_op(void *in, void *inout, int *len, MPI_Datatype *type)
{
    (void)type;
    const exact_acc *a = in;
    exact_acc *b = inout;
    for (int k = 0; k < *len; k++)
        exact_merge(&b[k], &a[k]);
}

int dem_mpi_exact_allreduce(MPI_Comm comm, exact_acc *acc, int count)
{
    MPI_Datatype t;
    MPI_Op op;
    int e = MPI_Type_contiguous((int)sizeof(exact_acc), MPI_BYTE, &t);
    if (e != MPI_SUCCESS)
        return e;
    if ((e = MPI_Type_commit(&t)) == MPI_SUCCESS && (e = MPI_Op_create(merge_op, 1, &op)) == MPI_SUCCESS) {
        e = MPI_Allreduce(MPI_IN_PLACE, acc, count, t, op, comm);
        MPI_Op_free(&op);
    }
    MPI_Type_free(&t);
    return e;
}

int dem_mpi_agreed_who(MPI_Comm comm, int e, int *who)
{
    /* one MPI_MINLOC over (code, rank), a 0 counted as the largest int: the lowest failing code and the lowest rank
     * that had it */
    int rank;
    MPI_Comm_rank(comm, &rank);
    struct {
        int code, rank;
    } in = {e ? e : INT_MAX, rank}, out = in;
    MPI_Allreduce(&in, &out, 1, MPI_2INT, MPI_MINLOC, comm);
    if (who)
        *who = out.code != INT_MAX ? out.rank : -1;
    return out.code != INT_MAX ? out.code : 0;
}

int dem_mpi_agreed(MPI_Comm comm, int e)
{
    /* a dem_status is negative, MPI's codes positive: an MPI failure counts as the device's (DEM_ERR_DEVICE) */
    return dem_mpi_agreed_who(comm, e > 0 ? DEM_ERR_DEVICE : e, NULL);
}
