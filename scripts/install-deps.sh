#!/usr/bin/env bash
# Installs the Debian packages this project builds and tests with, if any are missing.
# Called by the Makefile (target `deps`); safe to run again: it does nothing when all are present.
# With --paraview it also installs ParaView and pvpython (make test-paraview).
set -euo pipefail

PKGS=(
  build-essential pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers clinfo   # OpenCL: PoCL CPU device + ICD loader
  libhdf5-dev hdf5-tools                                      # HDF5 output
  libcmocka-dev                                               # test framework
  libcyaml-dev libyaml-dev                                    # scene files (YAML -> C structs)
  python3-h5py python3-matplotlib                             # tools/plot_series.py, tests/xdmf_check.py
  clang libclang-rt-14-dev                                    # make fuzz (libFuzzer, sanitizers)
)
# ParaView (about 440 MB) only for `make test-paraview`
if [ "${1:-}" = "--paraview" ]; then
  PKGS+=(paraview python3-paraview)
fi

missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
