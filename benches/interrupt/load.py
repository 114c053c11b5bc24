#!/usr/bin/env python3
"""How long Ctrl-C takes to give the prompt back during the `:load` of a
large file (issue 35, point 6b): docs/perf/interrupts.md, "Ctrl-C during
the `:load` of 100 MB".

    python3 benches/interrupt/load.py BINARY [RUNS] [MB]

Writes a file of MB megabytes of spheres (100 by default), starts the
session BINARY on a pseudo-terminal, and RUNS times (29 by default) types
`:load big.ray`, waits a random time within the load (its length measured
first), types Ctrl-C and times the wait for the next prompt. Prints the
moments, the waits, their median and 90th percentile, as JSON. With
`COMMAND=reload`, the file is loaded once and each time `:reload` is
typed instead (the file read, parsed and every input run again).
"""

import json
import os
import pty
import random
import select
import statistics
import sys
import tempfile
import time

PROMPT = b"ray> "


def read_until(fd, needle, timeout, after=()):
    """Reads the pseudo-terminal until `needle` comes, after one of the
    texts `after` if any is given (the line editor draws its prompt again
    as a line is typed); the seconds it took."""
    started = time.monotonic()
    seen = b""
    while True:
        marks = [seen.find(text) for text in after if text in seen]
        start = min(marks) if marks else (None if after else 0)
        if start is not None and needle in seen[start:]:
            return time.monotonic() - started
        left = timeout - (time.monotonic() - started)
        if left <= 0:
            raise TimeoutError(f"no {needle!r} within {timeout} s: {seen[-300:]!r}")
        ready, _, _ = select.select([fd], [], [], left)
        if ready:
            seen += os.read(fd, 65536)


# The part of the load's length the moments of Ctrl-C are drawn from
# (`SPREAD=0.7,1` to look at the end of it).
SPREAD = tuple(float(part) for part in os.environ.get("SPREAD", "0.05,0.95").split(","))

# What the session says when a load ends: stopped, or done.
ENDED = (b"Ctrl-C", b"as it was", b"in the scene")

# The command interrupted: `load` (the file loaded, then taken back) or
# `reload` (the file loaded once, then read and run again).
RELOAD = os.environ.get("COMMAND", "load") == "reload"
TYPED = b":reload\r" if RELOAD else b":load big.ray\r"


def main():
    binary = os.path.abspath(sys.argv[1])
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 29
    megabytes = int(sys.argv[3]) if len(sys.argv) > 3 else 100
    folder = tempfile.mkdtemp(prefix="rayrepl-interrupt-")
    line = "put sphere center 1, 2, 3 radius 0.5 kd 0.8 ks 0.3 phong 50 color 220, 40, 40 end\n"
    with open(os.path.join(folder, "big.ray"), "w") as file:
        file.write(line * (megabytes * 1_000_000 // len(line)))
    pid, fd = pty.fork()
    if pid == 0:
        os.chdir(folder)
        os.environ.update(TERM="xterm-256color", RAYREPL_LESSONS=os.path.join(folder, "lessons"))
        os.execv(binary, [binary])
    read_until(fd, PROMPT, 30)
    # The whole load, once, to know when to interrupt it.
    os.write(fd, b":load big.ray\r")
    whole = read_until(fd, PROMPT, 300, ENDED)
    if RELOAD:
        os.write(fd, TYPED)
        whole = read_until(fd, PROMPT, 300, ENDED)
    else:
        os.write(fd, b":undo\r")
        read_until(fd, PROMPT, 60, (b"took back",))
    random.seed(35)
    moments, waits = [], []
    for _ in range(runs):
        moment = random.uniform(*SPREAD) * whole
        os.write(fd, TYPED)
        time.sleep(moment)
        os.write(fd, b"\x03")
        sent = time.monotonic()
        read_until(fd, PROMPT, 60, ENDED)
        waits.append(round((time.monotonic() - sent) * 1000, 1))
        moments.append(round(moment, 2))
        if not RELOAD:
            # A load that ended before the Ctrl-C is taken back.
            os.write(fd, b":reset\r")
            read_until(fd, PROMPT, 60, (b"empty again",))
        time.sleep(0.5)
    os.write(fd, b":quit\r")
    ordered = sorted(waits)
    print(json.dumps({
        "load_s": round(whole, 2),
        "moments_s": moments,
        "waits_ms": waits,
        "median_ms": statistics.median(waits),
        "p90_ms": ordered[int(0.9 * (len(ordered) - 1))],
    }))


main()
