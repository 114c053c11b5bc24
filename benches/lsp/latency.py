"""How fast `rayrepl lsp` answers on a 10,000-line file, and whether its
memory stays flat over many edits (docs/perf/front-ends.md, "The language server").

    python3 benches/lsp/latency.py [target/release/rayrepl] [edits]

Speaks the protocol's framing itself (a benchmark needs no client library):
opens the file, then types one character at a time at its end, each edit
followed by the wait for its diagnostics; times hovers and completions in
between; reads the server's resident memory from /proc as it goes.
"""

import json
import statistics
import subprocess
import sys
import time

BINARY = sys.argv[1] if len(sys.argv) > 1 else "target/release/rayrepl"
EDITS = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
LINES = 10_000

HEAD = "camera distance 40 angle 1 end\nambient 0.2\nlight vector 0.5, 0, 0.6 intensity 0.8 end\n"
PROC = "proc ball(x, y, r)\n  put sphere center x, y, 0 radius r kd 1 ks 0 phong 1 color 255, 120, 40 end\nend\n"


def scene() -> str:
    body = []
    for i in range((LINES - 6) // 2):
        body.append(f"let x{i} = {i % 100} / 10")
        body.append(f"ball(x{i} - 5, {i % 37} / 4 - 4, 0.1)")
    return HEAD + PROC + "\n".join(body) + "\n"


class Server:
    def __init__(self):
        self.process = subprocess.Popen([BINARY, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.next_id = 0

    def send(self, message: dict):
        body = json.dumps({"jsonrpc": "2.0", **message}).encode()
        self.process.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.process.stdin.flush()

    def receive(self) -> dict:
        length = 0
        while (line := self.process.stdout.readline().strip()) != b"":
            if line.lower().startswith(b"content-length:"):
                length = int(line.split(b":")[1])
        return json.loads(self.process.stdout.read(length))

    def request(self, method: str, params: dict) -> dict:
        self.next_id += 1
        self.send({"id": self.next_id, "method": method, "params": params})
        while "id" not in (answer := self.receive()) or answer["id"] != self.next_id:
            pass
        return answer

    def notify(self, method: str, params: dict):
        self.send({"method": method, "params": params})

    def wait_for(self, method: str) -> dict:
        while (message := self.receive()).get("method") != method:
            pass
        return message

    def resident_kib(self) -> int:
        with open(f"/proc/{self.process.pid}/status") as status:
            return next(int(line.split()[1]) for line in status if line.startswith("VmRSS:"))


def milliseconds(work) -> float:
    start = time.perf_counter()
    work()
    return (time.perf_counter() - start) * 1000


def main():
    text = scene()
    uri = "file:///bench/big.ray"
    server = Server()
    server.request("initialize", {"processId": None, "rootUri": None, "capabilities": {}})
    server.notify("initialized", {})
    opened = milliseconds(lambda: (
        server.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "ray", "version": 1, "text": text}}),
        server.wait_for("textDocument/publishDiagnostics"),
    ))
    line = text.count("\n")
    column = 0
    edits, hovers, completions, memory = [], [], [], []
    for version in range(2, EDITS + 2):
        # `#` then letters: a comment, so the program stays valid and whole.
        character = "#" if column == 0 else "x"
        position = {"line": line, "character": column}
        change = {"range": {"start": position, "end": position}, "text": character}
        edits.append(milliseconds(lambda: (
            server.notify("textDocument/didChange", {
                "textDocument": {"uri": uri, "version": version}, "contentChanges": [change]}),
            server.wait_for("textDocument/publishDiagnostics"),
        )))
        column += 1
        if version % 10 == 0:
            at = {"textDocument": {"uri": uri}, "position": {"line": 3, "character": 6}}
            hovers.append(milliseconds(lambda: server.request("textDocument/hover", at)))
            at = {"textDocument": {"uri": uri}, "position": {"line": 7, "character": 4}}
            completions.append(milliseconds(lambda: server.request("textDocument/completion", at)))
        if version % (EDITS // 10) == 0:
            memory.append(server.resident_kib())
    server.request("shutdown", None)
    server.notify("exit", None)
    server.process.wait()

    def summary(values):
        return f"median {statistics.median(values):.1f} ms, max {max(values):.1f} ms"

    print(f"{LINES} lines, {len(text)} bytes; open and first diagnostics {opened:.0f} ms")
    print(f"edit to diagnostics ({len(edits)}): {summary(edits)}")
    print(f"hover ({len(hovers)}): {summary(hovers)}")
    print(f"completion ({len(completions)}): {summary(completions)}")
    print("resident memory every tenth of the edits (MiB):", " ".join(f"{kib / 1024:.0f}" for kib in memory))


main()
