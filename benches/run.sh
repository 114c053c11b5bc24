#!/usr/bin/env bash
# Prints the benchmark table of BENCHMARKS.md: wall time (median of RUNS
# runs), peak memory, and rayrepl's own --stats line, for each target of the
# issues, with POV-Ray 3.7 side by side on the same machine in the same run.
#
#   bash benches/run.sh            # RUNS=3 by default
#   RUNS=5 bash benches/run.sh
#
# Needs: a release build (done here), /usr/bin/time, and povray for the
# comparison (apt-get install povray; skipped with a note when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${RUNS:-3}
cargo build --release --quiet
BIN=$PWD/target/release/rayrepl
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# A 1-million-line program for the parser.
{
  echo "camera distance 10 angle 1 end"
  echo "ambient 0.2"
  for ((i = 0; i < 1000; i++)); do echo "let x$i = 1 + 2 * 3"; done
} > "$WORK/chunk.ray"
{
  head -2 "$WORK/chunk.ray"
  for ((i = 0; i < 1000; i++)); do tail -n +3 "$WORK/chunk.ray"; done
} > "$WORK/million.ray"

# median WALL_SECONDS CPU_SECONDS MAXRSS_MB of RUNS runs of a command
measure() {
  local times=() cpus=() rss=()
  for ((r = 0; r < RUNS; r++)); do
    /usr/bin/time -f "%e %U %S %M" -o "$WORK/time" "$@" > /dev/null 2> "$WORK/stderr" || {
      echo "FAILED: $*" >&2; cat "$WORK/stderr" >&2; return 1; }
    read -r t u k m < "$WORK/time"
    times+=("$t"); cpus+=("$(awk -v u="$u" -v k="$k" 'BEGIN { printf "%.2f", u + k }')"); rss+=("$m")
  done
  local mid=$((RUNS / 2))
  local t c m
  t=$(printf '%s\n' "${times[@]}" | sort -g | sed -n "$((mid + 1))p")
  c=$(printf '%s\n' "${cpus[@]}" | sort -g | sed -n "$((mid + 1))p")
  m=$(printf '%s\n' "${rss[@]}" | sort -g | sed -n "$((mid + 1))p")
  echo "$t $c $((m / 1024))"
}

# rayrepl's --stats line for one run of the command
stats() {
  "$@" --stats 2>&1 > /dev/null | grep -E "Mrays/s" | tail -1 | sed -E 's/.* in ([0-9.]+) s: /\1 s render, /'
}

row() {
  local name=$1 target=$2; shift 2
  local result
  local wall cpu mem
  read -r wall cpu mem <<< "$(measure "$@")"
  printf '| %s | %s | %s s | %s s | %s MB |\n' "$name" "$target" "$wall" "$cpu" "$mem"
}

echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(free -g | awk '/Mem/ {print $2}') GiB"
echo "Runs: median of $RUNS, wall time, release build, $(date -u +%Y-%m-%d)"
echo
echo "Load average before the run: $(cut -d' ' -f1-3 /proc/loadavg) (CPU time is the figure to trust on a busy machine)"
echo
echo "| benchmark | target | wall time | CPU time (user + sys) | peak memory |"
echo "|---|---|---|---|---|"
row "parse + evaluate 1,000,002 lines" "< 1 s (parse)" "$BIN" --check "$WORK/million.ray"
row "Menger depth 5: evaluate 3.2 M boxes" "< 2 s, < 1.5 GB" "$BIN" --check benches/scenes/sponge5.ray
row "solar 1920x1080 depth 5" "5x faster than POV-Ray" "$BIN" benches/scenes/solar.ray --width 1920 --height 1080 -o "$WORK/solar.png"
if command -v povray > /dev/null; then
  row "POV-Ray 3.7 solar 1920x1080 (+WT2)" "" povray +Ibenches/pov/solar.pov "+O$WORK/solar_pov.png" +W1920 +H1080 +WT2 -D -V -GA File_Gamma=1.0
else
  echo "| POV-Ray 3.7 | not installed (apt-get install povray) | | | |"
fi
mkdir -p "$WORK/anim"
row "solar animation 100 frames 800x600 (PNG)" "< 5 s" "$BIN" benches/scenes/solar.ray --anim 100 -o "$WORK/anim/solar.png"
row "Menger depth 4 1920x1080 (evaluate + BVH + render)" "< 1.5 s" "$BIN" benches/scenes/sponge4.ray --width 1920 --height 1080 -o "$WORK/sponge4.png"
row "100,000 spheres 800x600" "" "$BIN" benches/scenes/spheres100k.ray -o "$WORK/spheres.png"
row "huge and tiny coordinates 800x600" "" "$BIN" benches/scenes/scales.ray -o "$WORK/scales.png"
echo
echo "Rays (rayrepl --stats, one run each):"
echo
echo "| scene | rays |"
echo "|---|---|"
echo "| solar 1920x1080 | $(stats "$BIN" benches/scenes/solar.ray --width 1920 --height 1080 -o "$WORK/s.png") |"
echo "| solar animation 100 x 800x600 | $(stats "$BIN" benches/scenes/solar.ray --anim 100 -o "$WORK/anim/solar.png") |"
echo "| Menger depth 4 1920x1080 | $(stats "$BIN" benches/scenes/sponge4.ray --width 1920 --height 1080 -o "$WORK/s.png") |"
echo "| 100,000 spheres 800x600 | $(stats "$BIN" benches/scenes/spheres100k.ray -o "$WORK/s.png") |"
echo "| huge and tiny 800x600 | $(stats "$BIN" benches/scenes/scales.ray -o "$WORK/s.png") |"
