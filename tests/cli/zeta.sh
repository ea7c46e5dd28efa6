# The nodal damping ratio: --zeta and [params] zeta resolve to gamma_i = zeta * 2 sqrt(m_i kappa_i).
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" run paper-plane --zeta 1 --max-iter 20
expect_match "$OUT" 'gamma=0\.002 \(zeta=1\)' "--zeta 1 on the paper plane is gamma = 0.002"
expect_exit 0 "$DB" run paper-plane --gamma 0.001 --max-iter 20 --json
expect_match "$OUT" '"gamma":0\.001,"zeta_min":0\.5,"zeta_max":0\.5' "JSON gives zeta beside gamma"
expect_exit 2 "$DB" run paper-plane --zeta 1 --gamma 0.002
expect_exit 0 "$DB" bounds paper-plane --zeta 0.5
expect_match "$OUT" 'gamma=0\.001 \(zeta=0\.5\)' "bounds --zeta"
expect_exit 0 "$DB" suggest paper-plane --zeta 1 --no-verify
expect_match "$OUT" 'largest stable dt at gamma = 0\.002 \(zeta = 1\)' "suggest --zeta"

# A scene with zeta: the same gamma per node as --zeta; with gamma too, exit 2 naming the key.
cat > "$WORK/z.toml" <<'TOML'
name = "z"
[grid]
nx = 4
nz = 4
spacing = 0.57
[params]
zeta = 2
TOML
expect_exit 0 "$DB" run "$WORK/z.toml" --max-iter 5
expect_match "$OUT" 'gamma=0\.004 \(zeta=2\)' "[params] zeta"
expect_exit 0 "$DB" run "$WORK/z.toml" --max-iter 5 --trace "$WORK/t.csv"
expect_match "$(head -1 "$WORK/t.csv")" 'gamma,gamma_effective,zeta,zeta_effective,' "trace CSV has zeta"
printf 'gamma = 0.002\n' >> "$WORK/z.toml"
expect_exit 2 "$DB" run "$WORK/z.toml"
expect_match "$ERR" 'z\.toml:[0-9]+: \[params\]: zeta and gamma exclude each other' "both keys: file and key named"
finish
