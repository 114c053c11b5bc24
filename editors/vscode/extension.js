// The VS Code client of `rayrepl lsp`: it starts the server for `.ray`
// files (the program set by `rayrepl.path`) and shows the scene's picture
// in a panel beside the editor, rendered by the server's `rayrepl.render`
// command (the bytes `rayrepl FILE -o out.png` writes) and again at each save.
"use strict";

const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const program = vscode.workspace.getConfiguration("rayrepl").get("path", "rayrepl");
  client = new LanguageClient(
    "rayrepl",
    "rayrepl",
    { command: program, args: ["lsp"] },
    { documentSelector: [{ language: "ray" }] },
  );
  client.start();
  let panel;
  const show = async (document) => {
    const settings = vscode.workspace.getConfiguration("rayrepl.picture");
    const size = { width: settings.get("width", 400), height: settings.get("height", 300) };
    let html;
    try {
      const picture = await client.sendRequest("workspace/executeCommand", {
        command: "rayrepl.render",
        arguments: [document.uri.toString(), size],
      });
      html = `<img alt="the rendered scene" width="${picture.width}" height="${picture.height}"
                   src="data:image/png;base64,${picture.png}">`;
    } catch (error) {
      html = `<p>${String(error.message).replace(/&/g, "&amp;").replace(/</g, "&lt;")}</p>`;
    }
    if (!panel) {
      panel = vscode.window.createWebviewPanel("rayrepl.picture", "Picture", vscode.ViewColumn.Beside, {});
      panel.onDidDispose(() => { panel = undefined; });
    }
    panel.title = `Picture: ${document.uri.path.split("/").pop()}`;
    panel.webview.html = `<!DOCTYPE html><html><body>${html}</body></html>`;
  };
  context.subscriptions.push(
    vscode.commands.registerCommand("rayrepl.showPicture", () => {
      const editor = vscode.window.activeTextEditor;
      if (editor && editor.document.languageId === "ray") {
        show(editor.document);
      }
    }),
    vscode.workspace.onDidSaveTextDocument((document) => {
      if (panel && document.languageId === "ray") {
        show(document);
      }
    }),
  );
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
