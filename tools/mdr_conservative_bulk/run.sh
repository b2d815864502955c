#!/bin/bash
# tools/mdr_conservative_bulk/run.sh - the "own split + potential bulk" variant of MDR's Part II (loops.py; docs/
# laws/mdr.md "A conservative bulk response, tried") in the engine: a copy of HEAD (git archive) with engine.patch
# applied (common/laws/mdr_core.h, mdr.h, mdr_particle.h, dem_kernels.h: mdr_surface sums each particle's dV and caps
# at this step's positions and leaves the pressure kappa dV / V_geo in the row's slot of the mean surface
# displacement, which the own split no longer needs; the side's force takes its gradient). Not libdem's law: its
# stability estimate does not see the bulk's coupling, its energies are the bulk's p dV / 2, and MPI and the
# checkpoints carry the row as they are. Then the held 64-sphere box of tools/mdr_energy_box at psi_b 0.7 (about 75 s),
# and with TABLET=1 the E 5 GPa, Y 60 MPa, psi_b 0.3 tablet of docs/tableting.md pressed to 100 MPa, run to 5 ms at
# dt_rayleigh DTR (default 0.05; about 1 to 2 hours on one core).
# usage: bash tools/mdr_conservative_bulk/run.sh [OUTDIR]   (default out/mdr_conservative_bulk)
set -e
cd "$(dirname "$0")/../.."
OUT=${1:-out/mdr_conservative_bulk}
mkdir -p "$OUT"
rm -rf "$OUT/copy"
mkdir -p "$OUT/copy"
git archive HEAD | tar -x -C "$OUT/copy"
patch -s -d "$OUT/copy" -p1 < tools/mdr_conservative_bulk/engine.patch ||
    { echo "mdr_conservative_bulk: engine.patch does not apply to HEAD: remake it" >&2; exit 1; }
make -s -C "$OUT/copy" build/dem > "$OUT/build.log" 2>&1 ||
    { echo "mdr_conservative_bulk: the copy did not build (see $OUT/build.log)" >&2; exit 1; }
dem=$OUT/copy/build/dem
sed -e "s/PSIB/0.7/; s/DAMP/0.2/; s/DTR/0.05/" tools/mdr_energy_box/box.yaml > "$OUT/box.yaml"
POCL_MAX_PTHREAD_COUNT=1 "$dem" run "$OUT/box.yaml" -o "$OUT/box.h5" --quiet > "$OUT/box.log" 2>&1 ||
    echo "mdr_conservative_bulk: the box stopped (see $OUT/box.log)"
/usr/bin/python3 tools/mdr_energy_box/analyse.py "$OUT/box.h5"
[ "${TABLET:-0}" = 1 ] || exit 0
sed -e 's/young: 2.87e9,/young: 5.0e9,/' -e 's/bulk_fraction: 0.5,/bulk_fraction: 0.3,/' \
    -e 's/until_stress: 5.0e7,/until_stress: 100.0e6,/' -e "s/dt_rayleigh: 0.05, duration: 0.0086/dt_rayleigh: ${DTR:-0.05}, duration: 0.0050/" \
    scenes/tablet_strength_mdr.yaml > "$OUT/tablet.yaml"
[ "$(grep -c 'young: 5.0e9,\|bulk_fraction: 0.3,\|until_stress: 100.0e6,\|duration: 0.0050}' "$OUT/tablet.yaml")" = 4 ] ||
    { echo "mdr_conservative_bulk: scenes/tablet_strength_mdr.yaml changed: update this script's sed" >&2; exit 1; }
POCL_MAX_PTHREAD_COUNT=1 "$dem" run "$OUT/tablet.yaml" -o "$OUT/tablet.h5" --quiet > "$OUT/tablet.log" 2>&1 ||
    echo "mdr_conservative_bulk: the tablet stopped (see $OUT/tablet.log)"
tail -n 2 "$OUT/tablet.log"
