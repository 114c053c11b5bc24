#!/usr/bin/env bash
# Side by side: rayrepl and the Embree-based renderer of benches/embree on
# the three benchmark scenes, in one run, on this machine.
#
#   benches/embree/run.sh            # 5 timed runs of each program per scene
#   RUNS=9 benches/embree/run.sh     # 9
#   EMBREE_ARGS=--packets benches/embree/run.sh   # Embree with 4x4 packets
#
# For each scene it renders once with both, checks that the images are
# byte-identical (cmp; if not, counts the pixels that differ) and that the
# ray counts agree, then times both alternately (rayrepl, Embree, rayrepl,
# ...), RUNS runs each, and prints the median (and min-max) of the render
# and BVH build times each program prints, with the ratio rayrepl / Embree
# (below 1: rayrepl is faster), taken run by run (pairs) and then the
# median: pairing keeps the ratio meaningful when the machine's speed
# drifts during the run.
#
# Needs Embree 3 (Debian: apt-get install -y libembree-dev).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
RUNS=${RUNS:-5}
THREADS=${THREADS:-2}
# Extra flags of the Embree renderer (--packets, --quality high, ...).
read -r -a EMBREE_ARGS <<<"${EMBREE_ARGS:-}"
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"
cd "$ROOT"

cargo build --release --quiet
cargo build --release --quiet --manifest-path benches/embree/Cargo.toml
RAYREPL=target/release/rayrepl
EMBREE=benches/embree/target/release/embree-render

# scene width height
SCENES=(
  "sponge4 1920 1080"
  "spheres100k 800 600"
  "solar 1920 1080"
)

# The median and the range of the numbers on stdin: "median (min-max)".
stats() {
  sort -g | awk '{ v[NR] = $1 } END {
    m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    printf "%.3f (%.3f-%.3f)\n", m, v[1], v[NR] }'
}

# The ratios a/b, line by line, of the numbers in the files $1 (a) and $2
# (b); "n/a" for a zero b (a time below the printout's precision).
pair_ratios() {
  paste "$1" "$2" | awk '$1 > 0 && $2 > 0 { printf "%.4f\n", $1 / $2 }'
}

# "median (min-max)" of the pair ratios, or n/a.
ratio_stats() {
  local ratios
  ratios=$(pair_ratios "$1" "$2")
  if [[ -z "$ratios" ]]; then echo "n/a"; else echo "$ratios" | stats | sed 's/\([0-9]\.[0-9][0-9]\)[0-9]/\1/g'; fi
}

# Field extractors for the printouts of both programs.
render_time() { sed -n 's/.* rays in \([0-9.]*\) s.*/\1/p' "$1"; }
build_time() { sed -n 's/^evaluate [0-9.]* s, build \([0-9.]*\) s.*/\1/p' "$1"; }
commit_time() { sed -n 's/.*rtcCommitScene \([0-9.]*\) s.*/\1/p' "$1"; }
rays() { sed -n 's/^frames 1: \([0-9]*\) primary, \([0-9]*\) shadow, \([0-9]*\) reflection.*/\1 \2 \3/p' "$1"; }

# Pixels that differ between two PPM images of the same size (same header).
differing_pixels() {
  local header
  header=$(head -c 64 "$1" | awk 'BEGIN { RS = "\n" } NR <= 3 { n += length($0) + 1 } END { print n }')
  cmp -l "$1" "$2" | awk -v h="$header" '{ p[int(($1 - 1 - h) / 3)] = 1 } END { print length(p) }'
}

printf '%s\n' "rayrepl $(git rev-parse --short HEAD), $RUNS runs each, $THREADS threads, Embree flags: ${EMBREE_ARGS[*]:-none}, outputs in $OUT"
TABLE=()
for entry in "${SCENES[@]}"; do
  read -r name width height <<<"$entry"
  scene=benches/scenes/$name.ray
  args=(--width "$width" --height "$height" --threads "$THREADS")
  "$RAYREPL" "$scene" "${args[@]}" -o "$OUT/$name-rayrepl.ppm" --stats -q 2>"$OUT/$name-rayrepl.check"
  "$EMBREE" "$scene" "${args[@]}" "${EMBREE_ARGS[@]}" -o "$OUT/$name-embree.ppm" 2>"$OUT/$name-embree.check"
  if cmp -s "$OUT/$name-rayrepl.ppm" "$OUT/$name-embree.ppm"; then
    same="identical"
  else
    same="$(differing_pixels "$OUT/$name-rayrepl.ppm" "$OUT/$name-embree.ppm") pixels differ"
  fi
  rays_rayrepl=$(rays "$OUT/$name-rayrepl.check")
  rays_embree=$(rays "$OUT/$name-embree.check")
  if [[ "$rays_rayrepl" != "$rays_embree" ]]; then
    echo "$name: ray counts differ: rayrepl $rays_rayrepl, Embree $rays_embree" >&2
    exit 1
  fi
  isa=$(sed -n 's/^isa: //p' "$OUT/$name-embree.check")
  : >"$OUT/$name-rayrepl.log"
  : >"$OUT/$name-embree.log"
  for _ in $(seq "$RUNS"); do
    "$RAYREPL" "$scene" "${args[@]}" -o "$OUT/$name-rayrepl.ppm" --stats -q 2>>"$OUT/$name-rayrepl.log"
    "$EMBREE" "$scene" "${args[@]}" "${EMBREE_ARGS[@]}" -o "$OUT/$name-embree.ppm" 2>>"$OUT/$name-embree.log"
  done
  render_time "$OUT/$name-rayrepl.log" >"$OUT/$name-rayrepl.render"
  render_time "$OUT/$name-embree.log" >"$OUT/$name-embree.render"
  build_time "$OUT/$name-rayrepl.log" >"$OUT/$name-rayrepl.build"
  build_time "$OUT/$name-embree.log" >"$OUT/$name-embree.build"
  r_render=$(stats <"$OUT/$name-rayrepl.render")
  e_render=$(stats <"$OUT/$name-embree.render")
  r_build=$(stats <"$OUT/$name-rayrepl.build")
  e_build=$(stats <"$OUT/$name-embree.build")
  e_commit=$(commit_time "$OUT/$name-embree.log" | stats)
  render_ratio=$(ratio_stats "$OUT/$name-rayrepl.render" "$OUT/$name-embree.render")
  build_ratio=$(ratio_stats "$OUT/$name-rayrepl.build" "$OUT/$name-embree.build")
  total=$(echo "$rays_rayrepl" | awk '{ print $1 + $2 + $3 }')
  per_thread() { awk -v n="$total" -v t="${1%% *}" -v k="$THREADS" 'BEGIN { printf "%.2f", n / t / 1e6 / k }'; }
  echo
  echo "$name ${width}x${height}: $rays_rayrepl rays (primary shadow reflection), same counts; images $same"
  echo "  render  rayrepl $r_render s, Embree $e_render s, rayrepl/Embree $render_ratio"
  echo "  build   rayrepl $r_build s, Embree $e_build s (rtcCommitScene $e_commit s), rayrepl/Embree $build_ratio"
  echo "  Mrays/s per thread: rayrepl $(per_thread "$r_render"), Embree $(per_thread "$e_render") ($isa)"
  TABLE+=("| $name ${width}x${height} | ${r_render%% *} | ${e_render%% *} | ${render_ratio%% *} | ${r_build%% *} | ${e_build%% *} | ${build_ratio%% *} | $(per_thread "$r_render") / $(per_thread "$e_render") | ${isa%%,*} | $same |")
done
echo
echo "| scene | render rayrepl (s) | render Embree (s) | ratio | build rayrepl (s) | build Embree (s) | ratio | Mrays/s per thread rayrepl / Embree | Embree ISA | images |"
echo "|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${TABLE[@]}"
