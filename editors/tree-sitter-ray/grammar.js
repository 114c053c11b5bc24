/**
 * @file The tree-sitter grammar of the `.ray` scene language.
 *
 * It follows grammar/scene.lalrpop (the grammar rayrepl parses with) rule
 * for rule; its keywords are those of the words table (src/lang/words.rs), which a
 * test checks (tools/generate/src/tree_sitter.rs); strings are in single
 * quotes, and comments have none, for that test. After a change here:
 * `tree-sitter generate` in this folder, and commit src/ with it.
 */

/// <reference types="tree-sitter-cli/dsl" />
// @ts-check

const PREC = {
  or: 1,
  and: 2,
  not: 3,
  add: 1,
  multiply: 2,
  unary: 3,
};

/** One or more `rule`s separated by commas. */
function commaSep1(rule) {
  return seq(rule, repeat(seq(',', rule)));
}

module.exports = grammar({
  name: 'ray',

  extras: $ => [/\s/, $.comment],

  // `2end` is `2` and `end`, and `spheres` a name, as the lexer reads them.
  word: $ => $.identifier,

  rules: {
    source_file: $ => repeat(choice($._item, $._instruction)),

    _item: $ => choice($.camera, $.ambient, $.light, $.procedure),

    camera: $ => seq('camera', 'distance', field('distance', $._expression),
      'angle', field('angle', $._expression), 'end'),

    ambient: $ => seq('ambient', field('intensity', $._expression)),

    // `light vector ...` and `light rotation ...` mean the same (SPEC 2).
    light: $ => seq('light', choice('vector', 'rotation'), field('rotation', $.triple),
      'intensity', field('intensity', $._expression), 'end'),

    procedure: $ => seq('proc', field('name', $.identifier), field('parameters', $.parameters),
      repeat($._instruction), 'end'),

    parameters: $ => seq('(', optional(commaSep1($.identifier)), ')'),

    // ---- Instructions ----

    _instruction: $ => choice($.let, $.object_definition, $.call, $.put, $.if, $.print),

    let: $ => seq('let', field('name', $.identifier), '=', field('value', $._expression)),

    object_definition: $ => seq('object', field('name', $.identifier), '=', field('value', $._object)),

    call: $ => seq(field('name', $.identifier), field('arguments', $.arguments)),

    arguments: $ => seq('(', optional(commaSep1($._expression)), ')'),

    put: $ => seq('put', $._object),

    if: $ => seq('if', field('condition', $._condition), 'then', repeat($._instruction),
      optional($.else), 'end'),

    else: $ => seq('else', repeat($._instruction)),

    // An extension of this project (docs/language.md, section 12).
    print: $ => seq('print', commaSep1($._expression)),

    // ---- Objects ----

    _object: $ => choice($.identifier, $.sphere, $.plane, $.box,
      $.translate, $.rotate, $.scale, $.group),

    sphere: $ => seq('sphere', 'center', field('center', $.triple),
      'radius', field('radius', $._expression), $.texture, 'end'),

    plane: $ => seq('plane', 'rotation', field('rotation', $.triple),
      'shift', field('shift', $._expression), $.texture, 'end'),

    box: $ => seq('box', 'center', field('center', $.triple),
      'length', field('length', $.triple), $.texture, 'end'),

    texture: $ => seq('kd', field('kd', $._expression), 'ks', field('ks', $._expression),
      'phong', field('phong', $._expression), 'color', field('color', $.triple)),

    translate: $ => seq('translate', $._object, 'by', field('vector', $.triple), 'end'),

    rotate: $ => seq('rotate', $._object, 'by', field('rotation', $.triple), 'end'),

    scale: $ => seq('scale', $._object, 'by', field('factor', $._expression), 'end'),

    group: $ => seq('group', repeat($._object), 'end'),

    triple: $ => seq($._expression, ',', $._expression, ',', $._expression),

    // ---- Conditions: `|`, then `&`, then `!`, then comparisons ----

    _condition: $ => choice($.or_condition, $.and_condition, $.not_condition,
      $.comparison, $.parenthesized_condition),

    or_condition: $ => prec.left(PREC.or, seq($._condition, '|', $._condition)),

    and_condition: $ => prec.left(PREC.and, seq($._condition, '&', $._condition)),

    not_condition: $ => prec(PREC.not, seq('!', $._condition)),

    comparison: $ => seq($._expression, choice('=', '!=', '<', '<=', '>', '>='), $._expression),

    parenthesized_condition: $ => seq('(', $._condition, ')'),

    // ---- Expressions: `+ -`, then `* /`, then unary `-` ----

    _expression: $ => choice($.binary_expression, $.unary_expression, $.number,
      $.identifier, 'pi', $.function_call, $.parenthesized_expression),

    binary_expression: $ => choice(
      prec.left(PREC.add, seq($._expression, choice('+', '-'), $._expression)),
      prec.left(PREC.multiply, seq($._expression, choice('*', '/'), $._expression)),
    ),

    unary_expression: $ => prec(PREC.unary, seq('-', $._expression)),

    function_call: $ => seq(field('function', choice('sin', 'cos', 'sqrt')), '(', $._expression, ')'),

    parenthesized_expression: $ => seq('(', $._expression, ')'),

    // `[0-9]*(\.[0-9]+)?([eE][+-]?[0-9]+)?` with at least one digit.
    number: _ => /([0-9]+(\.[0-9]+)?|\.[0-9]+)([eE][+-]?[0-9]+)?/,

    identifier: _ => /[A-Za-z_][A-Za-z0-9_]*/,

    comment: _ => token(seq('#', /.*/)),
  },
});
