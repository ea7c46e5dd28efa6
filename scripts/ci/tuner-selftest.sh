#!/usr/bin/env bash
# CI job: the tuner survives a person. Under Xvfb, `dampbound gui --self-test` operates every
# widget (tabs, buttons, checkboxes, combos and an entry of each, sliders, text and number
# fields, the cut tool with a cut dragged across the mesh, drags on the mesh and the plots) on
# every shipped scene, then a seeded random monkey of 1000 input events on paper-plane and on
# tissue-block (two processes at once). Fails on an abort, a hang (a frame over 60 s) or a
# non-zero exit; prints the widgets visited and the monkey's seed.
set -euo pipefail
cd "$(dirname "$0")/../.."
start=$(date +%s)
DB=build/app/dampbound
if [ ! -x "$DB" ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBOUND_WERROR=ON >/dev/null
  cmake --build build -j "$(nproc)" --target dampbound
fi
command -v xvfb-run >/dev/null || { echo "tuner-selftest: FAIL: xvfb-run is not installed"; exit 1; }
unset DISPLAY
seed=${DAMPBOUND_MONKEY_SEED:-20261128}
# Two windows side by side (each under its own Xvfb): the widgets of every scene with the
# monkey on paper-plane, and the monkey on tissue-block (with the widgets of one small scene).
run_one() {
  timeout 900 xvfb-run -a -s "-screen 0 1280x800x24 -noreset" "$DB" gui --self-test \
    --monkey-events 1000 --monkey-seed "$seed" --size 1024x640 "$@"
}
log_b=$(mktemp)
run_one --self-test-scenes two-node --monkey-scenes tissue-block >"$log_b" 2>&1 &
pid_b=$!
sleep 3  # xvfb-run -a picks a free display by its lock file: let the first one take its own
set +e
run_one --monkey-scenes paper-plane
rc=$?
wait "$pid_b"
rc_b=$?
set -e
sed 's/^/[tissue-block] /' "$log_b"
rm -f "$log_b"
if [ "$rc" -ne 0 ] || [ "$rc_b" -ne 0 ]; then
  echo "tuner-selftest: FAIL: gui --self-test exited $rc and $rc_b (seed $seed)"
  exit 1
fi
echo "tuner-selftest: OK in $(( $(date +%s) - start )) s"
