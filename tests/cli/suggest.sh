# dampbound suggest: stable values, each verified by a run (docs/criteria.md).
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" --digits 8 suggest paper-plane
expect_match "$OUT" 'gamma_min +0\.002 +set by paper eq\. 5' "lower end from eq. 5"
expect_match "$OUT" 'gamma_max +0\.039804692 +set by exact upper limit \(semi-implicit-euler\)' "upper end exact"
expect_match "$OUT" '1296 nodes like 0 ' "one node class"
expect_match "$OUT" 'fastest settling gamma +0\.002 .*rho = 0\.96' "fastest settling"
expect_match "$OUT" 'fastest-settling gamma +gamma=0\.002 +zeta=1 +dt=0\.05 +verified: settled at [0-9]+' "verified by a run (settled rule)"

expect_exit 0 "$DB" --digits 8 suggest paper-plane --gamma 0.002
expect_match "$OUT" 'exact limit +dt < 0\.50396164 s' "largest stable dt"
expect_match "$OUT" 'all criteria +dt <= 0\.31830989 s, set by Delingette' "all criteria"
expect_match "$OUT" '99% of the exact limit +gamma=0\.002 +zeta=1 +dt=0\.49892202 +settled' "verified at 99%"

expect_exit 1 "$DB" --digits 8 suggest paper-plane --dt 0.6
expect_match "$OUT" 'no damping satisfies every criterion' "empty range"
expect_match "$OUT" 'largest stable dt at gamma_min: 0\.50396164 s' "what would do"

expect_exit 0 "$DB" --digits 8 suggest stiff-region --trials 4 --max-iter 400
expect_match "$OUT" '1127 nodes like 0 ' "outside class"
expect_match "$OUT" '169 nodes like [0-9]+ +m_i=0\.004 +kappa_i=0\.01 ' "stiff square class"
expect_match "$OUT" 'earliest settled iteration' "trials for non-uniform rates"

expect_exit 0 "$DB" --digits 8 suggest two-node --integrator verlet --no-verify
expect_match "$OUT" 'gamma_max +inf' "Verlet: no upper limit"
if printf '%s' "$OUT" | grep -q verification; then bad "--no-verify still ran"; else ok; fi

# Over the factorisation budget: what is proved stable without one (SPEC 9's Gershgorin
# proof on SPEC 7's index matrix), with the exact limit bracketed (it printed an error).
expect_exit 0 "$DB" --digits 8 suggest paper-plane --factor-budget 1e-9 --no-verify
expect_match "$OUT" 'gamma_max +0\.039775 +set by proved stable without a factorisation: Gershgorin on the exact index matrix, included' "over budget: the proved range"
expect_match "$OUT" 'exact limits not computed: one factorisation would take .* over the budget of 1e-09 GFlop' "over budget: says why"
expect_match "$OUT" 'the exact upper limit lies in \[0\.039775, 0\.039804694\)' "over budget: the bracket holds 0.039804692"
expect_match "$OUT" 'fastest settling gamma +0\.002 .*rho <= 0\.96\)' "over budget: best gamma with a bound on rho"
expect_exit 0 "$DB" --digits 8 suggest paper-plane --factor-budget 1e-9 --no-verify --gamma 0.002
expect_match "$OUT" 'proved stable dt <= 0\.48050615 s' "over budget: the proved dt"
expect_match "$OUT" 'it lies in \[0\.48050615, 0\.50396303\)' "over budget: the dt bracket holds 0.50396164"
expect_exit 0 "$DB" --digits 8 suggest paper-plane --factor-budget 1e-9 --integrator implicit-euler --no-verify
expect_match "$OUT" 'gamma_max +inf +set by proved stable without a factorisation: implicit Euler' "over budget: implicit Euler unconditional"
expect_exit 2 "$DB" --digits 8 suggest paper-plane --factor-budget 0
expect_match "$ERR" -- '--factor-budget' "names --factor-budget"

expect_exit 2 "$DB" --digits 8 suggest paper-plane --dt 0.05 --gamma 0.002
expect_one_line "$ERR" "--dt and --gamma exclude each other"
expect_exit 2 "$DB" suggest
expect_exit 2 "$DB" --digits 8 suggest paper-plane --dt -1
expect_match "$ERR" -- '--dt' "names --dt"

finish
