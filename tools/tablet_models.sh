#!/usr/bin/env bash
# make tablet-models: one press scene under the four contact models - classical Hertz-Mindlin,
# MC-stress, MC-strain lagged and iterated - one after the other, then their compaction curves side by side
# (tools/plot_tablet_models.py: one PNG and a Markdown table with each run's wall time).
#
#   TABLET_SCENE  the scene (default scenes/tablet_3k.yaml: 3000 spheres, minutes per model on 2 cores;
#                 scenes/tablet_100k.yaml is the 1e5-sphere press: on 2 cores 54 minutes classical, by tablet_3k's
#                 ratios about 1.5 hours lagged MC-strain and 9 iterated)
#   TABLET_OUT    where the runs go (default out/tablet_models): MODEL.h5, MODEL.log, times.txt, models.png, models.md
#   TABLET_MODELS the models (default: classical mc_stress mc_strain mc_strain_iterated)
#   DEM           the dem binary (default build/dem)
#   TABLET_ARGS   more `dem run` options for every model, e.g. "--stop-after 201300" (tablet_100k to 41 ms: the
#                 compaction, dwell and decompression; its ejection starts at 45 ms)
#   TABLET_TIME   a wall-time limit per model and sitting (`timeout`'s form: 90m, 2h): a run still going then is
#                 stopped by SIGTERM (dem run ends it cleanly: output complete, checkpoint, exit status 143), and
#                 the next `make tablet-models` with TABLET_TIME set continues it from its checkpoint into
#                 MODEL.2.h5, MODEL.3.h5, ... (MODEL.parts lists them: "file exit-status seconds"), keeping the
#                 models already done. The plot joins the parts; a run not yet done is drawn as far as it got.
#                 Without TABLET_TIME every model runs anew, whole.
# A run that fails is reported and left out of the plot; the others go on. Ctrl-C stops the run under way cleanly and
# this script with it (that part is not listed in MODEL.parts: the next call with TABLET_TIME runs it again from the
# checkpoint before it).
set -uo pipefail
cd "$(dirname "$0")/.."
SCENE=${TABLET_SCENE:-scenes/tablet_3k.yaml}
OUT=${TABLET_OUT:-out/tablet_models}
MODELS=${TABLET_MODELS:-classical mc_stress mc_strain mc_strain_iterated}
DEM=${DEM:-build/dem}
TIME=${TABLET_TIME:-}
[ -x "$DEM" ] || { echo "tablet-models: $DEM is missing: run make first" >&2; exit 1; }
# the Python that draws (scripts/find_python.sh: $PYTHON, else python3 on PATH or /usr/bin/python3), found before
# the runs so that a machine without one learns it at once
PY=$(scripts/find_python.sh h5py numpy matplotlib) || exit 1
mkdir -p "$OUT"
: > "$OUT/times.txt"
runs=()

. tools/timed_run.sh
# --foreground: timeout stays in the terminal's process group (Ctrl-C reaches dem) and signals dem alone, once
[ -n "$TIME" ] && TIMED_PREFIX=(timeout --foreground --preserve-status -s TERM "$TIME")

# one part of model $1's run into file $2 (log beside it), `dem run` arguments after; appends "file status seconds"
# to OUT/MODEL.parts
run_part() {
  local m=$1 file=$2
  shift 2
  timed_dem "${file%.h5}.log" "$@" -o "$file"
  echo "$file $TIMED_RC $TIMED_SECS" >> "$OUT/$m.parts"
}

for m in $MODELS; do
  parts="$OUT/$m.parts"
  last=$( [ -s "$parts" ] && tail -n 1 "$parts" )
  if [ -n "$TIME" ] && [ -n "$last" ]; then
    read -r file rc _ <<< "$last"
    case "$rc" in
      0) echo "tablet-models: $m is done ($parts)" >&2 ;;
      129 | 143) # stopped by SIGHUP or SIGTERM (TABLET_TIME): resumable
        k=$(wc -l < "$parts")
        echo "tablet-models: $m continues from ${file%.h5}.ckpt.h5 (log: $OUT/$m.$((k + 1)).log)" >&2
        # shellcheck disable=SC2086 # TABLET_ARGS is a list of options
        run_part "$m" "$OUT/$m.$((k + 1)).h5" --restart "${file%.h5}.ckpt.h5" ${TABLET_ARGS:-} ;;
      *) echo "tablet-models: $m failed before (exit $rc: ${file%.h5}.log); remove $OUT/$m.* to run it anew" >&2 ;;
    esac
  else
    rm -f "$parts" "$OUT/$m".[0-9]*.h5 "$OUT/$m".[0-9]*.log "$OUT/$m".[0-9]*.xmf "$OUT/$m".[0-9]*.ckpt.h5
    echo "tablet-models: $SCENE under $m (log: $OUT/$m.log)" >&2
    # shellcheck disable=SC2086 # TABLET_ARGS is a list of options
    run_part "$m" "$OUT/$m.h5" "$SCENE" --model "$m" ${TABLET_ARGS:-}
  fi
  # the run so far: its parts joined by '+', its status the last part's, its wall time theirs together
  files=$(awk '{ printf "%s%s", (NR > 1 ? "+" : ""), $1 }' "$parts")
  read -r rc secs <<< "$(awk '{ s += $3; r = $2 } END { printf "%s %.1f", r, s }' "$parts")"
  echo "$m $rc $secs" >> "$OUT/times.txt"
  case "$rc" in
    0 | 129 | 143) runs+=("$files") ;;
    *) echo "tablet-models: $m failed (exit $rc): $(tail -n 1 "$parts" | cut -d' ' -f1 | sed 's/\.h5$/.log/')" >&2 ;;
  esac
  case "$rc" in 129 | 143) echo "tablet-models: $m stopped (exit $rc) before its end; make tablet-models with \
TABLET_TIME set continues it" >&2 ;; esac
done
[ ${#runs[@]} -gt 0 ] || { echo "tablet-models: no run completed" >&2; exit 1; }
"$PY" tools/plot_tablet_models.py --times "$OUT/times.txt" -o "$OUT/models.png" --table "$OUT/models.md" \
  "${runs[@]}"
