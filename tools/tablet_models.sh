#!/usr/bin/env bash
# make tablet-models (issue 12, item 5): one press scene under the four contact models - classical Hertz-Mindlin,
# MC-stress, MC-strain lagged and iterated - one after the other, then their compaction curves side by side
# (tools/plot_tablet_models.py: one PNG and a Markdown table with each run's wall time).
#
#   TABLET_SCENE  the scene (default scenes/tablet_3k.yaml: 3000 spheres, minutes per model on 2 cores;
#                 scenes/tablet_100k.yaml is the issue's: on 2 cores 54 minutes classical, by tablet_3k's
#                 ratios about 1.5 hours lagged MC-strain and 9 iterated)
#   TABLET_OUT    where the runs go (default out/tablet_models): MODEL.h5, MODEL.log, times.txt, models.png, models.md
#   TABLET_MODELS the models (default: classical mc_stress mc_strain mc_strain_iterated)
#   DEM           the dem binary (default build/dem)
#   TABLET_ARGS   more `dem run` options for every model, e.g. "--stop-after 201300" (tablet_100k to 41 ms: the
#                 compaction, dwell and decompression, the first of the ejection)
# A run that fails is reported and left out of the plot; the others go on.
set -uo pipefail
cd "$(dirname "$0")/.."
. tools/timed_run.sh
SCENE=${TABLET_SCENE:-scenes/tablet_3k.yaml}
OUT=${TABLET_OUT:-out/tablet_models}
MODELS=${TABLET_MODELS:-classical mc_stress mc_strain mc_strain_iterated}
DEM=${DEM:-build/dem}
[ -x "$DEM" ] || { echo "tablet-models: $DEM is missing: run make first" >&2; exit 1; }
mkdir -p "$OUT"
: > "$OUT/times.txt"
runs=()
for m in $MODELS; do
  echo "tablet-models: $SCENE under $m (log: $OUT/$m.log)" >&2
  # shellcheck disable=SC2086 # TABLET_ARGS is a list of options
  timed_run tablet-models "$OUT" "$m" "$SCENE" --model "$m" ${TABLET_ARGS:-}
done
[ ${#runs[@]} -gt 0 ] || { echo "tablet-models: no run completed" >&2; exit 1; }
/usr/bin/python3 tools/plot_tablet_models.py --times "$OUT/times.txt" -o "$OUT/models.png" --table "$OUT/models.md" \
  "${runs[@]}"
