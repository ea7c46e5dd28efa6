# suggest --frame-dt: substeps per frame from the exact limit and the safe bound, each run.
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" --digits 8 suggest paper-plane --frame-dt 2
expect_match "$OUT" 'exact limit +4 substeps: dt = 0\.5 s < 0\.50396164 s; verified' "exact: 2/4 = 0.5 < 0.50396"
expect_match "$OUT" 'safe bound 5 substeps: dt = 0\.4 s < 0\.48050615 s; verified' "safe: 2/5 = 0.4 < 0.4805"
expect_exit 1 "$DB" --digits 8 suggest paper-plane --frame-dt 2 --max-iter 3
expect_match "$OUT" 'NOT verified' "a failed verification is reported, exit 1"
expect_exit 2 "$DB" --digits 8 suggest paper-plane --frame-dt 0
finish
