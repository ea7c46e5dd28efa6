#!/usr/bin/env bash
# Installs the rest of the dependencies (scripts/install-deps.sh), builds everything and runs
# every test: unit tests, CLI tests, headless EGL rendering (no DISPLAY
# needed) and the GUI under Xvfb (its test starts xvfb-run itself).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
unset DISPLAY
cd build && ctest --output-on-failure -j "$(nproc)"
