#!/usr/bin/env bash
# Sets everything up and runs the main job on the default case, the seed gear set's cup flexspline:
# `strainwave run cases/seed_190_192.toml`
# (or the case given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build/strainwave run "${1:-cases/seed_190_192.toml}"
