# dampbound gui closes within 1 s of SIGTERM or SIGINT whatever runs in the background: here
# the exact analysis, the stability map and playback on tissue-block, each signal sent 4 s
# after the window opened. The settings are still saved.
. "$(dirname "$0")/lib.inc"

if ! command -v xvfb-run >/dev/null 2>&1 || ! command -v Xvfb >/dev/null 2>&1; then
  echo "SKIP: Xvfb is not installed"
  exit 0
fi
# Xvfb of our own, so that the signal goes to dampbound itself and not to xvfb-run.
disp=:$((90 + RANDOM % 400))
Xvfb "$disp" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$WORK"' EXIT
sleep 1
for sig in TERM INT; do
  DISPLAY=$disp "$DB" gui tissue-block --play --tab map --size 1024x640 \
    --config-dir "$WORK/cfg-$sig" >"$WORK/out" 2>"$WORK/err" &
  pid=$!
  sleep 4
  if ! kill -0 "$pid" 2>/dev/null; then
    bad "SIG$sig: the tuner was gone before the signal: $(cat "$WORK/err")"
    continue
  fi
  t0=$(date +%s%N)
  kill -s "$sig" "$pid"
  while kill -0 "$pid" 2>/dev/null && [ $(( ($(date +%s%N) - t0) / 1000000 )) -lt 10000 ]; do
    sleep 0.02
  done
  ms=$(( ($(date +%s%N) - t0) / 1000000 ))
  if kill -0 "$pid" 2>/dev/null; then
    kill -9 "$pid"
    bad "SIG$sig: still running 10 s after the signal"
  elif [ "$ms" -gt 1000 ]; then
    bad "SIG$sig: exit took $ms ms (> 1000)"
  else
    ok
    echo "SIG$sig: exit after $ms ms"
  fi
  wait "$pid" 2>/dev/null
  [ -f "$WORK/cfg-$sig/settings.txt" ] && ok || bad "SIG$sig: settings not saved"
done
finish
