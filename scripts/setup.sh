#!/usr/bin/env bash
# Install cracklip's Debian 12 packages when missing, make OpenBLAS the
# system BLAS/LAPACK (PETSc and MUMPS link libblas.so.3 / liblapack.so.3,
# which Debian resolves through its alternatives; the default is the slow
# netlib reference build), then build (CMake).
# Idempotent: a second run installs nothing, changes no alternative and
# rebuilds only what changed. Works as root or through sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES="build-essential cmake pkg-config python3-dolfinx libdolfinx-dev python3-basix
python3-ufl python3-ffcx python3-petsc4py python3-slepc4py libslepc-real-dev pybind11-dev
python3-pybind11 python3-gmsh python3-meshio python3-pytest python3-scipy python3-matplotlib
libgtest-dev libopenblas0-pthread openmpi-bin"

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"

missing=""
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "cracklip setup: installing$missing" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

# OpenBLAS for libblas.so.3 and liblapack.so.3 (the package registers these
# alternatives at a higher priority; a system set to manual mode, or one where
# the priority lost, is switched explicitly; nothing happens when already set).
arch="$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)"
for lib in libblas.so.3 liblapack.so.3; do
  name="$lib-$arch"
  want="/usr/lib/$arch/openblas-pthread/$lib"
  [ -e "$want" ] || { echo "cracklip setup: $want missing after installing libopenblas0-pthread" >&2; exit 1; }
  if [ "$(readlink -f "/etc/alternatives/$name" 2>/dev/null)" != "$(readlink -f "$want")" ]; then
    echo "cracklip setup: $lib -> $want" >&2
    $SUDO update-alternatives --quiet --set "$name" "$want"
  fi
done

cmake -S . -B build -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
echo "cracklip setup: built python/cracklip/_cracklip module and C++ tests" >&2
