"""Notebooks executed by nbclient, as `jupyter execute` and nbgrader run
them: the example notebooks of examples/notebooks/ (so that they never go
stale) and notebooks the project has never seen (the scenarios cut into
cells where the kernel says an input is complete, and random scenes made
here), every picture of a `:render` compared byte for byte with the batch
renderer's picture of the same scene as a file; then `jupyter nbconvert
--execute --to html`, whose page must hold the pictures and colour the
code with the `.ray` lexer."""

import base64
import random
import subprocess
from pathlib import Path

import nbformat
import pytest
from jupyter_client.manager import start_new_kernel
from nbclient import NotebookClient

from conftest import RAYREPL, ROOT

EXAMPLES = sorted((ROOT / "examples" / "notebooks").glob("*.ipynb"))
METADATA = {"kernelspec": {"name": "rayrepl", "display_name": "rayrepl (.ray)", "language": "ray"}}


def execute(book):
    NotebookClient(book, timeout=120, kernel_name="rayrepl").execute()
    return book


def pictures(cell):
    return [
        base64.b64decode(output["data"]["image/png"])
        for output in cell.get("outputs", [])
        if output.get("output_type") == "display_data" and "image/png" in output.get("data", {})
    ]


def batch_render(items, width, height, time, folder):
    scene = folder / "scene.ray"
    scene.write_text(items)
    out = folder / "batch.png"
    flags = ["--width", str(width), "--height", str(height), "--time", repr(time)]
    subprocess.run([RAYREPL, str(scene), "-o", str(out), "--quiet", *flags], check=True)
    return out.read_bytes()


def check_renders(book, folder):
    """Each `:render` of `book` (executed) against the batch render of the
    items of the cells so far, as one file, at the size and time set so far.
    Returns how many pictures were compared."""
    items, size, time, compared = [], (800, 600), 1.0, 0
    for cell in book.cells:
        if cell.cell_type != "code":
            continue
        for output in cell.get("outputs", []):
            assert output["output_type"] != "error", "".join(output.get("traceback", []))
        lines = cell.source.splitlines()
        commands = [line.split() for line in lines if line.startswith(":")]
        items += [line for line in lines if not line.startswith(":")]
        for command in commands:
            if command[0] == ":size":
                size = (int(command[1]), int(command[2]))
            elif command[0] == ":time":
                time = float(command[1])
        if [":render"] in commands:
            [picture] = pictures(cell)
            assert picture == batch_render("\n".join(items) + "\n", *size, time, folder), cell.source
            compared += 1
    return compared


@pytest.mark.parametrize("path", EXAMPLES, ids=[path.stem for path in EXAMPLES])
def test_an_example_notebook_runs_and_its_pictures_are_the_batch_renders(path, tmp_path):
    book = execute(nbformat.read(path, as_version=4))
    compared = check_renders(book, tmp_path)
    if path.stem in ("first-scene", "procedures-and-recursion", "animation"):
        assert compared >= 1
    if path.stem == "animation":
        assert any(pictures(cell) for cell in book.cells if ":play" in cell.source)
    if path.stem == "lesson":
        plain = [o["data"].get("text/plain", "") for c in book.cells for o in c.get("outputs", []) if "data" in o]
        assert any("step 1 done" in text for text in plain) and any("not yet" in text for text in plain)


def cells_of(text):
    """`text` cut into cells at blank lines, each cell grown until the
    kernel says the input it holds is complete."""
    manager, client = start_new_kernel(kernel_name="rayrepl")
    try:
        cells, current = [], ""
        for paragraph in text.split("\n\n"):
            current = f"{current}\n\n{paragraph}" if current else paragraph
            client.is_complete(current)
            if client.get_shell_msg(timeout=30)["content"]["status"] == "complete":
                cells.append(current)
                current = ""
        assert current == "", "the whole file is complete"
        return cells
    finally:
        client.stop_channels()
        manager.shutdown_kernel(now=True)


SCENARIOS = sorted((ROOT / "scenarios").glob("*.ray"))


@pytest.mark.parametrize("scene", SCENARIOS, ids=[scene.stem for scene in SCENARIOS])
def test_a_scenario_cut_into_cells_renders_as_its_file(scene, tmp_path):
    cells = cells_of(scene.read_text())
    book = nbformat.v4.new_notebook(metadata=METADATA)
    book.cells = [nbformat.v4.new_code_cell(":size 96 72")] + [nbformat.v4.new_code_cell(c) for c in cells]
    book.cells.append(nbformat.v4.new_code_cell(":render"))
    execute(book)
    [picture] = pictures(book.cells[-1])
    expected = tmp_path / "expected.png"
    subprocess.run([RAYREPL, str(scene), "-o", str(expected), "--quiet", "--width", "96", "--height", "72"], check=True)
    assert picture == expected.read_bytes()


def random_scene_cells(rng):
    """A scene the project never saw, one item a cell, in file order."""
    number = lambda low, high: f"{rng.uniform(low, high):.3f}"
    texture = lambda: (
        f"kd {number(0, 1)} ks {number(0, 1)} phong {rng.randint(1, 80)} "
        f"color {rng.randint(0, 255)}, {rng.randint(0, 255)}, {rng.randint(0, 255)}"
    )
    cells = [f"camera distance {number(6, 14)} angle {number(0.6, 1.2)} end", f"ambient {number(0, 0.4)}"]
    for _ in range(rng.randint(1, 3)):
        cells.append(f"light vector {number(-1, 1)}, {number(-1, 1)}, {number(-1, 1)} intensity {number(0.2, 1)} end")
    for _ in range(rng.randint(2, 8)):
        kind = rng.choice(["sphere", "box", "plane"])
        if kind == "sphere":
            shape = f"sphere center {number(-3, 3)}, {number(-2, 2)}, {number(-3, 1)} radius {number(0.2, 1.5)} {texture()} end"
        elif kind == "box":
            shape = f"box center {number(-3, 3)}, {number(-2, 2)}, {number(-3, 0)} length {number(0.1, 3)}, {number(0.1, 2)}, {number(0.1, 2)} {texture()} end"
        else:
            shape = f"plane rotation {number(-0.5, 0.5)}, 0, {number(-0.5, 0.5)} shift {number(-3, -1)} {texture()} end"
        if rng.random() < 0.3:
            shape = f"rotate {shape} by {number(-1, 1)}, {number(-1, 1)}, {number(-1, 1)} end"
        cells.append(f"put {shape}")
    return cells


@pytest.mark.parametrize("seed", range(6))
def test_a_random_notebook_renders_as_its_file(seed, tmp_path):
    rng = random.Random(seed)
    cells = random_scene_cells(rng)
    width, height = rng.randint(8, 120), rng.randint(8, 90)
    book = nbformat.v4.new_notebook(metadata=METADATA)
    book.cells = [nbformat.v4.new_code_cell(f":size {width} {height}")]
    # Renders after some cells and at the end, each compared.
    for cell in cells:
        source = f"{cell}\n:render" if rng.random() < 0.25 else cell
        book.cells.append(nbformat.v4.new_code_cell(source))
    book.cells.append(nbformat.v4.new_code_cell(":render"))
    execute(book)
    assert check_renders(book, tmp_path) >= 1


def test_nbconvert_writes_a_page_with_the_pictures_and_coloured_code(tmp_path):
    source = ROOT / "examples" / "notebooks" / "first-scene.ipynb"
    subprocess.run(
        [str(Path(RAYREPL_VENV_BIN) / "jupyter"), "nbconvert", "--execute", "--to", "html",
         "--output-dir", str(tmp_path), str(source)],
        check=True,
        capture_output=True,
    )
    page = (tmp_path / "first-scene.html").read_text()
    assert page.count('src="data:image/png;base64,') >= 3
    assert '<span class="kt">sphere</span>' in page, "the .ray lexer coloured the cells"


RAYREPL_VENV_BIN = Path(__import__("sys").executable).parent
