# Sourced by tools/tablet_models.sh and tools/tablet_mass_scale.sh: one `dem run` timed and recorded.
#   timed_run TAG OUT NAME ARGS...  runs "$DEM" run ARGS -o OUT/NAME.h5 with its output in OUT/NAME.log, appends
#   "NAME exit-status seconds" to OUT/times.txt, adds OUT/NAME.h5 to the array `runs` when it succeeded and says so
#   (prefixed by TAG) when it failed.
timed_run() {
  local tag=$1 out=$2 name=$3 start end rc
  shift 3
  start=$(date +%s.%N)
  "$DEM" run "$@" -o "$out/$name.h5" > "$out/$name.log" 2>&1
  rc=$?
  end=$(date +%s.%N)
  echo "$name $rc $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')" >> "$out/times.txt"
  if [ "$rc" -eq 0 ]; then runs+=("$out/$name.h5"); else echo "$tag: $name failed (exit $rc): $out/$name.log" >&2; fi
}
