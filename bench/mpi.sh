#!/usr/bin/env bash
# make bench's MPI table (DEM_BENCH_ONLY=mpi: this table alone): `dem run` split over 1, 2 and 4 ranks of Open MPI
# (app/run_mpi.c) on the poured bed of 100 000 spheres that make bench times (bench/peer/run.sh --bed pours it once
# into out/peer/bed.csv: polydisperse, in the random order it was poured in), MPI_STEPS steps (default 500) of dt =
# 2e-6 s, fp64, PoCL. One process uses PoCL's threads on every core; each rank of a split run one thread (the fair
# match on a machine whose cores the ranks share). Every run's checkpoint must hash equal to the one-process run's
# before its time counts. The steps' time is a run's wall time ("dem: wrote ... s wall time") less that of a 1-step
# run (its fixed costs: first frame, output, checkpoint), per step. Columns: particle-steps/s, against one process,
# the ghosts held (a fraction of the particles), the bytes rank 0 sent per step, and where rank 0's step went
# (its part's step, the ghosts' exchange, the rest: checks, merged sums, splits anew), from dem's report.
# Markdown on stdout, and out/mpi/mpi.json.
set -euo pipefail
cd "$(dirname "$0")/.."
STEPS=${MPI_STEPS:-500}
OUT=out/mpi
DEM=build/dem
PY=$(scripts/find_python.sh) || exit 1
[ -x "$DEM" ] || { echo "bench/mpi.sh: $DEM is missing: run make first" >&2; exit 1; }
bash bench/peer/run.sh --bed # out/peer/bed.csv, poured once
mkdir -p "$OUT"
cp out/peer/bed.csv "$OUT/bed.csv"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
DT=2.0e-6
# The scene: the pour's (bench/peer/bed_pour.yaml: materials, walls, domain) with the poured particles from bed.csv,
# in their poured order, and this table's time and output
{
    echo "# written by bench/mpi.sh from bench/peer/bed_pour.yaml: its set-up, the poured particles, the table's steps"
    awk '/^particles:/ { skip = 1; print "particles:"; print "  - {material: grain, csv: bed.csv}"; next }
         /^time:/ { exit }
         skip && /^[a-z]/ { skip = 0 }
         !skip' bench/peer/bed_pour.yaml
} >"$OUT/bed.yaml"
cat >>"$OUT/bed.yaml" <<EOF
# make bench's MPI table (bench/mpi.sh): the bed as poured, its grains overlapping by more than 1 % of a radius
overlap_tolerance: 0.1
time: {dt: $DT, duration: 1.0}
output: {frame_every: 1.0, series_every: 1.0e-4, fields: [position, velocity]}
EOF
run() { # ranks, steps, output base: the run's log
    local np=$1 steps=$2 base=$3
    if [ "$np" = 1 ]; then
        "$DEM" run "$OUT/bed.yaml" -o "$base.h5" --stop-after "$steps" --progress 2>"$base.log"
    else
        POCL_CPU_MAX_CU_COUNT=1 POCL_MAX_PTHREAD_COUNT=1 mpirun --oversubscribe --bind-to none -np "$np" \
            -x POCL_CPU_MAX_CU_COUNT -x POCL_MAX_PTHREAD_COUNT "$DEM" run "$OUT/bed.yaml" -o "$base.h5" \
            --stop-after "$steps" --progress 2>"$base.log"
    fi
}
wall() { sed -n 's/.*; \([0-9.]*\) s wall time.*/\1/p' "$1" | tail -1; }
rows=()
ref=
for np in 1 2 4; do
    run "$np" 1 "$OUT/warm$np" # the kernels built into PoCL's cache
    run "$np" 1 "$OUT/one$np"
    run "$np" "$STEPS" "$OUT/run$np"
    h=$("$DEM" hash "$OUT/run$np.ckpt.h5")
    [ -n "$ref" ] || ref=$h
    [ "$h" = "$ref" ] || { echo "bench/mpi.sh: $np ranks hash $h, one process $ref: the bits differ" >&2; exit 1; }
    rows+=("$np $(wall "$OUT/one$np.log") $(wall "$OUT/run$np.log") $h")
done
"$PY" - "$STEPS" "$OUT" "${rows[@]}" <<'EOF'
import json, re, sys
steps, out = int(sys.argv[1]), sys.argv[2]
n = int(re.search(r": (\d+) particles,", open(out + "/run1.log").read())[1])
res, base = [], None
for row in sys.argv[3:]:
    np_, one, full, h = row.split()
    np_, per = int(np_), (float(full) - float(one)) / (steps - 1)
    rate = n / per
    base = base or rate
    log = open("%s/run%d.log" % (out, np_)).read()
    r = {"ranks": np_, "particles": n, "steps": steps, "step_s": per, "particle_steps_per_s": rate,
         "vs_one_process": rate / base, "hash": h}
    m = re.search(r"(\d+) ghosts \(([\d.]+) % more held\).*?\((\d+) splits? so far.*?rank 0 per step: its part's step "
                  r"([\d.e+-]+) ms, ghost exchange ([\d.e+-]+) ms \(([\d.e+-]+) kB sent\), check of the moves "
                  r"([\d.e+-]+) ms, merged sums ([\d.e+-]+) ms, splits anew ([\d.e+-]+) ms", log, re.S)
    if m:
        r.update(ghosts=int(m[1]), ghost_percent=float(m[2]), splits=int(m[3]), part_step_ms=float(m[4]),
                 exchange_ms=float(m[5]), sent_kB=float(m[6]),
                 other_ms=float(m[7]) + float(m[8]) + float(m[9]))
    res.append(r)
json.dump(res, open(out + "/mpi.json", "w"), indent=1)
print("| ranks | particle-steps/s | vs one process | ghosts | kB sent per step (rank 0) | rank 0 per step: part's step / exchange / rest [ms] |")
print("|---:|---:|---:|---:|---:|---|")
for r in res:
    if "ghosts" in r:
        print("| %d | %.3g | %.2f | %d (%.1f %%) | %.4g | %.3g / %.3g / %.3g |" % (r["ranks"], r["particle_steps_per_s"],
              r["vs_one_process"], r["ghosts"], r["ghost_percent"], r["sent_kB"], r["part_step_ms"],
              r["exchange_ms"], r["other_ms"]))
    else:
        print("| %d | %.3g | %.2f | - | - | %.3g ms a step (one process) |" % (r["ranks"], r["particle_steps_per_s"],
              r["vs_one_process"], 1e3 * r["step_s"]))
print("\n%d spheres (the poured bed, as poured), %d steps, fp64, PoCL; every run's checkpoint hash %s" %
      (res[0]["particles"], steps, res[0]["hash"]))
EOF
