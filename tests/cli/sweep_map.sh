# The stability map: sweep --map and dampbound map write a PNG through the headless EGL host.
. "$(dirname "$0")/lib.inc"

if ! "$DB" map --help >/dev/null 2>&1; then
  echo "no map subcommand in this build (DAMPBOUND_EGL=OFF): skipped"
  exit 0
fi
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }

expect_exit 0 "$DB" sweep --m 0.001:0.01:0.001 --kappa 0.001,0.002,0.005,0.01,0.1,0.3,0.5 \
  --zeta 0.25,0.5,1 --max-iter 60 -o "$WORK/s.csv" --map "$WORK/a.png" --progress none
expect_match "$OUT" "map +$WORK/a.png" "sweep --map"
is_png "$WORK/a.png" && ok || bad "sweep --map did not write a PNG"
expect_exit 0 "$DB" map "$WORK/s.csv" -o "$WORK/b.png" --size 1600x1200
expect_match "$OUT" 'map .* \(4 panels, lambda_max = [0-9.]+' "map report"
expect_match "$OUT" 'prediction +gamma < lower bound .* held in [0-9]+ of 140' "summary"
is_png "$WORK/b.png" && ok || bad "map did not write a PNG"
size=$(stat -c %s "$WORK/b.png")
[ "$size" -gt 20000 ] && ok || bad "map PNG suspiciously small ($size bytes)"
expect_exit 2 "$DB" map "$WORK/nonexistent.csv" -o "$WORK/c.png"
expect_one_line "$ERR" "map of a missing CSV"
finish
