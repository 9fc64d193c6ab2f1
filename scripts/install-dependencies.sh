#!/usr/bin/env bash
# Installs the Debian 12 packages cbc3d needs to build, test and run (as root).
# ParaView 5.11's SDK (paraview-dev) does not pull every -dev package its CMake
# config looks for; the list below is what find_package(ParaView) needs here.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive

packages=(
  # toolchain and test tools
  build-essential cmake git pkg-config googletest libgtest-dev xvfb xauth
  # ParaView 5.11 SDK (brings VTK 9.2) and Python for pvpython tests
  paraview paraview-dev python3-paraview python3-numpy
  # FE clients and converters the mesh tests hand meshes to; scipy cross-checks the checker
  python3-dolfinx-real python3-meshio python3-gmsh python3-netcdf4 python3-scipy
  # the sanitizer job (scripts/sanitizer-job.sh): clang with its ASan, UBSan and libFuzzer
  # runtimes, clang's OpenMP, and llvm-symbolizer for readable reports
  clang libclang-rt-14-dev libomp-14-dev llvm
  # core dependencies (serial HDF5 for the .xdmf's .h5; libnetcdf-dev, for .exo, is below;
  # libdeflate for the NIfTI reader's .nii.gz)
  libeigen3-dev libhdf5-dev libdeflate-dev
  # packages ParaView's CMake config requires at configure time
  qtbase5-dev qttools5-dev libqt5svg5-dev libqt5x11extras5-dev
  qtxmlpatterns5-dev-tools libqt5opengl5-dev libutfcpp-dev
  libhdf5-openmpi-dev libopenmpi-dev libogg-dev libtheora-dev libnetcdf-dev
  libgdal-dev libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  libprotobuf-dev protobuf-compiler libjsoncpp-dev liblz4-dev libxml2-dev
  libexpat1-dev libfreetype-dev libglew-dev libgl2ps-dev libpugixml-dev
  libdouble-conversion-dev libtiff-dev libpng-dev libjpeg-dev zlib1g-dev
  libsqlite3-dev libproj-dev libcgns-dev liblzma-dev libfmt-dev
  nlohmann-json3-dev libboost-dev libtbb-dev libgl-dev libx11-dev libxt-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "cbc3d: all ${#packages[@]} packages already installed"
  exit 0
fi
echo "cbc3d: installing ${#missing[@]} packages: ${missing[*]}"
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "cbc3d: packages installed"
