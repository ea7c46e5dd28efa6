#!/usr/bin/env bash
# The layers of core (core/CMakeLists.txt, docs/architecture.md) are enforced by the build:
# each layer compiles against a view of the headers of the layers below it. This preprocesses a
# one-line file against each view and checks that the includes a layer may make resolve (with
# everything they include in turn) and those it may not fail, so a view that grew too wide (or a
# header that moved) is caught. Preprocessing is what decides it: a header outside the view is
# a missing file to the preprocessor, and it costs a tenth of a parse.
# Then every public header (include/dampbound/) must include only public headers and compile
# alone against that folder: what a program that installed dampbound sees.
# Usage: layers.sh CXX SOURCE_DIR VIEWS_DIR INCLUDE_DIR...
set -euo pipefail
cxx=$1 src=$2 views=$3
shift 3
extra=()
for d in "$@"; do extra+=(-I "$d"); done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
probe() {  # probe LAYER HEADER yes|no
  local layer=$1 header=$2 want=$3
  printf '#include "%s"\n' "$header" >"$work/probe.cpp"
  if "$cxx" -std=c++17 -E -o /dev/null -I "$views/$layer" "${extra[@]}" "$work/probe.cpp" \
      >"$work/log" 2>&1; then
    got=yes
  elif grep -q "No such file\|file not found" "$work/log"; then
    got=no  # refused for the right reason: a header of a higher layer is not in the view
  else
    got="an error other than a missing header"
  fi
  if [ "$got" != "$want" ]; then
    echo "FAIL: $layer including $header: expected $([ "$want" = yes ] && echo to compile || echo to fail)"
    head -5 "$work/log"
    fails=$((fails + 1))
  else
    echo "ok: $layer $([ "$want" = yes ] && echo may || echo may not) include $header"
  fi
}
probe physics dampbound/physics/step.hpp yes
probe physics core/physics/integrate.hpp yes
probe physics dampbound/run/scene.hpp no
probe physics dampbound/analysis/linear_stability.hpp no
probe physics core/io/scene_file.hpp no
probe physics core/sweep/summary.hpp no
probe physics dampbound/monitor.hpp no
probe run dampbound/run/session.hpp yes
probe run core/physics/safe_bound.hpp yes
probe run core/io/scene_file.hpp no
probe io core/io/scene_file.hpp yes
probe io dampbound/run/scene.hpp yes
probe io core/analysis/criteria.hpp no
probe analysis dampbound/analysis/linear_stability.hpp yes
probe analysis core/analysis/linear_stability_exact.hpp yes
probe analysis core/io/format.hpp yes
probe analysis core/sweep/summary.hpp no
probe sweep core/sweep/summary.hpp yes
probe sweep core/analysis/claims.hpp yes
probe sweep dampbound/monitor.hpp no
probe embed dampbound/monitor.hpp yes
probe embed core/analysis/linear_stability_exact.hpp yes
probe embed core/sweep/runner.hpp no
# The public folder: every header in include/dampbound/ includes only public headers (what is
# installed) and compiles on its own against that folder alone.
for h in $(cd "$src/include" && find dampbound -name '*.hpp' | sort); do
  if grep -n '#include "core/' "$src/include/$h"; then
    echo "FAIL: public header $h includes a private header"
    fails=$((fails + 1))
  fi
  printf '#include "%s"\n' "$h" >"$work/probe.cpp"
  if ! "$cxx" -std=c++17 -fsyntax-only -I "$src/include" "${extra[@]}" "$work/probe.cpp" \
      >"$work/log" 2>&1; then
    echo "FAIL: public header $h does not compile against include/ alone"
    head -5 "$work/log"
    fails=$((fails + 1))
  fi
done
echo "ok: the $(cd "$src/include" && find dampbound -name '*.hpp' | wc -l) public headers include only public headers and compile alone"
[ "$fails" -eq 0 ] || { echo "layers: $fails probe(s) wrong"; exit 1; }
echo "layers: every layer sees the layers below it and none above"
