#!/bin/bash
# state_hashes.sh - a hash of the dynamic state of every shipped scene (scenes/, scenes/validation/, the restart test
# scene) after 150 steps, under every contact model, on both backends, in fp64 and fp32: one line per run,
# "scene backend model precision hash". A refactor that claims bit-identity compares this table before and after
# (docs/design.md "One description per kernel and buffer"):
#   tools/state_hashes.sh OLD_BUILD/dem > before.txt; tools/state_hashes.sh build/dem > after.txt; diff before.txt after.txt
# The hash is `dem hash` of the checkpoint (app/conform.h: positions, velocities, spins, forces, contact histories, wall
# forces, MC-strain forces, and the contact law's states where the law has memory - thornton_ning, run on the scenes
# whose materials give a yield_stress, and mdr, on those that give a bulk_fraction). A model a scene cannot take
# (MC-strain without gamma) is listed as refused. docs/state_hashes.txt is the reference table, and `dem conform` runs
# its reference lines on a device and compares (the same runs: `dem run SCENE --stop-after 150 --precision P --backend B
# [--model M]`). A change that is meant to keep the bits compares against it directly,
#   tools/state_hashes.sh build/dem | diff <(grep -v '^#' docs/state_hashes.txt) -
# NP=N runs each under `mpirun --oversubscribe -np N` (a run split over N ranks, app/run_mpi.c): its lines must equal
# the table's, but for the runs a split does not take yet (refused, exit 65, with the reason). ONLY="glass_die
# tablet_3k" runs those scenes alone.
set -u
DEM=$(readlink -f "${1:-build/dem}")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
MPI=()
if [ "${NP:-1}" -gt 1 ]; then
    MPI=(mpirun --oversubscribe -np "$NP")
    [ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
for s in "$ROOT"/scenes/*.yaml "$ROOT"/scenes/validation/*.yaml "$ROOT"/tests/scenes/restart_box.yaml; do
    b=$(basename "$s" .yaml)
    case "$b" in tablet_100k | tablet_1m | tablet_1m_gpu) continue ;; esac # 1e5-1e6 spheres: 16 runs with the fill, the reference among them
    [ -n "${ONLY:-}" ] && [[ " $ONLY " != *" $b "* ]] && continue
    for be in opencl reference; do
        models="scene mc_stress mc_strain mc_strain_iterated"
        grep -q yield_stress "$s" && models="$models thornton_ning" # the plastic law where a material yields
        grep -q bulk_fraction "$s" && models="$models mdr"          # MDR where a material gives its keys
        for model in $models; do
            for prec in fp64 fp32; do
                m=()
                [ "$model" != scene ] && m=(--model "$model")
                "${MPI[@]}" "$DEM" run "$s" -o "$T/o.h5" --quiet --stop-after 150 --precision $prec --backend $be "${m[@]}" \
                    > "$T/log" 2>&1
                rc=$?
                case $rc in # refused: the scene or model rejected (exit 2 or 65), as dem conform counts it
                0) h=$("$DEM" hash "$T/o.ckpt.h5") || h="failed(hash)" ;;
                2 | 65) h="refused" ;;
                *) h="failed($rc)" ;;
                esac
                echo "$b $be $model $prec $h"
            done
        done
    done
done
