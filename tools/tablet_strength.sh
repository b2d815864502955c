#!/usr/bin/env bash
# make tablet-strength: scenes/tablet_strength.yaml pressed to each of several pressures, ejected and broken across a
# diameter; then tensile strength against relative density, beside published MCC tablets and a Ryshkewitch-Duckworth
# fit (tools/plot_tablet_strength.py: strength.png and strength.md).
#
#   STRENGTH_PRESSURES  compaction pressures in MPa (default "25 50 100"; at 100 MPa the plastic law is already past
#                       its range, the spheres overlapping beyond the bore: docs/tableting.md)
#   STRENGTH_OUT        where the runs go (default out/tablet_strength): P.h5, P.log for each pressure P
#   STRENGTH_SCENE      the scene (default scenes/tablet_strength.yaml; its upper punch's until_stress is replaced)
#   DEM                 the dem binary (default build/dem)
#   STRENGTH_MODEL      a law to run instead of the scene's (passed as dem run --model; e.g. mdr, with
#                       STRENGTH_OUT=out/tablet_strength_mdr)
# About 5-6 minutes per pressure on 2 cores. A run that fails is reported and left out of the figure.
set -uo pipefail
cd "$(dirname "$0")/.."
SCENE=${STRENGTH_SCENE:-scenes/tablet_strength.yaml}
OUT=${STRENGTH_OUT:-out/tablet_strength}
PRESSURES=${STRENGTH_PRESSURES:-25 50 100}
DEM=${DEM:-build/dem}
[ -x "$DEM" ] || { echo "tablet-strength: $DEM is missing: run make first" >&2; exit 1; }
# the Python that draws (scripts/find_python.sh: $PYTHON, else python3 on PATH or /usr/bin/python3), found before
# the runs so that a machine without one learns it at once
PY=$(scripts/find_python.sh h5py numpy matplotlib) || exit 1
grep -q "until_stress: 5.0e7" "$SCENE" || { echo "tablet-strength: $SCENE has no 'until_stress: 5.0e7' to replace" >&2; exit 1; }
mkdir -p "$OUT"
runs=()
for p in $PRESSURES; do
  sed "s/until_stress: 5.0e7/until_stress: ${p}.0e6/" "$SCENE" > "$OUT/$p.yaml"
  echo "tablet-strength: $p MPa -> $OUT/$p.h5 (log $OUT/$p.log)" >&2
  if "$DEM" run "$OUT/$p.yaml" -o "$OUT/$p.h5" ${STRENGTH_MODEL:+--model "$STRENGTH_MODEL"} --quiet > "$OUT/$p.log" 2>&1; then
    runs+=("$OUT/$p.h5")
  else
    echo "tablet-strength: $p MPa failed (exit $?; $OUT/$p.log)" >&2
  fi
done
[ ${#runs[@]} -gt 0 ] || { echo "tablet-strength: no run finished" >&2; exit 1; }
PYTHONPATH=python "$PY" tools/plot_tablet_strength.py "$OUT" "${runs[@]}"
