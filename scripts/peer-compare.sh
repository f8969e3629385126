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
    "$corpus"/programs/linuxcnc/*.ngc
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0
fail=0
for prog in "$@"; do
  [[ -f "$prog" ]] || continue
  name=${prog#"$corpus"/}
  tbl=$(ls "$(dirname "$prog")"/*.tbl 2>/dev/null | head -1)
  bash "$tools/oracle.sh" "$prog" ${tbl:+"$tbl"} > "$work/ref.canon" 2>/dev/null
  "$swarf" canon "$prog" --dialect linuxcnc > "$work/ours.jsonl" 2> "$work/ours.err"
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
