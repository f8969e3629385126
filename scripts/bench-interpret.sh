#!/usr/bin/env bash
# Parse + interpret + record throughput of `swarf stats` (release build) against LinuxCNC's rs274
# on the corpus's large programs, in one run on one machine. Prints a Markdown table: best of
# RUNS wall-clock runs each, peak memory, and the ratio rs274 / Swarf.
#   scripts/bench-interpret.sh        (needs ../shared; RUNS=5 by default)
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SWARF_SHARED:-$root/../shared}
runs=${RUNS:-5}
programs=(
  "$shared/corpus/programs/camotics/la_peinture.gc"
  "$shared/corpus/programs/linuxcnc/stellabee1.ngc"
  "$shared/corpus/programs/camotics/tiger.nc"
  "$shared/corpus/programs/camotics/cameo.nc"
)
cargo build -q --release -p swarf-cli || exit 2
swarf=${CARGO_TARGET_DIR:-$root/target}/release/swarf
rs274=$(bash "$shared/tools/rs274/setup.sh" 2>/dev/null) || rs274=""
tbl=$shared/tools/rs274/default.tbl

tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT

# best wall seconds and peak KB of a command over $runs runs: "secs kb"
measure() {
  local best="" kb=0 out
  for _ in $(seq "$runs"); do
    /usr/bin/time -o "$tmp" -f "%e %M" "$@" > /dev/null 2> /dev/null < /dev/null
    out=$(tail -1 "$tmp")
    local t=${out% *} m=${out#* }
    if [[ -z "$best" ]] || awk "BEGIN{exit !($t < $best)}"; then best=$t; fi
    ((m > kb)) && kb=$m
  done
  echo "$best $kb"
}

echo "| program | size | Swarf \`stats\` | Swarf MB/s | Swarf peak | rs274 | rs274 peak | rs274 / Swarf |"
echo "|---|---|---|---|---|---|---|---|"
for prog in "${programs[@]}"; do
  [[ -f "$prog" ]] || continue
  bytes=$(stat -c %s "$prog")
  read -r st sk < <(measure "$swarf" stats "$prog" --dialect linuxcnc)
  if [[ -n "$rs274" ]]; then
    read -r rt rk < <(cd "$(dirname "$prog")" && measure "$rs274" -t "$tbl" -g "$(basename "$prog")")
  else
    rt=""; rk=""
  fi
  mbs=$(awk "BEGIN{printf \"%.0f\", $bytes/1e6/$st}")
  ratio=$([[ -n "$rt" ]] && awk "BEGIN{printf \"%.1f×\", $rt/$st}" || echo "—")
  printf "| %s | %.1f MB | %.3f s | %s | %d MB | %s | %s | %s |\n" \
    "$(basename "$prog")" "$(awk "BEGIN{print $bytes/1e6}")" "$st" "$mbs" "$((sk / 1024))" \
    "${rt:+$rt s}" "${rk:+$((rk / 1024)) MB}" "$ratio"
done
