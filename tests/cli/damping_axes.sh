# SPEC 10 beyond run and bounds: sweep axes (three more columns, read back by map), map
# --axes with the exact boundary, suggest's range per damping kind, figure's flags, and
# a sweep without the axes keeps its bytes.
. "$(dirname "$0")/lib.inc"
scene="$SRC/scenes/two-node.toml"
expect_exit 0 "$DB" sweep "$scene" --m 0.001 --kappa 0.001 --gamma 0.002 --kd 0,0.002 \
  --rayleigh-stiffness 0,0.1 --dt 0.05,0.5 --max-iter 200 -o "$WORK/d.csv" --progress none
expect_match "$OUT" "Session per trial: dashpot or Rayleigh" "says it runs step() per trial"
expect_match "$(cat "$WORK/d.csv")" "^trial,m,kappa,gamma,zeta,dt,policy,factor,kd,rayleigh_mass,rayleigh_stiffness,class" "three more columns"
expect_match "$(cat "$WORK/d.csv")" "kd=0,0.002 rayleigh-mass=0 rayleigh-stiffness=0,0.1" "the definition names the axes"
rows=$(grep -c '^[0-9]' "$WORK/d.csv")
[ "$rows" = 8 ] && ok || bad "8 rows expected, got $rows"
expect_exit 0 "$DB" map "$WORK/d.csv" --axes kd:dt --axes rayleigh_stiffness:dt -o "$WORK/d.png"
expect_match "$OUT" "2 panels" "two panels"
[ -s "$WORK/d.png" ] && ok || bad "no map PNG"
expect_exit 2 "$DB" map "$WORK/d.csv" --axes kd -o "$WORK/e.png"
expect_one_line "$ERR" "--axes"
expect_exit 2 "$DB" map "$WORK/d.csv" --axes kd:wobble -o "$WORK/e.png"
expect_match "$ERR" "unknown column 'wobble'" "names the column"
[ ! -e "$WORK/e.png" ] && ok || bad "a refused map left a file"
# No SPEC 10 axis: the CSV is the one a sweep wrote before the axes existed.
expect_exit 0 "$DB" sweep "$scene" --m 0.001 --kappa 0.001 --gamma 0.002 --dt 0.05 \
  --max-iter 50 -o "$WORK/p.csv" --progress none
expect_match "$(cat "$WORK/p.csv")" "^trial,m,kappa,gamma,zeta,dt,policy,factor,class,ran" "old columns"
# suggest: the stable range of each kind with the others held.
expect_exit 0 "$DB" --digits 8 suggest "$SRC/scenes/paper-plane.toml" --kd 0.002
expect_match "$OUT" "kd +now 0.002 +stable for kd in \[0, 0.0048391[0-9]*\)" "the dashpots' range"
expect_match "$OUT" "gamma_max  0.024180042" "the gamma range counts the dashpots"
expect_exit 2 "$DB" --digits 8 suggest paper-plane --kd -1
# figure takes the flags for a scene, refuses them for the paper's figures.
expect_exit 0 "$DB" figure "$SRC/scenes/two-node.toml" --kd 0.001 -o "$WORK/f.png"
expect_exit 2 "$DB" figure fig1 --kd 0.001 -o "$WORK/g.png"
expect_one_line "$ERR" "--kd"
finish
