#!/usr/bin/env bash
# The tuner's frame times on a big mesh (a benchmark, not a test): `dampbound gui --stats`
# under Xvfb (Mesa llvmpipe) on the paper's plane at 200 x 200 = 40 000 nodes (119 201
# springs), playing at 10 steps per frame, the Criteria tab open. Prints the stats JSON line
# and the frame-time percentiles after the first frame against the targets (>= 20 fps mean,
# no frame over 100 ms after the first).
#
#   bash bench/gui_frames.sh [SCENE] [FRAMES]     (defaults bench/scenes/plane-200.toml, 300)
set -euo pipefail
cd "$(dirname "$0")/.."
DB=${DAMPBOUND:-build/app/dampbound}
SCENE=${1:-bench/scenes/plane-200.toml}
FRAMES=${2:-300}
[ -x "$DB" ] || { echo "gui_frames.sh: $DB not built" >&2; exit 2; }
CONFIG=$(mktemp -d)
trap 'rm -rf "$CONFIG"' EXIT
line=$(xvfb-run -a -s "-screen 0 1600x1000x24" "$DB" gui "$SCENE" --frames "$FRAMES" --play \
  --steps-per-frame 10 --tab criteria --stats --config-dir "$CONFIG" | tail -n 1)
echo "$line"
python3 - "$line" <<'PY'
import json, sys
s = json.loads(sys.argv[1])
f = s["frame_ms_after_first"]
fps = 1000.0 / f["mean"] if f["mean"] > 0 else 0.0
print(f"frames after the first: {f['frames']}  mean {f['mean']:.1f} ms ({fps:.1f} fps)  "
      f"p50 {f['p50']:.1f}  p99 {f['p99']:.1f}  max {f['max']:.1f} ms  first {s['first_frame_ms']:.0f} ms")
print(f"target >= 20 fps: {'met' if fps >= 20 else 'NOT met'};  "
      f"target max <= 100 ms after the first: {'met' if f['max'] <= 100 else 'NOT met'}")
PY
