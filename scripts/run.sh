#!/usr/bin/env bash
# Sets everything up and runs the main job on the default case: `strainwave run cases/tube_torsion.toml`
# (or the case given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build/strainwave run "${1:-cases/tube_torsion.toml}"
