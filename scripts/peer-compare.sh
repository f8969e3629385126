#!/usr/bin/env bash
# Compares `swarf canon --dialect linuxcnc` with LinuxCNC's rs274 on the peer corpus.
#   scripts/peer-compare.sh [PROGRAM…]      (default: the programs the interpreter is held to)
# Needs ../shared (the corpus and tools/rs274). Prints one line per program and a summary;
# exits 1 when a program disagrees, 0 when all agree, 0 with a note when ../shared is absent.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SWARF_SHARED:-$root/../shared}
tools=$shared/tools/rs274
corpus=$shared/corpus
if [[ ! -x "$tools/oracle.sh" && ! -f "$tools/oracle.sh" ]]; then
  echo "peer-compare: $tools not found; nothing to compare"
  exit 0
fi
cargo build -q -p swarf-cli || exit 2
swarf=${CARGO_TARGET_DIR:-$root/target}/debug/swarf
if (($# == 0)); then
  set -- \
    "$corpus"/linuxcnc-tests/interp/g10/*/*.ngc \
    "$corpus"/linuxcnc-tests/interp/g52/*/*.ngc \
    "$corpus"/linuxcnc-tests/interp/rotation/*/*.ngc \
    "$corpus"/linuxcnc-tests/interp/unit-conversion/*.ngc \
    "$corpus"/linuxcnc-tests/interp/machine-coord-params/*.ngc \
    "$corpus"/linuxcnc-tests/interp/sequence-number/test.ngc \
    "$corpus"/linuxcnc-tests/interp/m98m99/*/test*.ngc \
    "$corpus"/programs/cncjs/*.nc \
    "$corpus"/programs/nist/example1.gcode \
    "$corpus"/programs/camotics/*.nc "$corpus"/programs/camotics/*.gc \
    "$corpus"/programs/linuxcnc/*.ngc \
    "$corpus"/linuxcnc-tests/ccomp/*/test.ngc \
    "$corpus"/linuxcnc-tests/interp/inside-corners/test.ngc \
    "$corpus"/linuxcnc-tests/interp/cam-nisley/cam.ngc \
    "$corpus"/linuxcnc-tests/interp/crazy-paths/test.ngc \
    "$corpus"/linuxcnc-tests/interp/inverse-time-with-comp/inverse.ngc \
    "$corpus"/programs/autodesk/test.fanuc.nc
fi
# rs274's tool table as the setup's registers: tool N's Z is register N's length, half its
# diameter D the radius (standalone rs274 reads both in inches), Q the lathe tool orientation.
table_setup() {
  python3 - "$1" <<'PY'
import re, sys
print('units = "inch"')
for line in open(sys.argv[1], encoding="utf-8", errors="replace"):
    line = line.split(";")[0]
    t = re.search(r"\bT(\d+)", line)
    if not t:
        continue
    print(f"[registers.{t.group(1)}]")
    z = re.search(r"\bZ([-+.\d]+)", line)
    d = re.search(r"\bD([-+.\d]+)", line)
    if z:
        print(f"length = {float(z.group(1))}")
    if d:
        print(f"radius = {float(d.group(1)) / 2}")
    q = re.search(r"\bQ(\d+)", line)
    if q and int(q.group(1)) > 0:
        print(f"orientation = {int(q.group(1))}")
PY
}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0
fail=0
for prog in "$@"; do
  [[ -f "$prog" ]] || continue
  name=${prog#"$corpus"/}
  tbl=$(ls "$(dirname "$prog")"/*.tbl 2>/dev/null | head -1)
  # A machine's position after a tool change, not rs274's stand-in canon's (see the script).
  bash "$tools/oracle.sh" "$prog" ${tbl:+"$tbl"} 2>/dev/null |
    python3 "$root/scripts/rs274-machine-canon.py" > "$work/ref.canon"
  table_setup "${tbl:-$tools/default.tbl}" > "$work/setup.toml"
  "$swarf" canon "$prog" --dialect linuxcnc --setup "$work/setup.toml" > "$work/ours.jsonl" 2> "$work/ours.err"
  if python3 "$tools/compare.py" "$work/ours.jsonl" "$work/ref.canon" > "$work/cmp.txt" 2>&1; then
    echo "agree     $name"
    pass=$((pass + 1))
  else
    echo "DISAGREE  $name: $(head -c 300 "$work/cmp.txt" | tr '\n' ' ')"
    fail=$((fail + 1))
  fi
done
echo "peer-compare: $pass agree, $fail disagree"
((fail == 0))
