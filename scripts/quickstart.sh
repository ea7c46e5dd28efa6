#!/usr/bin/env bash
# The first quick-start command: install what the tuner needs, build the dampbound program
# alone (no tests, benchmarks or Python module: scripts/test.sh adds those), and open the
# tuner on the paper's mesh (headless machines get the paper's protocol instead).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --app
bash scripts/build.sh --app
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec build/app/dampbound gui scenes/paper-plane.toml
else
  echo "no display: running the paper's protocol headless instead of the window"
  exec build/app/dampbound run scenes/paper-plane.toml
fi
