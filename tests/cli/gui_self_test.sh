# dampbound gui --self-test under Xvfb: every widget of paper-plane operated, the cut tool
# clicked and a cut dragged across the mesh (clicking "Cut tool" once aborted the tuner: a
# style colour popped that was never pushed), then a short seeded monkey. Exit 0: no abort, no
# hang. The Suggest tab's stiffness ceiling and Rayleigh pair are computed and both their apply
# buttons operated. The full run (every shipped scene, 1000 events on two) is
# scripts/ci/tuner-selftest.sh.
. "$(dirname "$0")/lib.inc"

if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIP: xvfb-run is not installed"
  exit 0
fi
expect_exit 0 xvfb-run -a -s "-screen 0 1280x800x24" "$DB" gui --self-test \
  --self-test-scenes paper-plane --monkey-scenes paper-plane --monkey-events 150 \
  --monkey-seed 7 --size 1024x640
expect_match "$OUT" "button 'Cut tool###cut_tool' in Mesh view" "the cut tool clicked"
expect_match "$OUT" "canvas 'mesh_view' in Mesh view" "the mesh dragged (a cut)"
expect_match "$OUT" "button 'Ceiling and pair' in Runs" "the stiffness ceiling and Rayleigh pair computed"
expect_match "$OUT" "button 'apply kappa = [0-9.e+-]+##ceiling' in Runs" "the ceiling's apply button"
expect_match "$OUT" "button 'apply alpha, beta' in Runs" "the Rayleigh pair's apply button"
expect_match "$OUT" "monkey: 150 input events" "the monkey's events"
expect_match "$OUT" "self-test: OK" "the OK line"
expect_exit 2 "$DB" gui --self-test --frames 3
expect_match "$ERR" "--self-test runs until it is done" "--self-test with --frames"
finish
