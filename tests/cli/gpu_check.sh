# scripts/gpu-check.sh where there is no GPU: it stops with one line and exit code 3, before
# building anything (no device node), and, asked to look through dampbound itself
# (--no-node-check, CUDA shown no device), with dampbound's reason.
. "$(dirname "$0")/lib.inc"

if ! compgen -G "/dev/nvidia[0-9]*" >/dev/null && ! command -v nvidia-smi >/dev/null; then
  expect_exit 3 bash "$SRC/scripts/gpu-check.sh" --build-dir "$WORK/build"
  expect_one_line "$OUT$ERR" "gpu-check without a GPU"
  expect_match "$OUT" '^gpu-check: no GPU on this machine' "gpu-check says why"
  [ ! -e "$WORK/build" ] && ok || bad "gpu-check built without a GPU"
fi
CUDA_VISIBLE_DEVICES="" expect_exit 3 bash "$SRC/scripts/gpu-check.sh" --dampbound "$DB" \
  --no-node-check --keep "$WORK/keep"
expect_one_line "$OUT$ERR" "gpu-check with no GPU for CUDA"
expect_match "$OUT" '^gpu-check: no GPU sweep here: .*(CUDA|GPU)' "gpu-check gives dampbound's reason"
expect_exit 2 bash "$SRC/scripts/gpu-check.sh" --bogus
expect_one_line "$ERR" "gpu-check --bogus"
finish
