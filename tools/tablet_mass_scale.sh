#!/usr/bin/env bash
# make tablet-mass-scale: what mass scaling (time.mass_scale, docs/scenes.md "Mass scaling") does to a
# press. One press scene under the classical law at several mass scales S, each with several random fills (the fill's
# seed), then tools/plot_tablet_mass_scale.py: the compaction curves and the press's numbers against S, with the
# spread between fills beside them (one PNG and a Markdown table with the wall times).
#
#   TABLET_SCENE  the scene (default scenes/tablet_3k.yaml: 3000 spheres, about 4 minutes per fill at S = 1 on 2 cores)
#   MASS_SCALES   the scales (default: 1 100 400 1600 6400)
#   MASS_SEEDS    the fills' seeds (default: 7 8 9)
#   MASS_OUT      where the runs go (default out/tablet_mass_scale): S<S>_seed<N>.yaml/.h5/.log, times.txt, PNG, table
#   DEM           the dem binary (default build/dem)
# Each run's scene is TABLET_SCENE with `mass_scale: S` added to its time map and the seed of its random fill set. Its
# approach stage (the punch swept through the loose fill at 1 m/s `until_force` 0.05 N) ends by distance instead,
# where the real-mass run's force criterion ended it (1.1586e-3 m in tablet_3k): a heavier powder pushes back harder
# while it is swept, so the force criterion would end the approach at once. A run that fails is reported and left
# out; the others go on.
set -uo pipefail
cd "$(dirname "$0")/.."
. tools/timed_run.sh
SCENE=${TABLET_SCENE:-scenes/tablet_3k.yaml}
OUT=${MASS_OUT:-out/tablet_mass_scale}
SCALES=${MASS_SCALES:-1 100 400 1600 6400}
SEEDS=${MASS_SEEDS:-7 8 9}
DEM=${DEM:-build/dem}
# the Python that draws (scripts/find_python.sh: $PYTHON, else python3 on PATH or /usr/bin/python3), found before
# the runs so that a machine without one learns it at once
PY=$(scripts/find_python.sh h5py numpy matplotlib) || exit 1
[ -x "$DEM" ] || { echo "tablet-mass-scale: $DEM is missing: run make first" >&2; exit 1; }
grep -q '^time: {.*}$' "$SCENE" || { echo "tablet-mass-scale: $SCENE has no one-line 'time: {...}' map" >&2; exit 1; }
mkdir -p "$OUT"
: > "$OUT/times.txt"
runs=()
for S in $SCALES; do
  for seed in $SEEDS; do
    name="S${S}_seed${seed}"
    sed -e "s/^time: {\(.*\)}$/time: {\1, mass_scale: $S}/" -e "s/seed: [0-9]*}/seed: $seed}/" \
        -e "s/until_force: 0.05}/until_distance: 1.1586e-3}/" "$SCENE" > "$OUT/$name.yaml"
    echo "tablet-mass-scale: $SCENE at mass scale $S, fill seed $seed (log: $OUT/$name.log)" >&2
    timed_run tablet-mass-scale "$OUT" "$name" "$OUT/$name.yaml"
  done
done
[ ${#runs[@]} -gt 0 ] || { echo "tablet-mass-scale: no run completed" >&2; exit 1; }
"$PY" tools/plot_tablet_mass_scale.py --times "$OUT/times.txt" -o "$OUT/mass_scale.png" \
  --table "$OUT/mass_scale.md" "${runs[@]}"
