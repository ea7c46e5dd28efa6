# One sweep, one model: the sweep id covers the mesh a scene reads, not only the scene's text.
# The same scene file over a changed mesh is another sweep: --resume does not take the old
# journal's classes, and merge refuses parts of the two.
. "$(dirname "$0")/lib.inc"

mkdir -p "$WORK/s/meshes"
cp "$SRC/scenes/quad-cloth.toml" "$WORK/s/"
cp "$SRC/scenes/meshes/quad-cloth.obj" "$WORK/s/meshes/"
SMALL=(--m 0.001 --kappa 0.001,0.002 --zeta 1 --max-iter 5 --progress none)
id_of() { sed -n 's/^# sweep-id: //p' "$1"; }

expect_exit 0 "$DB" sweep "$WORK/s/quad-cloth.toml" "${SMALL[@]}" -o "$WORK/a.csv" --shard 1/2
A=$(id_of "$WORK/a.csv")
# Move the first vertex a little: the scene file's bytes are unchanged.
awk 'BEGIN{d=0} /^v / && !d {$2 = $2 + 0.01; d=1} {print}' "$WORK/s/meshes/quad-cloth.obj" \
  >"$WORK/moved.obj" && mv "$WORK/moved.obj" "$WORK/s/meshes/quad-cloth.obj"
expect_exit 0 "$DB" sweep "$WORK/s/quad-cloth.toml" "${SMALL[@]}" -o "$WORK/b.csv" --shard 2/2
B=$(id_of "$WORK/b.csv")
if [ -n "$A" ] && [ -n "$B" ] && [ "$A" != "$B" ]; then ok; else bad "same sweep id '$A' for two meshes"; fi
expect_exit 2 "$DB" merge "$WORK/a.csv" "$WORK/b.csv" -o "$WORK/m.csv"
expect_match "$ERR" "belongs to sweep" "merge of two meshes"
[ -e "$WORK/m.csv" ] && bad "merge wrote output for parts of two meshes"
finish
