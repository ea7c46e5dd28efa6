# dampbound run and bounds: outputs, traces, help, bad flags and bad scene files.
. "$(dirname "$0")/lib.inc"

# The issue's acceptance command.
expect_exit 0 "$DB" run "$SRC/scenes/paper-plane.toml" --m 0.001 --kappa 0.001 --gamma 0.002 --json
expect_match "$OUT" '^\{.*"outcome":"(settled|diverged|not_settled)".*"iterations":[0-9]+' "run --json"
for key in max_displacement violations unstabilisable; do
  expect_match "$OUT" "\"$key\":" "run --json has $key"
done

# A shipped scene by name, text output.
expect_exit 0 "$DB" run two-node
expect_match "$OUT" '^answer +settled at [0-9]+, (checked to 1000|proven at [0-9]+ to stay to 1000); t = [0-9.]+ s, at gamma' "run text verdict, first"
[ "$(printf '%s\n' "$OUT" | grep -c 'settled')" = 1 ] && ok || bad "one verdict, said once: $OUT"

# Diverging run: reported as diverged, no NaN anywhere.
expect_exit 0 "$DB" run paper-plane --kappa 1 --gamma 0 --json --trace "$WORK/div.csv"
expect_match "$OUT" '"outcome":"diverged"' "stiff undamped run diverges"
if grep -qi nan "$WORK/div.csv" <<<"$OUT"; then bad "NaN in output"; else ok; fi
if grep -qi nan "$WORK/div.csv"; then bad "NaN in trace"; else ok; fi

# Threads: a 36100-node plane (big enough to split the node loops) gives the same trace
# bytes on 1 and 3 threads.
sed -e 's/nx = 36/nx = 190/; s/nz = 36/nz = 190/; s/policy = "fixed"/policy = "clamp"/' \
  "$SRC/scenes/paper-plane.toml" >"$WORK/big-plane.toml"
expect_exit 0 "$DB" run "$WORK/big-plane.toml" --max-iter 60 --trace "$WORK/t1.csv" --threads 1
expect_exit 0 "$DB" run "$WORK/big-plane.toml" --max-iter 60 --trace "$WORK/t3.csv" --threads 3
cmp -s "$WORK/t1.csv" "$WORK/t3.csv" && ok || bad "trace differs between 1 and 3 threads"
expect_exit 2 "$DB" run two-node --threads -1

# Trace: a header and one row per iteration.
expect_exit 0 "$DB" run paper-plane --gamma 0.001 --max-iter 40 --trace "$WORK/t.csv" --json
iters=$(printf '%s' "$OUT" | sed -E 's/.*"iterations":([0-9]+).*/\1/')
rows=$(($(wc -l <"$WORK/t.csv") - 1))
[ "$rows" -eq "$iters" ] && ok || bad "trace has $rows rows for $iters iterations"
expect_match "$(head -1 "$WORK/t.csv")" '^iteration,time,displacement,lower_bound,upper_bound,gamma,gamma_effective,zeta,zeta_effective,max_displacement' "trace header"
expect_match "$(sed -n 2p "$WORK/t.csv")" '^1,0\.05,' "first trace row"

# Flags override the scene; --max-iter stops the run.
expect_exit 0 "$DB" run paper-plane --gamma 0 --max-iter 7 --json
expect_match "$OUT" '"outcome":"not_settled","iterations":7' "--max-iter"
expect_match "$OUT" '"gamma":0,' "--gamma overrides"

# Help on every subcommand, with units.
for sub in run bounds; do
  expect_exit 0 "$DB" "$sub" --help
  expect_match "$OUT" '\(s\)|mass unit' "$sub --help names units"
done

# bounds: hand-computed values.
expect_exit 0 "$DB" bounds --m 0.001 --kappa 0.001 --dt 0.05
expect_match "$OUT" 'gamma_lo = 2\*sqrt\(m\*kappa\) = 0\.002$' "bounds lower"
expect_exit 0 "$DB" bounds --m 0.001 --kappa 0.001 --dt 0.05 --v 1,0,0 --force -0.001,0,0
expect_match "$OUT" '= 0\.019' "bounds upper"
expect_match "$OUT" 'stabilisable' "bounds check"
expect_exit 0 "$DB" bounds --m 0.001 --kappa 1 --dt 0.05 --v 1,0,0 --force -0.02,0,0
expect_match "$OUT" 'UNSTABILISABLE' "bounds check fails when lo > hi"

# Bad flags: one line naming the flag, exit 2.
for args in "--m -1" "--m nan" "--kappa 0" "--dt abc" "--policy wobbly" "--max-iter 0" "--gamma inf"; do
  # shellcheck disable=SC2086
  expect_exit 2 "$DB" run paper-plane $args
  expect_one_line "$ERR" "run $args"
  flag=${args%% *}
  expect_match "$ERR" -- "$flag" "error names $flag"
done
expect_exit 2 "$DB" bounds --m 0.001 --kappa 0.001 --dt 0.05 --v 1,0 --force 0,0,0
expect_match "$ERR" -- '--v' "bounds names --v"
expect_exit 2 "$DB" run
expect_exit 2 "$DB" frobnicate

# Bad scene files: one line FILE:LINE, exit 2, and no trace file left behind.
write() { printf '%b' "$2" >"$WORK/$1"; }
write unknown.toml '[grid]\nnx = 2\nnz = 2\nspacing = 1.0\nfoo = 3\n'
write missing.toml '[grid]\nnx = 2\nspacing = 1.0\n'
write negmass.toml '[grid]\nnx = 2\nnz = 2\nspacing = 1.0\n[params]\nm = -1\n'
write nospring.toml '[[node]]\nx = [0,0,0]\n[[spring]]\nnodes = [0, 3]\n'
write dup.toml '[[node]]\nx = [0,0,0]\n[[node]]\nx = [1,0,0]\n[[spring]]\nnodes = [0, 1]\n[[spring]]\nnodes = [0, 1]\n'
write nan.toml '[grid]\nnx = 2\nnz = 2\nspacing = nan\n'
write syntax.toml '[grid\nnx = 2\n'
for f in unknown:5 missing:1 negmass:6 nospring:4 dup:8 nan:4 syntax:1; do
  name=${f%%:*}; line=${f##*:}
  expect_exit 2 "$DB" run "$WORK/$name.toml" --trace "$WORK/$name.csv"
  expect_one_line "$ERR" "$name"
  expect_match "$ERR" "$name\.toml:$line: " "$name names file and line"
  [ ! -e "$WORK/$name.csv" ] && ok || bad "$name left a trace file"
done
expect_exit 2 "$DB" run "$WORK/does-not-exist.toml"
expect_match "$ERR" 'does-not-exist.toml: cannot open' "missing file"
expect_exit 2 "$DB" run paper-plane --trace /nonexistent-dir/t.csv
expect_match "$ERR" '/nonexistent-dir/t.csv' "unwritable trace names the path"

finish
