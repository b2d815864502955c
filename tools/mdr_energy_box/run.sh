#!/bin/bash
# tools/mdr_energy_box/run.sh - does a held MDR compact come to rest? box.yaml under four settings (psi_b and the
# MDR damping, dt_rayleigh), two runs at a time, then analyse.py's table; then the swinging sphere of b7_d2 followed
# step by step for 5 us from its checkpoint, and contact_loops.py's table of what its contacts give. About 10 minutes
# on 2 cores.
# usage: bash tools/mdr_energy_box/run.sh [OUTDIR]   (default out/mdr_energy_box; needs build/dem)
set -e
cd "$(dirname "$0")/../.."
OUT=${1:-out/mdr_energy_box}
mkdir -p "$OUT"
# name psi_b damping dt_rayleigh
set -- "b5_d2 0.5 0.2 0.05" "b7_d2 0.7 0.2 0.05" "b7_d2_half 0.7 0.2 0.025" "b5_d0 0.5 0.0 0.05"
run() {
    read -r name psib damp dtr <<< "$1"
    sed -e "s/PSIB/$psib/; s/DAMP/$damp/; s/DTR/$dtr/" tools/mdr_energy_box/box.yaml > "$OUT/$name.yaml"
    POCL_MAX_PTHREAD_COUNT=1 build/dem run "$OUT/$name.yaml" -o "$OUT/$name.h5" --quiet > "$OUT/$name.log" 2>&1 ||
        echo "mdr_energy_box: $name stopped (see $OUT/$name.log)"
}
run "$1" & run "$2"; wait
run "$3" & run "$4"; wait
/usr/bin/python3 tools/mdr_energy_box/analyse.py "$OUT"/b5_d2.h5 "$OUT"/b7_d2.h5 "$OUT"/b7_d2_half.h5 "$OUT"/b5_d0.h5
# b7_d2 continued for 5 us (about 1290 steps) with a frame at every step, the contacts in them
sed -e 's/duration: 0.0012}/duration: 0.001205}/' \
    -e 's/^output: .*/output: {frame_every: 3.9e-9, series_every: 3.9e-9, fields: [position, velocity, radius, contacts]}/' \
    "$OUT/b7_d2.yaml" > "$OUT/b7_d2_steps.yaml"
POCL_MAX_PTHREAD_COUNT=1 build/dem run "$OUT/b7_d2_steps.yaml" --restart "$OUT/b7_d2.ckpt.h5" -o "$OUT/b7_d2_steps.h5" \
    --quiet > "$OUT/b7_d2_steps.log" 2>&1
/usr/bin/python3 tools/mdr_energy_box/contact_loops.py "$OUT/b7_d2_steps.h5"
