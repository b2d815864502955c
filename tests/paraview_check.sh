#!/usr/bin/env bash
# make test-paraview: ParaView's own XDMF reader (pvpython) opens a dem run's output and must see every particle
# and every field at the last frame, a membrane scene's triangles as a second grid, and a press's walls (die, two
# cupped punches) as a grid of triangles that moves as the upper punch comes down.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d /tmp/dem-paraview-XXXXXX)
trap 'rm -rf "$out"' EXIT
./build/dem run tests/scenes/restart_box.yaml -o "$out/run.h5" --quiet
pvpython --force-offscreen-rendering tests/paraview_check.py "$out/run.xmf" 64 \
  position velocity angular_velocity force torque radius material
# a membrane scene: the membranes as a second grid of triangles over the particles' points
./build/dem run tests/scenes/membrane_tube.yaml -o "$out/mem.h5" --quiet
pvpython --force-offscreen-rendering tests/paraview_check.py "$out/mem.xmf" 225 position velocity force \
  radius material triangles=336
# a press: the die (96 points, 96 triangles) and two cupped punches (433 points, 816 triangles each); a short run
# (the upper punch comes down 0.4 mm)
sed -e 's/^time:.*/time: {dt_rayleigh: 0.2, duration: 0.004}/' -e 's/frame_every: 0.005/frame_every: 0.002/' \
  tests/scenes/tablet_concave.yaml > "$out/press.yaml"
./build/dem run "$out/press.yaml" -o "$out/press.h5" --quiet
pvpython --force-offscreen-rendering tests/paraview_check.py "$out/press.xmf" 600 position velocity radius material \
  walls=962,1728
