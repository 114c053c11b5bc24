// The extension's files agree with each other: every path the manifest
// names exists, the grammar is the language's, the language configuration's
// patterns compile and indent as the scenarios are indented.
"use strict";

const assert = require("node:assert/strict");
const fs = require("node:fs");
const path = require("node:path");
const { execFileSync } = require("node:child_process");

const root = path.join(__dirname, "..");
const manifest = JSON.parse(fs.readFileSync(path.join(root, "package.json"), "utf8"));
const [language] = manifest.contributes.languages;
const [grammar] = manifest.contributes.grammars;
assert.equal(language.id, "ray");
assert.deepEqual(language.extensions, [".ray"]);
assert.ok(fs.existsSync(path.join(root, manifest.main)), manifest.main);
const tm = JSON.parse(fs.readFileSync(path.join(root, grammar.path), "utf8"));
assert.equal(tm.scopeName, grammar.scopeName);
assert.equal(grammar.language, language.id);
const configuration = JSON.parse(fs.readFileSync(path.join(root, language.configuration), "utf8"));
assert.equal(configuration.comments.lineComment, "#");
const increase = new RegExp(configuration.indentationRules.increaseIndentPattern);
const decrease = new RegExp(configuration.indentationRules.decreaseIndentPattern);
for (const line of ["proc row(n)", "  if n > 0 then", "else"]) assert.ok(increase.test(line), line);
for (const line of ["end", "  end", "else"]) assert.ok(decrease.test(line), line);
for (const line of ["put sphere center 0, 0, 0 radius 1", "let a = 1 # then"]) assert.ok(!increase.test(line), line);
const commands = manifest.contributes.commands.map((command) => command.command);
const source = fs.readFileSync(path.join(root, manifest.main), "utf8");
for (const command of commands) assert.ok(source.includes(`"${command}"`), `${command} is registered`);
execFileSync(process.execPath, ["--check", path.join(root, manifest.main)]);
console.log(`the extension's manifest, grammar, language configuration and ${commands.length} command agree`);
