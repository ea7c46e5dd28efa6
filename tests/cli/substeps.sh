# suggest --frame-dt: substeps per frame from the exact limit and the safe bound, each run.
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" --digits 8 suggest paper-plane --frame-dt 2
expect_match "$OUT" 'exact limit +4 substeps: dt = 0\.5 s < 0\.50396164 s; verified' "exact: 2/4 = 0.5 < 0.50396"
expect_match "$OUT" 'safe bound +5 substeps: dt = 0\.4 s < 0\.48050615 s; verified' "safe: 2/5 = 0.4 < 0.4805"
expect_match "$OUT" '^answer +4 substeps per frame \(dt = 0\.5 s[;)]' "the answer: the exact count, verified"
expect_exit 1 "$DB" --digits 8 suggest paper-plane --frame-dt 2 --max-iter 3
expect_match "$OUT" 'NOT verified' "a failed verification is reported, exit 1"
expect_match "$OUT" 'by running +no count up to [0-9]+ substeps settled' "the search by running is reported"
expect_match "$OUT" '^answer +none verified' "no answer when nothing settles"
# kappa/m = 1000, gamma 0.02, frame 0.1 s: the exact count at rest (5) diverges from the 5 cm
# pull; the fewest count that settles is found by running.
expect_exit 0 "$DB" suggest paper-plane --frame-dt 0.1 --kappa 1 --gamma 0.02
expect_match "$OUT" 'exact limit +5 substeps: .*NOT verified: diverged at' "the exact count diverges"
expect_match "$OUT" 'the fewest that settles: 6 substeps; 5 substeps did not settle' "the bracket"
expect_match "$OUT" '^answer +6 substeps per frame' "the answer"
# At gamma 0.005 neither count settles (5 substeps each): the search runs 7 (settles) and 6
# (does not).
expect_exit 0 "$DB" suggest paper-plane --frame-dt 0.1 --kappa 1 --gamma 0.005
expect_match "$OUT" 'by running +7 substeps: dt = 0\.0142857 s; verified: settled' "found by running"
expect_match "$OUT" 'the fewest that settles: 7 substeps; 6 substeps did not settle' "the bracket, closed"
expect_exit 2 "$DB" --digits 8 suggest paper-plane --frame-dt 0
finish
