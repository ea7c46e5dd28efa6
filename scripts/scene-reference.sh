#!/usr/bin/env bash
# Writes docs/scene-format.md, the scene file reference, from the scene key table the reader
# checks keys against (core/io/scene_keys.cpp, printed by the hidden `dampbound scene-format`).
# tests/cli/scene_reference.sh fails when docs/scene-format.md is not what this writes.
#   scripts/scene-reference.sh [DAMPBOUND] [OUT]   (defaults: build/app/dampbound, docs/scene-format.md)
set -euo pipefail
cd "$(dirname "$0")/.."
db=${1:-build/app/dampbound}
out=${2:-docs/scene-format.md}
[ -x "$db" ] || { echo "scene-reference: $db is not built (bash scripts/build.sh --app)" >&2; exit 2; }
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
"$db" scene-format >"$tmp"
mv "$tmp" "$out"
trap - EXIT
echo "scene-reference: wrote $out ($(grep -c '^| `' "$out") keys)"
