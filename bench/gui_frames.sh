#!/usr/bin/env bash
# The tuner's frame times on a big mesh (a benchmark, not a test): `dampbound gui --stats`
# under Xvfb (Mesa llvmpipe) on the paper's plane at 200 x 200 = 40 000 nodes (119 201
# springs), playing at 10 steps per frame, the Criteria tab open. Prints each run's stats
# JSON line and frame-time percentiles after the first frame against the targets (>= 20 fps
# mean, no frame over 100 ms after the first); with RUNS > 1, how many runs met each target
# and the range of their means (a shared machine's load moves single runs a lot).
#
#   bash bench/gui_frames.sh [SCENE] [FRAMES] [RUNS]   (defaults bench/scenes/plane-200.toml, 300, 1)
#
# GUI_ARGS adds flags to every run, e.g. the analysis at the static equilibrium of a loaded
# plane, computed on the worker while the frames play:
#   GUI_ARGS="--linearise equilibrium" bash bench/gui_frames.sh bench/scenes/plane-200-loaded.toml 200 4
set -euo pipefail
cd "$(dirname "$0")/.."
DB=${DAMPBOUND:-build/app/dampbound}
SCENE=${1:-bench/scenes/plane-200.toml}
FRAMES=${2:-300}
RUNS=${3:-1}
[ -x "$DB" ] || { echo "gui_frames.sh: $DB not built" >&2; exit 2; }
[[ "$RUNS" =~ ^[1-9][0-9]*$ ]] || { echo "gui_frames.sh: RUNS must be a positive integer, got '$RUNS'" >&2; exit 2; }
CONFIG=$(mktemp -d)
LINES=$(mktemp)
trap 'rm -rf "$CONFIG" "$LINES"' EXIT
for ((r = 1; r <= RUNS; r++)); do
  rm -rf "${CONFIG:?}"/*
  line=$(xvfb-run -a -s "-screen 0 1600x1000x24" "$DB" gui "$SCENE" --frames "$FRAMES" --play \
    --steps-per-frame 10 --tab criteria --stats --config-dir "$CONFIG" ${GUI_ARGS:-} | tail -n 1)
  echo "$line"
  echo "$line" >>"$LINES"
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
done
if [ "$RUNS" -gt 1 ]; then
  python3 - "$LINES" <<'PY'
import json, sys
runs = [json.loads(l)["frame_ms_after_first"] for l in open(sys.argv[1]) if l.strip()]
means = sorted(r["mean"] for r in runs)
fps_met = sum(1000.0 / r["mean"] >= 20 for r in runs if r["mean"] > 0)
max_met = sum(r["max"] <= 100 for r in runs)
print(f"{len(runs)} runs: mean frame {means[0]:.1f} to {means[-1]:.1f} ms "
      f"({1000 / means[-1]:.1f} to {1000 / means[0]:.1f} fps), median {means[len(means) // 2]:.1f} ms; "
      f">= 20 fps in {fps_met} of {len(runs)}, no frame over 100 ms in {max_met} of {len(runs)}")
PY
fi
