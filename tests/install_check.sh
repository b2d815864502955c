#!/usr/bin/env bash
# install_check.sh - `make install` into a scratch prefix, then the README's library example ("Using the library"),
# compiled with nothing but `pkg-config --cflags --libs libdem` against that copy and run from another folder: it
# must build, and run silently (it prints only when dem_start or dem_step fails, e.g. when the installed library
# cannot find its kernel sources). Also checks that DESTDIR stages every file under it. Run by `make test`.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
make -s -C "$ROOT" install PREFIX="$T/prefix" > "$T/install.log" 2>&1 || { cat "$T/install.log"; exit 1; }
# the example: the first C block after the "Using the library" heading
awk '/^## Using the library/ {f = 1} f && /^```c$/ {c = 1; next} c && /^```$/ {exit} c {print}' "$ROOT/README.md" \
    > "$T/example_body.c"
[ -s "$T/example_body.c" ] || { echo "install_check: no C example found in README.md"; exit 1; }
{ echo '#include <stdio.h>'; grep '^#include' "$T/example_body.c"; echo 'int main(void) {';
  grep -v '^#include' "$T/example_body.c"; echo 'return 0; }'; } > "$T/example.c"
export PKG_CONFIG_PATH="$T/prefix/lib/pkgconfig"
flags=$(pkg-config --cflags --libs libdem)
cc -std=c11 "$T/example.c" $flags -o "$T/example" 2> "$T/cc.log" || { cat "$T/cc.log"; echo "install_check: the README example does not compile with: $flags"; exit 1; }
mkdir "$T/elsewhere" && cd "$T/elsewhere"
env -u DEM_SOURCE_DIR "$T/example" > "$T/out.log" 2>&1 || { cat "$T/out.log"; echo "install_check: the example failed"; exit 1; }
[ ! -s "$T/out.log" ] || { cat "$T/out.log"; echo "install_check: the example reported an error"; exit 1; }
# DESTDIR: everything under the staging root, nothing elsewhere
make -s -C "$ROOT" install PREFIX=/opt/libdem-check DESTDIR="$T/stage" > "$T/stage.log" 2>&1 || { cat "$T/stage.log"; exit 1; }
for f in lib/libdem.a lib/pkgconfig/libdem.pc include/dem.h include/dem_effects.h share/libdem/kernels/program.cl \
         share/libdem/common/dem_kernels.h share/libdem/include/dem_effects.h; do
    [ -f "$T/stage/opt/libdem-check/$f" ] || { echo "install_check: DESTDIR install lacks $f"; exit 1; }
done
[ ! -e /opt/libdem-check ] || { echo "install_check: DESTDIR install wrote outside the staging root"; exit 1; }
grep -q '^prefix=/opt/libdem-check$' "$T/stage/opt/libdem-check/lib/pkgconfig/libdem.pc"
echo "install_check: the README example builds with pkg-config and runs against the installed copy ($flags)"
