#!/usr/bin/env bash
# SPEC 8's early stop, timed: one sweep grid run under --rule first-entry, under the settled
# rule (the proof of docs/settled.md stops each settled trial once it is certified) and, with
# --full, under the settled rule stepped to the limit (--no-early-stop). Prints user CPU and
# wall seconds of each, the settled/first-entry ratio (the target: at most 2), and checks that
# the early-stopped and full settled CSVs agree on every trial's outcome, first entry, exit
# and settled iteration (and divergence iteration).
# Usage: bench/settled_vs_first_entry.sh DAMPBOUND [--full] [SWEEP FLAGS...]
#   default grid: the 10k-trial --m 0.001:0.01:0.0001 --kappa 0.0001:0.1:0.001 --zeta 0.5;
#   the issue's 100k grid: --m 0.0001:0.01:0.0001 --kappa 0.0001:0.1:0.0001 --zeta 0.5
set -euo pipefail
bin=$1
shift
full=0
if [[ ${1:-} == --full ]]; then full=1; shift; fi
grid=("$@")
[[ ${#grid[@]} -gt 0 ]] || grid=(--m 0.001:0.01:0.0001 --kappa 0.0001:0.1:0.001 --zeta 0.5)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "cores: $(nproc), load: $(cut -d' ' -f1-3 /proc/loadavg),$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
echo "grid: ${grid[*]}"
declare -A user wall
timed() {  # name, then the sweep's own flags
  local name=$1
  shift
  /usr/bin/time -f '%U %e' -o "$dir/$name.time" "$bin" sweep "${grid[@]}" --progress none \
    -o "$dir/$name.csv" "$@" >"$dir/$name.out"
  read -r user[$name] wall[$name] <"$dir/$name.time"
  printf '%-12s user %8.2f s  wall %8.2f s   %s\n' "$name" "${user[$name]}" "${wall[$name]}" \
    "$(grep -m1 -E '^(outcomes|restored|settled)' "$dir/$name.out" || true)"
}
timed first-entry --rule first-entry
timed settled --rule settled
awk -v s="${user[settled]}" -v f="${user[first-entry]}" \
  'BEGIN { printf "settled / first-entry: %.2fx user CPU (target <= 2)\n", s / f }'
if [[ $full == 1 ]]; then
  timed full --rule settled --no-early-stop
  awk -v s="${user[settled]}" -v f="${user[full]}" \
    'BEGIN { printf "early stop / to the limit: %.2fx user CPU\n", s / f }'
  # outcome, first_entry, left_at, settled_at, and iterations where diverged, per trial.
  cols() {
    grep -v '^#' "$1" | awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
      { o = $c["outcome"]; printf "%s %s %s %s %s %s\n", $c["trial"], o, $c["first_entry"],
        $c["left_at"], $c["settled_at"], o == "diverged" ? $c["iterations"] : "-" }'
  }
  if cmp -s <(cols "$dir/settled.csv") <(cols "$dir/full.csv"); then
    echo "verdicts: identical on all $(($(grep -vc '^#' "$dir/full.csv") - 1)) trials"
  else
    echo "verdicts: DIFFER"
    diff <(cols "$dir/settled.csv") <(cols "$dir/full.csv") | head
    exit 1
  fi
fi
