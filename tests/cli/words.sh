# Every message names what to fix (docs/hardening.md, "Words"): --digits in every row, the
# nearest flag for a misspelt one, caps stated, counts in the singular, every parameter of a
# run in its JSON and its VTU files, one series per VTU folder, merge checking rows.
. "$(dirname "$0")/lib.inc"

# max_digits TEXT: the most significant digits of any decimal number in TEXT.
max_digits() {
  printf '%s\n' "$1" | grep -oE '[0-9]*\.[0-9]+' | sed -E 's/\.//; s/^0+//' | awk '{ if (length($0) > m) m = length($0) } END { print m + 0 }'
}

# --digits reaches every row of bounds, without and with a scene.
expect_exit 0 "$DB" --digits 3 bounds --m 0.001 --kappa 0.003 --dt 0.1
d=$(max_digits "$OUT")
[ "$d" -le 3 ] && ok || bad "bounds --digits 3 prints a number of $d digits: $(printf '%s\n' "$OUT" | grep -E '[0-9]\.[0-9]{4,}' | head -2)"
expect_exit 0 "$DB" --digits 3 bounds two-node --worst 2
d=$(max_digits "$OUT")
[ "$d" -le 3 ] && ok || bad "bounds two-node --digits 3 prints a number of $d digits: $(printf '%s\n' "$OUT" | grep -E '[0-9]\.[0-9]{4,}' | head -2)"

# A misspelt flag: the nearest one; an unknown one: where the list is.
expect_exit 2 "$DB" run two-node --gama 0.1
expect_one_line "$ERR" "--gama"
expect_match "$ERR" "unknown flag --gama for 'run' \(did you mean --gamma\?\)" "--gama: did you mean --gamma"
expect_exit 2 "$DB" bounds two-node --wrost 3
expect_match "$ERR" "did you mean --worst\?" "--wrost: did you mean --worst"
expect_exit 2 "$DB" suggest two-node --frobnicate
expect_match "$ERR" "unknown flag --frobnicate for 'suggest' \(dampbound suggest --help lists the flags\)" "no near flag"
# A whole number that is not one: the flag and the accepted values, no "Value abc".
expect_exit 2 "$DB" run two-node --max-iter abc
expect_match "$ERR" "--max-iter: 'abc' is not a whole number \(give one from 1 to 100000000\)" "--max-iter abc"
case $ERR in *"not in range"*) bad "CLI11's words: $ERR" ;; *) ok ;; esac

# suggest --gamma without --dt: no word about a dt nobody gave; where no dt is stable, it says
# so first, exit 1.
expect_exit 1 "$DB" suggest two-node --gamma 1e6
case "$OUT$ERR" in *"dt must be > 0"*) bad "suggest --gamma 1e6 blames a dt: $ERR $OUT" ;; *) ok ;; esac
# 2 m / gamma = 2e-9 s: the exact limit (SPEC 7's root, evaluated without cancellation), said
# first; its run cannot settle in 1000 steps of 2e-9 s, so the answer is not verified (exit 1).
expect_match "$OUT" "^answer +use dt <= 2e-09 s at gamma = 1e\+06" "suggest --gamma 1e6: the limit, said first"

# --frame-dt past the cap: the cap, stated.
"$DB" suggest two-node --frame-dt 1e6 --no-verify >"$WORK/out" 2>"$WORK/err"
OUT=$(cat "$WORK/out")
expect_match "$OUT" "more than the cap of 1,000,000 substeps" "--frame-dt 1e6 states the cap"

# --worst past the free nodes: how many are shown.
expect_exit 0 "$DB" bounds two-node --worst 100
expect_match "$OUT" "the 1 free node \(100 asked\) by dt_safe_i" "--worst 100 on one free node"
case $OUT in *"worst 100"*) bad "--worst 100 says worst 100: $OUT" ;; *) ok ;; esac

# One spring, not "1 springs", anywhere in the three commands.
for cmd in "run two-node" "bounds two-node" "suggest two-node --no-verify"; do
  $DB $cmd >"$WORK/out" 2>&1
  if grep -Eq '(^|[^0-9.])1 (springs|nodes|anchors|runs|steps|free nodes)\b' "$WORK/out"; then
    bad "$cmd: $(grep -E '(^|[^0-9.])1 (springs|nodes|anchors|runs|steps|free nodes)\b' "$WORK/out" | head -1)"
  else ok; fi
done
expect_exit 0 "$DB" run two-node
expect_match "$OUT" "2 nodes, 1 spring, 0 anchors" "run two-node: 1 spring"

# run --json: every parameter that shaped the run.
expect_exit 0 "$DB" run two-node --json --kd 0.0005 --rayleigh-mass 0.25 --rayleigh-stiffness 0.001
for kv in '"kd":0.0005' '"rayleigh_mass":0.25' '"rayleigh_stiffness":0.001' '"reference":' \
          '"restore_fraction":' '"diverge_factor":' '"integrator":' '"policy":'; do
  expect_match "$OUT" "$kv" "run --json carries $kv"
done

# A VTU folder rerun: one series, its files those series.pvd lists, and the parameters in each.
V=$WORK/vtu
expect_exit 0 "$DB" run two-node --vtk "$V" --every 10 --max-iter 100
expect_exit 0 "$DB" run two-node --vtk "$V" --every 10 --max-iter 40 --kd 0.0005
listed=$(grep -oE 'step_[0-9]+\.vtu' "$V/series.pvd" | sort)
present=$(ls "$V" | grep -E '^step_[0-9]+\.vtu$' | sort)
[ "$listed" = "$present" ] && ok || bad "the folder's step files are not the series': listed $listed; present $present"
grep -q 'Name="kd" NumberOfTuples="1" format="ascii">0.0005<' "$V/step_000000.vtu" && ok ||
  bad "the .vtu carries no kd"

# merge refuses a row edited under an intact header.
GRID=(--m 0.001,0.002 --kappa 0.001,0.002 --zeta 1 --max-iter 60 --progress none)
expect_exit 0 "$DB" sweep two-node "${GRID[@]}" --shard 1/2 -o "$WORK/p1.csv"
expect_exit 0 "$DB" sweep two-node "${GRID[@]}" --shard 2/2 -o "$WORK/p2.csv"
expect_exit 0 "$DB" merge "$WORK/p1.csv" "$WORK/p2.csv" -o "$WORK/m.csv"
row=$(grep -E '^[0-9]+,' "$WORK/p2.csv" | head -1)
trial=${row%%,*}
edited=$(printf '%s' "$row" | awk -F, -v OFS=, '{ $2 = "0.005"; print }')
sed "s/^$row\$/$edited/" "$WORK/p2.csv" >"$WORK/p2e.csv"
rm -f "$WORK/m2.csv"
expect_exit 2 "$DB" merge "$WORK/p1.csv" "$WORK/p2e.csv" -o "$WORK/m2.csv"
expect_match "$ERR" "p2e.csv: trial $trial: m is 0.005, the sweep's grid has" "merge names the edited row"
[ ! -e "$WORK/m2.csv" ] && ok || bad "merge wrote a file from an edited part"

finish
