#!/usr/bin/env bash
# Builds and runs every test: unit tests, CLI tests, headless EGL rendering (no DISPLAY
# needed) and the GUI under Xvfb (its test starts xvfb-run itself).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
unset DISPLAY
cd build && ctest --output-on-failure -j "$(nproc)"
