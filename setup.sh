#!/bin/bash
# Set up impact3d on Debian 12: install the packages it needs (when missing),
# configure and build. Usage: ./setup.sh [--viz] [Release|Debug] [build-dir]
# (defaults: Release, ./build). Safe to run again: it only rebuilds.
# --viz also installs ParaView (paraview, python3-paraview) and xvfb, for the
# ParaView test (ctest -L viz; skipped without them) and offscreen pvbatch.
set -euo pipefail
cd "$(dirname "$0")"
viz=0
if [ "${1:-}" = "--viz" ]; then
  viz=1
  shift
fi
build_type=${1:-Release}
build_dir=${2:-build}

packages="gfortran gcc cmake make libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools
  libmetis-dev libptscotch-dev liblapack-dev numdiff python3 python3-numpy python3-h5py python3-matplotlib
  libexodusii-dev libnetcdf-dev python3-netcdf4 python3-meshio"
if [ "$viz" -eq 1 ]; then
  packages="$packages paraview python3-paraview xvfb xauth"
fi
missing=""
for p in $packages; do
  dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "setup: installing$missing"
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=""; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq $missing >/dev/null
fi

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
echo "setup: built $build_dir/impact3d ($build_type)"
