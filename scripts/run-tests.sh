#!/usr/bin/env bash
# Runs each test program (cmocka programs and shell checks), TEST_JOBS of them at a time (default: the number of
# CPUs), shows each one's whole output when it ends, with its wall time, and ends with one summary line
# "N passed, N failed".
#
# Why more than one at a time: a test program alternates between PoCL (its threads busy), PoCL compiling a kernel
# program, the serial reference, HDF5 files, Python reports and process start-up (one core or none), so one program
# alone leaves a core idle about a third of the time; two keep both busy. Three on 2 cores were slower: make test
# with an empty PoCL cache took 907 s three at a time against 819 s two at a time (2026-12-07). The programs share
# nothing but the PoCL kernel cache (whose entries are written whole and renamed into place) and the build, which make
# has finished before this runs; each one makes its own temporary directory. TEST_JOBS=1 runs them one after the
# other.
#
# Order: the longest first, by the wall times of the last run (build/test-times.txt, written at the end; TEST_TIMES
# names another file), so that a long program does not start last and run alone; programs without a time keep their
# order, after those with one. A clone that has not run the tests yet takes the times committed in
# tests/test-times.txt (measured on the 2-core development VM; only the order depends on them).
#
# Each program runs in a subshell that writes its exit status to a file: a program that dies of a signal outside a
# `wait` would otherwise leave bash's job table unseen (a non-interactive bash reports and forgets it) and be lost.
# Its standard output is line-buffered (stdbuf -oL), so a crash loses none of it and its lines keep their order
# with its standard error in the log.
#
# Signals: started from a script, a background job inherits SIGINT and SIGQUIT ignored, and dem run leaves a signal
# ignored that its caller ignores (nohup's SIGHUP): `env --default-signal` gives the programs the dispositions they
# would have in the foreground (test_tablet checks dem's answer to a real SIGINT). Ctrl-C reaches them all (they stay
# in make's process group), but a program waiting in system() ignores it and would go on alone: on SIGINT or SIGTERM
# this script starts nothing more, sends SIGTERM to each running program and its children, waits for them, and dies
# of the same signal, so make stops too.
set -u
here=$(dirname "$0")
jobs_max=${TEST_JOBS:-$(nproc)}
case "$jobs_max" in '' | *[!0-9]*) jobs_max=0 ;; *) jobs_max=$((10#$jobs_max)) ;; esac
[ "$jobs_max" -gt 0 ] || { echo "run-tests: TEST_JOBS must be a positive integer, not '${TEST_JOBS-}'" >&2; exit 2; }
times_file=${TEST_TIMES:-build/test-times.txt}

# PoCL's worker threads: the cores shared out over the programs that run at once (one each on 2 cores, two at a
# time), unless POCL_MAX_PTHREAD_COUNT or POCL_CPU_MAX_CU_COUNT (its newer name) is set already, even empty. PoCL
# starts one thread per core by default; two programs of two threads each on 2 cores wake and wait for each other's
# threads at every kernel launch, and a small scene's step is mostly launches: 20 000 steps of tablet_small took 3.5 s
# with two threads each and 1.9 s with one, two runs at a time (2026-12-07). Every kernel's bits are the same on any
# number of threads; the programs that check that for each family of laws (tests/test_util.h, test_pocl_threads:
# classical, the multi-contact models, membranes, MDR, Thornton-Ning and adhesion) raise their own PoCL to
# two threads whatever this sets, so a race between work-groups can still show in make test.
if [ -z "${POCL_MAX_PTHREAD_COUNT+x}" ] && [ -z "${POCL_CPU_MAX_CU_COUNT+x}" ]; then
  cores=$(nproc)
  POCL_MAX_PTHREAD_COUNT=$((cores / jobs_max > 0 ? cores / jobs_max : 1))
  export POCL_MAX_PTHREAD_COUNT
fi
logdir=$(mktemp -d "${TMPDIR:-/tmp}/dem-tests.XXXXXX") || exit 1
trap 'rm -rf "$logdir"' EXIT

# the last wall time of program $1: the last run's, else the committed one
last_secs() {
  local f
  for f in "$times_file" tests/test-times.txt; do
    [ -r "$f" ] && awk -v n="$1" '$1 == n { s = $2 } END { if (s != "") print s; else exit 1 }' "$f" && return
  done
  echo 0
}

# the programs, longest first (a stable sort keeps the given order among equals)
order=()
while read -r _ t; do order+=("$t"); done < <(
  i=0
  for t in "$@"; do
    printf '%s %06d %s\n' "$(last_secs "$(basename "$t")")" "$i" "$t"
    i=$((i + 1))
  done | sort -k1,1nr -k2,2n | cut -d' ' -f2-)

pass=0; fail=0; failed=(); times=()
declare -A name_of start_of
running=()
signal=
trap 'signal=INT' INT
trap 'signal=TERM' TERM

# waits for one running program to end, then reports it; returns at once when a signal ended the wait
reap() {
  local done_pid='' n rc
  wait -n -p done_pid "${running[@]}"
  [ -n "${done_pid-}" ] || return 0
  n=${name_of[$done_pid]}
  rc=$(cat "$logdir/$n.rc" 2>/dev/null) || rc=255
  local secs=$(( $(date +%s) - start_of[$done_pid] ))
  echo "=== $n"
  cat "$logdir/$n.log"
  if [ "$rc" -eq 0 ]; then
    pass=$((pass + 1))
    echo "--- $n: $secs s"
  else
    fail=$((fail + 1)); failed+=("$n")
    echo "--- $n: $secs s, FAILED (exit status $rc)"
  fi
  times+=("$n $secs")
  unset "name_of[$done_pid]" "start_of[$done_pid]"
  local keep=() p
  for p in "${running[@]}"; do [ "$p" != "$done_pid" ] && keep+=("$p"); done
  running=("${keep[@]}")
}

# SIGTERM to process $1 and its descendants, the children first (from /proc: a minimal Debian has no pgrep)
kill_tree() {
  local c
  # shellcheck disable=SC2013 # the files hold pids separated by spaces
  for c in $(cat /proc/"$1"/task/*/children 2> /dev/null); do kill_tree "$c"; done
  kill -TERM "$1" 2> /dev/null
}

for t in "${order[@]}"; do
  while [ -z "$signal" ] && [ "${#running[@]}" -ge "$jobs_max" ]; do reap; done
  [ -z "$signal" ] || break
  n=$(basename "$t")
  ( if [ "${t%.py}" != "$t" ]; then
      # a Python test runs under scripts/find_python.sh's Python (with matplotlib: it draws), or fails saying what
      # is missing, not under its #! line's /usr/bin/python3
      py=$("$here/find_python.sh" h5py numpy matplotlib) && env --default-signal=INT,QUIT stdbuf -oL "$py" "$t"
    else
      env --default-signal=INT,QUIT stdbuf -oL "$t"
    fi > "$logdir/$n.log" 2>&1 < /dev/null
    echo "$?" > "$logdir/$n.rc" ) &
  name_of[$!]=$n
  start_of[$!]=$(date +%s)
  running+=("$!")
done
while [ -z "$signal" ] && [ "${#running[@]}" -gt 0 ]; do reap; done

if [ -n "$signal" ]; then
  echo "run-tests: SIG$signal: stopping ${#running[@]} running program(s); $pass passed, $fail failed before" >&2
  for p in "${running[@]}"; do kill_tree "$p"; done
  wait
  rm -rf "$logdir"
  trap - "$signal" EXIT
  kill -s "$signal" $$
fi

# this run's times, then the earlier ones of the programs it did not run
if [ -d "$(dirname "$times_file")" ] && [ ${#times[@]} -gt 0 ]; then
  { printf '%s\n' "${times[@]}"
    if [ -r "$times_file" ]; then
      awk 'NR == FNR { ran[$1] = 1; next } !($1 in ran)' <(printf '%s\n' "${times[@]}") "$times_file"
    fi
  } > "$logdir/times" && mv "$logdir/times" "$times_file"
fi
[ ${#failed[@]} -gt 0 ] && echo "failed programs: ${failed[*]}"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
