#!/usr/bin/env bash
# mpi_check.sh - the MPI layer's tests (build/tests/test_mpi_*: tests/test_mpi_sum.c, tests/test_mpi_halo.c,
# tests/test_mpi_api.c: dem_create_mpi through dem.h's calls) on 1, 2
# and 3 ranks of Open MPI (mpirun --oversubscribe: more ranks than this machine's cores), each run under a time limit
# so that a rank left waiting in a collective ends the check instead of hanging it; then `mpirun -np N dem run`
# against the one-process run (tests/mpi_run_check.sh). Run by make test.
set -u
cd "$(dirname "$0")/.."
bins=(build/tests/test_mpi_*)
[ -x "${bins[0]}" ] || { echo "mpi_check: no build/tests/test_mpi_* (make builds them)" >&2; exit 1; }
command -v mpirun >/dev/null || { echo "mpi_check: no mpirun (scripts/install-deps.sh installs openmpi-bin)" >&2; exit 1; }
# Open MPI refuses root unless told (CI and make test-fresh run as root); one PoCL thread per rank (the ranks share
# two cores)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 POCL_CPU_MAX_CU_COUNT=1 POCL_MAX_PTHREAD_COUNT=1
rc=0
for bin in "${bins[@]}"; do
    for np in 1 2 3; do
        echo "== $(basename "$bin"), $np rank(s)"
        timeout 600 mpirun -np "$np" --oversubscribe --bind-to none "$bin" || { echo "mpi_check: $bin on $np rank(s) failed" >&2; rc=1; }
    done
done
# a program that never calls dem_create_mpi links libdem.a alone, without MPI: the library needs none of its symbols
if nm -u build/libdem.a | grep -Eq ' (MPI_|PMPI_|ompi_)'; then
    echo "mpi_check: build/libdem.a needs MPI's symbols (only libdem_mpi.a may):" >&2
    nm -u build/libdem.a | grep -E ' (MPI_|PMPI_|ompi_)' | sort -u | head >&2
    rc=1
fi
# dem run under mpirun against the one-process run (output, checkpoints, restarts, failures, signals)
bash tests/mpi_run_check.sh || rc=1
exit $rc
