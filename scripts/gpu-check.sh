#!/usr/bin/env bash
# The GPU sweep on a GPU machine, in one go and within about 8 minutes (docs/gpu.md):
#   1. builds dampbound with its CUDA code in build-gpu/ (or takes --dampbound PATH);
#   2. runs the same trials on the GPU and on the CPU and compares the CSVs byte for byte:
#      4000 trials of the paper's mesh with every trial run (fixed policy, settled rule),
#      3429 of the paper-upper preset (its 1/1000 part), 216 with dashpot and Rayleigh damping;
#   3. times both on the paper-upper part (spring evaluations per second, as `sweep` prints);
#   4. runs larger parts of `--preset paper-upper` on the GPU, 1/100 and then 1/10, while ten
#      times the last part fits before the 7th minute, and projects the whole preset's time
#      from the largest (set-up + N x the part's stepping);
#   5. prints one summary. Exit 0 when every CSV matched, 1 when one differed, 3 when there is
#      no GPU here (one line says why), 2 when the build or a run failed.
# Needs only the working tree and the build tools (cmake, a C++ compiler, nvcc); nothing is
# downloaded.
#   scripts/gpu-check.sh [--dampbound PATH] [--build-dir DIR] [--keep DIR] [--no-node-check]
# --keep DIR keeps the CSVs and outputs; --no-node-check skips the look for /dev/nvidia* and
# nvidia-smi and asks dampbound itself (tests/cli/gpu_check.sh).
set -uo pipefail
cd "$(dirname "$0")/.."
DB="" BUILD=build-gpu KEEP="" NODES=1
while [ $# -gt 0 ]; do
  case "$1" in
    --dampbound) DB=$2; shift 2 ;;
    --build-dir) BUILD=$2; shift 2 ;;
    --keep) KEEP=$2; shift 2 ;;
    --no-node-check) NODES=0; shift ;;
    *) echo "gpu-check: unknown option '$1' (--dampbound PATH, --build-dir DIR, --keep DIR, --no-node-check)" >&2
       exit 2 ;;
  esac
done
start=$SECONDS
die() { echo "gpu-check: $*" >&2; exit 2; }

# No GPU device node and no driver tool: nothing to check, and no build for nothing.
if [ "$NODES" = 1 ] && ! compgen -G "/dev/nvidia[0-9]*" >/dev/null &&
   ! command -v nvidia-smi >/dev/null; then
  echo "gpu-check: no GPU on this machine (no /dev/nvidia* device, no nvidia-smi): nothing to check"
  exit 3
fi

if [ -z "$DB" ]; then
  command -v cmake >/dev/null || die "cmake is missing"
  gen=(); command -v ninja >/dev/null && gen=(-G Ninja)
  mkdir -p "$BUILD"
  cmake -S . -B "$BUILD" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DDAMPBOUND_CUDA=ON \
    -DDAMPBOUND_TESTS=OFF -DDAMPBOUND_BENCH=OFF -DDAMPBOUND_PYTHON=OFF -DDAMPBOUND_GUI=OFF \
    -DDAMPBOUND_EGL=OFF >"$BUILD/gpu-check-configure.log" 2>&1 ||
    die "configuring $BUILD failed (a dependency missing? scripts/install-deps.sh): $BUILD/gpu-check-configure.log"
  cmake --build "$BUILD" -j "$(nproc)" --target dampbound >"$BUILD/gpu-check-build.log" 2>&1 ||
    die "building dampbound failed: $BUILD/gpu-check-build.log"
  DB=$BUILD/app/dampbound
fi
[ -x "$DB" ] || die "no dampbound at $DB"
build_s=$((SECONDS - start))

WORK=${KEEP:-$(mktemp -d)}
mkdir -p "$WORK"
[ -n "$KEEP" ] || trap 'rm -rf "$WORK"' EXIT

# The GPU as dampbound sees it: `--device gpu` on one trial says why not in one line.
if ! "$DB" sweep --m 0.001 --kappa 0.001 --zeta 1 --max-iter 2 --progress none --device gpu \
    -o "$WORK/probe.csv" >/dev/null 2>"$WORK/probe.err"; then
  echo "gpu-check: no GPU sweep here: $(tail -n 1 "$WORK/probe.err" | sed -E 's/^dampbound: (error: )?--device gpu: //')"
  exit 3
fi
device=$(sed -n 's/^sweep: device gpu: //p' "$WORK/probe.err")

# run NAME DEVICE ARGS...: one sweep, its time line kept; the CSV is $WORK/NAME.DEVICE.csv.
run() {
  local name=$1 dev=$2; shift 2
  "$DB" sweep "$@" --device "$dev" --progress none -o "$WORK/$name.$dev.csv" \
    >"$WORK/$name.$dev.out" 2>"$WORK/$name.$dev.err" ||
    die "sweep $name on the $dev failed: $(tail -n 1 "$WORK/$name.$dev.err")"
}
seconds() { awk '$1 == "time" { print $2 }' "$WORK/$1.out"; }
rate() { awk '$1 == "time" { for (i = 1; i < NF; i++) if ($(i + 1) == "spring") print $i }' "$WORK/$1.out"; }

# 2. The same trials on both: every trial of the paper's mesh run (no similarity), the
# paper-upper part, and SPEC 10's damping (which the CPU steps through Session).
declare -A CASES=(
  [grid]="--m 0.001:0.02:0.001 --kappa 0.001:0.1:0.001 --zeta 0.5,1 --max-iter 200 --no-similarity"
  [upper]="--preset paper-upper --shard 1/1000"
  [damped]="--m 0.001,0.002 --kappa 0.001:0.006:0.001 --zeta 0.5 --kd 0,0.001,0.004 --rayleigh-mass 0,0.5 --rayleigh-stiffness 0,0.01,0.05 --max-iter 100"
)
trials=0 same=0 differ=""
for name in grid upper damped; do
  # shellcheck disable=SC2086
  run "$name" gpu ${CASES[$name]}
  # shellcheck disable=SC2086
  run "$name" cpu ${CASES[$name]}
  n=$(grep -v '^#' "$WORK/$name.cpu.csv" | grep -vc '^trial')
  trials=$((trials + n))
  if cmp -s "$WORK/$name.gpu.csv" "$WORK/$name.cpu.csv"; then same=$((same + n)); else differ+=" $name"; fi
done

# 3-4. Rates on the paper-upper part, and the preset's projection: its classes are
# interleaved across parts, so a part of 1/N takes 1/N of the stepping; the set-up (the whole
# grid enumerated by every part) is measured apart, with one iteration per trial.
run setup gpu --preset paper-upper --shard 1/1000 --max-iter 1
setup=$(seconds setup.gpu)
part=1000 part_s=$(seconds upper.gpu) rate_of=upper.gpu
# A larger part (1/100, then 1/10) while ten times the last one fits before the 7th minute:
# more classes fill more of the GPU's threads, so the projection comes closer to the whole.
for next in 100 10; do
  left=$((420 - (SECONDS - start)))
  awk -v s="$part_s" -v u="$setup" -v l="$left" 'BEGIN { exit !(10 * (s - u) + u < l) }' || break
  run "upper$next" gpu --preset paper-upper --shard "1/$next"
  part=$next part_s=$(seconds "upper$next.gpu") rate_of=upper$next.gpu
done
project() {  # PART SECONDS SETUP -> the whole preset's seconds
  awk -v n="$1" -v s="$2" -v u="$3" 'BEGIN { d = s - u; if (d < 0) d = 0; printf "%.0f", u + n * d }'
}
human() { awk -v s="$1" 'BEGIN { if (s < 120) printf "%.0f s", s; else if (s < 7200) printf "%.1f min", s / 60; else printf "%.1f h", s / 3600 }'; }
gpu_whole=$(project "$part" "$part_s" "$setup")
cpu_whole=$(project 1000 "$(seconds upper.cpu)" "$setup")
gpu_rate=$(rate "$rate_of") cpu_rate=$(rate upper.cpu)
cpu_name=$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo)

echo "gpu-check summary"
echo "  gpu          $device"
echo "  cpu          $cpu_name, $(nproc) threads, kernel copy $("$DB" --version | sed -n 's/.*sweep kernel: \([a-z0-9]*\).*/\1/p')"
if [ -z "$differ" ]; then
  echo "  identical    $same of $trials trials: the GPU's CSVs equal the CPU's byte for byte (grid 4000, paper-upper 1/1000, SPEC 10 damping)"
else
  echo "  DIFFERENT    the GPU's CSV differs from the CPU's in:$differ ($same of $trials trials in matching files)"
fi
echo "  rate         GPU $gpu_rate spring evaluations/s (paper-upper 1/$part), CPU $cpu_rate (1/1000, $(nproc) threads)"
echo "  paper-upper  1/$part on the GPU in $part_s s (set-up $setup s): the whole about $(human "$gpu_whole"); on this CPU about $(human "$cpu_whole")"
echo "  took         $((SECONDS - start)) s (build $build_s s)"
[ -z "$differ" ] || exit 1
