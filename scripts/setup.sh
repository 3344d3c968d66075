#!/usr/bin/env bash
# Installs the Debian 12 packages strainwave needs (only the missing ones, non-interactively) and builds it in
# Release mode under build/. Safe to run again: quick when everything is present.
#   setup.sh main   what the main job needs: the libraries of `strainwave` and that one target (scripts/run.sh)
#   setup.sh all    also the tests' and benches' packages (GoogleTest, PETSc/MPI, ParaView, Chromium, CalculiX) and
#                   every target (scripts/test.sh; the default)
# Prints how long the packages and the build took.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-all}
[[ $mode == main || $mode == all ]] || { echo "setup.sh: mode must be main or all, not '$mode'" >&2; exit 2; }
start=$SECONDS

packages=(g++ cmake make pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas-dev libopenblas0-pthread libtet1.5-dev libvtk9-dev
  libtomlplusplus-dev nlohmann-json3-dev libcli11-dev libfftw3-dev libsundials-dev libspectra-dev)
if [[ $mode == all ]]; then
  packages+=(libgtest-dev libpetsc-real-dev openmpi-bin paraview xvfb xauth chromium calculix-ccx)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# CHOLMOD's speed depends on the BLAS behind libblas.so.3: OpenBLAS, not Debian's reference BLAS.
if ! readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3 | grep -q openblas; then
  echo "setup: warning: libblas.so.3 is not OpenBLAS ($(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3)); CHOLMOD will be slow" >&2
fi

# ParaView's Python modules for pvbatch (scripts/pvbatch.sh, the tests of the views): Debian's python3-paraview
# conflicts with python3-vtk9, which libvtk9-dev needs, so it is unpacked privately instead of installed.
pv_dir=build/paraview-python
if [[ $mode == all && ! -d "$pv_dir/usr/lib/python3/dist-packages/paraview" ]]; then
  mkdir -p "$pv_dir"
  (cd "$pv_dir" && apt-get download python3-paraview >/dev/null 2>&1) || {
    sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
    $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    (cd "$pv_dir" && apt-get download python3-paraview >/dev/null)
  }
  dpkg -x "$pv_dir"/python3-paraview_*.deb "$pv_dir"
  rm -f "$pv_dir"/python3-paraview_*.deb
fi

packages_s=$((SECONDS - start))

# The main job's build leaves out the tests (GoogleTest may be missing) and PETSc; the whole build asks for both. A
# tree configured for the tests stays so when the main job is built in it.
if [[ $mode == all ]]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON -DSW_WITH_PETSC=ON >/dev/null
  cmake --build build -j"$(nproc)"
else
  testing=()
  [[ -f build/CMakeCache.txt ]] || testing=(-DBUILD_TESTING=OFF)
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${testing[@]}" >/dev/null
  cmake --build build -j"$(nproc)" --target strainwave
fi
echo "setup ($mode): packages ${packages_s} s, build $((SECONDS - start - packages_s)) s" >&2
