#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs every Debian 12 package runnel needs. Idempotent: does nothing when all are present.
set -euo pipefail

packages=(
  g++ cmake make pkg-config git
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libglm-dev libglfw3-dev libepoxy-dev libimgui-dev
  libnanoflann-dev libhdf5-dev libgtest-dev libgmock-dev libbenchmark-dev libpng-dev
  libtomlplusplus-dev libcli11-dev
  nlohmann-json3-dev  # runnel-viewer session logs (strokes.json) are read back: the standard C++ JSON parser
  ffmpeg  # runnel-viewer --record out.mp4 (H.264), and ffprobe counts its frames in the tests
  libgdal-dev gdal-bin  # GeoTIFF in and out; gdalinfo checks the georeferencing in the tests
  libudunits2-0  # the CF checker's units (cfunits loads UDUNITS-2): the NetCDF exports checked CF-valid
  libkissfft-dev  # spectral (inverse FFT) terrain synthesis: BSD-licensed, any grid size
  libopenmpi-dev openmpi-bin  # mpirun -np K runnel sweep (optional at build time)
  python3 python3-numpy python3-h5py
  python3-dev python3-venv pybind11-dev python3-pybind11 python3-pytest python3-matplotlib  # the Python package
  # ParaView (pvpython and its Python, whose VTK has the XDMF3 and PLY readers) and meshio: the tests
  # read the series and PLY outputs back with the readers users open them with. Not python3-vtk9,
  # which Debian's python3-paraview conflicts with: installing runnel must not remove ParaView.
  paraview python3-paraview python3-meshio
  xvfb xdotool x11-utils libgl1-mesa-dri
  libegl1 libegl-mesa0  # runnel-viewer --headless: EGL without a display (Mesa's surfaceless platform)
  clang-format
  clang libclang-rt-14-dev  # scripts/sanitize.sh: ASan + UBSan build and the libFuzzer targets
  clang-15  # PoCL's own compiler: the kernels compiled for x86 CPUs without AVX-512 (tests/compute/test_lanes.cpp)
  patchelf  # scripts/gpu-bundle.sh: the bundle's binaries find their libraries through an RPATH
  oclgrind  # scripts/oclgrind-check.sh (a CTest): every kernel access checked, data races found
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
