# dampbound gui closes promptly on a close request whatever runs in the background: the
# window manager's close button (a WM_DELETE_WINDOW message, tests/tools/x_close_request.c),
# SIGTERM and SIGINT, on tissue-block playing with the stability map computing, each request
# 3 s after the window opened, while two busy loops at nice 5 keep both cores full (another
# build, another tuner). The time is from the request to the process gone: at most 500 ms
# under this load (docs/gui.md promises 0.3 s; on the shared 2-core machine, load 7 to 10
# before the busy loops, the new tuner took 150 to 355 ms); the exit code is 0 and the
# settings are saved.
#
# The old tuner failed it: Mesa's shader disk cache thread runs at nice 19 and, with the cores
# busy, waited 0.6 to 4.6 s for the CPU it needs to die (the process with it); and a SIGTERM
# that reached the frame's thread through the handler LLVM installs crashed it (exit 139).
. "$(dirname "$0")/lib.inc"

BOUND_MS=${DAMPBOUND_CLOSE_BOUND_MS:-500}
if ! command -v Xvfb >/dev/null 2>&1; then
  echo "SKIP: Xvfb is not installed"
  exit 0
fi
if ! cc -O2 -o "$WORK/xclose" "$SRC/tests/tools/x_close_request.c" -lX11 2>"$WORK/cc.err"; then
  echo "SKIP: cannot build the X close helper: $(head -1 "$WORK/cc.err")"
  exit 0
fi
# Xvfb of our own, so that the signal goes to dampbound itself and not to xvfb-run.
disp=:$((90 + RANDOM % 400))
Xvfb "$disp" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
busy=()
cleanup() { kill "$xvfb" "${busy[@]}" 2>/dev/null; rm -rf "$WORK"; }
trap cleanup EXIT
sleep 1
for _ in 1 2; do
  nice -n 5 sh -c 'while :; do :; done' &
  busy+=($!)
done
worst=0
for how in close TERM INT close TERM INT; do
  cfg="$WORK/cfg-$how-$RANDOM"
  DISPLAY=$disp "$DB" gui tissue-block --play --tab map --size 1024x640 \
    --config-dir "$cfg" >"$WORK/out" 2>"$WORK/err" &
  pid=$!
  sleep 3
  if ! kill -0 "$pid" 2>/dev/null; then
    bad "$how: the tuner was gone before the request: $(cat "$WORK/err")"
    continue
  fi
  if [ "$how" = close ]; then
    t0=$(DISPLAY=$disp "$WORK/xclose" "$pid") || { bad "close: no window to close"; kill -9 "$pid"; continue; }
  else
    t0=$(date +%s%N)
    kill -s "$how" "$pid"
  fi
  while kill -0 "$pid" 2>/dev/null && [ $(( ($(date +%s%N) - t0) / 1000000 )) -lt 10000 ]; do
    sleep 0.005
  done
  ms=$(( ($(date +%s%N) - t0) / 1000000 ))
  [ "$ms" -gt "$worst" ] && worst=$ms
  if kill -0 "$pid" 2>/dev/null; then
    kill -9 "$pid"
    bad "$how: still running 10 s after the request"
  elif [ "$ms" -gt "$BOUND_MS" ]; then
    bad "$how: exit took $ms ms (> $BOUND_MS)"
  else
    ok
  fi
  wait "$pid"
  rc=$?
  [ "$rc" -eq 0 ] && ok || bad "$how: exit code $rc: $(tail -2 "$WORK/err")"
  echo "$how: exit after $ms ms, code $rc"
  [ -f "$cfg/settings.txt" ] && ok || bad "$how: settings not saved"
done
echo "longest close: $worst ms (bound $BOUND_MS ms)"
finish
