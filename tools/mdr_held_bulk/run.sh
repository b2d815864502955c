#!/bin/bash
# tools/mdr_held_bulk/run.sh - are the bursts of a dense MDR compact fed by (M10)'s bulk increments? The MCC tablet
# of scenes/tablet_strength_mdr.yaml at psi_b 0.7 pressed towards 100 MPa (docs/tableting.md "What went wrong at psi_b
# 0.7") is run to its 2.0 ms checkpoint (step 390010, in the reference: the same bits as PoCL's, and faster on one
# core), then continued 0.5 ms twice in the reference: under the law, and under a copy of the tree in which (M10)
# gives no bulk increment (delta_BULK held where it is, the bulk springs still acting: one condition in
# common/laws/mdr_core.h made false, which the copy's build then carries). windows.py tables the two side by side.
# The copy is HEAD's (git archive), not the working tree's. About 15 minutes on 2 cores, 7 of them the first run.
# usage: bash tools/mdr_held_bulk/run.sh [OUTDIR]   (default out/mdr_held_bulk)
# The held copy's driver continues any checkpoint: OUTDIR/continue_held SCENE.yaml CKPT.h5 STEPS EVERY [WALL [P]]
# (docs/laws/mdr.md "Energy": the E 5 GPa tablet was continued so by hand from the end of its dwell; the 64-sphere
# box of tools/mdr_energy_box was continued by hand with an earlier driver, before this script).
set -e
cd "$(dirname "$0")/../.."
OUT=${1:-out/mdr_held_bulk}
mkdir -p "$OUT"
make -s build/dem build/libdem.a build/libdemapp.a
# the copy whose law holds the bulk increments
rm -rf "$OUT/held"
mkdir -p "$OUT/held"
git archive HEAD | tar -x -C "$OUT/held"
core=$OUT/held/common/laws/mdr_core.h
sed -i 's|^    if (p->psi < m->psi_b) { /\* (M10)|    if (0 \&\& p->psi < m->psi_b) { /* (M10)|' "$core"
grep -q '^    if (0 && p->psi < m->psi_b) { /\* (M10)' "$core" ||
    { echo "mdr_held_bulk: (M10)'s condition not found in $core: update this script's sed" >&2; exit 1; }
make -s -C "$OUT/held" build/libdem.a build/libdemapp.a > "$OUT/held_build.log" 2>&1 ||
    { echo "mdr_held_bulk: the held copy did not build (see $OUT/held_build.log)" >&2; exit 1; }
pc_c=$(pkg-config --cflags hdf5)
pc_l=$(pkg-config --libs hdf5 libcyaml yaml-0.1)
for v in law held; do
    root=.
    [ $v = held ] && root=$OUT/held
    cc -std=c11 -O2 -ffp-contract=off -D_GNU_SOURCE -I"$root/include" -I"$root/common" -I"$root/app" $pc_c \
        tools/mdr_held_bulk/continue.c "$root/build/libdemapp.a" "$root/build/libdem.a" $pc_l -lOpenCL -lm -lpthread \
        -o "$OUT/continue_$v"
done
# the tablet at psi_b 0.7 to 2.0 ms
sed -e 's/bulk_fraction: 0.5,/bulk_fraction: 0.7,/' -e 's/until_stress: 5.0e7,/until_stress: 100.0e6,/' \
    scenes/tablet_strength_mdr.yaml > "$OUT/tablet.yaml"
[ "$(grep -c 'bulk_fraction: 0.7,\|until_stress: 100.0e6,' "$OUT/tablet.yaml")" = 2 ] ||
    { echo "mdr_held_bulk: scenes/tablet_strength_mdr.yaml changed: update this script's sed" >&2; exit 1; }
build/dem run "$OUT/tablet.yaml" -o "$OUT/tablet.h5" --backend reference --stop-after 390010 --quiet \
    > "$OUT/tablet.log" 2>&1 || { echo "mdr_held_bulk: the tablet's run failed (see $OUT/tablet.log)" >&2; exit 1; }
# both continuations, 97510 steps (0.5 ms) with a line every 250 steps; wall 2 is the upper punch
"$OUT/continue_law" "$OUT/tablet.yaml" "$OUT/tablet.ckpt.h5" 97510 250 2 > "$OUT/law.txt" &
law=$!
"$OUT/continue_held" "$OUT/tablet.yaml" "$OUT/tablet.ckpt.h5" 97510 250 2 > "$OUT/held.txt"
wait $law
/usr/bin/python3 tools/mdr_held_bulk/windows.py "$OUT/law.txt" "$OUT/held.txt"
