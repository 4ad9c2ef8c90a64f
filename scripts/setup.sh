#!/usr/bin/env bash
# Install cracklip's Debian 12 packages when missing, then build (CMake).
# Idempotent: a second run installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES="build-essential cmake pkg-config python3-dolfinx libdolfinx-dev python3-basix
python3-ufl python3-ffcx python3-petsc4py python3-slepc4py libslepc-real-dev pybind11-dev
python3-pybind11 python3-gmsh python3-meshio python3-pytest python3-scipy python3-matplotlib
libgtest-dev"

missing=""
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "cracklip setup: installing$missing" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

cmake -S . -B build -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
echo "cracklip setup: built python/cracklip/_cracklip module and C++ tests" >&2
