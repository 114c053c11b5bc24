"""The kernelspecs the tests start: `rayrepl jupyter install --prefix` into
a temporary folder on JUPYTER_PATH, once per interrupt mode, so that
Jupyter's own clients start the kernel exactly as a user's notebook does."""

import os
import subprocess
import tempfile
from pathlib import Path

RAYREPL = os.environ["RAYREPL"]
ROOT = Path(__file__).resolve().parents[2]

_prefix = tempfile.mkdtemp(prefix="rayrepl-kernels-")
for mode in ("message", "signal"):
    folder = Path(_prefix) / mode
    subprocess.run(
        [RAYREPL, "jupyter", "install", "--prefix", str(folder), "--interrupt-mode", mode],
        check=True,
        capture_output=True,
    )
    kernels = folder / "share" / "jupyter" / "kernels"
    # The signal-mode spec under a name of its own, beside the default one.
    if mode == "signal":
        (kernels / "rayrepl").rename(kernels / "rayrepl-signal")
# The lessons' progress of the kernels the tests start, away from the user's.
os.environ["XDG_DATA_HOME"] = tempfile.mkdtemp(prefix="rayrepl-data-")
os.environ["JUPYTER_PATH"] = os.pathsep.join(
    str(Path(_prefix) / mode / "share" / "jupyter") for mode in ("message", "signal")
)
