# dampbound reproduce on a tiny grid: the report, its figures and maps, every claim judged.
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" reproduce -o "$WORK/rep" --grid 4 --threads 2
for f in report.md fig1.png fig2.png fig1.csv fig2.csv map-lower.png map-upper.png \
         sweep-lower.csv sweep-upper.csv map-lower-settled.png sweep-lower-settled.csv; do
  [ -s "$WORK/rep/$f" ] && ok || bad "reproduce did not write $f"
done
report=$(cat "$WORK/rep/report.md")
rows=$(grep -cE '^\| [0-9]+ \|' "$WORK/rep/report.md")
[ "$rows" -eq 8 ] && ok || bad "report has $rows claim rows, wanted 8"
expect_match "$report" '34 iterations .*\| gamma = 0\.002: (restored|not restored|diverged) at [0-9]+' "Fig. 1 claim measured"
expect_match "$report" '652 iterations .*\| factor 1\.0: (restored|not restored|diverged) at [0-9]+' "Fig. 2 claim measured"
expect_match "$report" '\*\*(holds|does not hold|partly)\*\*' "verdicts"
# SPEC 8: the rule that judges each claim; "keeps oscillating" is about the settled behaviour,
# and where the rules differ both verdicts are given.
expect_match "$report" '\| Rule \| Verdict \|' "rule column"
expect_match "$report" 'keeps oscillating .*\| gamma = 0\.0005: restored at 230 by the first entry; settled rule: settled at [0-9]+, (checked to [0-9]+|proven at [0-9]+ to stay to [0-9]+) \(entered the 1% band at 230, left it at [0-9]+.*\| settled \| \*\*' \
  "claim 1 judged by the settled rule, both verdicts given"
expect_match "$report" 'remained stable thereafter .*\| settled \| \*\*' "claim 3 judged by the settled rule"
expect_match "$report" 'not restored \(paper sec\. 4\) \| settled rule: held in [0-9]+ of [0-9]+ trials .*; first entry: held in [0-9]+ of [0-9]+ trials .*\| settled \| \*\*' \
  "the sweep's keeps-oscillating claim under both rules"
expect_match "$(grep -v '^#' "$WORK/rep/sweep-lower-settled.csv" | head -1)" ',first_entry,left_at,settled_at$' \
  "settled reduced sweep CSV"
expect_match "$report" 'held in [0-9]+ of [0-9]+ trials' "sweep claims counted"
# Nothing half-written is left behind.
left=$(find "$WORK/rep" -name '*.tmp*' -o -name '*.journal' | wc -l)
[ "$left" -eq 0 ] && ok || bad "temporary files left: $left"
# A folder that cannot be made: exit 2, one line naming it.
expect_exit 2 "$DB" reproduce -o /nonexistent-dir/sub --skip-sweeps
expect_one_line "$ERR" "unwritable -o"
expect_match "$ERR" '/nonexistent-dir/sub' "names the folder"
finish
