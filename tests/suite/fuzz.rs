//! Property tests: no input makes the parser panic, and random valid
//! programs parse, with the precedence of SPEC 2.

use proptest::prelude::*;
use rayrepl::lang::ast::{InstrKind, Item};
use rayrepl::lang::{SourceId, SourceMap, is_incomplete, parse_file, parse_items};

use crate::common::sexpr::{cond, expr};

// ---- Anything at all ------------------------------------------------------------

/// Every keyword, symbol, and some names, numbers and noise (the
/// hostile runs insert them too).
pub(crate) fn vocabulary() -> Vec<&'static str> {
    rayrepl::lang::words::keyword_names().chain(SYMBOLS_AND_NOISE.iter().copied()).collect()
}

/// The symbols of the language, a few names and numbers, and some noise
/// (the keywords come from the lexer: see [`vocabulary`]).
const SYMBOLS_AND_NOISE: &[&str] = &[
    "+",
    "-",
    "*",
    "/",
    "(",
    ")",
    ",",
    "=",
    "<",
    "&",
    "|",
    "!",
    ">",
    "<=",
    ">=",
    "!=",
    "x",
    "time",
    "spher",
    "cemera",
    "0",
    "1.5",
    ".5",
    "1e3",
    "\n",
    "# comment\n",
    "$",
    "é",
    "1e999",
    ".",
];

/// Checks that parsing and rendering `text` neither panics nor points outside it.
fn survives(text: &str) {
    let mut map = SourceMap::new();
    let id = map.add("fuzz.ray", text, 3);
    for result in [parse_file(id, text), parse_items(id, text)] {
        if let Err(diagnostic) = result {
            assert!(diagnostic.span.start <= diagnostic.span.end);
            assert!(diagnostic.span.end as usize <= text.len());
            assert!(!diagnostic.message.is_empty());
            let plain = diagnostic.render(&map, false);
            assert!(!plain.contains('\u{1b}'));
            let _ = diagnostic.render(&map, true);
        }
    }
    let _ = is_incomplete(text);
}

proptest! {
    // Many cases: this stands in for a cargo-fuzz target, within CI's time.
    #![proptest_config(ProptestConfig::with_cases(5_000))]

    #[test]
    fn token_soup_never_panics(
        tokens in prop::collection::vec(prop::sample::select(vocabulary()), 0..60),
        spaced in any::<bool>(),
    ) {
        let text = tokens.join(if spaced { " " } else { "" });
        survives(&text);
    }

    #[test]
    fn random_text_never_panics(text in any::<String>()) {
        survives(&text);
    }

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        survives(&String::from_utf8_lossy(&bytes));
    }
}

// ---- Valid programs ---------------------------------------------------------------

/// An expression tree, printed with as few parentheses as precedence needs
/// (plus random extra ones), and in S-expression form to compare with the AST.
#[derive(Debug, Clone)]
enum E {
    Num(u16),
    Var(&'static str),
    Pi,
    Neg(Box<E>),
    Bin(char, Box<E>, Box<E>),
    Call(&'static str, Box<E>),
    Paren(Box<E>),
}

/// Binding strength: sums 1, products 2, unary minus 3, atoms 4.
fn strength(e: &E) -> u8 {
    match e {
        E::Bin('+' | '-', ..) => 1,
        E::Bin(..) => 2,
        E::Neg(_) => 3,
        _ => 4,
    }
}

/// `e` as source text, parenthesised if it binds looser than `min`.
fn print_expr(e: &E, min: u8) -> String {
    let text = match e {
        E::Num(n) => n.to_string(),
        E::Var(name) => name.to_string(),
        E::Pi => "pi".to_string(),
        // A space keeps `- -1` from reading as a comment-free `--1`: both lex the same.
        E::Neg(inner) => format!("- {}", print_expr(inner, 3)),
        E::Bin(op, a, b) => {
            let s = strength(e);
            format!("{} {op} {}", print_expr(a, s), print_expr(b, s + 1))
        }
        E::Call(f, arg) => format!("{f}({})", print_expr(arg, 0)),
        E::Paren(inner) => format!("({})", print_expr(inner, 0)),
    };
    if strength(e) < min { format!("({text})") } else { text }
}

/// The S-expression the parser should produce for `e`.
fn expected_expr(e: &E) -> String {
    match e {
        E::Num(n) => n.to_string(),
        E::Var(name) => name.to_string(),
        E::Pi => "pi".to_string(),
        E::Neg(inner) => format!("(neg {})", expected_expr(inner)),
        E::Bin(op, a, b) => format!("({op} {} {})", expected_expr(a), expected_expr(b)),
        E::Call(f, arg) => format!("({f} {})", expected_expr(arg)),
        E::Paren(inner) => expected_expr(inner),
    }
}

fn expr_tree() -> impl Strategy<Value = E> {
    let leaf = prop_oneof![
        any::<u16>().prop_map(E::Num),
        prop::sample::select(&["x", "y", "time", "radius_2"][..]).prop_map(E::Var),
        Just(E::Pi),
    ];
    leaf.prop_recursive(5, 40, 2, |inner| {
        prop_oneof![
            inner.clone().prop_map(|e| E::Neg(Box::new(e))),
            (prop::sample::select(&['+', '-', '*', '/'][..]), inner.clone(), inner.clone())
                .prop_map(|(op, a, b)| E::Bin(op, Box::new(a), Box::new(b))),
            (prop::sample::select(&["sin", "cos", "sqrt"][..]), inner.clone())
                .prop_map(|(f, e)| E::Call(f, Box::new(e))),
            inner.prop_map(|e| E::Paren(Box::new(e))),
        ]
    })
}

/// A condition tree, printed like [`E`].
#[derive(Debug, Clone)]
enum C {
    Or(Box<C>, Box<C>),
    And(Box<C>, Box<C>),
    Not(Box<C>),
    Cmp(&'static str, E, E),
    Paren(Box<C>),
}

/// Binding strength: `|` 1, `&` 2, `!` 3, comparisons 4.
fn cond_strength(c: &C) -> u8 {
    match c {
        C::Or(..) => 1,
        C::And(..) => 2,
        C::Not(_) => 3,
        _ => 4,
    }
}

fn print_cond(c: &C, min: u8) -> String {
    let text = match c {
        C::Or(a, b) => format!("{} | {}", print_cond(a, 1), print_cond(b, 2)),
        C::And(a, b) => format!("{} & {}", print_cond(a, 2), print_cond(b, 3)),
        C::Not(inner) => format!("!{}", print_cond(inner, 3)),
        C::Cmp(op, a, b) => format!("{} {op} {}", print_expr(a, 0), print_expr(b, 0)),
        C::Paren(inner) => format!("({})", print_cond(inner, 0)),
    };
    if cond_strength(c) < min { format!("({text})") } else { text }
}

fn expected_cond(c: &C) -> String {
    match c {
        C::Or(a, b) => format!("(or {} {})", expected_cond(a), expected_cond(b)),
        C::And(a, b) => format!("(and {} {})", expected_cond(a), expected_cond(b)),
        C::Not(inner) => format!("(not {})", expected_cond(inner)),
        C::Cmp(op, a, b) => format!("({op} {} {})", expected_expr(a), expected_expr(b)),
        C::Paren(inner) => expected_cond(inner),
    }
}

fn cond_tree() -> impl Strategy<Value = C> {
    let comparison = (prop::sample::select(&["=", "!=", "<", "<=", ">", ">="][..]), expr_tree(), expr_tree())
        .prop_map(|(op, a, b)| C::Cmp(op, a, b));
    comparison.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| C::Or(Box::new(a), Box::new(b))),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| C::And(Box::new(a), Box::new(b))),
            inner.clone().prop_map(|c| C::Not(Box::new(c))),
            inner.prop_map(|c| C::Paren(Box::new(c))),
        ]
    })
}

/// Source text of a random expression.
fn expr_text() -> impl Strategy<Value = String> {
    expr_tree().prop_map(|e| print_expr(&e, 0))
}

fn triple_text() -> impl Strategy<Value = String> {
    (expr_text(), expr_text(), expr_text()).prop_map(|(a, b, c)| format!("{a}, {b}, {c}"))
}

fn texture_text() -> impl Strategy<Value = String> {
    (expr_text(), expr_text(), expr_text(), triple_text())
        .prop_map(|(kd, ks, phong, color)| format!("kd {kd} ks {ks} phong {phong} color {color}"))
}

/// Source text of a random object expression.
fn obj_text() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        Just("s".to_string()),
        (triple_text(), expr_text(), texture_text())
            .prop_map(|(c, r, t)| format!("sphere center {c} radius {r} {t} end")),
        (triple_text(), expr_text(), texture_text())
            .prop_map(|(r, d, t)| format!("plane rotation {r} shift {d} {t} end")),
        (triple_text(), triple_text(), texture_text())
            .prop_map(|(c, l, t)| format!("box center {c} length {l} {t} end")),
    ];
    leaf.prop_recursive(3, 12, 3, |inner| {
        prop_oneof![
            (inner.clone(), triple_text()).prop_map(|(o, v)| format!("translate {o} by {v} end")),
            (inner.clone(), triple_text()).prop_map(|(o, r)| format!("rotate {o} by {r} end")),
            (inner.clone(), expr_text()).prop_map(|(o, k)| format!("scale {o} by {k} end")),
            prop::collection::vec(inner, 0..3).prop_map(|members| format!("group {} end", members.join(" "))),
        ]
    })
}

/// Source text of a random instruction.
fn instr_text() -> impl Strategy<Value = String> {
    let simple = prop_oneof![
        expr_text().prop_map(|e| format!("let x = {e}")),
        obj_text().prop_map(|o| format!("object o = {o}")),
        prop::collection::vec(expr_text(), 0..3).prop_map(|args| format!("p({})", args.join(", "))),
        obj_text().prop_map(|o| format!("put {o}")),
    ];
    simple.prop_recursive(3, 12, 3, |inner| {
        (cond_tree(), prop::collection::vec(inner.clone(), 0..3), prop::option::of(prop::collection::vec(inner, 0..3)))
            .prop_map(|(c, then, otherwise)| {
                let otherwise = otherwise.map(|o| format!(" else {}", o.join("\n"))).unwrap_or_default();
                format!("if {} then {}{otherwise} end", print_cond(&c, 0), then.join("\n"))
            })
    })
}

fn proc_text() -> impl Strategy<Value = String> {
    (prop::collection::vec(prop::sample::select(&["a", "b", "c"][..]), 0..3), prop::collection::vec(instr_text(), 0..3))
        .prop_map(|(params, body)| format!("proc q({})\n{}\nend", params.join(", "), body.join("\n")))
}

fn light_text() -> impl Strategy<Value = String> {
    (prop::sample::select(&["vector", "rotation"][..]), triple_text(), expr_text())
        .prop_map(|(spelling, r, i)| format!("light {spelling} {r} intensity {i} end"))
}

fn file_text() -> impl Strategy<Value = String> {
    (
        expr_text(),
        expr_text(),
        expr_text(),
        prop::collection::vec(light_text(), 0..3),
        prop::collection::vec(proc_text(), 0..3),
        prop::collection::vec(instr_text(), 0..4),
    )
        .prop_map(|(d, a, ambient, lights, procs, instrs)| {
            format!(
                "# generated\ncamera distance {d} angle {a} end\nambient {ambient}\n{}\n{}\n{}\n",
                lights.join("\n"),
                procs.join("\n"),
                instrs.join("\n")
            )
        })
}

proptest! {
    #[test]
    fn expressions_parse_with_spec_precedence(e in expr_tree()) {
        let text = format!("let x = {}", print_expr(&e, 0));
        let program = parse_items(SourceId(0), &text).map_err(|d| TestCaseError::fail(d.message))?;
        let Some(Item::Instr(instr)) = program.items.first() else { panic!("one instruction") };
        let InstrKind::Let(_, parsed) = &instr.kind else { panic!("a let") };
        prop_assert_eq!(expr(parsed), expected_expr(&e), "{}", text);
    }

    #[test]
    fn conditions_parse_with_spec_precedence(c in cond_tree()) {
        let text = format!("if {} then end", print_cond(&c, 0));
        let program = parse_items(SourceId(0), &text).map_err(|d| TestCaseError::fail(format!("{text}: {}", d.message)))?;
        let Some(Item::Instr(instr)) = program.items.first() else { panic!("one instruction") };
        let InstrKind::If(parsed, _, _) = &instr.kind else { panic!("an if") };
        prop_assert_eq!(cond(parsed), expected_cond(&c), "{}", text);
    }

    #[test]
    fn random_valid_files_parse(text in file_text()) {
        let result = parse_file(SourceId(0), &text);
        prop_assert!(result.is_ok(), "{}\n{:?}", text, result.err().map(|d| d.message));
        prop_assert!(!is_incomplete(&text), "{}", text);
    }

    #[test]
    fn random_valid_session_inputs_parse(
        parts in prop::collection::vec(prop_oneof![instr_text(), proc_text(), light_text()], 0..5),
    ) {
        let text = parts.join("\n");
        let result = parse_items(SourceId(0), &text);
        prop_assert!(result.is_ok(), "{}\n{:?}", text, result.err().map(|d| d.message));
        prop_assert!(!is_incomplete(&text), "{}", text);
    }
}
