# docs/cli.md is what scripts/cli-reference.sh writes from this build's --help.
. "$(dirname "$0")/lib.inc"

expect_exit 0 bash "$SRC/scripts/cli-reference.sh" "$DB" "$WORK/cli.md"
if diff -u "$SRC/docs/cli.md" "$WORK/cli.md" >"$WORK/cli.diff"; then
  ok
else
  bad "docs/cli.md is stale: run bash scripts/cli-reference.sh (diff: $(head -c 600 "$WORK/cli.diff"))"
fi
for sub in run bounds suggest sweep check gui figure map merge reproduce; do
  expect_match "$(cat "$WORK/cli.md")" "## dampbound $sub" "section for $sub"
done

finish
