# bounds --worst N: the nodes that limit dt and gamma, and why.
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" bounds "$SRC/scenes/paper-plane.toml" --worst 2
expect_match "$OUT" 'worst 2 by dt_safe_i' "text table"
expect_match "$OUT" 'typical node' "uniform plane: typical"
expect_exit 0 "$DB" bounds "$SRC/scenes/tissue-cap.toml" --worst 1 --json
expect_match "$OUT" '^\{"median_mass":.*"by_dt_safe":\[\{"node":0,.*"cause":"degree [0-9.]+x above the median"' "JSON, cause in words"
expect_exit 2 "$DB" bounds paper-plane --json
finish
