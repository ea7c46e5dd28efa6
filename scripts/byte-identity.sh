#!/usr/bin/env bash
# Behaviour must not change when code moves: run a fixed list of commands with two
# dampbound binaries and compare everything they write, byte for byte.
#
#   scripts/byte-identity.sh OLD_BINARY NEW_BINARY [WORK_DIR]
#
# Compared per command: exit status, stdout, stderr and every file written (run JSON
# and --trace CSV of every shipped scene under both rules, the paper plane under every
# policy and integrator, figure fig1/fig2 PNG + CSV, a small sweep CSV + map PNG, merge
# of its shards, bounds and suggest text, check --junit, bounds of a bench scene at its
# static equilibrium). PNGs are compared as bytes:
# stb encodes deterministically, so equal bytes mean equal pixels. The only edit made
# before comparing: JUnit's wall-clock time="..." attributes, a sweep's speed line, the
# progress notes of a wait (stderr) and a rule line's estimate in seconds, and the
# folder where each binary found the default scene are dropped. Compare builds of the same
# configuration (a -march=native build rounds implicit Euler's sparse solves differently).
# Exit 0 when every output matches, 1 when any differs (each difference is listed).
set -euo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: $0 OLD_BINARY NEW_BINARY [WORK_DIR]" >&2
  exit 2
fi
old=$(realpath "$1")
new=$(realpath "$2")
for b in "$old" "$new"; do
  [[ -x $b ]] || { echo "byte-identity: $b is not an executable" >&2; exit 2; }
done
root=$(cd "$(dirname "$0")/.." && pwd)
work=${3:-$(mktemp -d)}
mkdir -p "$work"

# One command per line; {out} is the binary's shared output folder.
commands() {
  local s
  for s in "$root"/scenes/*.toml; do
    local n; n=$(basename "$s" .toml)
    echo "run $s --json --trace {out}/$n.trace.csv"
    echo "run $s --json --rule first-entry --trace {out}/$n.first.trace.csv"
    # The tissue block's exact analysis and verified suggestion take minutes.
    [[ $n == tissue-block ]] && continue
    echo "bounds $s"
    echo "suggest $s"
  done
  local p i
  for p in fixed clamp upper lower safe; do
    for i in semi-implicit-euler forward-euler verlet rk4 implicit-euler; do
      echo "run $root/scenes/paper-plane.toml --json --policy $p --integrator $i --max-iter 400 --trace {out}/plane.$p.$i.csv"
    done
  done
  echo "run $root/scenes/paper-plane.toml --policy upper --factor 1.05 --rule first-entry"
  echo "bounds --m 0.001 --kappa 0.001 --dt 0.05 --v 1,0,0 --force 0.5,0,0"
  echo "bounds --system single-node --m 0.001 --kappa 0.001 --dt 0.05 --v 1,0,0 --force 0.5,0,0"
  for i in forward-euler verlet rk4 implicit-euler; do
    echo "bounds $root/scenes/stiff-region.toml --integrator $i --after 20"
  done
  echo "suggest $root/scenes/paper-plane.toml --gamma 0.001"
  echo "suggest $root/scenes/two-node.toml --dt 0.3"
  echo "figure fig1 -o {out}/fig1.png --csv {out}/fig1.csv --size 800x500"
  echo "figure fig2 -o {out}/fig2.png --csv {out}/fig2.csv --size 800x500"
  echo "figure $root/scenes/paper-plane-policies.toml -o {out}/policies.png --size 800x500"
  echo "sweep --m 0.001,0.002 --kappa 0.0005:0.002:0.0005 --zeta 0.5,1 --dt 0.05 --max-iter 300 --threads 2 --progress none -o {out}/sweep.csv --map {out}/sweep.png"
  echo "sweep --m 0.001 --kappa 0.001,0.01 --factor 0.5,1,1.05 --policy upper --dt 0.05 --max-iter 300 --rule settled --threads 1 --progress none -o {out}/upper.csv"
  echo "sweep --m 0.001,0.002 --kappa 0.0005:0.002:0.0005 --zeta 0.5,1 --dt 0.05 --max-iter 300 --shard 1/2 --progress none -o {out}/part1.csv"
  echo "sweep --m 0.001,0.002 --kappa 0.0005:0.002:0.0005 --zeta 0.5,1 --dt 0.05 --max-iter 300 --shard 2/2 --progress none -o {out}/part2.csv"
  echo "merge {out}/part1.csv {out}/part2.csv -o {out}/merged.csv"
  echo "map {out}/sweep.csv -o {out}/map.png"
  echo "check $root/scenes --junit {out}/check.xml"
  # At a static equilibrium, where a certificate fails in the anchors' cluster (8 s each).
  echo "bounds $root/bench/scenes/plane-200-loaded.toml --equilibrium"
}

run_all() {  # binary out_dir
  local bin=$1 out=$2 k=0 line
  rm -rf "$out"; mkdir -p "$out/files"
  while IFS= read -r line; do
    k=$((k + 1))
    local d; d=$(printf '%s/%03d' "$out" "$k")
    mkdir -p "$d"
    local cmd=${line//\{out\}/$out/files}
    echo "$line" > "$d/command"
    # shellcheck disable=SC2086
    (cd "$out/files" && "$bin" $cmd > "$d/stdout" 2> "$d/stderr"; echo $? > "$d/status") || true
    sed -i "s|$out/files|{out}|g; s|$root|{root}|g" "$d/stdout" "$d/stderr"
    # A sweep's speed line is wall-clock, not behaviour.
    [[ $line == sweep* ]] && sed -i '/^time  /d' "$d/stdout"
    # So are the progress notes on stderr (a wait over 2 s, docs/cli.md) and the seconds a
    # sweep's rule line estimates at its measured rate.
    sed -i -E '/^dampbound: [a-z]+: .*(\(Ctrl-C stops\)|done in [0-9.]+ s)$/d' "$d/stderr"
    sed -i -E 's/, about [0-9.e+-]+ s at this rate\)/)/' "$d/stdout"
  done < <(commands)
  # A sweep names its scene by the path where the binary found it (beside its own tree).
  sed -i -E 's|^# scene: .*/scenes/|# scene: {scenes}/|' "$out"/files/*.csv
  [[ -f $out/files/check.xml ]] && sed -i 's/ time="[^"]*"//g; s|'"$root"'|{root}|g' "$out/files/check.xml"
  echo "$k"
}

echo "byte-identity: old $old" >&2
n=$(run_all "$old" "$work/old")
echo "byte-identity: new $new" >&2
run_all "$new" "$work/new" > /dev/null

if diff -r -q "$work/old" "$work/new" > "$work/differences"; then
  files=$(find "$work/old" -type f | wc -l)
  echo "byte-identity: $n commands, $files files, all identical ($work)"
  exit 0
fi
echo "byte-identity: outputs differ ($work):"
while read -r _ a _ b _; do
  echo "  $(cat "$(dirname "$a")/command" 2>/dev/null || echo "$a"): $(basename "$a")"
done < "$work/differences"
exit 1
