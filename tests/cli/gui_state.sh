# The tuner under real X events (Xvfb, xdotool): a key tap shorter than a frame still acts
# (Space pauses), and a settings file with a bad value is reported at that value's line and
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

# 1. A tap of Space shorter than a frame acts. The frames are made long (the hidden
# --debug-frame-sleep, 150 ms each) and xdotool presses and releases Space with no delay, so
# both events arrive within one frame, which ImGui 1.86 alone reads as never pressed. The run
# plays one step per frame from the start (--frames plays); the tap pauses it, so the session
# ends with fewer iterations than frames. With the tap lost (ui/glfw_host.cpp's held release
# reverted) it ran all 40 steps.
frames=40
"$DB" gui two-node --frames $frames --steps-per-frame 1 --debug-frame-sleep 150 \
  --max-iter 100000 --stats --size 1024x640 --config-dir "$WORK/c1" >"$WORK/out" 2>"$WORK/err" &
pid=$!
xdotool search --sync --onlyvisible --pid "$pid" >/dev/null 2>&1
sleep 2
xdotool mousemove 700 400 sleep 0.3 keydown --delay 0 space keyup --delay 0 space
wait "$pid"
STATS=$(grep '^{' "$WORK/out" | tail -1)
its=$(json_field "$STATS" iterations)
if [ "${its:-0}" -gt 0 ] && [ "${its:-0}" -lt $((frames - 2)) ]; then
  ok
  echo "a tap of Space within one frame paused the run at $its of $frames steps"
else
  bad "a tap of Space within one frame did not pause the run ($its of $frames steps): $STATS $(cat "$WORK/err")"
fi

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
