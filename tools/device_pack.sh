#!/usr/bin/env bash
# device_pack.sh - packs what a lent GPU machine needs for tools/device_check.sh into .device/ (git-ignored), to be
# named in the device tool's `carry`. That machine has the NVIDIA driver but none of our Debian packages and no
# network, so the check runs the programs built here: dem, dem-bench and the test programs (stripped), with the
# shared libraries they load from this machine's Debian (HDF5, libcyaml, libyaml, the OpenCL ICD loader and theirs;
# not the C library, which the device's own serves: the binaries need GLIBC_2.35 at most - not yet seen there, no
# session has been lent a machine) and the poured bed of `make bench-peer` (gzipped) for make bench's bed table.
# About 35 MB; the working tree travels beside it.
#   tools/device_pack.sh            builds (make all), then packs
# Then, in a session that is lent a GPU (the device tool; tools/device_check.sh says what it runs):
#   run(command="bash tools/device_check.sh", carry=[".device"], timeout_s=600)
set -euo pipefail
cd "$(dirname "$0")/.."
make -s all >/dev/null
D=.device
rm -rf "$D"
mkdir -p "$D/build/tests" "$D/lib"
cp build/dem build/dem-bench "$D/build/"
for t in build/tests/test_*; do
  case "$t" in */test_mpi_*) continue ;; esac # the MPI layer's tests run under mpirun, in make test (not a device's)
  [ -x "$t" ] && cp "$t" "$D/build/tests/"
done
strip "$D/build/dem" "$D/build/dem-bench" "$D"/build/tests/*
# every library the programs load, but the C library's own (the device's serves them)
ldd "$D/build/dem" "$D/build/dem-bench" "$D"/build/tests/* | awk '$3 ~ /^\// { print $3 }' | sort -u |
  grep -Ev '/(libc|libm|libpthread|libdl|librt|libresolv|ld-linux-x86-64)\.so' |
  while read -r lib; do cp -L "$lib" "$D/lib/"; done
if [ -f out/peer/bed.csv ]; then
  gzip -c out/peer/bed.csv > "$D/bed.csv.gz"
else
  echo "device_pack: no out/peer/bed.csv (make bench-peer pours it): the check will skip the bed table" >&2
fi
git rev-parse HEAD > "$D/REV"
pwd > "$D/SOURCE_DIR" # the source folder the programs were built with (DEM_DEFAULT_SOURCE_DIR)
echo "device_pack: $(du -sh "$D" | cut -f1) in $D (commit $(cut -c1-7 "$D/REV"))" >&2
