# docs/scene-format.md is what scripts/scene-reference.sh writes from the scene key table, and
# that table is the one the reader checks keys against.
. "$(dirname "$0")/lib.inc"

expect_exit 0 bash "$SRC/scripts/scene-reference.sh" "$DB" "$WORK/scene-format.md"
if diff -u "$SRC/docs/scene-format.md" "$WORK/scene-format.md" >"$WORK/scene.diff"; then
  ok
else
  bad "docs/scene-format.md is stale: run bash scripts/scene-reference.sh (diff: $(head -c 600 "$WORK/scene.diff"))"
fi
ref=$(cat "$WORK/scene-format.md")
for section in grid node spring mesh mesh_region region params perturb protocol cut run expect; do
  expect_match "$ref" "^## \`\[\[?$section\]\]?\`" "section for $section"
done
# Hidden from --help, so docs/cli.md does not list it.
expect_exit 0 "$DB" --help
if printf '%s' "$OUT" | grep -q scene-format; then bad "--help lists scene-format"; else ok; fi

# Every key of every shipped scene is in the reference under its section.
/usr/bin/python3 - "$SRC/scenes" "$WORK/scene-format.md" >"$WORK/missing" 2>&1 <<'PY'
import glob, re, sys, tomllib
documented = set()
section = None
for line in open(sys.argv[2]):
    m = re.match(r"## (Top level|`(.*)`)", line)
    if m:
        section = m.group(2) or ""
    m = re.match(r"\| `([a-z_]+)` \|", line)
    if m:
        documented.add((section, m.group(1)))
inherits = {"[[run]]": "[params]"}
missing = []
for path in sorted(glob.glob(sys.argv[1] + "/*.toml")):
    root = tomllib.load(open(path, "rb"))
    for key, value in root.items():
        if isinstance(value, dict):
            tables, name = [value], "[%s]" % key
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            tables, name = value, "[[%s]]" % key
        else:
            tables, name = [], None
            if ("", key) not in documented:
                missing.append("%s: %s" % (path, key))
        for t in tables:
            for k in t:
                if (name, k) not in documented and (inherits.get(name), k) not in documented:
                    missing.append("%s: %s %s" % (path, name, k))
print("\n".join(missing))
sys.exit(1 if missing else 0)
PY
if [ $? -eq 0 ]; then ok; else bad "shipped scene keys missing from the reference: $(head -c 600 "$WORK/missing")"; fi

# A key the table does not list is refused, in every section, with the file and line.
base='[grid]
nx = 3
nz = 3
spacing = 1.0
[[perturb]]
node = 4
displacement = [0.0, 1.0, 0.0]
'
try_key() {  # try_key WHERE TEXT: the scene with TEXT appended must be refused naming WHERE
  printf '%s%s\n' "$base" "$2" >"$WORK/s.toml"
  expect_exit 2 "$DB" run "$WORK/s.toml" &&
    expect_match "$ERR" "s\.toml:[0-9]+: unknown key 'bogus' in $1" "unknown key in $1"
}
try_key '\[params\]' '[params]
bogus = 1'
try_key '\[protocol\]' '[protocol]
bogus = 1'
try_key '\[\[perturb\]\]' '[[perturb]]
node = 3
bogus = 1'
try_key '\[\[run\]\]' '[[run]]
label = "a"
bogus = 1'
try_key '\[\[expect\]\]' '[[expect]]
outcome = "restored"
bogus = 1'
printf 'bogus = 1\n%s' "$base" >"$WORK/top.toml"
expect_exit 2 "$DB" run "$WORK/top.toml" &&
  expect_match "$ERR" "top\.toml:1: unknown key 'bogus' in the scene" "unknown key at the top level"
# [[run]] takes every [params] key besides its own.
printf '%s[[run]]\nlabel = "a"\nrayleigh_mass = 1.0\nmax_iterations = 10\n' "$base" >"$WORK/run.toml"
expect_exit 0 "$DB" run "$WORK/run.toml"

finish
