#!/usr/bin/env bash
# Installs whatever touchdown needs that is missing (Debian 12 packages), then configures and builds.
# Idempotent: a second run installs nothing and rebuilds only what changed.
#   scripts/setup.sh [BUILD_DIR] [extra cmake arguments...]
# Every script that builds goes through here with the same configuration: RelWithDebInfo and
# warnings as errors (-DTD_WERROR=ON, the project's rule). So build/ keeps one configuration
# whichever script configured it last (scripts/quickstart.sh, then scripts/test.sh, rebuilds
# nothing). Extra arguments come after these and win (-DTD_WERROR=OFF to turn it off).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$here/build}
shift || true

packages=(gcc make cmake pkg-config libsundials-dev libsuitesparse-dev libgsl-dev libhdf5-dev
          libcmocka-dev libconfig-dev gnuplot-nox
          zlib1g-dev                                 # the sweep journal's CRC-32 (the tool)
          libzip-dev                                 # touchdown fmu writes the FMU's zip archive
          libslicot-dev                              # control-system numerics (lib/control)
          openmpi-bin libopenmpi-dev                 # touchdown sweep across nodes (optional: TD_MPI)
          hdf5-tools python3 python3-h5py python3-scipy python3-venv clang-format)  # test-only: h5dump
                                            # reads HDF5 flags, python3 (with h5py) checks JSON and
                                            # HDF5 files, scipy.signal is the controllers' reference,
                                            # python3-venv holds the FMU importer of the tests (fmpy,
                                            # tests/fmu/requirements.txt), clang-format checks the layout

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done

if ((${#missing[@]})); then
    echo "setup: installing ${missing[*]}" >&2
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
        sudo=sudo
    fi
    export DEBIAN_FRONTEND=noninteractive
    $sudo apt-get update -qq
    $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTD_WERROR=ON "$@" >/dev/null
cmake --build "$build" --parallel "$(nproc)"
