# dampbound gui --pin / --save-scene / --export / --tab map: the tuner to a CI check in one
# command, under Xvfb: tune, pin two runs, save; `check` passes on the file, and fails once a
# parameter in it is edited; the scripted export writes what the Export button writes.
. "$(dirname "$0")/lib.inc"

if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIP: xvfb-run is not installed"
  exit 0
fi
XV=(xvfb-run -a -s "-screen 0 1600x1000x24 -noreset")
CFG="$WORK/config"
SAVED="$WORK/tuned.toml"

# 1. Tune (gamma), pin two runs from the command line, save, export.
expect_exit 0 "${XV[@]}" "$DB" gui --pin gamma=0.0005,name=under "$SRC/scenes/paper-plane.toml" \
  --gamma 0.0015 --pin gamma=0.002,name=at --frames 5 --size 1024x640 \
  --save-scene "$SAVED" --export "$WORK/export" --export-prefix run --config-dir "$CFG"
expect_match "$ERR" "saved $SAVED: 2 runs, 3 expectations" "save summary"
[ -s "$SAVED" ] && ok || bad "no saved scene"
for f in run_plots.png run_traces.csv run_runs.csv; do
  [ -s "$WORK/export/$f" ] && ok || bad "export: no $f"
done
expect_match "$(cat "$WORK/export/run_runs.csv")" '^under,' "exported runs.csv has the pin"
# The runs' verdicts in the settled rule's words, as run --json has them; the current run
# (5 frames: unfinished) is left out unless asked for.
RUNS="$(cat "$WORK/export/run_runs.csv")"
expect_match "$RUNS" '^run,scene,watched,m,kappa,gamma,dt,policy,factor,rule,outcome,first_entry,left_at,settled_at,diverged_at,verdict,' "runs.csv has the band history"
expect_match "$RUNS" '^at,paper-plane,[^,]*,[^,]*,[^,]*,0.002,[^,]*,[^,]*,[^,]*,settled,settled,[0-9]+,,[0-9]+,,settled at [0-9]+,1000,' "a pin settled before the limit says where"
grep -q '^"\?current' "$WORK/export/run_runs.csv" && bad "the unfinished current run was exported" || ok
expect_exit 0 "${XV[@]}" "$DB" gui "$SRC/scenes/paper-plane.toml" --frames 2 --export "$WORK/export2" \
  --export-unfinished --config-dir "$CFG"
grep -q '^"current' "$WORK/export2/dampbound_runs.csv" && ok || bad "--export-unfinished: no current run"

# 2. The saved scene is a check: it passes headless.
expect_exit 0 "$DB" check "$SAVED" --junit "$WORK/tuned.xml"
expect_match "$OUT" 'check: [1-9][0-9]* passed, 0 failed' "saved scene passes"
expect_match "$OUT" '\[under\] \[settled\] outcome == settled' "the pin is checked (settled rule)"
expect_match "$(grep -c '^gamma = 0.0015' "$SAVED")" '^1$' "tuned gamma is [params]"

# 3. Edit the pinned run's gamma in the file: the check fails.
sed 's/^gamma = 0.0005$/gamma = 0.0009/' "$SAVED" >"$WORK/edited.toml"
cmp -s "$SAVED" "$WORK/edited.toml" && bad "the edit changed nothing" || ok
expect_exit 1 "$DB" check "$WORK/edited.toml"
expect_match "$OUT" 'FAIL .*\[under\]' "edited run fails"

# 4. The headless figure draws the saved scene's pins.
expect_exit 0 "$DB" figure "$SAVED" -o "$WORK/fig.png"
expect_match "$OUT" 'under ' "figure lists the pin"

# 5. The Map tab (its passes finish before the last frame), at the smallest supported size.
expect_exit 0 "${XV[@]}" "$DB" gui "$SRC/scenes/paper-plane.toml" --frames 3 --tab map \
  --size 1024x640 --screenshot "$WORK/map.png" --config-dir "$CFG"
[ -s "$WORK/map.png" ] && ok || bad "no map screenshot"

# 5b. The Suggest tab computes when scripted, and the last frame waits for it.
expect_exit 0 "${XV[@]}" "$DB" gui "$SRC/scenes/paper-plane.toml" --frames 2 --tab suggest \
  --size 1024x640 --screenshot "$WORK/suggest.png" --config-dir "$CFG"
expect_match "$ERR" 'gui: suggest: gamma in \[[0-9.e-]+, [0-9.e-]+\), fastest settling at' "--tab suggest computes"
# ... and the substeps for its frame time (--frame-dt; 1/60 s by default), the counts `suggest
# --frame-dt` gives, each verified.
expect_match "$ERR" 'gui: substeps at frame 0.0166667 s: exact limit 1 substep \(settled at [0-9]+\), safe bound 1 substep \(settled' "--tab suggest gives the substeps"
expect_exit 0 "${XV[@]}" "$DB" gui "$SRC/scenes/paper-plane.toml" --frames 2 --tab suggest \
  --frame-dt 2 --size 1024x640 --config-dir "$CFG"
want=$("$DB" suggest "$SRC/scenes/paper-plane.toml" --frame-dt 2 --no-verify 2>&1 | grep -E "^  (exact limit|safe bound)" | grep -Eo '[0-9]+ substeps' | head -2 | tr '\n' ' ')
got=$(printf '%s\n' "$ERR" | grep -Eo '(exact limit|safe bound) [0-9]+ substeps' | grep -Eo '[0-9]+ substeps' | tr '\n' ' ')
[ -n "$want" ] && [ "$want" = "$got" ] && ok || bad "gui --frame-dt 2 substeps '$got', suggest --frame-dt 2 '$want'"
expect_exit 2 "$DB" gui "$SRC/scenes/paper-plane.toml" --frame-dt 0
expect_match "$ERR" '--frame-dt' "bad --frame-dt named"

# 6. Bad input: one line naming the flag, exit 2, nothing written.
expect_exit 2 "${XV[@]}" "$DB" gui "$SRC/scenes/paper-plane.toml" --frames 2 --pin foo=1 \
  --save-scene "$WORK/bad.toml" --config-dir "$CFG"
expect_match "$ERR" '--pin foo=1: unknown key' "bad --pin named"
expect_one_line "$ERR" "bad --pin"
[ -e "$WORK/bad.toml" ] && bad "bad --pin wrote a file" || ok
expect_exit 2 "$DB" gui "$SRC/scenes/paper-plane.toml" --frames 2 --save-scene /nonexistent/x.toml
expect_match "$ERR" '--save-scene' "unwritable --save-scene named"
expect_exit 2 "$DB" gui "$SRC/scenes/paper-plane.toml" --export "$WORK/e2"
expect_match "$ERR" '--export needs --frames' "--export without --frames"

finish
