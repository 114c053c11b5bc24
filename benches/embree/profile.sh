#!/usr/bin/env bash
# The profile side by side (issue 34, point 4): where the time of rayrepl and
# of the Embree-based renderer (single rays, and 4x4 packets) goes, per
# phase, on the three benchmark scenes.
#
#   benches/embree/profile.sh              # all three scenes
#   SCENES="sponge4" benches/embree/profile.sh
#   FREQ=3999 OUT=/tmp/prof benches/embree/profile.sh
#
# For each scene (sponge4 1920x1080, spheres100k 800x600, solar 1920x1080,
# the scenes and sizes of run.sh) and each program (rayrepl; embree-render;
# embree-render --packets) it runs the program once, ONE thread
# (--threads 1, so that every sample belongs to the one traced thread),
# under `perf record -F $FREQ --call-graph dwarf` (the software clock: no
# hardware counters are needed), and prints
#   - the program's own times (evaluate, build, render) and the process's
#     wall, user and sys time (/usr/bin/time), under perf;
#   - the share of samples per phase: walk, leaf tests, ray set-up,
#     shading, BVH build, scene evaluation/parse, other, with the implied
#     milliseconds (share x the process's user + sys time);
#   - the five largest symbols of "other".
# The phases are given by the function names of each sample's call chain,
# inlined functions included (addr2line over the line tables of the
# release build): benches/embree/phases.py holds the patterns. The top 40
# symbols of `perf report` are kept in $OUT/NAME-PROGRAM.top.
#
# Needs perf, addr2line (binutils), python3 and Embree 3
# (apt-get install -y libembree-dev).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
FREQ=${FREQ:-1999}
OUT=${OUT:-$(mktemp -d)}
mkdir -p "$OUT"
cd "$ROOT"

cargo build --release --quiet
cargo build --release --quiet --manifest-path benches/embree/Cargo.toml
RAYREPL=$ROOT/target/release/rayrepl
EMBREE=$ROOT/benches/embree/target/release/embree-render

# scene width height
ALL_SCENES=(
  "sponge4 1920 1080"
  "spheres100k 800 600"
  "solar 1920 1080"
)
read -r -a ONLY <<<"${SCENES:-}"

echo "rayrepl $(git rev-parse --short HEAD), 1 thread, perf -F $FREQ --call-graph dwarf, outputs in $OUT"
echo "uptime: $(uptime)"
for entry in "${ALL_SCENES[@]}"; do
  read -r name width height <<<"$entry"
  if [[ ${#ONLY[@]} -gt 0 && ! " ${ONLY[*]} " =~ " $name " ]]; then continue; fi
  scene=benches/scenes/$name.ray
  args=(--width "$width" --height "$height" --threads 1)
  echo
  echo "== $name ${width}x${height}"
  for program in rayrepl embree embree-packets; do
    case $program in
      rayrepl) cmd=("$RAYREPL" "$scene" "${args[@]}" -o "$OUT/$name-$program.ppm" --stats -q) ;;
      embree) cmd=("$EMBREE" "$scene" "${args[@]}" -o "$OUT/$name-$program.ppm") ;;
      embree-packets) cmd=("$EMBREE" "$scene" "${args[@]}" --packets -o "$OUT/$name-$program.ppm") ;;
    esac
    data=$OUT/$name-$program.data
    perf record -q --no-buildid-cache -F "$FREQ" --call-graph dwarf,16384 -o "$data" -- \
      /usr/bin/time -f '%e %U %S' -o "$OUT/$name-$program.time" "${cmd[@]}" 2>"$OUT/$name-$program.log" >/dev/null
    perf report -i "$data" -g none --no-children --sort dso,symbol --stdio 2>/dev/null |
      awk '/%/ && !/^#/ && n < 40 { print; n++ }' >"$OUT/$name-$program.top"
    perf script -i "$data" -F time,ip,sym,dso 2>/dev/null |
      python3 benches/embree/phases.py "$ROOT" "$RAYREPL" "$EMBREE" >"$OUT/$name-$program.phases"
    read -r wall user sys <"$OUT/$name-$program.time"
    cpu_ms=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.0f", (u + s) * 1000 }')
    times=$(grep -E '^evaluate' "$OUT/$name-$program.log" | head -1 || true)
    render=$(sed -n 's/.* rays in \([0-9.]*\) s.*/\1/p' "$OUT/$name-$program.log" | head -1)
    echo "-- $program: wall $wall s, user $user s, sys $sys s; render ${render:-?} s; $times"
    awk -F '\t' -v cpu="$cpu_ms" '
      $1 == "total" { printf "   %-18s %6d samples\n", "total", $2; next }
      $1 == "other-top" { printf "   other: %-60.60s %6d\n", $2, $3; next }
      { printf "   %-18s %5.1f%%  %6.0f ms\n", $1, $3, $3 * cpu / 100 }' "$OUT/$name-$program.phases"
  done
done
