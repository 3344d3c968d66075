#!/usr/bin/env bash
# Runs ParaView's pvbatch headless with its Python modules. Debian 12's python3-paraview conflicts with python3-vtk9
# (which libvtk9-dev needs), so it is not installed: scripts/setup.sh unpacks it into build/paraview-python instead.
# Usage: scripts/pvbatch.sh SCRIPT.py [ARGS...]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
pydir="$here/build/paraview-python/usr/lib/python3/dist-packages"
if [ ! -d "$pydir/paraview" ] || ! command -v pvbatch >/dev/null || ! command -v xvfb-run >/dev/null; then
  echo "pvbatch.sh: ParaView is not set up; run scripts/setup.sh (it installs paraview and xvfb)" >&2
  exit 2
fi
# xvfb-run -a races when two start at once (both take the same display, one aborts with "bad X server connection"):
# one X server at a time, across processes, by a lock.
PYTHONPATH="$pydir${PYTHONPATH:+:$PYTHONPATH}" exec flock "${TMPDIR:-/tmp}/strainwave-pvbatch.lock" \
  xvfb-run -a pvbatch "$@"
