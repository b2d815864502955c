#!/usr/bin/env bash
# make bench's MPI table (DEM_BENCH_ONLY=mpi: this table alone): `dem run` split over 1, 2 and 4 ranks of Open MPI
# (app/run_mpi.c) on the poured bed of 100 000 spheres that make bench times (bench/peer/run.sh --bed pours it once
# into out/peer/bed.csv: polydisperse, in the random order it was poured in), MPI_STEPS steps (default 500) of dt =
# 2e-6 s, fp64, PoCL; then the same bed tiled 5 x 2 times (1e6 spheres, copies side by side as make bench's bed table
# tiles it, the x+ and y+ walls moved to the tiles' far sides), MPI_STEPS_1E6 steps (default 100). MPI_SIZES=1e5
# leaves the 1e6 rows out: they take about 10 minutes on 2 cores, most of it setting up and writing 1e6 spheres.
# One process uses PoCL's threads on every core; each rank of a split run one thread (the fair match on a machine
# whose cores the ranks share). Every run's checkpoint must hash equal to the one-process run's of its size before
# its time counts. The steps' time is a run's wall time ("dem: wrote ... s wall time") less that of a 1-step run
# (its fixed costs: first frame, output, checkpoint), per step. Columns: particle-steps/s, against one process, the
# ghosts held (a fraction of the particles), the bytes rank 0 sent per step, and where rank 0's step went (its
# part's step, the ghosts' exchange, the rest: checks, merged sums, splits anew), from dem's report. Markdown on
# stdout, and out/mpi/mpi.json.
set -euo pipefail
cd "$(dirname "$0")/.."
STEPS=${MPI_STEPS:-500}
STEPS_1E6=${MPI_STEPS_1E6:-100}
SIZES=${MPI_SIZES:-1e5 1e6}
[ "$STEPS" -ge 2 ] && [ "$STEPS_1E6" -ge 2 ] || { echo "bench/mpi.sh: MPI_STEPS and MPI_STEPS_1E6 must be 2 or more (a 1-step run is the baseline subtracted)" >&2; exit 2; }
OUT=out/mpi
DEM=build/dem
PY=$(scripts/find_python.sh) || exit 1
[ -x "$DEM" ] || { echo "bench/mpi.sh: $DEM is missing: run make first" >&2; exit 1; }
bash bench/peer/run.sh --bed # out/peer/bed.csv, poured once
mkdir -p "$OUT"
cp out/peer/bed.csv "$OUT/bed.csv"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
DT=2.0e-6
# The scene: the pour's (bench/peer/bed_pour.yaml: materials, walls, domain) with the poured particles from a CSV in
# their poured order, and this table's time and output; tiled tx x ty times, the x+ and y+ walls and the domain's
# far sides moved out to the tiles'
scene() { # csv name, tx, ty: the scene on stdout
    local lx ly
    lx=$(awk "BEGIN { print 0.1 * $2 }")
    ly=$(awk "BEGIN { print 0.1 * $3 }")
    echo "# written by bench/mpi.sh from bench/peer/bed_pour.yaml: its set-up, the poured particles ($2 x $3 tiles), the table's steps"
    awk -v csv="$1" -v lx="$lx" -v ly="$ly" '
         /^particles:/ { skip = 1; print "particles:"; print "  - {material: grain, csv: " csv "}"; next }
         /^time:/ { exit }
         skip && /^[a-z]/ { skip = 0 }
         /name: x\+/ { sub(/point: \[0\.1, 0, 0\]/, "point: [" lx ", 0, 0]") }
         /name: y\+/ { sub(/point: \[0, 0\.1, 0\]/, "point: [0, " ly ", 0]") }
         /^domain:/ { sub(/hi: \[0\.105, 0\.105,/, "hi: [" lx + 0.005 ", " ly + 0.005 ",") }
         !skip' bench/peer/bed_pour.yaml
    echo "# make bench's MPI table (bench/mpi.sh): the bed as poured, its grains overlapping by more than 1 % of a radius"
    echo "overlap_tolerance: 0.1"
    echo "time: {dt: $DT, duration: 1.0}"
    echo "output: {frame_every: 1.0, series_every: 1.0e-4, fields: [position, velocity]}"
}
scene bed.csv 1 1 >"$OUT/bed.yaml"
case " $SIZES " in *" 1e6 "*)
    # the tiles: every sphere of the bed copied at x + 0.1 a, y + 0.1 c (the comment and header lines once)
    awk -F, '/^#/ || /^x,/ { print; next } /^[[:space:]]*$/ { next } { line[++n] = $0 }
             END { for (a = 0; a < 5; a++) for (c = 0; c < 2; c++) for (k = 1; k <= n; k++) {
                       m = split(line[k], f, ","); s = sprintf("%.17g,%.17g", f[1] + 0.1 * a, f[2] + 0.1 * c)
                       for (q = 3; q <= m; q++) s = s "," f[q]
                       print s } }' "$OUT/bed.csv" >"$OUT/bed1m.csv"
    scene bed1m.csv 5 2 >"$OUT/bed1m.yaml" ;;
esac
run() { # scene, ranks, steps, output base: the run's log
    local sc=$1 np=$2 steps=$3 base=$4
    if [ "$np" = 1 ]; then
        "$DEM" run "$sc" -o "$base.h5" --stop-after "$steps" --progress 2>"$base.log"
    else
        POCL_CPU_MAX_CU_COUNT=1 POCL_MAX_PTHREAD_COUNT=1 mpirun --oversubscribe --bind-to none -np "$np" \
            -x POCL_CPU_MAX_CU_COUNT -x POCL_MAX_PTHREAD_COUNT "$DEM" run "$sc" -o "$base.h5" \
            --stop-after "$steps" --progress 2>"$base.log"
    fi
}
wall() { sed -n 's/.*; \([0-9.]*\) s wall time.*/\1/p' "$1" | tail -1; }
rows=()
for size in $SIZES; do
    case $size in
    1e5) sc=$OUT/bed.yaml tag= steps=$STEPS ;;
    1e6) sc=$OUT/bed1m.yaml tag=_1m steps=$STEPS_1E6 ;;
    *) echo "bench/mpi.sh: MPI_SIZES takes 1e5 and 1e6, not $size" >&2; exit 2 ;;
    esac
    ref=
    for np in 1 2 4; do
        # the kernels built into PoCL's cache, once per rank count (a 1e6 run after the 1e5 runs finds them)
        [ "$size" != "${SIZES%% *}" ] || run "$sc" "$np" 1 "$OUT/warm$np$tag"
        run "$sc" "$np" 1 "$OUT/one$np$tag"
        run "$sc" "$np" "$steps" "$OUT/run$np$tag"
        h=$("$DEM" hash "$OUT/run$np$tag.ckpt.h5")
        [ -n "$ref" ] || ref=$h
        [ "$h" = "$ref" ] || { echo "bench/mpi.sh: $size, $np ranks hash $h, one process $ref: the bits differ" >&2; exit 1; }
        rows+=("$size $steps $np $(wall "$OUT/one$np$tag.log") $(wall "$OUT/run$np$tag.log") $h $OUT/run$np$tag.log")
        rm -f "$OUT/warm$np$tag".*h5 "$OUT/one$np$tag".*h5 # at 1e6 half a GB a checkpoint
    done
done
"$PY" - "$OUT" "${rows[@]}" <<'EOF'
import json, re, sys
out = sys.argv[1]
res, base = [], {}
for row in sys.argv[2:]:
    size, steps, np_, one, full, h, logp = row.split()
    steps, np_ = int(steps), int(np_)
    log = open(logp).read()
    n = int(re.search(r": (\d+) particles,", log)[1])
    per = (float(full) - float(one)) / (steps - 1)
    rate = n / per
    base.setdefault(size, rate)
    r = {"ranks": np_, "particles": n, "steps": steps, "step_s": per, "particle_steps_per_s": rate,
         "vs_one_process": rate / base[size], "hash": h}
    m = re.search(r"(\d+) ghosts \(([\d.]+) % more held\).*?\((\d+) splits? so far.*?rank 0 per step: its part's step "
                  r"([\d.e+-]+) ms, ghost exchange ([\d.e+-]+) ms \(([\d.e+-]+) kB sent\), check of the moves "
                  r"([\d.e+-]+) ms, merged sums ([\d.e+-]+) ms, splits anew ([\d.e+-]+) ms", log, re.S)
    if m:
        r.update(ghosts=int(m[1]), ghost_percent=float(m[2]), splits=int(m[3]), part_step_ms=float(m[4]),
                 exchange_ms=float(m[5]), sent_kB=float(m[6]),
                 other_ms=float(m[7]) + float(m[8]) + float(m[9]))
    res.append(r)
json.dump(res, open(out + "/mpi.json", "w"), indent=1)
print("| spheres | steps | ranks | particle-steps/s | vs one process | ghosts | kB sent per step (rank 0) | "
      "rank 0 per step: part's step / exchange / rest [ms] | checkpoint hash |")
print("|---:|---:|---:|---:|---:|---:|---:|---|---|")
for r in res:
    if "ghosts" in r:
        print("| %d | %d | %d | %.3g | %.2f | %d (%.1f %%) | %.4g | %.3g / %.3g / %.3g | %s |" % (
            r["particles"], r["steps"], r["ranks"], r["particle_steps_per_s"], r["vs_one_process"], r["ghosts"],
            r["ghost_percent"], r["sent_kB"], r["part_step_ms"], r["exchange_ms"], r["other_ms"], r["hash"]))
    else:
        print("| %d | %d | %d | %.3g | %.2f | - | - | %.3g ms a step (one process) | %s |" % (
            r["particles"], r["steps"], r["ranks"], r["particle_steps_per_s"], r["vs_one_process"],
            1e3 * r["step_s"], r["hash"]))
print("\nThe poured bed as poured, and 5 x 2 tiles of it; fp64, PoCL; each size's split runs hash equal to its "
      "one-process run")
EOF
