#!/usr/bin/env bash
# install_check.sh - `make install` into a scratch prefix, then, against that copy and from another folder:
#  - the README's library example ("Using the library"), compiled with nothing but `pkg-config --cflags --libs libdem`
#    (the shared library), must build and run silently (it prints only when dem_start or dem_step fails, e.g. when the
#    installed library cannot find its kernel sources);
#  - tests/install_check.cpp, compiled by g++ with the shared library and again with the static one
#    (`pkg-config --static`), must build with -Wall -Wextra -pedantic -Werror and run; the first must need
#    libdem.so.MAJOR (the soname), the second no libdem.so at all;
#  - each library must define, as global symbols, exactly the functions the installed headers declare (the shared
#    one as its dynamic symbols, nm -D); dem_debug.h and the internal bits' header must not be installed.
#  - the Python package (python/libdem), copied beside them, loads the installed libdem.so and steps a run.
#  - libdem_mpi.so (libdem with its MPI layer) exports exactly dem.h's and dem_mpi.h's functions, and
#    tests/install_check_mpi.c, built with `pkg-config --cflags --libs libdem-mpi` alone, runs split over 2 ranks
#    with one process's bits.
# Also checks that DESTDIR stages every file under it. Run by `make test`.
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
P="$T/prefix"
fail() { echo "install_check: $*"; exit 1; }
# the Python that runs the installed package below, and whose version names the install's dist-packages folder
python=$("$ROOT/scripts/find_python.sh" 2>&1) || fail "$python"
make -s -C "$ROOT" install PREFIX="$P" PYTHON="$python" > "$T/install.log" 2>&1 || { cat "$T/install.log"; exit 1; }

# the installed files: both libraries, the soname's links, the public headers and only those
VERSION=$(sed -n 's/^#define DEM_VERSION "\(.*\)"/\1/p' "$ROOT/include/dem.h")
SONAME=libdem.so.${VERSION%%.*}
for f in lib/libdem.a "lib/libdem.so.$VERSION" lib/pkgconfig/libdem.pc include/dem.h include/dem_effects.h \
         include/dem_membrane.h include/dem_press.h; do
    [ -f "$P/$f" ] || fail "the install lacks $f"
done
[ "$(readlink "$P/lib/$SONAME")" = "libdem.so.$VERSION" ] || fail "lib/$SONAME does not link to libdem.so.$VERSION"
[ "$(readlink "$P/lib/libdem.so")" = "$SONAME" ] || fail "lib/libdem.so does not link to $SONAME"
readelf -d "$P/lib/libdem.so.$VERSION" | grep -q "(SONAME).*\[$SONAME\]" || fail "libdem.so.$VERSION has no soname $SONAME"
for f in include/dem_debug.h include/dem_internal_bits.h; do
    [ ! -e "$P/$f" ] || fail "$f is installed: it is internal"
done

# what the libraries export: the functions the installed headers declare, no more and no fewer (gcc's -aux-info
# writes every declaration with the header it came from)
echo '#include <dem.h>' | cc -std=c11 -fsyntax-only -aux-info "$T/decl.txt" -I"$P/include" -x c -
grep -F "/* $P/include/" "$T/decl.txt" | sed -n 's/.*[ *]\(dem_[a-z0-9_]*\) (.*/\1/p' | sort -u > "$T/declared.txt"
[ "$(wc -l < "$T/declared.txt")" -ge 90 ] || fail "only $(wc -l < "$T/declared.txt") functions found in the headers"
nm -D --defined-only "$P/lib/libdem.so.$VERSION" | awk '{print $NF}' | sort -u > "$T/shared.txt"
nm -g --defined-only "$P/lib/libdem.a" | awk 'NF == 3 {print $3}' | sort -u > "$T/static.txt"
for lib in shared static; do
    if ! diff "$T/declared.txt" "$T/$lib.txt" > "$T/$lib.diff"; then
        sed -n 's/^> /  exported, not declared: /p; s/^< /  declared, not exported: /p' "$T/$lib.diff" | head -20
        fail "the $lib library's global symbols are not the public headers' functions"
    fi
done
nexp=$(wc -l < "$T/shared.txt")

export PKG_CONFIG_PATH="$P/lib/pkgconfig"
cflags=$(pkg-config --cflags libdem)
libs=$(pkg-config --libs libdem)
slibs=$(pkg-config --static --libs libdem)
case " $slibs " in *" -lOpenCL "*) ;; *) fail "pkg-config --static --libs gives no -lOpenCL: $slibs" ;; esac
mkdir "$T/elsewhere"

# the README example (C, the shared library; run from another folder, without DEM_SOURCE_DIR)
awk '/^## Using the library/ {f = 1} f && /^```c$/ {c = 1; next} c && /^```$/ {exit} c {print}' "$ROOT/README.md" \
    > "$T/example_body.c"
[ -s "$T/example_body.c" ] || fail "no C example found in README.md"
{ echo '#include <stdio.h>'; grep '^#include' "$T/example_body.c"; echo 'int main(void) {';
  grep -v '^#include' "$T/example_body.c"; echo 'return 0; }'; } > "$T/example.c"
cc -std=c11 "$T/example.c" $cflags $libs -Wl,-rpath,"$P/lib" -o "$T/example" 2> "$T/cc.log" ||
    { cat "$T/cc.log"; fail "the README example does not compile with: $cflags $libs"; }
(cd "$T/elsewhere" && env -u DEM_SOURCE_DIR "$T/example" > "$T/out.log" 2>&1) ||
    { cat "$T/out.log"; fail "the README example failed"; }
[ ! -s "$T/out.log" ] || { cat "$T/out.log"; fail "the README example reported an error"; }

# the C++ program, shared and static
CXXFLAGS="-std=c++11 -Wall -Wextra -pedantic -Werror"
g++ $CXXFLAGS "$ROOT/tests/install_check.cpp" $cflags $libs -Wl,-rpath,"$P/lib" -o "$T/cpp_shared" 2> "$T/cxx.log" ||
    { cat "$T/cxx.log"; fail "the C++ program does not build against the shared library ($cflags $libs)"; }
g++ $CXXFLAGS "$ROOT/tests/install_check.cpp" $cflags ${slibs/-ldem/-Wl,-Bstatic -ldem -Wl,-Bdynamic} \
    -o "$T/cpp_static" 2> "$T/cxx.log" ||
    { cat "$T/cxx.log"; fail "the C++ program does not build against the static library ($cflags $slibs)"; }
readelf -d "$T/cpp_shared" | grep -q "(NEEDED).*\[$SONAME\]" || fail "the shared build does not need $SONAME"
! readelf -d "$T/cpp_static" | grep -q "(NEEDED).*libdem" || fail "the static build needs a shared libdem"
for v in shared static; do
    (cd "$T/elsewhere" && env -u DEM_SOURCE_DIR "$T/cpp_$v" > "$T/cpp_$v.log" 2>&1) ||
        { cat "$T/cpp_$v.log"; fail "the C++ program ($v) failed"; }
done
cmp -s "$T/cpp_shared.log" "$T/cpp_static.log" || { cat "$T"/cpp_*.log; fail "the two C++ builds printed differently"; }

# the Python package: copied into PREFIX's dist-packages with a link to the installed libdem.so, which libdem.sim
# loads (run from another folder, the tree out of sight)
pysite=$(echo "$P"/lib/python3*/dist-packages)
[ -f "$pysite/libdem/__init__.py" ] && [ -f "$pysite/libdem/sim.py" ] || fail "the install lacks the Python package"
[ "$(readlink "$pysite/libdem/libdem.so")" = "$P/lib/$SONAME" ] || fail "the Python package's libdem.so is no link to $SONAME"
(cd "$T/elsewhere" && env -u DEM_SOURCE_DIR -u LIBDEM_PATH PYTHONPATH="$pysite" "$python" -c "
import libdem, libdem.sim as m
assert libdem.__file__.startswith('$pysite/'), libdem.__file__
assert m.library_path() == '$pysite/libdem/libdem.so', m.library_path()
with m.Sim() as s:
    g = s.add_material(density=1000, young=1e7, poisson=0.3, restitution=0.5, friction=0.3)
    s.add_particles([[0, 0, 0]], radius=0.001, material=g, v=[[0, 0, 0.1]])
    s.set_domain([-0.01] * 3, [0.01] * 3); s.set_dt(1e-6); s.start(backend='reference'); s.step(10)
    assert abs(s.get('x')[0, 2] - 1e-6) < 1e-18, s.get('x')
" > "$T/py.log" 2>&1) || { cat "$T/py.log"; fail "the installed Python package does not run the installed library"; }

# the MPI library: its files, its exports (dem.h's and dem_mpi.h's functions), a program split over 2 ranks
MPI_SONAME=libdem_mpi.so.${VERSION%%.*}
for f in "lib/libdem_mpi.so.$VERSION" lib/pkgconfig/libdem-mpi.pc include/dem_mpi.h; do
    [ -f "$P/$f" ] || fail "the install lacks $f"
done
[ "$(readlink "$P/lib/$MPI_SONAME")" = "libdem_mpi.so.$VERSION" ] || fail "lib/$MPI_SONAME does not link to libdem_mpi.so.$VERSION"
mcflags=$(pkg-config --cflags libdem-mpi) && mlibs=$(pkg-config --libs libdem-mpi) || fail "pkg-config knows no libdem-mpi"
echo '#include <dem_mpi.h>' | cc -std=c11 -fsyntax-only -aux-info "$T/mdecl.txt" $mcflags -x c -
grep -F "/* $P/include/" "$T/mdecl.txt" | sed -n 's/.*[ *]\(dem_[a-z0-9_]*\) (.*/\1/p' | sort -u > "$T/mdeclared.txt"
grep -qx dem_create_mpi "$T/mdeclared.txt" || fail "dem_mpi.h declares no dem_create_mpi"
nm -D --defined-only "$P/lib/libdem_mpi.so.$VERSION" | awk '{print $NF}' | sort -u > "$T/mpi.txt"
if ! diff "$T/mdeclared.txt" "$T/mpi.txt" > "$T/mpi.diff"; then
    sed -n 's/^> /  exported, not declared: /p; s/^< /  declared, not exported: /p' "$T/mpi.diff" | head -20
    fail "libdem_mpi.so's global symbols are not the public headers' functions"
fi
cc -std=c11 -Wall -Wextra -Werror "$ROOT/tests/install_check_mpi.c" $mcflags $mlibs -Wl,-rpath,"$P/lib" \
    -o "$T/mpi_prog" 2> "$T/mcc.log" || { cat "$T/mcc.log"; fail "the MPI program does not build with: $mcflags $mlibs"; }
readelf -d "$T/mpi_prog" | grep -q "(NEEDED).*\[$MPI_SONAME\]" || fail "the MPI program does not need $MPI_SONAME"
! readelf -d "$T/mpi_prog" | grep -q "(NEEDED).*\[$SONAME\]" || fail "the MPI program needs libdem as well as libdem_mpi"
(cd "$T/elsewhere" && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 300 \
    mpirun -np 2 --oversubscribe --bind-to none "$T/mpi_prog" > "$T/mpi.log" 2>&1) ||
    { cat "$T/mpi.log"; fail "the MPI program failed against the installed libdem_mpi"; }

# DESTDIR: everything under the staging root, nothing elsewhere
make -s -C "$ROOT" install PREFIX=/opt/libdem-check DESTDIR="$T/stage" PYTHON="$python" > "$T/stage.log" 2>&1 || { cat "$T/stage.log"; exit 1; }
for f in lib/libdem.a "lib/libdem.so.$VERSION" "lib/$SONAME" lib/libdem.so lib/pkgconfig/libdem.pc include/dem.h \
         "lib/libdem_mpi.so.$VERSION" "lib/$MPI_SONAME" lib/libdem_mpi.so lib/pkgconfig/libdem-mpi.pc include/dem_mpi.h \
         include/dem_effects.h include/dem_membrane.h include/dem_press.h share/libdem/kernels/program.cl \
         share/libdem/common/dem_kernels.h share/libdem/common/laws/laws.h share/libdem/common/dem_internal_bits.h share/libdem/include/dem_effects.h; do
    [ -e "$T/stage/opt/libdem-check/$f" ] || fail "DESTDIR install lacks $f"
done
stsite=$(echo "$T"/stage/opt/libdem-check/lib/python3*/dist-packages)
[ -f "$stsite/libdem/output.py" ] || fail "DESTDIR install lacks the Python package"
[ "$(readlink "$stsite/libdem/libdem.so")" = "/opt/libdem-check/lib/$SONAME" ] || fail "the staged package's libdem.so link is not the final path"
[ ! -e /opt/libdem-check ] || fail "DESTDIR install wrote outside the staging root"
grep -q '^prefix=/opt/libdem-check$' "$T/stage/opt/libdem-check/lib/pkgconfig/libdem.pc"
echo "install_check: the README example (C, shared) and a C++ program (shared and static) build with pkg-config and"
echo "  run against the installed copy; both libraries export exactly the $nexp functions of the public headers;"
echo "  libdem_mpi.so exports those and dem_create_mpi ($(wc -l < "$T/mpi.txt"))"
cat "$T/cpp_shared.log" "$T/mpi.log"
