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
# One X server at a time, across processes (a lock), with a 24-bit screen for OpenGL. Under load Xvfb sometimes is
# not ready when pvbatch connects ("bad X server connection", SIGABRT, seen in CI): that case alone is retried.
# flock -o: the lock stays with flock itself, not with the command's children; an Xvfb that outlived its xvfb-run
# (seen once in a CI run: left behind holding the inherited lock, it stalled every later render) cannot hold it.
export PYTHONPATH="$pydir${PYTHONPATH:+:$PYTHONPATH}"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3 4; do
  set +e
  flock -o "${TMPDIR:-/tmp}/strainwave-pvbatch.lock" xvfb-run -a -s "-screen 0 1600x1200x24" pvbatch "$@" 2> >(tee "$log" >&2)
  rc=$?
  set -e
  wait  # the tee of stderr
  grep -q "bad X server connection" "$log" || exit $rc
  echo "pvbatch.sh: the X server was not ready (attempt $attempt); retrying" >&2
  sleep 2
done
exit $rc
