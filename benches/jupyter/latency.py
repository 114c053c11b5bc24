"""How the notebook kernel compares with a piped script on the same input,
how fast it starts, and whether its memory grows over many cells
(docs/perf/front-ends.md, "The notebook kernel").

    target/jupyter-venv/bin/python benches/jupyter/latency.py [target/release/rayrepl] [rounds] [cells]

Needs the venv of tests/jupyter/run (jupyter_client). Installs the
kernelspec in a temporary prefix. Paired rounds: a cell that renders
scenarios/solar.ray at 320x240 (from the request to the kernel's `idle`,
the picture encoded and sent), then the same input piped to `rayrepl`
(the whole process), alternating; medians and their ratio. Then the time
from starting the kernel to its kernel_info reply, and the kernel's
resident memory after 10, 100 and `cells` cells that each render.
"""

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from jupyter_client.manager import start_new_kernel

BINARY = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "target/release/rayrepl")
ROUNDS = int(sys.argv[2]) if len(sys.argv) > 2 else 15
CELLS = int(sys.argv[3]) if len(sys.argv) > 3 else 1000
SOLAR = Path("scenarios/solar.ray").resolve()
CELL = f":reset\n:size 320 240\n:load {SOLAR}\n:render"

prefix = tempfile.mkdtemp()
subprocess.run([BINARY, "jupyter", "install", "--prefix", prefix], check=True, capture_output=True)
os.environ["JUPYTER_PATH"] = str(Path(prefix) / "share" / "jupyter")


def run(client, code):
    msg_id = client.execute(code)
    while True:
        message = client.get_iopub_msg(timeout=120)
        if (message["parent_header"].get("msg_id") == msg_id and message["msg_type"] == "status"
                and message["content"]["execution_state"] == "idle"):
            break
    client.get_shell_msg(timeout=120)


def rss_kib(pid):
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    return 0


started = time.monotonic()
manager, client = start_new_kernel(kernel_name="rayrepl")
client.kernel_info()
client.get_shell_msg(timeout=30)
start_time = time.monotonic() - started

run(client, CELL)  # warm the caches of both sides alike
subprocess.run([BINARY], input=CELL.encode(), capture_output=True)
kernel_times, script_times = [], []
for _ in range(ROUNDS):
    began = time.perf_counter()
    run(client, CELL)
    kernel_times.append(time.perf_counter() - began)
    began = time.perf_counter()
    subprocess.run([BINARY], input=CELL.encode(), capture_output=True, check=True)
    script_times.append(time.perf_counter() - began)
kernel, script = statistics.median(kernel_times), statistics.median(script_times)
print(f"solar 320x240 cell: kernel {kernel * 1000:.1f} ms, piped script {script * 1000:.1f} ms, "
      f"ratio {kernel / script:.2f} ({ROUNDS} paired rounds, medians)")
print(f"start to kernel_info reply: {start_time * 1000:.0f} ms")

pid = manager.provisioner.process.pid
run(client, ":reset\n:size 32 24\nlight vector 0, 0, 1 intensity 1 end\n"
            "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 200, 50, 50 end")
for done in range(1, CELLS + 1):
    run(client, ":render")
    if done in (10, 100, CELLS):
        print(f"after {done} cells that render: {rss_kib(pid) / 1024:.1f} MiB resident")
client.stop_channels()
manager.shutdown_kernel(now=True)
