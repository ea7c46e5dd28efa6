# The tuner under real X events (Xvfb, xdotool): a key tap shorter than a frame still acts
# (Space plays), and a settings file with a bad value is reported at that value's line and
# left as it is.
. "$(dirname "$0")/lib.inc"

if ! command -v Xvfb >/dev/null 2>&1 || ! command -v xdotool >/dev/null 2>&1; then
  echo "SKIP: Xvfb or xdotool is not installed"
  exit 0
fi
disp=:$((90 + RANDOM % 400))
Xvfb "$disp" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$WORK"' EXIT
sleep 1
export DISPLAY=$disp

json_field() { printf '%s' "$1" | sed -nE "s/.*\"$2\":\"?([^,\"}]*)\"?.*/\1/p"; }

# 1. A tap of Space (xdotool presses and releases at once, between two frames) plays the run.
# The frames are timed first, so that the window stays open about 6 s whatever the machine.
t0=$(date +%s%N)
"$DB" gui two-node --frames 30 --stats --size 1024x640 --config-dir "$WORK/c0" >"$WORK/out" 2>&1
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
frames=$(( 30 * 6000 / (ms > 1 ? ms : 1) ))
[ "$frames" -lt 60 ] && frames=60
"$DB" gui two-node --frames "$frames" --stats --size 1024x640 --config-dir "$WORK/c1" \
  >"$WORK/out" 2>"$WORK/err" &
pid=$!
xdotool search --sync --onlyvisible --name . >/dev/null 2>&1
sleep 1.5
xdotool mousemove 700 400 sleep 0.2 keydown space keyup space
wait "$pid"
STATS=$(grep '^{' "$WORK/out" | tail -1)
its=$(json_field "$STATS" iterations)
[ "${its:-0}" -gt 0 ] && ok || bad "a tap of Space did not play the run: $STATS $(cat "$WORK/err")"

# 2. A settings file whose gamma (line 3) the parameters' check refuses: the warning names
# line 3, and the file is the same after the tuner closed.
mkdir -p "$WORK/c2"
printf 'dampbound-gui-settings 1\nm = 0.001\ngamma = -1\ndt = 0.05\nlog_y = true\nshow_max = true\n' \
  >"$WORK/c2/settings.txt"
cp "$WORK/c2/settings.txt" "$WORK/settings.before"
expect_exit 0 "$DB" gui --frames 2 --stats --config-dir "$WORK/c2"
expect_match "$ERR" "settings.txt \(line 3: gamma must be >= 0\)" "the bad value's own line"
cmp -s "$WORK/c2/settings.txt" "$WORK/settings.before" && ok ||
  bad "the settings file was overwritten: $(cat "$WORK/c2/settings.txt")"

finish
