#!/usr/bin/env bash
# Installs what clothsim needs on Debian 12 (apt packages; skipped when all are present) and
# builds it in Release mode in ./build. Usage: scripts/setup.sh   (as root, or with sudo)
set -euo pipefail
cd "$(dirname "$0")/.."

# lld: LLVM's linker, which CMakeLists.txt uses instead of gold when present (an executable
# links in 1.3 s against 3.0 s).
# libmumps-dev: MUMPS' double- and single-precision libraries (solvers/mumps_factorization;
# Trilinos depends on it too). libopenblas0-serial: an optimised BLAS for MUMPS' dense kernels (Debian's alternatives
# pick it over the reference BLAS; factorisations twice as fast).
# paraview python3-paraview xvfb xauth: ParaView's pvbatch/pvpython for scripts/render.py
# and for the tests that read VTK files back (Debian's ParaView renders through X only:
# xvfb-run gives it a virtual display). ffmpeg: render.py's movie. gnuplot-nox: the plots
# of --compare, --convergence and --sweep. Not libvtk9-dev: it depends on python3-vtk9,
# which conflicts with python3-paraview (installing one removes the other).
packages=(cmake g++ make lld libdeal.ii-dev trilinos-all-dev libopenmpi-dev openmpi-bin gmsh
          libgmsh-dev zlib1g-dev libmumps-dev libmetis-dev libopenblas0-serial paraview python3-paraview xvfb xauth
          ffmpeg gnuplot-nox)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
