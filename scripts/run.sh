#!/usr/bin/env bash
# Sets up what the main job needs (setup.sh main: its packages, the one target) and runs the main job on the default
# case, the seed gear set's cup flexspline:
# `strainwave run cases/seed_190_192.toml`
# (or the case given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh main
start=$SECONDS
build/strainwave run "${1:-cases/seed_190_192.toml}"
echo "run.sh: the run ${1:-cases/seed_190_192.toml} took $((SECONDS - start)) s" >&2
