#!/usr/bin/env bash
# make test-paraview: ParaView's own XDMF reader (pvpython) opens a dem run's output and must see every particle
# and every field at the last frame, and a membrane scene's triangles as a second grid.
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
