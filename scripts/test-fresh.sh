#!/usr/bin/env bash
# make test-fresh: the README's two commands, on the first try, on a bare Debian 12 machine.
#
# Builds (once, then cached) a minbase Debian 12 root with only build-essential, git, python3, ca-certificates and
# pkg-config, from this machine's own apt sources; unpacks a new copy of it for every run; clones the project's
# committed HEAD into it; and runs `make run`, then `make test`, as root inside the chroot. Fails if either fails,
# or if `make run` leaves no HDF5 file or PNG in out/. /proc, /sys, /dev and /dev/pts are mounted for the run and
# unmounted on every exit path; the copy is deleted only once nothing is mounted below it.
#
# Environment: DEM_FRESH_CACHE (where the bare root's tarball is kept, default /var/cache/libdem-test-fresh),
# DEM_FRESH_KEEP=1 (leave the used root in place for a look, unmounted; later runs leave it alone), DEM_FRESH_REV (what to clone, default HEAD).
set -euo pipefail

SRC=$(cd "$(dirname "$0")/.." && pwd)
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "test-fresh: needs root (mmdebstrap, chroot, mount) or sudo" >&2; exit 1; }
  exec sudo --preserve-env=DEM_FRESH_CACHE,DEM_FRESH_KEEP,DEM_FRESH_REV bash "$0" "$@"
fi
bash "$SRC/scripts/install-deps.sh" --fresh

SUITE=bookworm
INCLUDE=build-essential,git,python3,ca-certificates,pkg-config
CACHE=${DEM_FRESH_CACHE:-/var/cache/libdem-test-fresh}
REV=${DEM_FRESH_REV:-HEAD}
say() { echo "test-fresh: $*"; }

# This machine's apt sources (deb822 .sources and one-line .list files that are enabled), pasted into the root.
sources=()
[ -s /etc/apt/sources.list ] && grep -q '^[[:space:]]*deb' /etc/apt/sources.list && sources+=(/etc/apt/sources.list)
for f in /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list; do [ -s "$f" ] && sources+=("$f"); done
[ ${#sources[@]} -gt 0 ] || { echo "test-fresh: this machine has no apt sources to build the root from" >&2; exit 1; }

# The cached bare root is named after what made it, so a change of packages or sources builds a new one.
key=$( { echo "$SUITE minbase $INCLUDE"; cat "${sources[@]}"; } | sha256sum | cut -c1-16)
tarball=$CACHE/$SUITE-minbase-$key.tar
mkdir -p "$CACHE"
if [ ! -s "$tarball" ]; then
  say "building the bare root (mmdebstrap --variant=minbase, $INCLUDE) into $tarball"
  rm -f "$CACHE/$SUITE"-minbase-*.tar "$CACHE/$SUITE"-minbase-*.tar.part
  t0=$(date +%s)
  mmdebstrap --quiet --format=tar --variant=minbase --include="$INCLUDE" "$SUITE" "$tarball.part" "${sources[@]}"
  mv "$tarball.part" "$tarball"
  say "bare root built in $(( $(date +%s) - t0 )) s"
else
  say "bare root from the cache: $tarball"
fi

# release DIR: unmount everything below DIR (deepest first), then delete DIR only if nothing is mounted there any more.
release() {
  local dir=$1 m
  for m in $(findmnt -rn -o TARGET | grep "^$dir/" | sort -r); do
    umount "$m" 2>/dev/null || umount -l "$m" || true
  done
  if findmnt -rn -o TARGET | grep -q "^$dir/"; then
    echo "test-fresh: something is still mounted below $dir; leaving it in place (unmount it, then delete it)" >&2
    return 1
  fi
  rm -rf --one-file-system "$dir"
}
# A run killed outright (SIGKILL, a lost machine) cannot clean up after itself: the next run does it.
for old in /var/tmp/libdem-fresh.*; do
  [ -d "$old" ] || continue
  pid=$(cat "$old/pid" 2>/dev/null || echo 0)
  { [ -e "$old/kept" ] || kill -0 "$pid" 2>/dev/null; } && continue
  say "removing the root a killed run left: $old"
  release "$old" || exit 1
done

work=$(mktemp -d /var/tmp/libdem-fresh.XXXXXX)
echo $$ > "$work/pid"
root=$work/root
mounts=()
cleanup() {
  local rc=$?
  trap - EXIT INT TERM HUP
  if [ "${DEM_FRESH_KEEP:-0}" = 1 ]; then
    for (( i=${#mounts[@]}-1; i>=0; i-- )); do umount "${mounts[$i]}" 2>/dev/null || umount -l "${mounts[$i]}" || true; done
    touch "$work/kept"
    say "root kept at $root"
  else
    release "$work" || { [ "$rc" -eq 0 ] && rc=1; }
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

mkdir -p "$root"
tar -C "$root" -xf "$tarball"
cp -L /etc/resolv.conf "$root/etc/resolv.conf"
git clone -q --no-local "$SRC" "$root/root/libdem"
git -C "$root/root/libdem" checkout -q --detach "$(git -C "$SRC" rev-parse "$REV")"
say "cloned $(git -C "$root/root/libdem" log -1 --format='%h %s') into $root/root/libdem"

mount_in() { # mount_in TARGET mount-args...
  local target=$root$1; shift
  mkdir -p "$target"
  mount "$@" "$target"
  mounts+=("$target")
}
mount_in /proc -t proc proc
mount_in /sys -t sysfs sysfs
mount_in /dev --bind /dev
mount_in /dev/pts --bind /dev/pts

# As a new user on a bare machine: a clean environment, root, the README's commands verbatim.
in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    bash -c "cd /root/libdem && $1"
}
logdir=$work/logs
mkdir -p "$logdir"
step() { # step NAME COMMAND: runs it in the root, shows and keeps its output, reports its time
  local t0 rc=0
  say "== $2 (in the bare root)"
  t0=$(date +%s)
  in_root "$2" 2>&1 | tee "$logdir/$1.log" || rc=$?
  times+=("$2: $(( $(date +%s) - t0 )) s")
  if [ "$rc" -ne 0 ]; then echo "test-fresh: FAILED: '$2' exited $rc on the first try in a bare Debian 12 root" >&2; exit 1; fi
}
times=()
step run "make run"
for f in out/hydrogel_514.h5 out/hydrogel_514.png; do
  [ -s "$root/root/libdem/$f" ] || { echo "test-fresh: FAILED: make run left no $f" >&2; exit 1; }
done
step test "make test"
downloaded=$(grep -ho 'install-deps: downloading .*' "$logdir"/*.log | sed 's/install-deps: downloading //' | paste -sd';' || true)
say "passed: $(IFS=\;; echo "${times[*]}"); first run downloaded ${downloaded:-nothing}"
