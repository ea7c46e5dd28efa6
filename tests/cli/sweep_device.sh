# sweep --device: cpu is the default; without a usable GPU, gpu says why in one line and exits
# 2 leaving no file, auto runs on the CPU and says so; with a GPU both write the CPU's bytes.
# Shards and merge work the same whichever device ran (the runner's resume through a device:
# tests/core/sweep/device_test.cpp).
. "$(dirname "$0")/lib.inc"

GRID=(--m 0.001:0.004:0.001 --kappa 0.001:0.004:0.001 --zeta 0.5,1 --max-iter 80
      --progress none)
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/cpu.csv"
expect_match "$OUT" 'batched kernel' "the CPU's time line"
expect_exit 0 "$DB" sweep "${GRID[@]}" --device cpu -o "$WORK/cpu2.csv"
cmp -s "$WORK/cpu.csv" "$WORK/cpu2.csv" && ok || bad "--device cpu differs from the default"

"$DB" sweep "${GRID[@]}" --device gpu -o "$WORK/gpu.csv" >"$WORK/out" 2>"$WORK/err"
code=$?
if [ "$code" -eq 2 ]; then
  # No GPU here (or a build without CUDA): one line naming the flag, no output.
  ERR=$(cat "$WORK/err")
  expect_one_line "$ERR" "--device gpu without a GPU"
  expect_match "$ERR" '^dampbound: (error: )?--device gpu: .*(CUDA|GPU)' "--device gpu says why"
  [ ! -e "$WORK/gpu.csv" ] && [ ! -e "$WORK/gpu.csv.journal" ] && ok ||
    bad "--device gpu without a GPU left a file"
  [ ! -s "$WORK/out" ] && ok || bad "--device gpu without a GPU printed to stdout"
  expect_exit 0 "$DB" sweep "${GRID[@]}" --device auto -o "$WORK/auto.csv"
  expect_match "$ERR" '^sweep: device cpu: no GPU sweep here, ' "auto says it took the CPU"
  expect_match "$OUT" 'batched kernel' "auto ran the batched kernel"
  device=cpu
else
  [ "$code" -eq 0 ] && ok || bad "--device gpu exited $code: $(cat "$WORK/err")"
  expect_match "$(cat "$WORK/err")" '^sweep: device gpu: ' "--device gpu names the GPU"
  expect_match "$(cat "$WORK/out")" 'GPU ' "the time line names the GPU"
  cmp -s "$WORK/cpu.csv" "$WORK/gpu.csv" && ok || bad "the GPU's CSV differs from the CPU's"
  expect_exit 0 "$DB" sweep "${GRID[@]}" --device auto -o "$WORK/auto.csv"
  expect_match "$ERR" '^sweep: device gpu: ' "auto took the GPU"
  device=gpu
fi
cmp -s "$WORK/cpu.csv" "$WORK/auto.csv" && ok || bad "--device auto ($device) differs from the CPU"
# Shards through --device auto merge into the CPU's whole sweep.
for k in 1 2; do
  expect_exit 0 "$DB" sweep "${GRID[@]}" --device auto --shard $k/2 -o "$WORK/part$k.csv"
done
expect_exit 0 "$DB" merge "$WORK/part1.csv" "$WORK/part2.csv" -o "$WORK/merged.csv"
cmp -s "$WORK/merged.csv" "$WORK/cpu.csv" && ok || bad "merged --device auto parts differ"
# Bad values and contradictions: one line, exit 2.
expect_exit 2 "$DB" sweep "${GRID[@]}" --device tpu -o "$WORK/x.csv"
expect_one_line "$ERR" "--device tpu"
expect_match "$ERR" 'device' "--device tpu names the flag"
if [ "$device" = gpu ]; then
  expect_exit 2 "$DB" sweep "${GRID[@]}" --device gpu --plain -o "$WORK/x.csv"
  expect_match "$ERR" '--plain' "--device gpu --plain"
fi
[ ! -e "$WORK/x.csv" ] && ok || bad "a refused sweep left its CSV"
finish
