#!/usr/bin/env bash
# The bad-input battery (docs/hardening.md): every case of scenes.txt and cases.txt, the
# generated scenes below, and outputs on a full disk, each checked for its exit code, exactly
# one line on stderr, and no file created, changed or removed. Usage: run.sh DAMPBOUND SRC.
set -u
DB=$(realpath "$1")
SRC=$(realpath "$2")
HERE=$SRC/tests/battery
W=$(mktemp -d)
S=$W/scenes
FULL=$W/full
MOUNTED=0
cleanup() {
  if [ "$MOUNTED" = 1 ]; then umount "$FULL" 2>/dev/null; fi
  rm -rf "$W"
}
trap cleanup EXIT
export W S SRC
PASSES=0
FAILS=0
fail() { echo "FAIL: $*" >&2; FAILS=$((FAILS + 1)); }

# --- fixtures
mkdir -p "$W/dir" "$S/meshes/dir.obj" "$W/jdir.csv.journal" "$W/repro/report.md"
mkfifo "$W/fifo" "$S/meshes/fifo.obj"
truncate -s 1G "$W/huge.toml"
truncate -s 300M "$S/meshes/huge.obj"
cat >"$W/ok.toml" <<'TOML'
name = "battery"
[grid]
nx = 3
nz = 3
spacing = 1
[params]
m = 0.001
kappa = 0.001
gamma = 0.002
[[perturb]]
node = 4
displacement = [0, 1, 0]
[protocol]
max_iterations = 200
[[run]]
label = "under"
gamma = 0.001
[[expect]]
rule = "first-entry"
outcome = "restored"
TOML
printf '[mesh]\nfile = "/nonexistent/x.obj"\n' >"$W/abs-missing.toml"
printf '[mesh]\nfile = "scenes/meshes/huge.obj"\n' >"$W/mesh-huge.toml"
: >"$W/torn.csv.journal"
echo "dampbound-journal v1 sweep=0000000000000000 1/1 classes=1" >"$W/other.csv.journal"
sweep=(sweep "$W/ok.toml" --m 0.001:0.002:0.001 --kappa 0.001 --zeta 0.5,1 --max-iter 20
       --progress none)
"$DB" "${sweep[@]}" -o "$W/whole.csv" >/dev/null &&
  "$DB" "${sweep[@]}" -o "$W/part1.csv" --shard 1/2 >/dev/null &&
  "$DB" "${sweep[@]}" -o "$W/part2.csv" --shard 2/2 >/dev/null ||
  { echo "FAIL: cannot make the sweep fixtures" >&2; exit 1; }
sed 's|^# trials: .*|# trials: 18446744073709551615|' "$W/whole.csv" >"$W/trials-max.csv"
sed 's|^# shard: .*|# shard: 1/2147483647|' "$W/part1.csv" >"$W/shard-max.csv"
sed 's|^# shard: .*|# shard: 0/0|' "$W/part1.csv" >"$W/shard-zero.csv"
sed 's|^# shard: .*|# shard: 1/999999999|' "$W/part1.csv" >"$W/shard-1e9.csv"
sed '$ s|,[^,]*,[^,]*$||' "$W/whole.csv" >"$W/short-row.csv"
sed '$ s|,settled,|,fine,|; $ s|,not_settled,|,fine,|; $ s|,diverged,|,fine,|' "$W/whole.csv" \
  >"$W/bad-outcome.csv"
# Meshes named by scenes.txt.
M=$S/meshes
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' >"$M/no-face.obj"
printf 'v 0 0 0\nv 1 0 zzz\nv 0 1 0\nf 1 2 3\n' >"$M/bad-number.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n' >"$M/corner-zero.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n' >"$M/corner-far.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n' >"$M/vertex-twice.obj"
printf 'v 0 0 0\nv 1 0 \033[2J\033]0;pwned\007\nv 0 1 0\nf 1 2 3\n' >"$M/escape.obj"
printf 'v 0 0 %s\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' "$(printf 'x%.0s' $(seq 200))" >"$M/long-token.obj"
printf 'v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$M/nan.obj"
printf 'v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$M/two-coordinates.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$M/triangle.obj"
# Scenes of scenes.txt, one file per block.
awk -v dir="$S" '
  /^#/ && !inblock { next }
  /^=== / { split(substr($0, 5), p, " [|] "); file = dir "/" p[1] ".toml"; inblock = 1;
            print p[1] "\t" p[2] >> (dir "/.expect"); printf "" > file; next }
  inblock { print >> file }' "$HERE/scenes.txt"
# Scenes no text editor would write.
gen() { printf '%s\t%s\n' "$1" "$2" >>"$S/.expect"; }
python3 - "$S" <<'PY'
import sys
d = sys.argv[1]
def w(name, data):
    open(f"{d}/{name}.toml", "wb").write(data)
w("dotted", b"a" + b".a" * 40000 + b" = 1\n")
w("dotted-header", b"[" + b"a." * 70 + b"a]\nx = 1\n")
w("deep-array", b"x = " + b"[" * 100000 + b"]" * 100000 + b"\n")
w("deep-inline", b"x = " + b"{a = " * 2000 + b"1" + b"}" * 2000 + b"\n")
w("nul", b"name = \"a\x00b\"\n[grid]\nnx = 3\nnz = 3\nspacing = 1\n")
w("bom-torn", b"\xef\xbb\xbb[grid]\nnx = 3\n")
w("bad-utf8", b"name = \"\xc3\x28\"\n")
w("overlong-utf8", b"name = \"\xc0\xaf\"\n")
w("surrogate", b"name = \"\xed\xa0\x80\"\n")
w("binary", bytes(range(256)) * 4)
w("big", b"# " + b"x" * (17 << 20) + b"\n")
PY
gen dotted 'a dotted key or table name has more than 64 parts'
gen dotted-header 'a dotted key or table name has more than 64 parts'
gen deep-array 'nested deeper than 64 levels'
gen deep-inline 'nested deeper than 64 levels'
gen nul 'holds a NUL byte'
gen bom-torn 'broken byte-order mark'
gen bad-utf8 'not valid UTF-8'
gen overlong-utf8 'not valid UTF-8'
gen surrogate 'not valid UTF-8'
gen binary 'NUL byte|not valid UTF-8'

# --- one case: EXIT REGEX ARGS...
# Every entry's type, size and mode, and for files their inode and modification time (to the
# nanosecond): any write, truncation, replacement or removal changes one of them, without
# hashing 20 MB per case. (A folder's time is not compared: a temporary file made and removed
# again, as a refused write does, touches it and loses nothing.)
snapshot() {
  find "$W" -mindepth 1 \( -type d -printf '%P %y %s %m\n' \) -o -printf '%P %y %s %m %i %T@\n' |
    sort
  for dev in /dev/null /dev/full /dev/zero; do [ -c "$dev" ] && echo "$dev char"; done
}
BEFORE=$(snapshot)
one_case() {
  local want=$1 regex=$2
  shift 2
  (cd "$W" && timeout 30 "$DB" "$@" </dev/null >"$W/../battery.out.$$" 2>"$W/../battery.err.$$")
  local got=$? err out
  err=$(cat "$W/../battery.err.$$")
  out=$(cat "$W/../battery.out.$$")
  rm -f "$W/../battery.out.$$" "$W/../battery.err.$$"
  local what="dampbound $*"
  if [ "$want" -eq 1 ]; then  # a failed check: its report is on stdout
    err="dampbound: error: $(printf '%s\n' "$out" | grep -m1 '^FAIL')"
  fi
  if [ "$got" -ne "$want" ]; then
    fail "exit $got, wanted $want: $what: $err"
  elif [ "$(printf '%s' "$err" | wc -l)" -ne 0 ] || [ -z "$err" ]; then
    fail "stderr is not exactly one line: $what: $err"
  elif ! printf '%s' "$err" | grep -Eq -- "^dampbound: error: .*($regex)"; then
    fail "message does not match /$regex/: $what: $err"
  elif printf '%s%s' "$err" "$out" | LC_ALL=C grep -q "$(printf '\033')"; then
    fail "an escape sequence reaches the terminal: $what"
  else
    local now
    now=$(snapshot)
    if [ "$now" != "$BEFORE" ]; then
      fail "files changed: $what: $(diff <(echo "$BEFORE") <(echo "$now") | grep '^[<>]' | head -3)"
      BEFORE=$now
    else
      PASSES=$((PASSES + 1))
    fi
  fi
}

while IFS=$'\t' read -r name regex; do
  one_case 2 "\.(toml|obj):[0-9]+: .*($regex)" run "$S/$name.toml"
done <"$S/.expect"
while IFS='|' read -r code regex args; do
  code=${code// /}
  [ -z "$code" ] || [ "${code:0:1}" = "#" ] && continue
  regex=${regex# }; regex=${regex% }
  eval "set -- $args"
  one_case "$code" "$regex" "$@"
done <"$HERE/cases.txt"

# --- outputs on a full disk (a 64 KiB tmpfs filled up; needs root and mount)
mkdir -p "$FULL"
if mount -t tmpfs -o size=64k tmpfs "$FULL" 2>/dev/null; then
  MOUNTED=1
  dd if=/dev/zero of="$FULL/filler" bs=4k 2>/dev/null
  BEFORE=$(snapshot)
  # A sweep's own check of the free space may refuse first.
  NOSPACE='No space left on device|write failed|GB is free'
  small=("$W/ok.toml" --m 0.001 --kappa 0.001 --zeta 1 --max-iter 5 --progress none)
  one_case 2 "$NOSPACE" run ok.toml --trace "$FULL/t.csv"
  one_case 2 "$NOSPACE" figure ok.toml -o "$FULL/x.png"
  one_case 2 "$NOSPACE" figure ok.toml -o "$W/x.png" --csv "$FULL/x.csv"
  one_case 2 "$NOSPACE" check ok.toml --junit "$FULL/j.xml"
  one_case 2 "$NOSPACE" sweep "${small[@]}" -o "$FULL/x.csv"
  one_case 2 "$NOSPACE" merge "$W/part1.csv" "$W/part2.csv" -o "$FULL/m.csv"
  one_case 2 "$NOSPACE" map "$W/whole.csv" -o "$FULL/m.png"
else
  echo "battery: skipped the full-disk cases (mounting a tmpfs needs root)"
fi

echo "battery: $PASSES of $((PASSES + FAILS)) cases kept the promise, $FAILS did not"
[ "$FAILS" -eq 0 ]
