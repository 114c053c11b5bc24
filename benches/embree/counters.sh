#!/usr/bin/env bash
# Simulated counters side by side (issue 34, point 4).
#
# The PMU of the benchmark machine is not available (`perf stat -e
# instructions` says <not supported>), so this script reads the counters a
# simulator gives instead: valgrind's cachegrind, with its cache and branch
# simulators, counts the instructions exactly and simulates an I1/D1 + LL
# cache and a simple branch predictor. These are NOT hardware counters: the
# caches are cachegrind's model (two levels, LRU, no prefetch) and its
# branch predictor is a simple model, not Zen 2's.
#
# For each scene (sponge4 960x540, spheres100k 800x600, solar 960x540) and
# each program (rayrepl; embree-render; embree-render --packets) it runs
# cachegrind twice, ONE thread: at 8x8 (the fixed costs: parse, evaluation,
# BVH build) and at the measured size. The difference is the cost of
# rendering the extra pixels; divided by the extra rays (primary + shadow +
# reflection, from the programs' --stats / standard error lines) it gives
# per-ray figures. Each image under valgrind is compared (cmp) with the one
# the same program writes without valgrind, and the ray counts of the three
# programs are compared.
#
#   benches/embree/counters.sh                       # all three scenes
#   SCENES="solar" SIZE="96 54" benches/embree/counters.sh   # quick check
#   OUT=/tmp/cg RAYREPL=/path/rayrepl EMBREE=/path/embree-render benches/embree/counters.sh
#
# Environment: RAYREPL, EMBREE (the binaries; default the release builds
# under $ROOT, which this script does not build: `cargo build --release` and
# `cargo build --release --manifest-path benches/embree/Cargo.toml`),
# SCENES (a subset), SIZE ("W H", overrides every scene's measured size),
# PROGRAMS (subset of "rayrepl embree embree-packets"), OUT (where the
# cachegrind files, images and printouts go; default a new temporary
# directory), CACHE (the cachegrind cache options), SUMMARY_ONLY=1 (no runs:
# print the tables again from the files already in $OUT).
#
# Cache configuration (AMD EPYC Zen 2): I1 32 KiB 8-way, D1 32 KiB 8-way,
# 64 B lines; LL = the 16 MiB 16-way L3 (cachegrind has only two levels, so
# the 512 KiB L2 is not simulated). valgrind's own detection on this KVM
# guest gives a bogus 256 MiB direct-mapped LL, hence the explicit options.
#
# Needs valgrind (3.19 tried; apt-get install -y valgrind), python3, and the
# two binaries. It takes about 7 minutes for all three scenes on a Zen 2
# core (36 runs; under cachegrind the slowest takes some 40 s), 8 seconds
# with SCENES=solar SIZE="96 54". It uses one core: the runs are one after
# the other. For an L2-sized LL instead of the L3:
#   CACHE="--I1=32768,8,64 --D1=32768,8,64 --LL=524288,8,64" benches/embree/counters.sh
#
# Output: per scene, a table with, for each program, the 8x8 run's Ir
# (fixed cost), then the render share (measured run minus the 8x8 run) of
# Ir (instructions), D1 misses (reads + writes), LLd misses (data, reads +
# writes), mispredictions (conditional + indirect), each in total and per
# ray. Then, for rayrepl, the ten largest functions of the render share
# (the per-function events of the two runs subtracted, as cg_diff would) by
# Ir, D1 misses and mispredictions, and the ten largest source files and
# source lines (inlined code keeps its own file and line) by Ir and D1
# misses. Image mismatches stop the script. The raw files are
# $OUT/NAME-PROGRAM-WxH.cg (cg_annotate them) and .err (the programs'
# standard error, with the ray counts).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
RAYREPL=${RAYREPL:-$ROOT/target/release/rayrepl}
EMBREE=${EMBREE:-$ROOT/benches/embree/target/release/embree-render}
OUT=${OUT:-$(mktemp -d)}
CACHE=${CACHE:---I1=32768,8,64 --D1=32768,8,64 --LL=16777216,16,64}
read -r -a PROGS <<<"${PROGRAMS:-rayrepl embree embree-packets}"
read -r -a ONLY <<<"${SCENES:-}"
read -r -a CACHE_ARGS <<<"$CACHE"
mkdir -p "$OUT"

for bin in "$RAYREPL" "$EMBREE"; do
  [[ -x $bin ]] || { echo "missing $bin (build it with cargo build --release)" >&2; exit 1; }
done
command -v valgrind >/dev/null || { echo "needs valgrind" >&2; exit 1; }

# scene width height
ALL_SCENES=(
  "sponge4 960 540"
  "spheres100k 800 600"
  "solar 960 540"
)

# command_of PROGRAM SCENE W H IMAGE: the program's command line, into the array CMD
command_of() {
  local program=$1 scene=$2 w=$3 h=$4 img=$5
  case $program in
    rayrepl) CMD=("$RAYREPL" "$scene" --width "$w" --height "$h" --threads 1 -o "$img" -q --stats) ;;
    embree) CMD=("$EMBREE" "$scene" --width "$w" --height "$h" --threads 1 -o "$img") ;;
    embree-packets) CMD=("$EMBREE" "$scene" --width "$w" --height "$h" --threads 1 -o "$img" --packets) ;;
    *) echo "unknown program $program" >&2; exit 1 ;;
  esac
}

echo "cachegrind counters, $(date -u '+%Y-%m-%d %H:%M UTC'), $(valgrind --version), 1 thread"
echo "cache: $CACHE"
echo "rayrepl: $RAYREPL"
echo "embree:  $EMBREE"
echo "outputs in $OUT"

for entry in "${ALL_SCENES[@]}"; do
  [[ -n ${SUMMARY_ONLY:-} ]] && break
  read -r name width height <<<"$entry"
  if [[ ${#ONLY[@]} -gt 0 && ! " ${ONLY[*]} " =~ " $name " ]]; then continue; fi
  if [[ -n ${SIZE:-} ]]; then read -r width height <<<"$SIZE"; fi
  scene=$ROOT/benches/scenes/$name.ray
  for program in "${PROGS[@]}"; do
    for size in "8 8" "$width $height"; do
      read -r w h <<<"$size"
      base=$OUT/$name-$program-${w}x$h
      # the reference image, without valgrind
      command_of "$program" "$scene" "$w" "$h" "$base.native.ppm"
      "${CMD[@]}" 2>"$base.native.err"
      command_of "$program" "$scene" "$w" "$h" "$base.ppm"
      valgrind --tool=cachegrind --cache-sim=yes --branch-sim=yes "${CACHE_ARGS[@]}" \
        --cachegrind-out-file="$base.cg" --log-file="$base.vg" "${CMD[@]}" 2>"$base.err"
      if cmp -s "$base.ppm" "$base.native.ppm"; then same=same; else same=DIFFERENT; fi
      echo "  $name $program ${w}x$h: image under valgrind $same as without it"
      [[ $same == same ]] || exit 1
    done
  done
done

ROOT_PREFIX=$ROOT/ python3 - "$OUT" "${SIZE:-}" "${ONLY[*]:-}" "${PROGS[*]}" <<'EOF'
import os, re, sys
out, size, only, progs = sys.argv[1:5]
progs = progs.split()
scenes = [("sponge4", 960, 540), ("spheres100k", 800, 600), ("solar", 960, 540)]
if only.strip():
    scenes = [s for s in scenes if s[0] in only.split()]
if size.strip():
    w, h = map(int, size.split())
    scenes = [(n, w, h) for n, _, _ in scenes]

def summary(path):
    events = None
    for line in open(path):
        if line.startswith("events:"):
            events = line.split()[1:]
        elif line.startswith("summary:"):
            return dict(zip(events, map(int, line.split()[1:])))
    raise SystemExit("no summary in " + path)

def rays(path):
    text = open(path).read()
    m = re.search(r"(\d+) primary, (\d+) shadow, (\d+) reflection rays", text)
    return tuple(map(int, m.groups()))

def functions(path):
    """per function, per source file and per source line (inlined code is
    given its own file and line by the debug info) sums of the events"""
    events, fl, fn = None, "?", "?"
    acc = {"function": {}, "source file": {}, "source line": {}}
    for line in open(path):
        if line.startswith("events:"):
            events = line.split()[1:]
        elif line.startswith("fl="):
            fl = line[3:].strip()
        elif line.startswith("fn="):
            fn = line[3:].strip()
        elif line[:1].isdigit():
            num, *vals = line.split()
            for kind, key in (("function", fn), ("source file", fl), ("source line", f"{fl}:{num}")):
                d = acc[kind].setdefault(key, [0] * len(events))
                for i, v in enumerate(vals):
                    d[i] += int(v)
    return events, acc

def fmt(x):
    return f"{x:,.0f}"

for name, w, h in scenes:
    print(f"\n== {name}: render share = {w}x{h} run minus 8x8 run; per ray = / extra rays")
    hdr = ("program", "fixed Ir (8x8)", "rays", "Ir", "Ir/ray", "D1 miss", "D1/ray",
           "LLd miss", "LLd/ray", "mispred", "mispred/ray")
    rows, counts = [], {}
    for p in progs:
        small = f"{out}/{name}-{p}-8x8"
        big = f"{out}/{name}-{p}-{w}x{h}"
        s, b = summary(small + ".cg"), summary(big + ".cg")
        rs, rb = rays(small + ".err"), rays(big + ".err")
        counts[p] = rb
        n = sum(rb) - sum(rs)
        d = {k: b[k] - s[k] for k in b}
        ir = d["Ir"]
        d1 = d["D1mr"] + d["D1mw"]
        ll = d["DLmr"] + d["DLmw"]
        mp = d["Bcm"] + d["Bim"]
        rows.append((p, fmt(s["Ir"]), fmt(n), fmt(ir), f"{ir / n:.0f}", fmt(d1), f"{d1 / n:.2f}",
                     fmt(ll), f"{ll / n:.3f}", fmt(mp), f"{mp / n:.2f}"))
    widths = [max(len(str(r[i])) for r in rows + [hdr]) for i in range(len(hdr))]
    for r in [hdr] + rows:
        print("  " + "  ".join(str(c).rjust(wd) for c, wd in zip(r, widths)))
    if len(set(counts.values())) > 1:
        print("  RAY COUNTS DIFFER:", counts)
    else:
        print("  ray counts (primary, shadow, reflection) agree:", next(iter(counts.values())))
    if "rayrepl" in progs:
        ev, fs = functions(f"{out}/{name}-rayrepl-8x8.cg")
        ev, fb = functions(f"{out}/{name}-rayrepl-{w}x{h}.cg")
        for kind in ("function", "source file", "source line"):
            diff = {}
            for fn, vals in fb[kind].items():
                base = fs[kind].get(fn, [0] * len(ev))
                diff[fn] = dict(zip(ev, (a - c for a, c in zip(vals, base))))
            tot = {k: sum(v[k] for v in diff.values()) for k in ev}
            for label, key in (("Ir", lambda v: v["Ir"]),
                               ("D1 misses", lambda v: v["D1mr"] + v["D1mw"]),
                               ("mispredictions", lambda v: v["Bcm"] + v["Bim"])):
                if kind != "function" and label == "mispredictions":
                    continue
                total = key(tot)
                print(f"  rayrepl render share, top 10 by {kind}, by {label} (of {fmt(total)}):")
                for fn, v in sorted(diff.items(), key=lambda kv: -key(kv[1]))[:10]:
                    fn = fn.replace(os.environ.get("ROOT_PREFIX", "////"), "")
                    fn = re.sub(r"^/root/\.cargo/registry/src/[^/]+/|^/rustc/[0-9a-f]+/library/", "", fn)
                    print(f"    {100 * key(v) / max(total, 1):5.1f}%  {fmt(key(v)):>15}  {fn[:110]}")
EOF
