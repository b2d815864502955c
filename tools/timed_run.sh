# Sourced by tools/tablet_models.sh and tools/tablet_mass_scale.sh: one `dem run` timed and recorded.
#   timed_dem LOG ARGS...  runs "$DEM" run ARGS (after the command in the array TIMED_PREFIX, e.g. a timeout) with its
#   output in LOG; sets TIMED_RC (its exit status) and TIMED_SECS (its wall time, 0.1 s).
#   timed_run TAG OUT NAME ARGS...  runs "$DEM" run ARGS -o OUT/NAME.h5 with its output in OUT/NAME.log, appends
#   "NAME exit-status seconds" to OUT/times.txt, adds OUT/NAME.h5 to the array `runs` when it succeeded and says so
#   (prefixed by TAG) when it failed.
TIMED_PREFIX=()
timed_dem() {
  local log=$1 start end
  shift
  start=$(date +%s.%N)
  "${TIMED_PREFIX[@]}" "$DEM" run "$@" > "$log" 2>&1
  TIMED_RC=$?
  end=$(date +%s.%N)
  TIMED_SECS=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
}
timed_run() {
  local tag=$1 out=$2 name=$3
  shift 3
  timed_dem "$out/$name.log" "$@" -o "$out/$name.h5"
  echo "$name $TIMED_RC $TIMED_SECS" >> "$out/times.txt"
  if [ "$TIMED_RC" -eq 0 ]; then runs+=("$out/$name.h5"); else echo "$tag: $name failed (exit $TIMED_RC): $out/$name.log" >&2; fi
}
