#!/usr/bin/env bash
# Runs each test program (cmocka programs and shell checks), TEST_JOBS of them at a time (default: the number of
# CPUs), shows each one's whole output when it ends, with its wall time, and ends with one summary line
# "N passed, N failed".
#
# Why more than one at a time: a test program alternates between PoCL (every core busy), the serial reference,
# HDF5 files, Python reports and process start-up (one core or none), so one program alone leaves a core idle about
# a third of the time; two keep both busy. The programs share nothing but the PoCL kernel cache (whose entries are
# written whole and renamed into place) and the build, which make has finished before this runs; each one makes its
# own temporary directory. TEST_JOBS=1 runs them one after the other.
#
# Order: the longest first, by the wall times of the last run (build/test-times.txt, written at the end; TEST_TIMES
# names another file), so that a long program does not start last and run alone; programs without a time keep their
# order, after those with one. A clone that has not run the tests yet takes the times committed in
# tests/test-times.txt (measured 2026-12-04; only the order depends on them).
#
# Started from a script, a background job inherits SIGINT and SIGQUIT ignored, and dem run leaves a signal ignored
# that its caller ignores (nohup's SIGHUP): `env --default-signal` gives the programs the dispositions they would
# have in the foreground (test_tablet checks dem's answer to a real SIGINT). Ctrl-C reaches them all: they stay in
# make's process group.
set -u
jobs_max=${TEST_JOBS:-$(nproc)}
case "$jobs_max" in '' | *[!0-9]* | 0) echo "run-tests: TEST_JOBS must be a positive integer, not '$jobs_max'" >&2; exit 2 ;; esac
times_file=${TEST_TIMES:-build/test-times.txt}
order_file=$times_file
[ -r "$order_file" ] || order_file=tests/test-times.txt
logdir=$(mktemp -d "${TMPDIR:-/tmp}/dem-tests.XXXXXX") || exit 1
trap 'rm -rf "$logdir"' EXIT

# the programs, longest first by the last run's times (a stable sort keeps the given order among equals)
order=()
while read -r _ t; do order+=("$t"); done < <(
  i=0
  for t in "$@"; do
    secs=$( [ -r "$order_file" ] && awk -v n="$(basename "$t")" '$1 == n { print $2 }' "$order_file" | tail -n 1 )
    printf '%s %06d %s\n' "${secs:-0}" "$i" "$t"
    i=$((i + 1))
  done | sort -k1,1nr -k2,2n | cut -d' ' -f2-)

pass=0; fail=0; failed=(); times=()
declare -A pid_of start_of
running=()

# waits for one running program to end, then reports it
reap() {
  local done_pid t rc
  wait -n -p done_pid "${running[@]}"
  rc=$?
  for t in "${!pid_of[@]}"; do [ "${pid_of[$t]}" = "$done_pid" ] && break; done
  local secs=$(( $(date +%s) - start_of[$t] ))
  echo "=== $t"
  cat "$logdir/$(basename "$t").log"
  echo "--- $(basename "$t"): $secs s"
  times+=("$(basename "$t") $secs")
  if [ "$rc" -eq 0 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); failed+=("$t"); fi
  unset "pid_of[$t]"
  local keep=() p
  for p in "${running[@]}"; do [ "$p" != "$done_pid" ] && keep+=("$p"); done
  running=("${keep[@]}")
}

for t in "${order[@]}"; do
  while [ "${#running[@]}" -ge "$jobs_max" ]; do reap; done
  start_of[$t]=$(date +%s)
  env --default-signal=INT,QUIT "$t" > "$logdir/$(basename "$t").log" 2>&1 < /dev/null &
  pid_of[$t]=$!
  running+=("$!")
done
while [ "${#running[@]}" -gt 0 ]; do reap; done

if [ -d "$(dirname "$times_file")" ]; then printf '%s\n' "${times[@]}" > "$times_file"; fi
[ ${#failed[@]} -gt 0 ] && echo "failed programs: ${failed[*]}"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
