#!/usr/bin/env bash
# Configures and builds dampbound in build/ (Release, warnings as errors).
#   build.sh --app   the dampbound program only (what scripts/install-deps.sh --app allows)
#   build.sh         everything: tests, benchmarks, the Python module
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  --app)
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBOUND_WERROR=ON \
      -DDAMPBOUND_TESTS=OFF -DDAMPBOUND_BENCH=OFF -DDAMPBOUND_PYTHON=OFF >/dev/null
    cmake --build build -j "$(nproc)" --target dampbound ;;
  "")
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBOUND_WERROR=ON \
      -DDAMPBOUND_TESTS=ON -DDAMPBOUND_BENCH=ON -DDAMPBOUND_PYTHON=ON >/dev/null
    cmake --build build -j "$(nproc)" ;;
  *) echo "build.sh: unknown option '$1' (use --app, or nothing for everything)" >&2; exit 2 ;;
esac
