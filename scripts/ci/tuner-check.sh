#!/usr/bin/env bash
# CI job: from the tuner to a check. Tunes the paper's mesh in the real window under Xvfb,
# pins two runs, saves the scene with what they measured, and checks it headless with
# `dampbound check`; then edits a parameter in the saved file and requires the check to fail.
# Also checks the committed walk-through scene scenes/paper-plane-tuned.toml.
# Run from the repository root; builds build/app/dampbound when it is missing.
set -euo pipefail
cd "$(dirname "$0")/../.."
start=$(date +%s)
DB=build/app/dampbound
if [ ! -x "$DB" ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBOUND_WERROR=ON >/dev/null
  cmake --build build -j "$(nproc)" --target dampbound
fi
command -v xvfb-run >/dev/null || { echo "tuner-check: FAIL: xvfb-run is not installed"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY

echo "== tune, pin two runs, save (the real window under Xvfb)"
xvfb-run -a -s "-screen 0 1600x1000x24 -noreset" "$DB" gui scenes/paper-plane.toml \
  --gamma 0.0015 --pin gamma=0.0005,name=under --pin gamma=0.002,name=at \
  --frames 5 --size 1024x640 --save-scene "$tmp/tuned.toml" --config-dir "$tmp/config"

echo "== check the saved scene"
"$DB" check "$tmp/tuned.toml" --junit "$tmp/tuned.xml"

echo "== check the committed walk-through scene"
"$DB" check scenes/paper-plane-tuned.toml

echo "== an edited parameter must fail the check"
sed 's/^gamma = 0.0005$/gamma = 0.0009/' "$tmp/tuned.toml" >"$tmp/edited.toml"
if cmp -s "$tmp/tuned.toml" "$tmp/edited.toml"; then
  echo "tuner-check: FAIL: the edit found nothing to change"
  exit 1
fi
set +e
"$DB" check "$tmp/edited.toml"
rc=$?
set -e
if [ "$rc" -ne 1 ]; then
  echo "tuner-check: FAIL: the edited scene's check exited $rc, wanted 1"
  exit 1
fi
echo "tuner-check: OK (saved scene passes, edited scene fails) in $(( $(date +%s) - start )) s"
