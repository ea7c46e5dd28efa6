# What a person reads: no "SPEC N" (the docs cite it, the output speaks words) and an unknown
# subcommand answered with the visible ones only.
. "$(dirname "$0")/lib.inc"

no_spec() {  # no_spec WHAT: stdout and stderr of the last command carry no "SPEC <digit>"
  if printf '%s\n%s' "$OUT" "$ERR" | grep -Eq 'SPEC [0-9]'; then
    bad "$1 prints SPEC: $(printf '%s\n%s' "$OUT" "$ERR" | grep -E -m1 'SPEC [0-9]')"
  else ok; fi
}
S=$SRC/scenes
expect_exit 0 "$DB" run "$S/two-node.toml" && no_spec "run two-node"
expect_exit 0 "$DB" run "$S/quad-cloth-dashpots.toml" --max-iter 50 --verbose && no_spec "run --verbose"
expect_exit 0 "$DB" bounds "$S/two-node.toml" && no_spec "bounds two-node"
expect_exit 0 "$DB" bounds "$S/quad-cloth-dashpots.toml" && no_spec "bounds (damped)"
expect_exit 0 "$DB" bounds "$S/stiff-region.toml" --worst 3 && no_spec "bounds --worst"
"$DB" suggest "$S/two-node.toml" >"$WORK/out" 2>"$WORK/err"
OUT=$(cat "$WORK/out"); ERR=$(cat "$WORK/err"); no_spec "suggest"
expect_exit 0 "$DB" check "$S/two-node-damping.toml" && no_spec "check"
expect_exit 0 "$DB" sweep --m 0.001 --kappa 0.001,0.002 --zeta 0.5,1 --dt 0.05 --max-iter 50 \
  -o "$WORK/s.csv" --progress none && no_spec "sweep"
if grep -Eq 'SPEC [0-9]' "$WORK/s.csv"; then bad "the sweep CSV's header cites SPEC"; else ok; fi
# The shipped scenes' names and descriptions: the tuner shows them under its scene combo.
if grep -E '^(name|description) *=.*SPEC [0-9]' "$S"/*.toml; then
  bad "a shipped scene's description cites SPEC"
else ok; fi

# An unknown subcommand lists what --help lists: not the hidden scene-format.
expect_exit 2 "$DB" frobnicate
expect_one_line "$ERR" "unknown subcommand"
expect_match "$ERR" "unknown subcommand 'frobnicate' \(one of: .*run.*\)" "names the word and the commands"
case $ERR in *scene-format*) bad "the hidden scene-format is listed: $ERR" ;; *) ok ;; esac
HELP=$("$DB" --help)
for c in $(sed -E 's/.*one of: (.*)\)$/\1/; s/,//g' <<<"$ERR"); do
  expect_match "$HELP" "^  $c +" "$c (listed) is in --help"
done

finish
