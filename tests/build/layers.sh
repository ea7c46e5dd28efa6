#!/usr/bin/env bash
# The layers of core (core/CMakeLists.txt, docs/architecture.md) are enforced by the build:
# each layer compiles against a view of the headers of the layers below it. This compiles a
# one-line file against each view and checks that the includes a layer may make compile and
# those it may not fail, so a view that grew too wide (or a header that moved) is caught.
# Usage: layers.sh CXX VIEWS_DIR INCLUDE_DIR...
set -euo pipefail
cxx=$1 views=$2
shift 2
extra=()
for d in "$@"; do extra+=(-I "$d"); done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
probe() {  # probe LAYER HEADER yes|no
  local layer=$1 header=$2 want=$3
  printf '#include "%s"\n' "$header" >"$work/probe.cpp"
  if "$cxx" -std=c++17 -fsyntax-only -I "$views/$layer" "${extra[@]}" "$work/probe.cpp" \
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
probe physics core/step.hpp yes
probe physics core/stiffness.hpp yes
probe physics core/analysis/linear_stability.hpp no
probe physics core/io/scene_file.hpp no
probe physics core/sweep/summary.hpp no
probe physics core/monitor.hpp no
probe io core/io/scene_file.hpp yes
probe io core/analysis/criteria.hpp no
probe analysis core/analysis/linear_stability.hpp yes
probe analysis core/io/format.hpp yes
probe analysis core/sweep/summary.hpp no
probe sweep core/sweep/summary.hpp yes
probe sweep core/analysis/claims.hpp yes
probe sweep core/monitor.hpp no
probe monitor core/monitor.hpp yes
probe monitor core/analysis/linear_stability_exact.hpp yes
probe monitor core/sweep/runner.hpp no
[ "$fails" -eq 0 ] || { echo "layers: $fails probe(s) wrong"; exit 1; }
echo "layers: every layer sees the layers below it and none above"
