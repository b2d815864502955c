#!/usr/bin/env bash
# device_check.sh - the checks a lent GPU machine is for, in one call of the device tool (the test
# suite and make bench's bed table on the GPU; tablet_1m's speed and memory), from what
# tools/device_pack.sh packed into .device/ here:
#   run(command="bash tools/device_check.sh", carry=[".device"], timeout_s=600)
#   run(command="bash tools/device_check.sh bench tablet", ...)     some stages only (a second call)
# Stages, in order: devices (the OpenCL platforms and devices seen), conform (`dem conform --device 0`: every shipped
# scene x model x precision against the reference's state hashes; at most 90 s: 24 s on PoCL with 2 cores, its
# kernels cached), tests (every test program with DEM_DEVICE=0, the GPU's index when NVIDIA's is the one ICD; sixteen
# at a time, each stopped after 170 s), bench (make bench's bed table at 1e5 and 1e6, fp64 and fp32, as poured,
# sorted and sorted in one pass (dem_config.one_pass: does joining the contact passes pay on this device?), the state
# hashes against the reference at 1e5 and one pass's against the two passes'; at most 180 s), tablet (tablet_1m, 2000 steps from its fill:
# particle-steps/s, device time per kernel and the device memory held; at most 60 s): at most 9 minutes (devices
# 20 s). Everything goes to $OUT (the device tool's folder;
# out/device here), seven files: check.log (all), conform.txt, tests.log, bench.txt, bench_bed.json, tablet.log,
# summary.txt. Each stage's programs are stopped at its limit,
# so one that hangs costs that and not the call; their output is line-buffered, so a stopped program leaves what
# it printed. DEM_CHECK_TESTS (a list or glob of test programs, e.g. "build/tests/test_neighbor") runs some tests
# only, DEM_CHECK_TABLET_STEPS the tablet's steps (2000), DEM_BENCH_BED_SIZES the bed table's rows (bench/bench.c; 23 by default: 1e5 and 1e6).
# Here, without an NVIDIA driver, it runs the same stages on whatever OpenCL device 0 is (PoCL): that is how this
# script was checked (a copy of the tree without build/, the packed build folder's path gone).
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
D=$ROOT/.device
OUT=${OUT:-$ROOT/out/device}
mkdir -p "$OUT"
STAGES=${*:-devices conform tests bench tablet}
STEPS=${DEM_CHECK_TABLET_STEPS:-2000}
LOG=$OUT/check.log
say() { echo "[$(date +%T)] $*" | tee -a "$LOG" >&2; }
[ -x "$D/build/dem" ] || { say "no $D/build/dem: run tools/device_pack.sh here and carry .device"; exit 1; }
tree=$(git rev-parse --verify -q HEAD 2>/dev/null || echo '?')
say "commit $(cat "$D/REV" 2>/dev/null) packed, tree at $tree; $(nproc) cores"

# The programs were built here with their source folder (kernels, scenes, test scenes, build/dem) compiled in as the
# path they were built at: the same path must name this tree there, and build/ the packed programs.
SRC=$(cat "$D/SOURCE_DIR")
if [ "$SRC" != "$ROOT" ] && [ ! -e "$SRC" ]; then
  mkdir -p "$(dirname "$SRC")" && ln -s "$ROOT" "$SRC"
fi
[ -e "$ROOT/build" ] || ln -s .device/build "$ROOT/build"
export LD_LIBRARY_PATH=$D/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export DEM_SOURCE_DIR=$ROOT

# NVIDIA's OpenCL driver, for the ICD loader we carry (the machine may have no /etc/OpenCL/vendors)
nv=$(find /usr/local/nvidia /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/lib -maxdepth 3 -name 'libnvidia-opencl.so*' \
  2>/dev/null | head -1)
if [ -n "$nv" ]; then
  mkdir -p /tmp/dem-icd && echo "$nv" > /tmp/dem-icd/nvidia.icd
  export OCL_ICD_VENDORS=/tmp/dem-icd
  export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$(dirname "$nv")
  say "NVIDIA OpenCL: $nv"
else
  say "no libnvidia-opencl.so found: the checks run on whatever OpenCL device the loader finds"
fi
command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm \
  --format=csv,noheader >> "$LOG" 2>&1
: > "$OUT/summary.txt"

for stage in $STAGES; do
  case $stage in
  devices)
    timeout 20 build/dem devices >> "$LOG" 2>&1
    say "devices: exit $?"
    ;;
  conform)
    DEM_DEVICE=0 timeout 90 stdbuf -oL build/dem conform --device 0 > "$OUT/conform.txt" 2>&1
    rc=$?
    say "conform: exit $rc: $(tail -1 "$OUT/conform.txt")"
    echo "conform (exit $rc): $(tail -1 "$OUT/conform.txt")" >> "$OUT/summary.txt"
    ;;
  tests)
    T=$(mktemp -d)
    start=$(date +%s)
    ls ${DEM_CHECK_TESTS:-build/tests/test_*} | grep -v '/test_mpi_' | xargs -P 16 -I{} bash -c \
      'n=$(basename {}); DEM_DEVICE=0 timeout 170 stdbuf -oL {} > '"$T"'/$n.log 2>&1; echo "$n $?" >> '"$T"'/status'
    for f in "$T"/*.log; do echo "=== $(basename "$f" .log)"; cat "$f"; done > "$OUT/tests.log"
    sort "$T/status" >> "$LOG"
    pass=$(awk '$2 == 0' "$T/status" | wc -l)
    fail=$(awk '$2 != 0 { printf "%s(%s) ", $1, $2 }' "$T/status")
    say "tests: $pass of $(wc -l < "$T/status") passed in $(( $(date +%s) - start )) s${fail:+; failed: $fail}"
    echo "tests: $pass of $(wc -l < "$T/status") passed${fail:+; failed (exit status): $fail}" >> "$OUT/summary.txt"
    rm -rf "$T"
    ;;
  bench)
    if [ -f "$D/bed.csv.gz" ]; then
      gunzip -c "$D/bed.csv.gz" > /tmp/dem-bed.csv
      DEM_DEVICE=0 DEM_BENCH_ONLY=bed DEM_BENCH_BED=/tmp/dem-bed.csv DEM_BENCH_JSON=$OUT/bench_bed.json \
        DEM_BENCH_BED_SIZES=${DEM_BENCH_BED_SIZES:-23} \
        DEM_BENCH_CONFORM=$OUT/conform.txt timeout 180 stdbuf -oL build/dem-bench > "$OUT/bench.txt" 2>&1
      rc=$?
      say "bench: exit $rc"
      echo "bench (bed table): exit $rc, bench.txt and bench_bed.json" >> "$OUT/summary.txt"
    else
      say "bench: skipped (no bed packed)"
    fi
    ;;
  tablet)
    DEM_DEVICE=0 DEM_PROFILE=1 timeout 60 build/dem run scenes/tablet_1m.yaml --stop-after "$STEPS" --progress \
      -o /tmp/dem-tablet_1m.h5 > "$OUT/tablet.log" 2>&1
    rc=$?
    say "tablet_1m, $STEPS steps: exit $rc"
    { echo "tablet_1m, $STEPS steps: exit $rc"; grep "^step " "$OUT/tablet.log" | tail -1
      grep -E "memory held|device time per step" "$OUT/tablet.log"; } >> "$OUT/summary.txt"
    ;;
  *)
    say "unknown stage $stage (devices, conform, tests, bench, tablet)"
    ;;
  esac
done
cat "$OUT/summary.txt" >&2
