#!/bin/bash
# state_hashes.sh - a hash of the dynamic state of every shipped scene (scenes/, scenes/validation/, the restart test
# scene) after 150 steps, under every contact model, on both backends, in fp64 and fp32: one line per run,
# "scene backend model precision hash". A refactor that claims bit-identity compares this table before and after
# (docs/design.md "One description per kernel and buffer"):
#   tools/state_hashes.sh OLD_BUILD/dem > before.txt; tools/state_hashes.sh build/dem > after.txt; diff before.txt after.txt
# The hash covers positions, velocities, spins, forces, contact histories, wall forces and MC-strain forces of the
# checkpoint (and the contact law's states under thornton_ning, run on the scenes whose materials give a
# yield_stress). A model a scene cannot take (MC-strain without gamma) is listed as refused. docs/state_hashes.txt is
# the reference table: a change that is meant to keep the bits compares against it directly,
#   tools/state_hashes.sh build/dem | diff <(grep -v '^#' docs/state_hashes.txt) -
set -u
DEM=$(readlink -f "${1:-build/dem}")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
for s in "$ROOT"/scenes/*.yaml "$ROOT"/scenes/validation/*.yaml "$ROOT"/tests/scenes/restart_box.yaml; do
    b=$(basename "$s" .yaml)
    case "$b" in tablet_100k | tablet_1m) continue ;; esac # 1e5-1e6 spheres: 16 runs with the fill, the reference among them
    rm -rf "$T/data" && { cp -r "$(dirname "$s")/data" "$T/" 2>/dev/null || true; }
    for be in opencl reference; do
        models="scene mc_stress mc_strain mc_strain_iterated"
        grep -q yield_stress "$s" && models="$models thornton_ning" # the plastic law where a material yields
        for model in $models; do
            for prec in fp64 fp32; do
                sed "s/^precision:.*/precision: $prec/; /^backend:/d" "$s" > "$T/s.yaml"
                echo "backend: $be" >> "$T/s.yaml"
                m=()
                [ "$model" != scene ] && m=(--model "$model")
                if "$DEM" run "$T/s.yaml" -o "$T/o.h5" --quiet --stop-after 150 "${m[@]}" > "$T/log" 2>&1; then
                    law=() # a law with memory: its states too
                    [ "$model" = thornton_ning ] && law=(-d /state/pair_law -d /state/wall_law)
                    h=$(h5dump -d /state/x -d /state/v -d /state/w -d /state/force -d /state/pair_hist \
                        -d /state/wall_force -d /state/pair_mc_fn "${law[@]}" "$T/o.ckpt.h5" 2>/dev/null | tail -n +2 |
                        md5sum | cut -c1-16)
                else
                    h="refused"
                fi
                echo "$b $be $model $prec $h"
            done
        done
    done
done
