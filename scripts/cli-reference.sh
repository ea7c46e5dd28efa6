#!/usr/bin/env bash
# Writes docs/cli.md, the command-line reference, from the program's own --help (one section
# per subcommand). tests/cli/cli_reference.sh fails when docs/cli.md is not what this writes.
#   scripts/cli-reference.sh [DAMPBOUND] [OUT]   (defaults: build/app/dampbound, docs/cli.md)
set -euo pipefail
cd "$(dirname "$0")/.."
db=${1:-build/app/dampbound}
out=${2:-docs/cli.md}
[ -x "$db" ] || { echo "cli-reference: $db is not built (bash scripts/build.sh --app)" >&2; exit 2; }
help() { "$db" "$@" --help | sed -e 's|^Usage: [^ ]*dampbound|Usage: dampbound|' -e 's/[[:space:]]*$//'; }
subcommands=$(help | awk '/^Subcommands:/ {on = 1; next} on && /^  [a-z]/ {print $1}')
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
{
  echo "# Command-line reference"
  echo
  echo "Every subcommand's \`--help\`, as \`dampbound\` prints it (written by"
  echo "\`scripts/cli-reference.sh\`; a test fails when this page is stale). The README shows the"
  echo "three jobs people come for; this page is the full list of options."
  echo
  for sub in "" $subcommands; do
    if [ -z "$sub" ]; then echo "## dampbound"; else echo "## dampbound $sub"; fi
    echo
    echo '```text'
    if [ -z "$sub" ]; then help; else help "$sub"; fi
    echo '```'
    echo
  done
} >"$tmp"
mv "$tmp" "$out"
trap - EXIT
echo "cli-reference: wrote $out ($(echo $subcommands | wc -w) subcommands)"
