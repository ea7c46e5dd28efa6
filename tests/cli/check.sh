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
expect_match "$OUT" 'FAIL .*wrong.toml:13 outcome == diverged \(measured restored at [0-9]+\)' "fail line"
expect_match "$(cat "$WORK/wrong.xml")" '<failure message="measured restored' "junit failure"

# A malformed scene is a failure of check, reported with file and line.
printf '[grid]\nnx = 2\n' >"$WORK/broken.toml"
expect_exit 1 "$DB" check "$WORK/broken.toml"
expect_match "$OUT" 'broken.toml:1: missing' "broken scene reported"
expect_exit 2 "$DB" check "$WORK/nothing-here"

finish
