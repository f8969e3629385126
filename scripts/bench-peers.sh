#!/usr/bin/env bash
# Throughput and peak memory of Swarf against the interpreters a user could pick instead, in one
# run on one machine, on the corpus's large programs and a generated 1M-line surfacing program:
#   Swarf   `swarf stats` (read, decode, parse, interpret, record the toolpath), the plain
#           release build (`cargo build --release`)
#   rs274   LinuxCNC's reference interpreter (../shared/tools/rs274), canonical calls to /dev/null
#   gcode-toolpath  npm, cncjs's interpreter (Node.js), moves counted
#   pygcode PyPI, its Machine over every line (Python), moves counted
# Prints a Markdown table: best of RUNS wall-clock runs (one run where a run takes over 10 s;
# TIMEOUT seconds at most), MB/s, peak RSS, and each peer's time over Swarf's; Swarf's
# throughput also over its time beyond starting the process (that of `swarf --version`). Swarf
# is measured in rounds, before the peers and after each of them, and its best counts.
#   scripts/bench-peers.sh            (RUNS=10, TIMEOUT=600; needs ../shared for the corpus files)
# It ends with the wasm32 build's figure on the generated program (Node, in-process; `cargo xtask
# wasm-tools` installs the wasm32 target and wasm-bindgen-cli it needs where they are missing).
# The peers are installed once under target/peers (npm and pip; nothing is committed).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${SWARF_SHARED:-$root/../shared}
runs=${RUNS:-10}
limit=${TIMEOUT:-600}
target=${CARGO_TARGET_DIR:-$root/target}
peers=$target/peers

cargo build -q --release -p swarf-syntax --example surfacing || exit 2
cargo build -q --release -p swarf-cli --bin swarf || exit 2
swarf=$target/release/swarf
generated=$peers/surfacing-1M.nc
mkdir -p "$peers"
[[ -s "$generated" ]] || "$target/release/examples/surfacing" 1000000 > "$generated"
if [[ ! -d "$peers/node/node_modules/gcode-toolpath" ]]; then
  npm install --silent --no-audit --no-fund --prefix "$peers/node" gcode-toolpath@3.0.0 > /dev/null 2>&1 \
    || echo "bench-peers: npm could not install gcode-toolpath; its column stays empty" >&2
fi
if [[ ! -d "$peers/py/pygcode" ]]; then
  python3 -m pip install -q --target "$peers/py" pygcode==0.2.1 > /dev/null 2>&1 \
    || echo "bench-peers: pip could not install pygcode; its column stays empty" >&2
fi
rs274=$(bash "$shared/tools/rs274/setup.sh" 2>/dev/null) || rs274=""
tbl=$shared/tools/rs274/default.tbl

programs=(
  "$shared/corpus/programs/camotics/la_peinture.gc"
  "$shared/corpus/programs/linuxcnc/stellabee1.ngc"
  "$shared/corpus/programs/camotics/tiger.nc"
  "$generated"
)
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT

# "secs kb" for a command: its best wall-clock time of $runs runs (the first run's when it is
# slower than 10 s) and its peak RSS, or "timeout 0" when it does not finish within $limit
# seconds. The first run goes through /usr/bin/time for the RSS (its time is in hundredths of a
# second, so it counts only for a slow program); the timed runs are read off bash's
# microsecond clock, with no wrapper process. A non-zero exit status still counts (rs274 ends some
# programs with one); "fail 0" when nothing was measured.
measure() {
  local best="" kb=0 out n=0 rc t
  : > "$tmp"
  timeout "$limit" /usr/bin/time -o "$tmp" -f "%e %M" "$@" > /dev/null 2> /dev/null < /dev/null
  rc=$?
  if ((rc == 124)); then
    echo "timeout 0"
    return
  fi
  out=$(tail -1 "$tmp")
  if [[ ! "$out" =~ ^[0-9.]+\ [0-9]+$ ]]; then
    echo "fail 0"
    return
  fi
  kb=${out#* }
  if awk "BEGIN{exit !(${out% *} >= 10)}"; then
    echo "${out% *} $kb"
    return
  fi
  # The first run finished within the limit, so the timed runs go without the `timeout`
  # wrapper (whose own start would count); bash's clock reads microseconds.
  local start end
  while ((n++ < runs)); do
    start=$EPOCHREALTIME
    "$@" > /dev/null 2> /dev/null < /dev/null
    end=$EPOCHREALTIME
    t=$(awk "BEGIN{printf \"%.4f\", $end - $start}")
    if [[ -z "$best" ]] || awk "BEGIN{exit !($t < $best)}"; then
      best=$t
    fi
  done
  echo "${best:-${out% *}} $kb"
}

# Swarf's round on program $1: "secs kb" (see `measure`).
swarf_round() {
  measure "$swarf" stats "$1" --dialect linuxcnc
}

# Another round of Swarf's runs on program $1: the best time so far, `st`, is kept or bettered.
swarf_again() {
  local again
  read -r again _ < <(swarf_round "$1")
  st=$(least "$st" "$again")
}

# The lesser of two measured times (a failed measurement, not a number, loses).
least() {
  awk -v a="$1" -v b="$2" 'BEGIN{
    an = (a ~ /^[0-9.]+$/); bn = (b ~ /^[0-9.]+$/)
    if (an && bn) print (a + 0 <= b + 0 ? a : b); else if (an) print a; else print b }'
}

# One table cell: "1.23 s, 45 MB/s, 67 MB (12.3×)": its time over Swarf's ($3), for $4 bytes.
cell() {
  local t=$1 kb=$2 one=$3 bytes=$4
  case $t in
    timeout) echo "> ${limit} s" ;;
    fail) echo "fails" ;;
    "") echo "—" ;;
    *) awk "BEGIN{printf \"%.3f s, %.1f MB/s, %d MB (%.1f×)\", $t, $bytes/1e6/$t, $kb/1024, $t/$one}" ;;
  esac
}

# Swarf's cell: "0.0650 s, 61 MB/s, 18 MB / 66 MB/s": its time and throughput with the process
# start, its peak RSS, and its throughput over the time beyond its start ($start_secs: `swarf
# --version` measured the same way).
swarf_cell() {
  awk "BEGIN{printf \"%.4f s, %.0f MB/s, %d MB / %.0f MB/s\", $1, $3/1e6/$1, $2/1024, $3/1e6/($1-$start_secs)}"
}

read -r start_secs _ < <(measure "$swarf" --version)

echo "start of the process (swarf --version): $(awk "BEGIN{printf \"%.2f ms\", $start_secs*1000}")"
echo
echo "| program | size | lines | Swarf | rs274 | gcode-toolpath (npm) | pygcode (PyPI) |"
echo "|---|---|---|---|---|---|---|"
for prog in "${programs[@]}"; do
  [[ -f "$prog" ]] || continue
  bytes=$(stat -c %s "$prog")
  lines=$(wc -l < "$prog")
  read -r st sk < <(swarf_round "$prog")
  r=("" 0) g=("" 0) p=("" 0)
  # Swarf's runs again after each peer's: its runs take a fraction of a second where a peer's
  # take seconds, and a shared machine's speed drifts over seconds, so its best of the rounds
  # is its best over the stretch of time the peers' runs sample.
  if [[ -n "$rs274" ]]; then
    read -r -a r < <(cd "$(dirname "$prog")" && measure "$rs274" -t "$tbl" -g "$(basename "$prog")")
    swarf_again "$prog"
  fi
  if [[ -d "$peers/node/node_modules/gcode-toolpath" ]]; then
    read -r -a g < <(NODE_PATH=$peers/node/node_modules measure node "$root/scripts/peers/gcode_toolpath.js" "$prog")
    swarf_again "$prog"
  fi
  if [[ -d "$peers/py/pygcode" ]]; then
    read -r -a p < <(PYTHONPATH=$peers/py measure python3 "$root/scripts/peers/pygcode_run.py" "$prog")
    swarf_again "$prog"
  fi
  printf "| %s | %.1f MB | %d | %s | %s | %s | %s |\n" "$(basename "$prog")" \
    "$(awk "BEGIN{print $bytes/1e6}")" "$lines" "$(swarf_cell "$st" "$sk" "$bytes")" \
    "$(cell "${r[0]}" "${r[1]}" "$st" "$bytes")" \
    "$(cell "${g[0]}" "${g[1]}" "$st" "$bytes")" "$(cell "${p[0]}" "${p[1]}" "$st" "$bytes")"
done

# Swarf's wasm build on the generated program (in Node, in-process: no file reading or process
# start), from the on-demand test in crates/toolpath, with the wasm32 target and
# wasm-bindgen-test-runner installed where they are missing.
(cd "$root" && cargo xtask wasm-tools > "$target/wasm-tools.log" 2>&1) ||
  echo "bench-peers: the wasm32 tools could not be installed (see $target/wasm-tools.log)" >&2
(cd "$root" && cargo test -p swarf-toolpath --release --target wasm32-unknown-unknown \
  --test wasm_throughput -- --include-ignored --nocapture > "$target/wasm-bench.log" 2>&1)
wasm=$(grep -o "wasm32 stats: .*" "$target/wasm-bench.log")
echo
if [[ -n "$wasm" ]]; then
  echo "Swarf wasm32 in Node (generated 1M-line program, parse + interpret + record): ${wasm#wasm32 stats: }"
else
  echo "Swarf wasm32 in Node: not measured (see $target/wasm-tools.log and $target/wasm-bench.log)"
fi
