# dampbound gui: the real window under Xvfb (xvfb-run -a provides the display, so this also
# passes with DISPLAY unset): frames, screenshot, stats, persistence, errors.
. "$(dirname "$0")/lib.inc"

if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIP: xvfb-run is not installed"
  exit 0
fi
XV=(xvfb-run -a -s "-screen 0 1600x1000x24")
CFG="$WORK/config"

# json_field JSON KEY: a number or a quoted string's content.
json_field() { printf '%s' "$1" | sed -nE "s/.*\"$2\":\"?([^,\"}]*)\"?.*/\1/p"; }

# png_size FILE: "W H" from the IHDR chunk.
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8}'; }

# png_check FILE: with python3, decodes the PNG (RGBA or RGB, 8 bit) and prints
# "distinct=N mesh=M" (M = pixels of the mesh view's "within bounds" node colour).
png_check() {
  python3 - "$1" <<'EOF'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n"
pos, idat = 8, b""
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
bpp = {6: 4, 2: 3}[ctype]
raw, stride = zlib.decompress(idat), w * bpp
prev, rows, i = bytearray(stride), [], 0
for _ in range(h):
    f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
    i += 1 + stride
    for x in range(stride):
        a = line[x - bpp] if x >= bpp else 0
        b, c = prev[x], (prev[x - bpp] if x >= bpp else 0)
        if f == 1: line[x] = (line[x] + a) & 255
        elif f == 2: line[x] = (line[x] + b) & 255
        elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    prev = line
colors, mesh = set(), 0
for line in rows:
    for x in range(0, stride, bpp):
        r, g, b = line[x], line[x + 1], line[x + 2]
        colors.add((r, g, b))
        if abs(r - 120) <= 10 and abs(g - 200) <= 10 and abs(b - 140) <= 10:
            mesh += 1
print("distinct=%d mesh=%d" % (len(colors), mesh))
EOF
}

# 1. N frames playing, a screenshot and the stats line.
FRAMES=12 SPF=5
expect_exit 0 "${XV[@]}" "$DB" gui "$SRC/scenes/paper-plane.toml" --frames $FRAMES \
  --steps-per-frame $SPF --size 1024x640 --screenshot "$WORK/gui.png" --stats --config-dir "$CFG"
STATS=$(printf '%s\n' "$OUT" | grep '^{' | tail -1)
expect_match "$STATS" '"frames":12,' "stats: frames"
for key in iterations mean_frame_ms steps_per_second renderer; do
  expect_match "$STATS" "\"$key\":" "stats has $key"
done
iters=$(json_field "$STATS" iterations)
outcome=$(json_field "$STATS" outcome)
at=$(json_field "$STATS" outcome_iteration)
if [ "$iters" = $((FRAMES * SPF)) ] || { [ "$outcome" = diverged ] && [ "$iters" = "$at" ]; }; then
  ok
else
  bad "iterations $iters, wanted $((FRAMES * SPF)) (outcome $outcome at $at)"
fi
# Frame-time percentiles without the startup frame (docs/gui.md).
expect_match "$STATS" '"frame_ms_after_first":\{"frames":11,"mean":[0-9.e+-]+,"p50":[0-9.e+-]+,"p99":[0-9.e+-]+,"max":[0-9.e+-]+\},"first_frame_ms":[0-9.e+-]+' \
  "stats: frame-time mean, p50, p99, max after the first frame"
ms=$(json_field "$STATS" mean_frame_ms)
awk -v m="$ms" 'BEGIN { exit !(m > 0) }' && ok || bad "mean frame time '$ms'"
if [ -s "$WORK/gui.png" ]; then ok; else bad "no screenshot"; fi
expect_match "$(png_size "$WORK/gui.png")" '^1024 640$' "screenshot has the window's size"
if command -v python3 >/dev/null 2>&1; then
  check=$(png_check "$WORK/gui.png")
  distinct=$(printf '%s' "$check" | sed -E 's/distinct=([0-9]+).*/\1/')
  mesh=$(printf '%s' "$check" | sed -E 's/.*mesh=([0-9]+)/\1/')
  [ "${distinct:-0}" -gt 100 ] && ok || bad "screenshot looks blank: $check"
  [ "${mesh:-0}" -gt 200 ] && ok || bad "mesh nodes not visible in the screenshot: $check"
else
  [ "$(wc -c <"$WORK/gui.png")" -gt 20000 ] && ok || bad "screenshot too small to hold a window"
fi
[ -s "$CFG/settings.txt" ] && ok || bad "settings not saved in --config-dir"
[ -s "$CFG/imgui.ini" ] && ok || bad "window layout not saved in --config-dir"
# A later start with that layout: its first frame is drawn (ImGui hid the remembered panels
# for one frame, and --frames 1 --screenshot wrote the bare background).
# Its first frame is built twice (a layout pass, then the drawn frame); only the drawn one steps.
expect_exit 0 "${XV[@]}" "$DB" gui paper-plane --frames 1 --size 1024x640 --steps-per-frame 3 \
  --stats --screenshot "$WORK/second.png" --config-dir "$CFG"
STATS=$(printf '%s\n' "$OUT" | grep '^{' | tail -1)
expect_match "$STATS" '"frames":1,"iterations":3,' "one frame of 3 steps after the layout pass"
if command -v python3 >/dev/null 2>&1; then
  check=$(png_check "$WORK/second.png")
  distinct=$(printf '%s' "$check" | sed -E 's/distinct=([0-9]+).*/\1/')
  [ "${distinct:-0}" -gt 100 ] && ok || bad "first frame of a later start looks blank: $check"
fi

# 2. Parameters persist: a run with --gamma, then one without a scene or flags.
expect_exit 0 "${XV[@]}" "$DB" gui two-node --gamma 0.0007 --frames 2 --stats --config-dir "$CFG"
expect_exit 0 "${XV[@]}" "$DB" gui --frames 2 --stats --config-dir "$CFG"
STATS=$(printf '%s\n' "$OUT" | grep '^{' | tail -1)
expect_match "$STATS" '"scene":"two-node"' "last scene remembered"
expect_match "$STATS" '"gamma":0.0007,' "last gamma remembered"

# 3. Corrupt settings and layout: one warning line each, defaults, no crash.
printf 'garbage\n\001\002\003' >"$CFG/settings.txt"
printf '[Window\n\001junk' >"$CFG/imgui.ini"
expect_exit 0 "${XV[@]}" "$DB" gui --frames 2 --stats --config-dir "$CFG"
expect_match "$ERR" 'warning: ignoring corrupt settings file .*settings.txt' "corrupt settings warned"
expect_match "$ERR" 'warning: ignoring corrupt window layout file' "corrupt layout warned"
expect_match "$OUT" '"scene":"paper-plane"' "corrupt settings fall back to paper-plane"

# 4. The demo pins two runs; a diverging run stops and says so; --tab opens a tab.
expect_exit 0 "${XV[@]}" "$DB" gui paper-plane --tab criteria --frames 2 --stats \
  --config-dir "$WORK/c5"
expect_match "$OUT" '"frames":2,' "--tab criteria"
expect_match "$OUT" '"exact_method":"per-mode' "--tab criteria: the exact analysis on show"
# --factor-budget reaches the tuner's analysis: over it nothing is factorised.
expect_exit 0 "${XV[@]}" "$DB" gui paper-plane --tab criteria --frames 2 --stats \
  --factor-budget 1e-9 --config-dir "$WORK/c5"
expect_match "$OUT" '"exact_method":"not computed \(factorisation over budget\)"' \
  "--factor-budget: the tuner's analysis over the budget"
# --linearise equilibrium: a loaded string is analysed where it sags to (remembered).
printf '%s\n' 'name = "sag"' '[[node]]' 'x = [0.0, 0.0, 0.0]' 'fixed = true' '[[node]]' \
  'x = [0.5, 0.0, 0.0]' 'force = [0.0, -0.0005, 0.0]' '[[node]]' 'x = [1.0, 0.0, 0.0]' \
  'fixed = true' '[[spring]]' 'nodes = [0, 1]' '[[spring]]' 'nodes = [1, 2]' >"$WORK/sag.toml"
expect_exit 0 "${XV[@]}" "$DB" gui "$WORK/sag.toml" --linearise equilibrium --tab criteria \
  --frames 2 --stats --config-dir "$WORK/c6"
expect_match "$OUT" '"exact_at":"equilibrium"' "--linearise equilibrium"
expect_match "$(cat "$WORK/c6/settings.txt")" '^exact_at_equilibrium = true' "--linearise remembered"
expect_exit 0 "${XV[@]}" "$DB" gui "$WORK/sag.toml" --tab criteria --frames 2 --stats \
  --config-dir "$WORK/c6"
expect_match "$OUT" '"exact_at":"equilibrium"' "the remembered choice"
expect_exit 0 "${XV[@]}" "$DB" gui "$WORK/sag.toml" --linearise rest --frames 2 --stats \
  --config-dir "$WORK/c6"
expect_match "$OUT" '"exact_at":"rest"' "--linearise rest"
expect_exit 2 "$DB" gui --linearise somewhere --frames 1 --config-dir "$WORK/c6"
expect_one_line "$ERR" "bad --linearise"
expect_match "$ERR" -- '--linearise' "bad --linearise names the flag"
expect_exit 0 "${XV[@]}" "$DB" gui paper-plane --demo --frames 2 --stats --config-dir "$WORK/c2"
expect_match "$OUT" '"pins":2,' "--demo pins two runs"
expect_exit 0 "${XV[@]}" "$DB" gui paper-plane --kappa 1 --gamma 0 --frames 30 \
  --steps-per-frame 10 --stats --config-dir "$WORK/c3"
STATS=$(printf '%s\n' "$OUT" | grep '^{' | tail -1)
expect_match "$STATS" '"outcome":"diverged"' "diverging run"
[ "$(json_field "$STATS" iterations)" = "$(json_field "$STATS" outcome_iteration)" ] && ok ||
  bad "a diverged run must stop at its outcome: $STATS"

# 5. No display: one line, exit 3. Bad flags: one line, exit 2.
expect_exit 3 env -u DISPLAY -u WAYLAND_DISPLAY "$DB" gui --frames 1 --config-dir "$WORK/c4"
expect_one_line "$ERR" "no display"
expect_match "$ERR" 'display' "no-display message"
expect_exit 2 "$DB" gui --screenshot "$WORK/x.png" --config-dir "$WORK/c4"
expect_match "$ERR" -- '--frames' "--screenshot needs --frames"
expect_exit 2 "$DB" gui --size 10x10 --frames 1 --config-dir "$WORK/c4"
expect_match "$ERR" -- '--size' "bad --size"
expect_exit 2 "$DB" gui --tab bogus --frames 1 --config-dir "$WORK/c4"
expect_match "$ERR" -- '--tab' "bad --tab"
expect_exit 2 "$DB" gui --factor-budget 0 --frames 1 --config-dir "$WORK/c4"
expect_match "$ERR" -- '--factor-budget' "bad --factor-budget"
expect_exit 2 "$DB" gui "$WORK/missing.toml" --frames 1 --config-dir "$WORK/c4"
expect_one_line "$ERR" "missing scene"

finish
