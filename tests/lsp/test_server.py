"""`rayrepl lsp` driven by pytest-lsp, a real client: it starts the server,
speaks the protocol and checks every message against the specification
(lsprotocol's types). `tests/lsp/run` builds its virtual environment."""

import os
import pathlib

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient

ROOT = pathlib.Path(__file__).resolve().parents[2]
RAYREPL = os.environ.get("RAYREPL", str(ROOT / "target" / "release" / "rayrepl"))

HEAD = "camera distance 10 angle 1 end\nambient 0.2\nlight vector 0.5, 0, 0.6 intensity 0.8 end\n"
BALL = "kd 1 ks 0 phong 1 color 255, 120, 40 end"


@pytest_lsp.fixture(
    config=ClientServerConfig(server_command=[RAYREPL, "lsp"]),
    params=["visual-studio-code", "neovim", "emacs"],
)
async def client(lsp_client: LanguageClient, request):
    # Each test runs as each of these clients, with the capabilities
    # pytest-lsp recorded from it.
    capabilities = pytest_lsp.client_capabilities(request.param)
    await lsp_client.initialize_session(types.InitializeParams(capabilities=capabilities))
    yield
    await lsp_client.shutdown_session()


async def open_document(client: LanguageClient, name: str, text: str) -> str:
    """Opens `text` as the file `name` and waits for its diagnostics."""
    uri = f"file:///work/{name}"
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(uri=uri, language_id="ray", version=1, text=text)
        )
    )
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    return uri


def at(line: int, character: int) -> types.Position:
    return types.Position(line=line, character=character)


async def ask(client: LanguageClient, request: str, params, uri: str, position: types.Position, **more):
    """The answer to the request `textDocument/<request>` at `position` of `uri`."""
    document = types.TextDocumentIdentifier(uri=uri)
    return await getattr(client, f"text_document_{request}_async")(
        params(text_document=document, position=position, **more)
    )


async def quick_fixes(client: LanguageClient, uri: str, diagnostic: types.Diagnostic):
    """The code actions offered for `diagnostic` of `uri`."""
    return await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            range=diagnostic.range,
            context=types.CodeActionContext(diagnostics=[diagnostic]),
        )
    )


def word(text: str, line: int, name: str, nth: int = 0) -> types.Position:
    """The position of the `nth` `name` on `line` of `text` (all ASCII)."""
    row = text.split("\n")[line]
    column = -1
    for _ in range(nth + 1):
        column = row.index(name, column + 1)
    return at(line, column)


@pytest.mark.asyncio
async def test_a_parse_error_has_its_place_code_and_help(client: LanguageClient):
    uri = await open_document(client, "typo.ray", HEAD + f"put spehre center 0, 0, 0 radius 1 {BALL}\n")
    [diagnostic] = client.diagnostics[uri]
    assert diagnostic.severity == types.DiagnosticSeverity.Error
    assert diagnostic.range.start == at(3, 11), "at `center`, which a name cannot be followed by"
    assert diagnostic.source == "rayrepl" and diagnostic.code == "unexpected-token"
    assert "help: did you mean `sphere`?" in diagnostic.message
    [related] = diagnostic.related_information
    assert related.location.range.start == at(3, 4) and "not a keyword" in related.message
    actions = await quick_fixes(client, uri, diagnostic)
    [fix] = actions
    assert fix.kind == types.CodeActionKind.QuickFix
    [edit] = fix.edit.changes[uri]
    assert edit.new_text == "sphere" and edit.range == types.Range(start=at(3, 4), end=at(3, 10))
    # Asked with the cursor on the misspelt word, as editors ask: the same fix.
    on_the_word = types.Diagnostic(range=types.Range(start=at(3, 6), end=at(3, 6)), message="")
    [fix] = await quick_fixes(client, uri, on_the_word)
    assert list(fix.edit.changes[uri]) == [edit]


@pytest.mark.asyncio
async def test_positions_are_utf16_and_changes_are_incremental(client: LanguageClient):
    # `é` is one UTF-16 unit, `🎨` two: the error's column counts them so.
    text = HEAD + "# é🎨\nlet a = 1 +\n"
    uri = await open_document(client, "unicode.ray", text.replace("let a = 1 +", "let é = 1"))
    [diagnostic] = client.diagnostics[uri]
    assert diagnostic.range.start == at(4, 4), diagnostic
    # Replace `é` (line 4, column 4) with `a`, then end the line with `+ 2`.
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
            content_changes=[
                types.TextDocumentContentChangePartial(range=types.Range(start=at(4, 4), end=at(4, 5)), text="a"),
                types.TextDocumentContentChangePartial(range=types.Range(start=at(4, 9), end=at(4, 9)), text=" + 2"),
            ],
        )
    )
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    assert list(client.diagnostics[uri]) == []
    hover = await ask(client, "hover", types.HoverParams, uri, at(4, 4))
    assert "`a = 3`" in hover.contents.value, hover


@pytest.mark.asyncio
async def test_warnings_about_the_scene_with_their_related_places(client: LanguageClient):
    text = HEAD + f"put sphere center 0, 0, 0 radius 1 {BALL}\nput sphere center 3, 0, 0 radius 1 kd 1 ks 0 phong 1 color 1, 0.5, 0 end\n"
    text += "put rotate sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 0, 0 end by 0, 0, 90 end\n"
    uri = await open_document(client, "warnings.ray", text)
    warnings = client.diagnostics[uri]
    assert all(w.severity == types.DiagnosticSeverity.Warning for w in warnings), warnings
    codes = {w.code for w in warnings}
    assert len(warnings) >= 2, warnings
    degrees = [w for w in warnings if "degrees" in w.message]
    assert degrees and degrees[0].range.start.line == 5, warnings
    assert len(codes) >= 2


@pytest.mark.asyncio
async def test_an_evaluation_error_names_the_call_chain(client: LanguageClient):
    text = HEAD + "proc f(n)\n  let x = 1 / n\n  f(n - 1)\nend\nf(2)\n"
    uri = await open_document(client, "division.ray", text)
    [diagnostic] = client.diagnostics[uri]
    assert diagnostic.severity == types.DiagnosticSeverity.Error
    assert diagnostic.range.start.line == 4 and diagnostic.message.startswith("division by zero")
    assert [r.location.range.start.line for r in diagnostic.related_information] == [5, 7], "the calls"


@pytest.mark.asyncio
async def test_a_runaway_recursion_is_stopped(client: LanguageClient):
    text = HEAD + "proc f(n) if n > 0 then f(n - 1) f(n - 1) end end\nf(60)\n"
    uri = await open_document(client, "runaway.ray", text)
    [diagnostic] = client.diagnostics[uri]
    assert diagnostic.code == "evaluation-too-long"


SCOPES = HEAD + """proc ball(x) put sphere center x, 0, 0 radius size kd 1 ks 0 phong 1 color 255, 200, 0 end end
proc small(x)
  let size = 0.2
  ball(x)
  print size
end
let size = 1
ball(0)
small(6)
"""


@pytest.mark.asyncio
async def test_definitions_and_references_follow_the_scopes(client: LanguageClient):
    uri = await open_document(client, "scoping.ray", SCOPES)

    async def definitions(position):
        return [location.range.start for location in await ask(client, "definition", types.DefinitionParams, uri, position)]

    async def references(position):
        context = types.ReferenceContext(include_declaration=True)
        found = await ask(client, "references", types.ReferenceParams, uri, position, context=context)
        return sorted(location.range.start.line for location in found)

    # `size` in `ball` reads the global (line 9), `size` printed in `small` its local (line 5).
    assert await definitions(word(SCOPES, 3, "size")) == [word(SCOPES, 9, "size")]
    assert await definitions(word(SCOPES, 7, "size")) == [word(SCOPES, 5, "size")]
    assert await references(word(SCOPES, 5, "size")) == [5, 7]
    assert await references(word(SCOPES, 9, "size")) == [3, 9]
    assert await references(word(SCOPES, 3, "ball")) == [3, 6, 10]


@pytest.mark.asyncio
async def test_rename_changes_one_symbol_and_refuses_keywords(client: LanguageClient):
    uri = await open_document(client, "rename.ray", SCOPES)
    document = types.TextDocumentIdentifier(uri=uri)
    local = word(SCOPES, 5, "size")
    prepared = await client.text_document_prepare_rename_async(
        types.PrepareRenameParams(text_document=document, position=local)
    )
    assert prepared.placeholder == "size"
    edit = await client.text_document_rename_async(
        types.RenameParams(text_document=document, position=local, new_name="tiny")
    )
    assert sorted(e.range.start.line for e in edit.changes[uri]) == [5, 7], "the local only"
    for refused, reason in [("sphere", "word of the language"), ("x", "already a name here"), ("2a", "not a name")]:
        with pytest.raises(Exception, match=reason):
            await client.text_document_rename_async(
                types.RenameParams(text_document=document, position=local, new_name=refused)
            )


@pytest.mark.asyncio
async def test_hover_gives_help_pages_signatures_and_values(client: LanguageClient):
    uri = await open_document(client, "hover.ray", SCOPES)

    async def hover(position):
        return (await ask(client, "hover", types.HoverParams, uri, position)).contents.value

    assert "```ray\nsphere center X, Y, Z radius R TEXTURE end" in await hover(word(SCOPES, 3, "sphere"))
    assert "proc ball(x)" in await hover(word(SCOPES, 10, "ball"))
    assert "`size = 1`" in await hover(word(SCOPES, 9, "size"))
    assert "local number of `small`" in await hover(word(SCOPES, 5, "size"))
    assert "parameter of `ball`" in await hover(word(SCOPES, 3, "x", 1))


@pytest.mark.asyncio
async def test_the_outline_lists_camera_lights_procedures_and_names(client: LanguageClient):
    uri = await open_document(client, "outline.ray", SCOPES)
    symbols = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(text_document=types.TextDocumentIdentifier(uri=uri))
    )
    assert [s.name for s in symbols] == ["camera", "ambient", "light 1", "ball", "small", "size"]
    small = symbols[4]
    assert [c.name for c in small.children] == ["x", "size"]


RING = HEAD + """proc ring(n, r)
  let step = 2 * pi / n
  put sphere center r, 0, 0 radius 0.2 kd 1 ks 0 phong 1 color 255, 0, 0 end
end
object ball = sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 255, 120, 40 end
"""


async def type_at_end(client: LanguageClient, uri: str, text: str, typed: str, version: int) -> types.Position:
    """Types `typed` at the end of `text` (a document open at `uri`); the position after it."""
    lines = text.split("\n")
    end = at(len(lines) - 1, len(lines[-1]))
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=[types.TextDocumentContentChangePartial(range=types.Range(start=end, end=end), text=typed)],
        )
    )
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    last = (text + typed).split("\n")
    return at(len(last) - 1, len(last[-1]))


@pytest.mark.asyncio
async def test_completion_follows_what_may_come_there_while_the_text_does_not_parse(client: LanguageClient):
    uri = await open_document(client, "ring.ray", RING)

    async def labels(position):
        return [item.label for item in await ask(client, "completion", types.CompletionParams, uri, position)]

    # Inside `ring`, where a number may come: its parameters and its local.
    inside = at(4, len("  let step = 2 * pi / "))
    assert {"n", "r", "step", "pi", "sin(x)"} <= set(await labels(inside))
    after_put = await type_at_end(client, uri, RING, "put ", 2)
    assert client.diagnostics[uri], "the text being typed does not parse"
    offered = await labels(after_put)
    for expected in ["sphere", "box", "plane", "translate", "rotate", "scale", "group", "ball"]:
        assert expected in offered, offered
    assert "put" not in offered and "n" not in offered, "no instruction, no local of `ring`"
    after_start = await type_at_end(client, uri, RING + "put ", "ball\nri", 3)
    assert await labels(after_start) == ["ring(n, r)"]
    [ring] = await ask(client, "completion", types.CompletionParams, uri, after_start)
    snippets = client.capabilities.text_document.completion.completion_item.snippet_support
    assert ring.text_edit.new_text == ("ring(${1:n}, ${2:r})$0" if snippets else "ring(")


@pytest.mark.asyncio
async def test_signature_help_names_the_parameter_being_typed(client: LanguageClient):
    uri = await open_document(client, "call.ray", RING)
    position = await type_at_end(client, uri, RING, "ring(12, ", 2)
    found = await ask(client, "signature_help", types.SignatureHelpParams, uri, position)
    [signature] = found.signatures
    assert signature.label == "proc ring(n, r)"
    assert found.active_parameter == 1
    start, end = signature.parameters[1].label
    assert signature.label[start:end] == "r"


@pytest.mark.asyncio
async def test_colour_swatches_for_numbers_and_the_picked_colour_in_0_to_255(client: LanguageClient):
    text = RING + "let g = 100\nput sphere center 0, 2, 0 radius 1 kd 1 ks 0 phong 1 color 0, g, 255 end\n"
    uri = await open_document(client, "colours.ray", text)
    document = types.TextDocumentIdentifier(uri=uri)
    swatches = await client.text_document_document_color_async(types.DocumentColorParams(text_document=document))
    assert [s.range.start.line for s in swatches] == [5, 7], "not the colour with a name in it"
    ball = swatches[1]
    assert (round(ball.color.red * 255), round(ball.color.green * 255), round(ball.color.blue * 255)) == (255, 120, 40)
    row = text.split("\n")[7]
    assert ball.range.start.character == row.index("255, 120, 40") and ball.range.end.character == len(row) - 4
    [written] = await client.text_document_color_presentation_async(
        types.ColorPresentationParams(
            text_document=document, color=types.Color(red=0.5, green=1.0, blue=0.0, alpha=1.0), range=ball.range
        )
    )
    assert written.label == "128, 255, 0"


def check_json(path: pathlib.Path) -> list[dict]:
    """What `rayrepl --check --json` says of the file at `path`."""
    import json
    import subprocess

    run = subprocess.run([RAYREPL, "--check", "--json", str(path)], capture_output=True, text=True)
    return [json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")]


CASES = sorted((ROOT / "tests" / "cases").glob("*/*.ray"))


@pytest.mark.asyncio
async def test_every_diagnostic_is_where_the_command_line_puts_it(client: LanguageClient):
    # Every invalid, valid and warning case: the same diagnostics, in the same
    # order, at the same lines and UTF-16 columns, with the same codes.
    assert len(CASES) > 100
    for path in CASES:
        expected = check_json(path)
        uri = await open_document(client, path.name, path.read_text(encoding="utf-8", errors="replace"))
        shown = [d for d in client.diagnostics[uri] if d.code != "evaluation-too-long"]
        got = [(d.code, d.range.start.line + 1, d.range.start.character + 1) for d in shown]
        want = [(d["code"], d["place"]["line"], d["place"]["column_utf16"]) for d in expected]
        assert got == want, path.name


@pytest.mark.asyncio
async def test_the_render_command_gives_the_batch_renderers_bytes(client: LanguageClient, tmp_path):
    import base64
    import subprocess

    scene = ROOT / "scenarios" / "solar.ray"
    text = scene.read_text()
    uri = await open_document(client, "solar.ray", text)
    written = tmp_path / "lsp.png"
    answer = await client.workspace_execute_command_async(
        types.ExecuteCommandParams(
            command="rayrepl.render", arguments=[uri, {"width": 160, "height": 120, "output": str(written)}]
        )
    )
    batch = tmp_path / "batch.png"
    subprocess.run([RAYREPL, str(scene), "--width", "160", "--height", "120", "-o", str(batch)], check=True, capture_output=True)
    assert (answer["width"], answer["height"]) == (160, 120)
    assert base64.b64decode(answer["png"]) == batch.read_bytes()
    assert written.read_bytes() == batch.read_bytes() and answer["written"] == str(written)
    with pytest.raises(Exception, match="width"):
        await client.workspace_execute_command_async(
            types.ExecuteCommandParams(command="rayrepl.render", arguments=[uri, {"width": 0}])
        )


@pytest.mark.asyncio
async def test_formatting_gives_what_rayrepl_fmt_writes(client: LanguageClient):
    import subprocess

    messy = HEAD + "proc p(n)\nif n>0 then\nput sphere center n,0,0 radius 1 # a ball\nkd 1 ks 0 phong 1 color 255,0,0 end\np(n-1)\nend\nend\np(3)\n"
    uri = await open_document(client, "messy.ray", messy)
    options = types.FormattingOptions(tab_size=2, insert_spaces=True)
    document = types.TextDocumentIdentifier(uri=uri)
    [edit] = await client.text_document_formatting_async(types.DocumentFormattingParams(text_document=document, options=options))
    expected = subprocess.run([RAYREPL, "fmt", "-"], input=messy, capture_output=True, text=True, check=True).stdout
    assert edit.new_text == expected and "    put sphere center n, 0, 0 radius 1 # a ball" in expected
    assert edit.range.start == at(0, 0) and edit.range.end == at(messy.count("\n"), 0)
    tidy = await open_document(client, "tidy.ray", expected)
    edits = await client.text_document_formatting_async(
        types.DocumentFormattingParams(text_document=types.TextDocumentIdentifier(uri=tidy), options=options)
    )
    assert list(edits) == [], "a formatted file is left alone"
    broken = await open_document(client, "broken.ray", HEAD + "put sphere\n")
    with pytest.raises(Exception, match="cannot be formatted until it parses"):
        await client.text_document_formatting_async(
            types.DocumentFormattingParams(text_document=types.TextDocumentIdentifier(uri=broken), options=options)
        )


FIXES = [
    ("put Sphere center 0, 0, 0 radius 1 " + BALL, "Sphere", "sphere"),
    ("put sphère center 0, 0, 0 radius 1 " + BALL, "sphère", "sphere"),
    ("put sphere centre 0, 0, 0 radius 1 " + BALL, "centre", "center"),
    ("put spehre center 0, 0, 0 radius 1 " + BALL, "spehre", "sphere"),
    ("let a = 1,5", "1,5", "1.5"),
    ("let a = \u22121", "\u2212", "-"),
    ("let a = 2 \u00d7 3", "\u00d7", "*"),
    ("put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color #ff8000 end", "#ff8000", "255, 128, 0"),
]


@pytest.mark.asyncio
@pytest.mark.parametrize("line, wrong, right", FIXES)
async def test_a_quick_fix_for_each_help_that_proposes_an_edit(client: LanguageClient, line, wrong, right):
    uri = await open_document(client, "fix.ray", HEAD + line + "\n")
    [diagnostic] = client.diagnostics[uri]
    actions = await quick_fixes(client, uri, diagnostic)
    [fix] = actions
    [edit] = fix.edit.changes[uri]
    start = line.index(wrong)
    # Columns in UTF-16 code units: every character here is one.
    assert edit.range == types.Range(start=at(3, start), end=at(3, start + len(wrong))), edit
    assert edit.new_text == right


@pytest.mark.asyncio
async def test_the_quick_fix_for_else_if_closes_the_outer_if_after_the_inner_one(client: LanguageClient):
    body = "if 1 < 2 then\n  print 1\nelse if 2 < 3 then\n  print 2\nend\nprint 3\n"
    uri = await open_document(client, "else_if.ray", HEAD + body)
    [diagnostic] = client.diagnostics[uri]
    assert "`else if` starts a second `if`" in diagnostic.message
    [fix] = await quick_fixes(client, uri, diagnostic)
    [edit] = fix.edit.changes[uri]
    assert edit.range == types.Range(start=at(7, 3), end=at(7, 3)) and edit.new_text == " end"
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
            content_changes=[types.TextDocumentContentChangePartial(range=edit.range, text=edit.new_text)],
        )
    )
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    assert list(client.diagnostics[uri]) == [], "the fix makes it run"
