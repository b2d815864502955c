#!/usr/bin/env bash
# examples_check.sh - the tutorial's scenes (docs/tutorial.md) run as the tutorial runs them, so that it cannot rot:
#  - examples/pour_press.yaml, the tutorial's scene, must pass `dem check`;
#  - examples/pour_press_small.yaml, its short version (300 beads), must run to its end: exit status 0, the HDF5 file
#    and its XDMF sidecar written, the piston's stages ending as the scene asks (the two until_force stops logged);
#  - in the output: the piston pushes on the beads at the end (a positive force, at least the first stop's 0.5 N),
#    and the walls carry the beads' weight - the vertical forces on floor, die and piston sum to minus the weight of
#    the beads (their radii and density from the file) within 1 %, once the pour has settled (before the piston
#    moves) and at the end (at rest under the piston).
# Checks the run itself with h5py, not the libdem Python package. Run by `make test` (and `make test-examples`).
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DEM="$ROOT/build/dem"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "examples_check: $*"; exit 1; }

"$DEM" check "$ROOT/examples/pour_press.yaml" > "$T/check.txt" 2>&1 || { cat "$T/check.txt"; fail "dem check examples/pour_press.yaml failed"; }
grep -q "^wall time      about " "$T/check.txt" || { cat "$T/check.txt"; fail "dem check printed no wall-time estimate"; }

rc=0
"$DEM" run "$ROOT/examples/pour_press_small.yaml" -o "$T/pp.h5" > "$T/run.log" 2>&1 || rc=$?
cat "$T/run.log"
[ "$rc" -eq 0 ] || fail "dem run examples/pour_press_small.yaml exited with $rc"
[ -s "$T/pp.h5" ] && [ -s "$T/pp.xmf" ] || fail "the run left no pp.h5 or pp.xmf"
grep -q "stage 2 of 4 (motion\[0\]) ended at step [0-9]* (t = [0-9.e-]* s): until_force 0.5 N reached" "$T/run.log" ||
    fail "no stage-end line for the piston's approach (until_force 0.5 N)"
grep -q "stage 3 of 4 (motion\[1\]) ended at step [0-9]* (t = [0-9.e-]* s): until_force 2 N reached" "$T/run.log" ||
    fail "no stage-end line for the piston's press (until_force 2 N)"

python=$("$ROOT/scripts/find_python.sh" 2>&1) || fail "$python"
"$python" - "$T/pp.h5" <<'PY' || fail "the output's forces are not what the scene implies"
import sys
import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
s = f["series"]
t = s["time"][:]
fz = s["wall_force"][:, :, 2]  # force each wall receives, z [N]
fn = s["wall_normal_force"][:, 2]  # the piston's, along its normal, compression positive
r = f["particles/radius"][:]
weight = (4.0 / 3.0 * np.pi * r ** 3).sum() * 1200.0 * 9.81  # the beads' density in the scene: 1200 kg/m^3
ok = True
print(f"examples_check: {len(r)} beads weigh {weight:.5g} N; piston force at the end {fn[-1]:.4g} N")
if not fn[-1] >= 0.5:
    print("examples_check: the piston does not press the beads at the end")
    ok = False
for when in (0.29, t[-1]):  # settled before the piston moves (settle 0.3 s), and at rest at the end
    i = min(np.searchsorted(t, when), len(t) - 1)
    total = fz[i].sum()
    print(f"examples_check: t = {t[i]:.4g} s: walls' vertical forces {total:.6g} N against the weight {-weight:.6g} N")
    if abs(total + weight) > 0.01 * weight:
        ok = False
sys.exit(0 if ok else 1)
PY
echo "examples_check: examples/pour_press.yaml checks; its short version ran, stopped at its forces and balances its weight"
