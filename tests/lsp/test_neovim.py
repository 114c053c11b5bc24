"""`rayrepl lsp` with Neovim's built-in client, headless (Debian's
`neovim`; skipped, saying so, where it is not installed): every test case's
diagnostics where `--check --json` puts them, and a hover, a completion, a
definition and a rename as Neovim receives them."""

import json
import os
import shutil
import subprocess

import pytest

from test_server import CASES, RAYREPL, ROOT, check_json

NEOVIM = shutil.which("nvim")


def neovim(files, asks, tmp_path) -> dict:
    answers = tmp_path / "answers.json"
    environment = {
        **os.environ,
        "RAYREPL": RAYREPL,
        "RAYREPL_FILES": "\n".join(str(f) for f in files),
        "RAYREPL_ASK": json.dumps(asks),
        "RAYREPL_ANSWERS": str(answers),
    }
    script = ROOT / "tests" / "lsp" / "neovim.lua"
    run = subprocess.run(
        [NEOVIM, "--headless", "--clean", "-u", str(script)], env=environment, timeout=600, capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    return json.loads(answers.read_text())


@pytest.mark.skipif(NEOVIM is None, reason="Neovim is not installed (apt-get install neovim)")
def test_neovim_gets_every_diagnostic_where_the_command_line_puts_it(tmp_path):
    answers = neovim(CASES, {}, tmp_path)
    for path in CASES:
        got = answers[path.name]
        assert got["published"] and got["shown"] == len(got["diagnostics"]), path.name
        shown = sorted((d["code"], d["line"] + 1, d["character"] + 1) for d in got["diagnostics"])
        want = sorted((d["code"], d["place"]["line"], d["place"]["column_utf16"]) for d in check_json(path))
        assert shown == want, path.name


@pytest.mark.skipif(NEOVIM is None, reason="Neovim is not installed (apt-get install neovim)")
def test_neovim_hovers_completes_goes_to_definitions_and_renames(tmp_path):
    scene = tmp_path / "scoping.ray"
    text = (ROOT / "scenarios" / "scoping.ray").read_text()
    scene.write_text(text)
    lines = text.split("\n")
    proc_line = next(i for i, line in enumerate(lines) if line.startswith("proc "))
    name = lines[proc_line].split()[1].split("(")[0]
    call_line = next(i for i, line in enumerate(lines) if line.startswith(name + "("))
    at_call = {"line": call_line, "character": 1}
    asks = {
        "scoping.ray": [
            {"method": "textDocument/hover", "position": at_call},
            {"method": "textDocument/definition", "position": at_call},
            {"method": "textDocument/completion", "position": {"line": call_line, "character": len(name) - 1}},
            {"method": "textDocument/rename", "position": at_call, "more": {"newName": "renamed"}},
            {"method": "textDocument/formatting", "position": at_call, "more": {"options": {"tabSize": 2, "insertSpaces": True}}},
        ]
    }
    hover, definition, completion, rename, formatting = neovim([scene], asks, tmp_path)["scoping.ray"]["asked"]
    assert f"proc {name}(" in hover["result"]["contents"]["value"]
    assert definition["result"][0]["range"]["start"]["line"] == proc_line
    assert any(item["label"].startswith(name + "(") for item in completion["result"])
    edits = next(iter(rename["result"]["changes"].values()))
    assert len(edits) >= 2 and all(edit["newText"] == "renamed" for edit in edits)
    # The bundled scenarios are formatted already: no edit.
    assert formatting.get("error") is None and not formatting.get("result"), formatting
