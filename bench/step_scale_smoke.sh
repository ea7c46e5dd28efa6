#!/usr/bin/env bash
# Smoke run of step_scale_bench: one line per mesh in the documented format, and a clear
# error with exit 2 for a bad flag. Times are not checked (a benchmark, not a timed test).
set -euo pipefail
BENCH=$1
out=$("$BENCH" --max-nodes 1100 --repeats 2)
echo "$out"
[ "$(echo "$out" | wc -l)" -eq 2 ] || { echo "expected 2 lines (plane 1024, block 1000)"; exit 1; }
echo "$out" | grep -Eq '^plane +1024 nodes +2945 springs +1 thread +[0-9.]+ \(median +[0-9.]+\) +2 threads +[0-9.]+ \(median +[0-9.]+\) ns/node-step +x[0-9.]+ \(pairs x[0-9.]+ to x[0-9.]+\) +[0-9]+ B/node +[0-9]+ B/spring' \
  || { echo "plane line not in the documented format"; exit 1; }
echo "$out" | grep -Eq '^block +1000 nodes +5859 springs' || { echo "no block line"; exit 1; }
[ "$("$BENCH" --max-nodes 1100 --mesh plane --repeats 1 | wc -l)" -eq 1 ] || { echo "--mesh plane"; exit 1; }
mon=$("$BENCH" --max-nodes 1100 --mesh plane --repeats 1 --what monitor)
echo "$mon"
echo "$mon" | grep -Eq '^plane +1024 nodes +2945 springs +1 thread +[0-9.]+ \(median +[0-9.]+\) +2 threads +[0-9.]+ \(median +[0-9.]+\) ns/node-call +x[0-9.]+ \(pairs x[0-9.]+ to x[0-9.]+\) +monitor$' \
  || { echo "--what monitor: line not in the documented format"; exit 1; }
for bad in "--threads 0" "--repeats 0" "--mesh cube" "--bogus 1" "--threads" "--what all"; do
  set +e
  err=$("$BENCH" $bad 2>&1 >/dev/null); rc=$?
  set -e
  [ "$rc" -eq 2 ] || { echo "'$bad': exit $rc, expected 2"; exit 1; }
  [ "$(echo "$err" | wc -l)" -eq 1 ] && echo "$err" | grep -q '^step_scale_bench: ' \
    || { echo "'$bad': expected one error line, got: $err"; exit 1; }
done
echo "step_scale_smoke: ok"
