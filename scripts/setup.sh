#!/usr/bin/env bash
# Installs the Debian 12 packages strainwave needs (only the missing ones, non-interactively) and builds it in
# Release mode under build/. Safe to run again: quick when everything is present.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake make pkg-config
  libeigen3-dev libsuitesparse-dev libopenblas-dev libopenblas0-pthread libtet1.5-dev libvtk9-dev libgtest-dev
  libtomlplusplus-dev nlohmann-json3-dev libcli11-dev libfftw3-dev libsundials-dev libpetsc-real-dev openmpi-bin
  paraview xvfb xauth chromium calculix-ccx)
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

# ParaView's Python modules for pvbatch (scripts/pvbatch.sh): Debian's python3-paraview conflicts with python3-vtk9,
# which libvtk9-dev needs, so it is unpacked privately instead of installed.
pv_dir=build/paraview-python
if [ ! -d "$pv_dir/usr/lib/python3/dist-packages/paraview" ]; then
  mkdir -p "$pv_dir"
  (cd "$pv_dir" && apt-get download python3-paraview >/dev/null 2>&1) || {
    sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
    $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get update -qq
    (cd "$pv_dir" && apt-get download python3-paraview >/dev/null)
  }
  dpkg -x "$pv_dir"/python3-paraview_*.deb "$pv_dir"
  rm -f "$pv_dir"/python3-paraview_*.deb
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
