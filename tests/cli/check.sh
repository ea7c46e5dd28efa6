# dampbound check: the shipped scenes pass, a failing expectation fails, JUnit is well-formed.
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" check "$SRC/scenes" --junit "$WORK/junit.xml"
expect_match "$OUT" 'check: [1-9][0-9]* passed, 0 failed' "shipped scenes pass"
if command -v python3 >/dev/null; then
  python3 - "$WORK/junit.xml" <<'PY' && ok || bad "junit not well-formed"
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
assert root.tag == "testsuites", root.tag
cases = root.findall("./testsuite/testcase")
assert len(cases) == int(root.get("tests")) > 0
assert int(root.get("failures")) == 0
PY
else
  expect_match "$(head -1 "$WORK/junit.xml")" '^<\?xml' "junit header"
fi

# A scene whose expectation cannot hold: exit 1, a FAIL line with the measured value.
cat >"$WORK/wrong.toml" <<'TOML'
[[node]]
x = [0, 0, 0]
fixed = true
[[node]]
x = [1, 0, 0]
[[spring]]
nodes = [0, 1]
[params]
gamma = 0.002
[[perturb]]
node = 1
displacement = [0.5, 0, 0]
[[expect]]
outcome = "diverged"
TOML
expect_exit 1 "$DB" check "$WORK/wrong.toml" --junit "$WORK/wrong.xml"
# An [[expect]] without a rule is judged by the default rule, settled (SPEC 8).
expect_match "$OUT" 'FAIL .*wrong.toml:13 \[settled\] outcome == diverged \(measured settled at [0-9]+' "fail line"
expect_match "$(cat "$WORK/wrong.xml")" '<failure message="measured settled' "junit failure"
sed 's/^outcome = "diverged"/rule = "first-entry"\noutcome = "diverged"/' "$WORK/wrong.toml" >"$WORK/wrong-first.toml"
expect_exit 1 "$DB" check "$WORK/wrong-first.toml"
expect_match "$OUT" 'FAIL .*wrong-first.toml:13 \[first-entry\] outcome == diverged \(measured restored at [0-9]+' "first-entry named"
sed 's/^outcome = "diverged"/outcome = "settled"/' "$WORK/wrong.toml" >"$WORK/default-settled.toml"
expect_exit 0 "$DB" check "$WORK/default-settled.toml"
expect_match "$OUT" 'pass .*default-settled.toml:13 \[settled\] outcome == settled' "no rule: settled"
# A key an [[expect]] does not have is bad input for check too: exit 2, file and line.
sed 's/^outcome = "diverged"/outcome = "settled"\nsettled_by = [1, 2]/' "$WORK/wrong.toml" >"$WORK/badkey.toml"
expect_exit 2 "$DB" check "$WORK/badkey.toml"
expect_match "$OUT$ERR" "badkey\.toml:[0-9]+: unknown key 'settled_by' in \[\[expect\]\]" "bad expect key"

# The settled rule (SPEC 8): the undamped oscillator enters the band at 31 and leaves it.
sed -e 's/^gamma = 0.002/gamma = 0.0/' -e 's/^outcome = "diverged"/rule = "settled"\noutcome = "not_settled"\nfirst_entry = [31, 31]\nleft = true/' \
  "$WORK/wrong.toml" >"$WORK/settled.toml"
expect_exit 0 "$DB" check "$WORK/settled.toml"
expect_match "$OUT" 'pass .*settled.toml:13 \[settled\] outcome == not_settled \(measured not settled, checked to 1000 \(entered the 1% band at 31, left it at [0-9]+\)\)' "settled pass line"
expect_match "$OUT" '\[settled\] left == true \(measured left at [0-9]+\)' "left pass line"
sed -e 's/^left = true/settled_at = [1, 1000]/' "$WORK/settled.toml" >"$WORK/never.toml"
expect_exit 1 "$DB" check "$WORK/never.toml"
expect_match "$OUT" 'FAIL .*\[settled\] settled_at in \[1, 1000\] \(measured none\)' "no settled iteration fails"

# Expectations that mix the rules' words are bad input, named by file and line.
write_expect() { printf '[[node]]\nx = [0, 0, 0]\nfixed = true\n[[node]]\nx = [1, 0, 0]\n[[spring]]\nnodes = [0, 1]\n[[perturb]]\nnode = 1\ndisplacement = [0.5, 0, 0]\n[[expect]]\n%b' "$2" >"$WORK/$1.toml"; }
write_expect restored-word 'outcome = "restored"\n'
write_expect left-first 'rule = "first-entry"\nleft = false\n'
write_expect bad-rule 'rule = "eventually"\n'
write_expect restored-settled 'rule = "settled"\noutcome = "restored"\n'
for f in restored-word:12 left-first:13 bad-rule:12 restored-settled:13; do
  name=${f%%:*}; line=${f##*:}
  expect_exit 2 "$DB" run "$WORK/$name.toml"
  expect_one_line "$ERR" "$name"
  expect_match "$ERR" "$name\.toml:$line: " "$name names file and line"
done

# A malformed scene is bad input (exit 2), reported with its file named once, and line.
printf '[grid]\nnx = 2\n' >"$WORK/broken.toml"
expect_exit 2 "$DB" check "$WORK/broken.toml"
expect_match "$OUT" '^FAIL  [^ ]*broken.toml:1: missing' "broken scene reported"
[ "$(grep '^FAIL' <<<"$OUT" | grep -o 'broken.toml' | wc -l)" = 1 ] && ok ||
  bad "the broken scene's line names its file more than once: $OUT"
# ... and so is an expectation that uses the first-entry rule's words without that rule.
expect_exit 2 "$DB" check "$WORK/restored-word.toml"
expect_one_line "$ERR" "not loaded"
expect_match "$ERR" '1 scene file\(s\) not loaded' "says a scene was not loaded"
expect_exit 2 "$DB" check "$WORK/nothing-here"

# Scenes with no expectation at all: nothing was checked, so exit 2 and no JUnit file.
mkdir -p "$WORK/bare"
cp "$SRC/scenes/two-node.toml" "$WORK/bare/"
expect_exit 2 "$DB" check "$WORK/bare" --junit "$WORK/bare.xml"
expect_one_line "$ERR" "no expectation"
expect_match "$ERR" 'no \[\[expect\]\] table in the 1 scene file' "names what is missing"
[ ! -e "$WORK/bare.xml" ] && ok || bad "a JUnit file was written for nothing checked"

finish
