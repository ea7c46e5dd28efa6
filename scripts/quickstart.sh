#!/usr/bin/env bash
# The first quick-start command: install, build, and open the interactive tuner on the
# paper's mesh (headless machines get the paper's reproduction instead).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec build/app/dampbound gui scenes/paper-plane.toml
else
  echo "no display: running the paper's protocol headless instead of the window"
  exec build/app/dampbound run scenes/paper-plane.toml
fi
