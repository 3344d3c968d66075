#!/usr/bin/env bash
# Sets everything up and runs the whole test suite (ctest). Each test runs its BLAS single-threaded, so two tests
# can share the two cores without collapsing each other.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh all
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 1500
