# SPEC 10 through the CLI: an independent NumPy step (tests/cli/damping_reference.py) against
# `run --trace` under the fixed and safe policies, the flags on run, bounds, suggest, and the
# scene keys' validation.
. "$(dirname "$0")/lib.inc"
PY3=$(command -v /usr/bin/python3 || true)
if [ -n "$PY3" ] && "$PY3" -c 'import numpy' 2>/dev/null; then
  for policy in fixed safe; do
    if "$PY3" "$SRC/tests/cli/damping_reference.py" "$DB" "$WORK" "$policy" >"$WORK/ref" 2>&1; then
      ok
    else
      bad "NumPy reference ($policy): $(cat "$WORK/ref")"
    fi
  done
else
  echo "NumPy absent: the reference step is skipped"
fi
scene="$SRC/scenes/paper-plane.toml"
for flag in --kd --rayleigh-mass --rayleigh-stiffness; do
  expect_exit 2 "$DB" run "$scene" "$flag" -1 && expect_one_line "$ERR" "$flag -1"
  expect_exit 2 "$DB" run "$scene" "$flag" nan
  expect_exit 0 "$DB" run "$scene" "$flag" 0.001 --max-iter 5
done
printf '[[node]]\nx = [0.0, 0.0, 0.0]\n[params]\nkd = -1\n' >"$WORK/bad.toml"
expect_exit 2 "$DB" run "$WORK/bad.toml" && expect_match "$ERR" "kd" "negative kd names the key"
# kd = 0 given explicitly changes nothing.
"$DB" run "$scene" --json --max-iter 50 >"$WORK/a.json"
"$DB" run "$scene" --json --max-iter 50 --kd 0 --rayleigh-mass 0 --rayleigh-stiffness 0 >"$WORK/b.json"
if cmp -s "$WORK/a.json" "$WORK/b.json"; then ok; else bad "kd = alpha = beta = 0 changed the run"; fi
finish
