#!/usr/bin/env bash
# make bench-peer: the same settled bed of 100 000 spheres, the same 2000 steps, in LIGGGHTS (Debian's
# 3.8.0, 1 and 2 MPI ranks) and in libdem (PoCL, fp64 and fp32). The floor forces after the steps must agree within
# 2 % before the timings count; then one Markdown table of particle-steps per second (also out/peer/peer.json).
#
#   1. the bed: bench/peer/bed_pour.yaml poured once (15-30 minutes on 2 cores), its checkpoint saved as out/peer/bed.csv
#      (x, y, z, radius, vx, vy, vz) and reused by every later run (delete it to pour again)
#   2. LIGGGHTS: bench/peer/in.peer on a data file and a floor STL made from bed.csv (bench/peer/peer.py)
#   3. libdem: out/peer/bed_run-{input,spatial}.yaml reading bed.csv (the particles as given, and sorted at load)
#   4. bench/peer/peer.py report: the check and the table
#
# `run.sh --bed` stops after step 1 (make bench uses the bed too).
# Environment: PEER_OUT (default out/peer), PEER_POUR (the pour scene), PEER_STEPS (default 2000): a smaller
# pour and fewer steps try the whole chain in a minute.
set -euo pipefail
cd "$(dirname "$0")/../.."

OUT=${PEER_OUT:-out/peer}
POUR=${PEER_POUR:-bench/peer/bed_pour.yaml}
STEPS=${PEER_STEPS:-2000}
DT=2.0e-6
PY=$(scripts/find_python.sh h5py numpy) || exit 1 # $PYTHON, else python3 on PATH or /usr/bin/python3 (scripts/find_python.sh)
DEM=build/dem
# the grains' material, as in bed_pour.yaml (LIGGGHTS' inputs and ours are written from these)
RHO=2500 YOUNG=5.0e6 POISSON=0.3 RESTITUTION=0.3 FRICTION=0.5
# LIGGGHTS' neighbour settings: skin half the smallest radius, binned, checked every step
SKIN=3.0e-4
DURATION=$(awk -v n="$STEPS" -v dt="$DT" 'BEGIN { printf "%.10g", n * dt }')

say() { echo "bench-peer: $*" >&2; }
die() { say "$*"; exit 1; }

[ -x "$DEM" ] || die "$DEM is missing: run make first"
mkdir -p "$OUT"
# Open MPI refuses root without both; single-copy (CMA) needs ptrace, which containers often forbid
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
now() { date +%s.%N; }

# 1. The bed, poured once.
if [ ! -s "$OUT/bed.csv" ]; then
  if [ ! -s "$OUT/pour.ckpt.h5" ]; then
    say "pouring the bed ($POUR; 15-30 minutes on 2 cores, once)"
    "$DEM" run "$POUR" -o "$OUT/pour.h5" --progress
  fi
  "$PY" tools/ckpt_to_csv.py "$OUT/pour.ckpt.h5" "$OUT/bed.csv.tmp" \
    --comment "make bench-peer's bed: $POUR poured (bench/peer/run.sh)"
  mv "$OUT/bed.csv.tmp" "$OUT/bed.csv"
fi
if [ -s "$OUT/pour.h5" ]; then "$PY" bench/peer/peer.py pour "$OUT/pour.h5" "$RHO"; fi
[ "${1:-}" = --bed ] && exit 0 # make bench wants the bed only (its table on a poured bed, bench/bench.c)
command -v liggghts >/dev/null && command -v mpirun >/dev/null || bash scripts/install-deps.sh --peer

# 2. Damping: LIGGGHTS turns e into c = 2 sqrt(5/6) |ln e| / sqrt(ln^2 e + pi^2) (the linear-spring formula), we
# solve the Hertz collision for c (docs/design.md). It gets the e whose c is ours, so both run the same law.
cc -std=c11 -O2 -Iinclude bench/peer/damping.c build/libdem.a -lOpenCL -lm -o "$OUT/damping"
eval "$("$OUT/damping" "$RESTITUTION")"   # c_dem e_liggghts c_liggghts e_hertz_liggghts
DAMPING="e = $RESTITUTION: libdem's c = $(printf %.4f "$c_dem"); LIGGGHTS given coefficientRestitution \
$(printf %.4f "$e_liggghts") computes the same c (its own c for e = $RESTITUTION, $(printf %.4f "$c_liggghts"), \
would rebound a Hertz contact at e = $e_hertz_liggghts)"
say "damping: $DAMPING"

# 3. LIGGGHTS, 1 and 2 ranks.
ZHI=$("$PY" bench/peer/peer.py lammps "$OUT/bed.csv" "$OUT/bed.data" "$OUT/floor.stl" "$RHO")
for np in 1 2; do
  log=$OUT/liggghts-np$np.log
  say "LIGGGHTS on $np rank(s), $STEPS steps"
  t0=$(now)
  # (-screen none crashes Debian's 3.8.0 while it reads the STL: it prints to the screen it has not got)
  if ! mpirun --oversubscribe -np "$np" liggghts -in bench/peer/in.peer -log "$log" -screen "${log%.log}.screen" \
      -var data "$OUT/bed.data" -var stl "$OUT/floor.stl" -var steps "$STEPS" -var dt "$DT" -var skin "$SKIN" \
      -var rho "$RHO" -var young "$YOUNG" -var poisson "$POISSON" -var restitution "$e_liggghts" \
      -var friction "$FRICTION"; then
    tail -20 "$log" >&2
    die "LIGGGHTS failed (log: $log)"
  fi
  say "  $(grep -m1 'Loop time' "$log") (process $(awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }') s)"
done

# 4. libdem, fp64 and fp32. Its "wall time" line times the steps phase (set-up excluded), which still holds the
# first step's one-off costs (PoCL compiles each kernel for its work-group size at the first launch) and the first
# and last frames and the checkpoint. So: a 1-step run to warm PoCL's kernel cache (discarded), a 1-step run whose
# steps phase is those fixed costs, and the full run; the steps' time is the difference.
for order in input spatial; do
  cat > "$OUT/bed_run-$order.yaml" <<EOF
# make bench-peer's timed run (written by bench/peer/run.sh): the bed of bed.csv, $STEPS steps of dt = $DT s
name: bench-peer bed
precision: fp64
# input: the particles in bed.csv's order (as poured: random); spatial: sorted along a Morton curve at load, and
# stored anew as they move (dem_config.reorder)
particle_order: $order
effects: [hertz, damping, friction, gravity, walls]
materials:
  - {name: grain, density: $RHO, young: $YOUNG, poisson: $POISSON, restitution: $RESTITUTION, friction: $FRICTION}
particles:
  - {material: grain, csv: bed.csv}
gravity: [0, 0, -9.81]
walls:
  - {type: plane, name: floor, material: grain, point: [0, 0, 0], normal: [0, 0, 1]}
  - {type: plane, name: x-, material: grain, point: [0, 0, 0], normal: [1, 0, 0]}
  - {type: plane, name: x+, material: grain, point: [0.1, 0, 0], normal: [-1, 0, 0]}
  - {type: plane, name: y-, material: grain, point: [0, 0, 0], normal: [0, 1, 0]}
  - {type: plane, name: y+, material: grain, point: [0, 0.1, 0], normal: [0, -1, 0]}
domain: {lo: [-0.005, -0.005, -0.005], hi: [0.105, 0.105, $ZHI]}
# a settled bed under gravity: its grains overlap by more than the default 1 % of a radius
overlap_tolerance: 0.1
time: {dt: $DT, duration: $DURATION}
output:
  frame_every: $DURATION
  series_every: $(awk -v d="$DURATION" 'BEGIN { printf "%.10g", d / 10 }')
  fields: [position, velocity]
EOF
done
DEMRUNS=()
for order in input spatial; do
  for prec in fp64 fp32; do
    base=$OUT/dem-$prec-$order
    label=$prec
    [ "$order" = spatial ] && label="$prec, particle_order spatial"
    say "libdem on PoCL, $label, $STEPS steps"
    for one in warm 1step; do
      t0=$(now)
      "$DEM" run "$OUT/bed_run-$order.yaml" --precision "$prec" -o "$base-$one.h5" --stop-after 1 --progress \
        2> "$base-$one.log" || { cat "$base-$one.log" >&2; die "dem run failed"; }
    done
    t1=$(now)
    "$DEM" run "$OUT/bed_run-$order.yaml" --precision "$prec" -o "$base.h5" --progress 2> "$base.log" ||
      { tail -20 "$base.log" >&2; die "dem run failed"; }
    t2=$(now)
    grep 'wall time' "$base-1step.log" "$base.log" | sed 's/^/bench-peer:   /' >&2
    DEMRUNS+=(--dem "$label:$base.h5:$base.log:$base-1step.log:$(awk -v a="$t1" -v b="$t2" 'BEGIN { print b - a }'):$(
      awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')")
  done
done

# 5. The check and the table.
CPU=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
POCL=$(clinfo 2>/dev/null | sed -n 's/^ *Platform Version *OpenCL [0-9.]* \(PoCL [^ ]*\).*/\1/p' | head -1)
POCL="${POCL:-PoCL ?} ($("$DEM" devices 2>/dev/null | sed -n 's/^0 *//p' | head -1))"
"$PY" bench/peer/peer.py report --json "$OUT/peer.json" --bed "$OUT/bed.csv" --density "$RHO" \
  --meta "nproc=$(nproc)" --meta "cpu=$CPU" --meta "pocl=$POCL" --meta "libdem=$("$DEM" --version)" \
  --meta "dt=$DT" --meta "damping=$DAMPING" \
  --meta "skin=$SKIN" \
  --liggghts "1:$OUT/liggghts-np1.log" --liggghts "2:$OUT/liggghts-np2.log" "${DEMRUNS[@]}"
