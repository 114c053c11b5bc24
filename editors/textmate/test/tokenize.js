// The .ray TextMate grammar, tokenized by VS Code's own tokenizer
// (vscode-textmate on the Oniguruma of vscode-oniguruma), checked against
// the lexer's reading of every scenario and every valid test case: each
// keyword of the words table gets a keyword's scope, each number a number's,
// each comment a comment's, and no other piece of text only `source.ray`.
// Then every word of the table alone, and a few lines with every scope
// written out.
'use strict';

const fs = require('fs');
const path = require('path');
const oniguruma = require('vscode-oniguruma');
const textmate = require('vscode-textmate');

const root = path.resolve(__dirname, '../../..');
const grammarPath = path.join(root, 'editors/textmate/ray.tmLanguage.json');

// The words of the language, read from the table itself (not from the
// grammar, which is what is tested): the keyword(...) and opener(...) rows,
// and the predefined names (`time`).
function tableWords() {
  const table = fs.readFileSync(path.join(root, 'src/lang/words.rs'), 'utf8');
  const rows = /\b(?:keyword|opener)\("([a-z]+)"|text: "([a-z]+)", kind: Kind::Predefined/g;
  return new Set([...table.matchAll(rows)].map((m) => m[1] || m[2]));
}

// Lexemes of a line as the lexer reads them: [start, end, kind].
function lexemes(line, keywords) {
  const out = [];
  let at = 0;
  while (at < line.length) {
    const rest = line.slice(at);
    let m;
    if ((m = /^\s+/.exec(rest))) {
      at += m[0].length;
      continue;
    }
    let kind;
    if (rest[0] === '#') {
      m = [rest];
      kind = 'comment';
    } else if ((m = /^(?:[0-9]+(?:\.[0-9]+)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?/.exec(rest))) {
      kind = 'number';
    } else if ((m = /^[A-Za-z_][A-Za-z0-9_]*/.exec(rest))) {
      kind = keywords.has(m[0]) ? 'keyword' : 'name';
    } else {
      m = /^(?:[<>!]=|.)/.exec(rest);
      kind = 'symbol';
    }
    out.push([at, at + m[0].length, kind]);
    at += m[0].length;
  }
  return out;
}

// The scope each kind of lexeme must have (one of the token's scopes starts so).
const expected = {
  comment: /^comment\.line\.number-sign\.ray$/,
  number: /^constant\.numeric\.ray$/,
  keyword: /^(keyword|storage\.type|support|constant\.language|variable\.language)\./,
  name: /^(variable\.other|entity\.name\.function)\.ray$/,
  symbol: /^(keyword\.operator|punctuation)\./,
};

async function loadGrammar() {
  const wasm = fs.readFileSync(path.join(path.dirname(require.resolve('vscode-oniguruma')), 'onig.wasm'));
  await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
  const registry = new textmate.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
      createOnigString: (text) => new oniguruma.OnigString(text),
    }),
    loadGrammar: async (scopeName) =>
      scopeName === 'source.ray'
        ? textmate.parseRawGrammar(fs.readFileSync(grammarPath, 'utf8'), grammarPath)
        : null,
  });
  return registry.loadGrammar('source.ray');
}

// Each line of `text` with its tokens.
function tokenizeLines(grammar, text) {
  let stack = textmate.INITIAL;
  return text.split(/\r?\n/).map((line) => {
    const result = grammar.tokenizeLine(line, stack);
    stack = result.ruleStack;
    return { line, tokens: result.tokens };
  });
}

function checkFile(grammar, file, keywords, failures, counts) {
  // Editors drop the byte-order mark, as the lexer skips it.
  const text = fs.readFileSync(file, 'utf8').replace(/^\uFEFF/, '');
  tokenizeLines(grammar, text).forEach(({ line, tokens }, index) => {
    const where = `${path.relative(root, file)}:${index + 1}`;
    for (const token of tokens) {
      const piece = line.slice(token.startIndex, token.endIndex);
      if (piece.trim() === '') continue;
      counts.tokens += 1;
      if (token.scopes.length === 1) failures.push(`${where}: \`${piece}\` has only source.ray`);
      if (token.scopes.some((s) => s.startsWith('invalid.'))) failures.push(`${where}: \`${piece}\` is ${token.scopes}`);
    }
    for (const [start, end, kind] of lexemes(line, keywords)) {
      counts[kind] = (counts[kind] || 0) + 1;
      const covering = tokens.filter((t) => t.startIndex < end && t.endIndex > start);
      const straddles = covering.some((t) => t.startIndex < start || t.endIndex > end);
      const scoped = covering.every((t) => t.scopes.some((s) => expected[kind].test(s)));
      if (straddles || !scoped) {
        const got = covering.map((t) => `${line.slice(t.startIndex, t.endIndex)}: ${t.scopes.join(' ')}`).join('; ');
        failures.push(`${where}: the ${kind} \`${line.slice(start, end)}\` is tokenized as ${got}`);
      }
    }
  });
}

// Lines with every token's innermost scope written out.
const knownLines = [
  [
    'proc branch(x, l) # a branch',
    [
      ['proc', 'keyword.control.ray'],
      ['branch', 'entity.name.function.ray'],
      ['(', 'punctuation.section.parens.begin.ray'],
      ['x', 'variable.other.ray'],
      [',', 'punctuation.separator.comma.ray'],
      ['l', 'variable.other.ray'],
      [')', 'punctuation.section.parens.end.ray'],
      ['#', 'punctuation.definition.comment.ray'],
      [' a branch', 'comment.line.number-sign.ray'],
    ],
  ],
  [
    'let r = sqrt(2.5e-1) * time - pi <= .5',
    [
      ['let', 'keyword.other.instruction.ray'],
      ['r', 'variable.other.ray'],
      ['=', 'keyword.operator.comparison.ray'],
      ['sqrt', 'support.function.ray'],
      ['(', 'punctuation.section.parens.begin.ray'],
      ['2.5e-1', 'constant.numeric.ray'],
      [')', 'punctuation.section.parens.end.ray'],
      ['*', 'keyword.operator.arithmetic.ray'],
      ['time', 'variable.language.ray'],
      ['-', 'keyword.operator.arithmetic.ray'],
      ['pi', 'constant.language.ray'],
      ['<=', 'keyword.operator.comparison.ray'],
      ['.5', 'constant.numeric.ray'],
    ],
  ],
  [
    'put translate sphere center 0,0,0 radius 1 kd 1 ks 0 phong 2 color 9,9,9 end by 1,2,3 end',
    [
      ['put', 'keyword.other.instruction.ray'],
      ['translate', 'support.type.transformation.ray'],
      ['sphere', 'support.type.shape.ray'],
      ['center', 'keyword.other.part.ray'],
      ...['0', ',', '0', ',', '0'].map((t) => [t, t === ',' ? 'punctuation.separator.comma.ray' : 'constant.numeric.ray']),
      ['radius', 'keyword.other.part.ray'],
      ['1', 'constant.numeric.ray'],
      ['kd', 'keyword.other.texture.ray'],
      ['1', 'constant.numeric.ray'],
      ['ks', 'keyword.other.texture.ray'],
      ['0', 'constant.numeric.ray'],
      ['phong', 'keyword.other.texture.ray'],
      ['2', 'constant.numeric.ray'],
      ['color', 'keyword.other.texture.ray'],
      ...['9', ',', '9', ',', '9'].map((t) => [t, t === ',' ? 'punctuation.separator.comma.ray' : 'constant.numeric.ray']),
      ['end', 'keyword.control.ray'],
      ['by', 'keyword.other.part.ray'],
      ...['1', ',', '2', ',', '3'].map((t) => [t, t === ',' ? 'punctuation.separator.comma.ray' : 'constant.numeric.ray']),
      ['end', 'keyword.control.ray'],
    ],
  ],
  [
    'if spheres != 2end | !x then camera distance 1 angle 1 end else ambient 1 end',
    [
      ['if', 'keyword.control.ray'],
      ['spheres', 'variable.other.ray'],
      ['!=', 'keyword.operator.comparison.ray'],
      ['2', 'constant.numeric.ray'],
      ['end', 'keyword.control.ray'],
      ['|', 'keyword.operator.logical.ray'],
      ['!', 'keyword.operator.logical.ray'],
      ['x', 'variable.other.ray'],
      ['then', 'keyword.control.ray'],
      ['camera', 'storage.type.ray'],
      ['distance', 'keyword.other.part.ray'],
      ['1', 'constant.numeric.ray'],
      ['angle', 'keyword.other.part.ray'],
      ['1', 'constant.numeric.ray'],
      ['end', 'keyword.control.ray'],
      ['else', 'keyword.control.ray'],
      ['ambient', 'storage.type.ray'],
      ['1', 'constant.numeric.ray'],
      ['end', 'keyword.control.ray'],
    ],
  ],
  [
    'x2end colour // no $',
    [
      ['x2end', 'variable.other.ray'],
      ['colour', 'variable.other.ray'],
      ['//', 'invalid.illegal.comment.ray'],
      ['no', 'variable.other.ray'],
      ['$', 'invalid.illegal.character.ray'],
    ],
  ],
];

function checkKnownLines(grammar, failures) {
  for (const [line, want] of knownLines) {
    const { tokens } = tokenizeLines(grammar, line)[0];
    const got = tokens
      .map((t) => [line.slice(t.startIndex, t.endIndex), t.scopes[t.scopes.length - 1]])
      .filter(([text]) => text.trim() !== '')
      .map(([text, scope]) => [text.startsWith(' ') && scope.startsWith('comment') ? text : text.trim(), scope]);
    if (JSON.stringify(got) !== JSON.stringify(want)) {
      failures.push(`\`${line}\`:\n  expected ${JSON.stringify(want)}\n  got      ${JSON.stringify(got)}`);
    }
  }
}

// Every word of the table, alone on a line, gets a keyword's scope.
function checkTableWords(grammar, keywords, failures) {
  for (const word of keywords) {
    const { tokens } = tokenizeLines(grammar, word)[0];
    const scoped = tokens.length === 1 && tokens[0].scopes.some((s) => expected.keyword.test(s));
    if (!scoped) failures.push(`the word \`${word}\` of the table is tokenized as ${JSON.stringify(tokens)}`);
  }
}

async function main() {
  const grammar = await loadGrammar();
  const keywords = tableWords();
  if (keywords.size < 30 || !keywords.has('time')) throw new Error(`only ${keywords.size} words read from src/lang/words.rs`);
  const folders = ['scenarios', 'tests/cases/valid', 'tests/cases/warnings'];
  const files = folders.flatMap((folder) =>
    fs
      .readdirSync(path.join(root, folder))
      .filter((name) => name.endsWith('.ray'))
      .sort()
      .map((name) => path.join(root, folder, name)),
  );
  const failures = [];
  const counts = { tokens: 0 };
  for (const file of files) checkFile(grammar, file, keywords, failures, counts);
  checkTableWords(grammar, keywords, failures);
  checkKnownLines(grammar, failures);
  for (const failure of failures) console.error(failure);
  const summary = Object.entries(counts).map(([kind, n]) => `${n} ${kind}`).join(', ');
  const known = `${keywords.size} words of the table alone, ${knownLines.length} known lines`;
  console.log(`${files.length} files (${summary}), ${known}: ${failures.length} failures`);
  process.exit(failures.length === 0 ? 0 : 1);
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
