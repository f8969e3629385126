#!/usr/bin/env bash
# Wall time and peak memory of `swarf check`, `canon` and `stats` (and `render` where a program
# is meant for it) on hostile programs, with the default setup: endless loops, runaway
# expressions, cycles and calls that would make billions of moves, a program as large as Swarf
# reads. Prints a Markdown table (wall seconds and peak RSS from `/usr/bin/time`, the codes of
# the diagnostics the run printed, in order) and exits 1 when a run takes more than LIMIT_MB
# (1000 MB) of memory.
#   scripts/bench-hostile.sh            (about two minutes on a 2-core machine)
#   scripts/bench-hostile.sh --web      (the web page's and its worker's wasm memory instead,
#                                        tests/e2e/bench-hostile-web.mjs; build the page first)
# The programs are generated into a temporary folder, removed at the end; the plain release
# build (`cargo build --release -p swarf-cli`) runs them, each command under TIMEOUT (120) s.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
limit_mb=${LIMIT_MB:-1000}
timeout_s=${TIMEOUT:-120}
target=${CARGO_TARGET_DIR:-$root/target}
web=0
[[ ${1:-} == --web ]] && web=1

((web)) || (cd "$root" && cargo build -q --release -p swarf-cli --bin swarf) || exit 2
swarf=$target/release/swarf
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# The programs: file name, then what it is (the table's first column).
names=()
declare -A what
add() {
  names+=("$1")
  what[$1]=$2
}

add repeated-warning.nc "a 13-line endless WHILE of ten \`G05.1 Q1\` lines"
{
  printf 'WHILE [1 EQ 1] DO1\n'
  for _ in {1..10}; do printf 'G05.1 Q1\n'; done
  printf 'END1\nM30\n'
} > "$dir/repeated-warning.nc"

# The one program run on a setup of its own: the default setup has no travel to leave.
add overtravel.nc "an overtravel in an endless loop (a setup with \`travel_mm\`)"
printf 'G01 F100\nWHILE [1 EQ 1] DO1\nX50.\nX150.\nX0\nEND1\n' > "$dir/overtravel.nc"
printf '[machine]\ntravel_mm = [[-100.0, -100.0, -100.0], [100.0, 100.0, 100.0]]\n' \
  > "$dir/travel.toml"

add expression-loop.nc "an endless loop of a 1,000-term expression"
{
  printf 'WHILE [1 EQ 1] DO1\n#1=[1'
  for _ in {2..1000}; do printf '+1'; done
  printf ']\nEND1\n'
} > "$dir/expression-loop.nc"

add moves-loop.nc "\`WHILE [1 EQ 1]\` with two moves"
printf 'G01 F100\nWHILE [1 EQ 1] DO1\nX1.\nX0\nEND1\n' > "$dir/moves-loop.nc"

add m99-main.nc "M99 in the main program"
printf 'G91 G00 X1.\nM99\n' > "$dir/m99-main.nc"

add subprogram-alone.nc "a subprogram file alone, ending in M99"
printf 'O100\nG91 G01 X1. F100\nM99\n' > "$dir/subprogram-alone.nc"

add tiny-peck.nc "\`G83 … Q.000001\` over 1000 mm"
printf 'G00 X0 Y0 Z10.\nG83 X1. Y1. Z-1000. R2. Q.000001 F100\nG80\nM30\n' > "$dir/tiny-peck.nc"

add deep-calls.nc "\`M98 … L9999\` calls nested 16 deep"
{
  printf 'G01 F100\nM98 P1 L9999\nM30\n'
  for i in {1..15}; do printf 'O%d\nM98 P%d L9999\nM99\n' "$i" $((i + 1)); done
  printf 'O16\nX1.\nX0\nM99\n'
} > "$dir/deep-calls.nc"

add counter-30mb.nc "30 MB of \`#1=[#1+1]\` lines"
yes '#1=[#1+1]' | head -n 3000000 > "$dir/counter-30mb.nc"

add circles-loop.nc "an endless GOTO loop of full circles (10M chords)"
printf 'G0 X0 Y0 Z0\nN10 G2 X0 Y0 I10. F100\nGOTO10\n' > "$dir/circles-loop.nc"

add huge-coordinates.nc "a 1e12 mm coordinate, also drawn (\`render\`)"
printf '#1=1000000\n#1=#1*#1\nG00 X1.\nG00 X#1 Y1.\nG00 X2.\nM30\n' > "$dir/huge-coordinates.nc"

# Every figure at its largest at once: a file of the most read (256 MiB) that opens with an
# endless loop (so the program is held whole, as much of it as may be: 256 MiB parsed), then
# moves; the loop fills the toolpath to the motion limit with what holds the most memory a
# move: moves that each change the tool and the feed, cutter-compensated moves (each keeps its
# programmed contour), drilled holes, plain moves.
largest() {
  add "$1" "256 MiB: $2, then 33M lines of moves"
  {
    printf '%b' "$3"
    yes $'X1.\nX0' | head -c $(((256 << 20) - 200))
    printf '\nM30\n'
  } > "$dir/$1"
}
largest largest-tools.nc "an endless loop of moves each changing tool and feed" \
  'WHILE [1 EQ 1] DO1\nT1 M6 G01 X1. F100\nT2 M6 X0 F200\nEND1\n'
largest largest-comp.nc "an endless loop of cutter-compensated moves" \
  'G10 L12 P1 R2.\nG17 G01 F100\nG41 D1 X0 Y0\nWHILE [1 EQ 1] DO1\nX10. Y0\nY10.\nX0\nY0\nEND1\n'
largest largest-holes.nc "an endless loop of G81 holes" \
  'G00 Z10.\nG99 G81 X0 Y0 Z-1. R1. F100\nWHILE [1 EQ 1] DO1\nX1.\nX0\nEND1\n'
largest largest-moves.nc "an endless loop of moves" \
  'G01 F100\nWHILE [1 EQ 1] DO1\nX1.\nX0\nEND1\n'

if ((web)); then
  for name in "${names[@]}"; do
    setup=
    [[ $name == overtravel.nc ]] && setup=travel.toml
    printf '%s\t%s\t%s\n' "$name" "${what[$name]}" "$setup"
  done > "$dir/programs.tsv"
  node "$root/tests/e2e/bench-hostile-web.mjs" "$dir"
  exit
fi

echo "| program | command | wall s | peak RSS MB | diagnostics (codes, in order) |"
echo "|---|---|---|---|---|"
over=0
for name in "${names[@]}"; do
  file=$dir/$name
  args=()
  [[ $name == overtravel.nc ]] && args=(--setup "$dir/travel.toml")
  commands=(check canon stats)
  [[ $name == huge-coordinates.nc ]] && commands+=(render)
  for command in "${commands[@]}"; do
    extra=()
    [[ $command == render ]] && extra=(-o "$dir/out.png")
    timeout "$timeout_s" /usr/bin/time -o "$dir/time" -f '%e %M' \
      "$swarf" "$command" "$file" "${args[@]}" "${extra[@]}" \
      > /dev/null 2> "$dir/err" < /dev/null
    rc=$?
    read -r secs kb < <(tail -1 "$dir/time")
    if ((rc == 124)) || [[ ! "$kb" =~ ^[0-9]+$ ]]; then
      secs="> $timeout_s" kb=0
    fi
    mb=$((kb * 1024 / 1000000))
    codes=$(grep -o '\[[ENW]-[A-Z0-9-]*\]' "$dir/err" | tr -d '[]' | awk '!seen[$0]++' |
      head -4 | paste -sd, - | sed 's/,/, /g')
    [[ $rc -gt 1 && $rc -ne 124 ]] && codes="exit $rc: $(head -c 200 "$dir/err")"
    if ((mb > limit_mb)) || ((rc == 124)); then
      over=1
      mb="**$mb**"
    fi
    echo "| ${what[$name]} | $command | $secs | $mb | ${codes:-none} |"
  done
done
if ((over)); then
  echo
  echo "bench-hostile: a run took more than $limit_mb MB or $timeout_s s (in bold)" >&2
  exit 1
fi
