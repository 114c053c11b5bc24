#!/usr/bin/env python3
"""Shares of perf samples per phase, for benches/embree/profile.sh.

    perf script -F time,ip,sym,dso -i perf.data | phases.py ROOT BINARY...

Reads the `perf script` output of a `perf record --call-graph dwarf`
profile (one call chain per sample). Every frame in one of the BINARIES
(rayrepl, embree-render; release builds with line tables) is expanded by
`addr2line -i` into its source locations, inlined calls included, and each
location in the project's own sources (ROOT/src, ROOT/benches/embree/src)
is named by the function that holds that line ("src/render/bvh.rs:
Bvh::build", found from the `fn` lines of the file). Frames in other
libraries keep perf's symbol (libembree3 has only its API symbols,
rtcIntersect1 and so on). Walking from the sampled instruction outwards,
the first name that matches one of the PATTERNS below gives the sample's
phase: a sample in glam's or core's code inlined into `sphere_hit` counts
as a leaf test, a sample in libm's `pow` called from `phong_power` as
shading, a sample inside Embree as walk when its chain reaches
`rtcIntersect*`/`rtcOccluded*` and as build when it reaches
`rtcCommitScene`. A sample that matches nothing is "other"; the five
largest names of "other" are printed so that nothing large hides there.

Embree samples whose chain does not unwind to its API count as build
before the first sample under rtcIntersect*/rtcOccluded*, as walk after.
A helper used by two phases (the f32 rounding) is skipped: the next name
outwards decides.

Prints `phase<TAB>samples<TAB>percent` lines, `total<TAB>N`, then
`other-top<TAB>name<TAB>samples` lines. PHASES_DEBUG=1 also prints, on
standard error, the 60 names that decided the most samples;
PHASES_DEBUG=NAME prints the first three call chains that NAME decided.
"""

import collections
import os
import re
import subprocess
import sys

# Phase patterns, tried in this order on each name, innermost first; the
# first name that matches a pattern decides. Names are "FILE:Type::fn" for
# the project's sources (the enclosing `fn` of the sampled line or call
# site) and perf's symbol elsewhere. Chosen from `perf report --no-children
# --sort dso,symbol` of both programs and from the source locations that
# addr2line gives for their sampled addresses (2026-12-07, rayrepl 74aa68d).
PATTERNS = [
    # Helpers used by more than one phase: skipped, the next name outwards
    # decides (f32 rounding: ray set-up and the build's node bounds).
    ("skip", r"src/render/bvh/wide\.rs:(widened|narrowed|margin|limit_above|round_down|round_up)$|embree/src/geometry\.rs:(round_up|round_down)$"),
    # BVH build: rayrepl's binned SAH build, the collapse into the wide tree
    # and the shared frame's set-up; Embree's rtcCommitScene (TBB is its
    # thread pool) and embree-render's bounds callback.
    ("build", r"src/render/bvh\.rs:(Bvh::build|build_range|sah_split|median_split|partition|Binning::|Bins::|Item::|Extent::|Box32::|Node::"
              r"|SharedFrame::(new|common_axes|local_bounds|padded|enclosing))"
              r"|src/render/bvh/wide\.rs:(WideBvh::(collapse|add|with_isa)|Plan::|WideNode::set_bounds)"
              r"|src/render/geometry\.rs:(Geometry::build|SceneGeometry::new)"
              r"|embree/src/geometry\.rs:(bounds|Geometry::build|Parts::new|Objects::new|Objects::bounds)$"
              r"|src/render/intersect\.rs:(\w+::bounds|Aabb::|ShapeClass::|\w+::middle_half_size)$"
              r"|rtcCommitScene|rtcCommitGeometry|^tbb::"),
    # The normal of the hit that won (intersect.rs): shading.
    ("shading", r"src/render/intersect\.rs:(\w+::(outward_normal|facing_normal|normal)|argmax|argmin)$"),
    # Leaf tests: the sphere, box and plane tests, rayrepl's loop over a
    # leaf's objects (test_range) and embree-render's intersect and
    # occluded callbacks around the same tests.
    ("leaf tests", r"src/render/intersect\.rs:(?!Ray::)|src/render/bvh\.rs:(test_range|goes_before|put_before|nearer_than|reach_past|FrameLeaves::\w+|ObjectLeaves::\w+)$"
                   r"|embree/src/geometry\.rs:(intersect|occluded|Objects::hit|goes_before|culling_distance)$"),
    # Ray set-up: camera rays; a query's ray made ready for the tree
    # (rayrepl's WideRay and the turn into the boxes' common frame,
    # embree-render's f32 rays, packets and turn); the origin and direction
    # of secondary rays.
    ("ray set-up", r"src/render/camera\.rs:|src/render/intersect\.rs:Ray::new$|src/render/bvh/wide\.rs:WideRay::"
                   r"|src/render/bvh\.rs:SharedFrame::local_ray|src/render/shade\.rs:(offset_origin|reflected)$"
                   r"|embree/src/shade\.rs:reflected$|embree/src/geometry\.rs:(f32_ray|set_lane|packet16|Objects::traversed|Query::new)$"),
    # Walk: the BVH traversal (rayrepl's wide walk, node tests, stack and the
    # query functions around it; Embree's traversal kernels, reached through
    # rtcIntersect* and rtcOccluded*, and embree-render's calls of them).
    ("walk", r"src/render/bvh/wide\.rs:|src/render/bvh\.rs:(Bvh::|SharedFrame::)"
             r"|src/render/geometry\.rs:(Geometry::(closest_hit|any_hit)|SceneGeometry::(closest_hit|any_hit))$"
             r"|rtcIntersect|rtcOccluded|embree/src/embree\.rs:"
             r"|embree/src/geometry\.rs:(Geometry::(closest_hit|closest_hits16|blocked16)|Query::context)$"),
    # Shading: the path loop, lights, the non-walk part of shadow rays (the
    # planes facing the light), Phong, reflection weights, colours, the
    # hit's surface (point, normal, material), the pixel's bytes, the loop
    # over tiles and pixels.
    ("shading", r"src/render/(shade|pixels|geometry)\.rs:|embree/src/(shade|render|geometry)\.rs:"),
    # The scene: parse and evaluation of the .ray file.
    ("scene eval/parse", r"src/lang/|src/scene|src/lint\.rs:|embree/src/main\.rs:evaluate$"),
]
COMPILED = [(phase, re.compile(p)) for phase, p in PATTERNS]
PHASES = ["walk", "leaf tests", "ray set-up", "shading", "build", "scene eval/parse", "other"]

TIME = re.compile(r"(\d+\.\d+):")
FRAME = re.compile(r"^\s+([0-9a-f]+) (.*) \((.*)\)$")
FN = re.compile(r"^(\s*)(?:pub(?:\([\w: ]+\))? )?(?:const )?(?:unsafe )?(?:extern \"C\" )?fn (\w+)")
IMPL = re.compile(r"^impl(?:<[^{]*?>)? (?:[\w:<>',& ]+ for )?([A-Za-z_]\w*)")


def load_segments(path):
    """The LOAD segments of an ELF file: (offset, vaddr, filesz)."""
    out = subprocess.run(["readelf", "-lW", path], capture_output=True, text=True, check=True).stdout
    segs = []
    for line in out.splitlines():
        f = line.split()
        if f and f[0] == "LOAD":
            segs.append((int(f[1], 16), int(f[2], 16), int(f[4], 16)))
    return segs


FUNCTIONS = {}


def function_at(path, line):
    """The `fn` holding `line` of the source file `path`, as Type::name."""
    if path not in FUNCTIONS:
        table = []
        impl = None
        try:
            with open(path, encoding="utf-8") as f:
                for k, text in enumerate(f, 1):
                    m = IMPL.match(text)
                    if m:
                        impl = m.group(1)
                    elif text.startswith("}"):
                        impl = None
                    m = FN.match(text)
                    if m:
                        inside = impl if (impl and m.group(1)) else None
                        table.append((k, (inside + "::" if inside else "") + m.group(2)))
        except OSError:
            pass
        FUNCTIONS[path] = table
    name = None
    for k, n in FUNCTIONS[path]:
        if k > line:
            break
        name = n
    return name


def main():
    root = os.path.realpath(sys.argv[1])
    binaries = [os.path.realpath(b) for b in sys.argv[2:]]
    segments = {b: load_segments(b) for b in binaries}
    samples = []  # each: list of (address, symbol, dso, inlined), innermost first
    current = None
    main_binary = None
    times, stamp = [], 0.0  # each sample's time (perf script -F time)
    for line in sys.stdin:
        line = line.rstrip("\n")
        m = FRAME.match(line)
        if m:
            # perf prints a frame's inlined calls as extra lines of the same
            # address, and sometimes only those: one frame per address.
            addr, sym, dso = int(m.group(1), 16), m.group(2), m.group(3)
            inlined = dso == "inlined"
            if not inlined and dso.startswith("/"):
                dso = os.path.realpath(dso)
                if dso in segments and main_binary is None:
                    main_binary = dso
            if current is None:
                current = []
            if current and current[-1][0] == addr:
                if not inlined and current[-1][3]:
                    current[-1] = (addr, sym, dso, False)
                continue
            current.append((addr, sym, dso, inlined))
        elif not line.strip():
            if current:
                samples.append(current)
                times.append(stamp)
            current = None
        else:
            t = TIME.search(line)
            if t:
                stamp = float(t.group(1))
    if current:
        samples.append(current)
        times.append(stamp)

    def vaddr(offset, dso):
        for s_off, s_vaddr, s_size in segments[dso]:
            if s_off <= offset < s_off + s_size:
                return offset - s_off + s_vaddr
        return None

    wanted = collections.defaultdict(set)
    chains = []
    for chain in samples:
        frames = []
        for i, (addr, sym, dso, inlined) in enumerate(chain):
            if inlined:  # only inlined lines: perf found line tables, so one of ours
                dso = main_binary
            a = None
            if dso in segments:
                # perf prints the file offset; callers' return addresses - 1.
                a = vaddr(addr - (1 if i else 0), dso)
                if a is not None:
                    wanted[dso].add(a)
            frames.append((dso, a, sym))
        chains.append(frames)

    locations = {}  # (dso, vaddr) -> [names of the own-source locations, innermost first]
    for dso, addrs in wanted.items():
        text = "".join("%x\n" % a for a in sorted(addrs))
        out = subprocess.run(["addr2line", "-a", "-i", "-e", dso], input=text,
                             capture_output=True, text=True, check=True).stdout.splitlines()
        key, names = None, []
        for line in out:
            if re.fullmatch(r"0x[0-9a-f]+", line):
                if key is not None:
                    locations[(dso, key)] = names
                key, names = int(line, 16), []
                continue
            path, _, num = line.rpartition(":")
            num = num.split()[0] if num else ""
            path = os.path.realpath(path) if path.startswith("/") else path
            if path.startswith(root + "/") and num.isdigit():
                rel = path[len(root) + 1:]
                if rel.startswith("src/") or rel.startswith("benches/embree/src/"):
                    fn = function_at(path, int(num))
                    if fn:
                        names.append("%s:%s" % (rel.replace("benches/", ""), fn))
        if key is not None:
            locations[(dso, key)] = names

    detail = collections.Counter()
    counts = collections.Counter()
    other = collections.Counter()
    first_walk = None
    for idx, frames in enumerate(chains):
        if any(re.match(r"rtc(Intersect|Occluded)", f[2]) for f in frames):
            first_walk = times[idx] if first_walk is None else min(first_walk, times[idx])
    for idx, frames in enumerate(chains):
        names = []
        for dso, a, sym in frames:
            if a is not None and locations.get((dso, a)):
                names.extend(locations[(dso, a)])
            names.append(sym)
        phase = None
        for name in names:
            for p, rx in COMPILED:
                if rx.search(name):
                    phase = p
                    break
            if phase == "skip":
                phase = None
                continue
            if phase:
                break
        if phase is None and frames:
            if "libembree" in frames[0][0]:
                # Embree's code whose chain did not unwind to its API: build
                # before the first sample of a walk, walk after it.
                phase = "build" if first_walk is None or times[idx] < first_walk else "walk"
            elif "libtbb" in frames[0][0]:
                phase = "build"
        if phase is None:
            phase = "other"
            dso, _, sym = frames[0] if frames else ("?", None, "?")
            other["%s (%s)" % (names[0] if names else sym, os.path.basename(dso))] += 1
        counts[phase] += 1
        if DEBUG:
            decided = next((n for n in names if any(rx.search(n) for q, rx in COMPILED if q != "skip")), names[0] if names else "?")
            detail[(phase, decided)] += 1
            if DEBUG == decided and detail[(phase, decided)] <= 3:
                print("debug-chain", [f[2] for f in frames[:3]], names[:8], file=sys.stderr)

    total = sum(counts.values())
    for p in PHASES:
        print("%s\t%d\t%.1f" % (p, counts[p], 100.0 * counts[p] / total if total else 0.0))
    print("total\t%d" % total)
    for name, n in other.most_common(5):
        print("other-top\t%s\t%d" % (name, n))
    if DEBUG:
        for (p, n), k in sorted(detail.items(), key=lambda x: -x[1])[:60]:
            print("debug\t%s\t%s\t%d" % (p, n, k), file=sys.stderr)


DEBUG = os.environ.get("PHASES_DEBUG")

if __name__ == "__main__":
    main()
