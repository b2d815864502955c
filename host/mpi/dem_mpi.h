/* dem_mpi.h - libdem's MPI layer, in its own archive (build/libdem_mpi.a): a program that never calls it links
 * without MPI, and libdem.a is the same with or without it (docs/design.md "Runs over MPI").
 *
 * What it holds so far: the exact sums (common/exact_sum.h) merged across the ranks of a communicator, the one
 * operation the run's global sums need whatever the decomposition - each rank sums its own particles' terms exactly
 * (the walls' forces: sim_wall_sums_exact; the energies), the accumulators are merged, and every rank rounds the
 * same integer to the same bits. The decomposed run itself (subdomains, ghosts, migration) is not here yet. */
#ifndef DEM_MPI_H
#define DEM_MPI_H
#include <mpi.h>
#include "exact_sum.h"

/* acc[0..count) replaced on every rank of comm by the merge of all ranks' acc[0..count): exact, so the result does
 * not depend on the number of ranks, their order or the reduction tree MPI chooses (the operation is commutative
 * and associative: integer addition, and an OR of the flags). The accumulators travel as bytes: the ranks must share
 * the byte order (every machine a run of ours meets: x86-64 and AArch64, little-endian). Returns MPI's error code
 * (MPI_SUCCESS: 0). Collective: every rank of comm calls it with the same count. */
int dem_mpi_exact_allreduce(MPI_Comm comm, exact_acc *acc, int count);
#endif /* DEM_MPI_H */
