//! Very deep nesting parses (or fails cleanly) without overflowing the stack.
//!
//! lalrpop's parser keeps its stack on the heap, but dropping a very deep AST
//! recurses, as would cloning or printing it. The program runs in a thread
//! with a 1 GiB stack; these tests do the same.

use rayrepl::lang::ast::{ExprKind, InstrKind, Item};
use rayrepl::lang::{SourceId, is_incomplete, parse_items};

const DEPTH: usize = 100_000;

/// Runs `test` in a thread with a 1 GiB stack, as the program does.
fn with_big_stack(test: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new()
        .stack_size(1 << 30)
        .spawn(test)
        .expect("a thread with a 1 GiB stack")
        .join()
        .expect("the test thread does not panic");
}

#[test]
fn deeply_nested_parentheses() {
    with_big_stack(|| {
        let text = format!("let x = {}1{}", "(".repeat(DEPTH), ")".repeat(DEPTH));
        let program = parse_items(SourceId(0), &text).expect("parses");
        let Item::Instr(instr) = &program.items[0] else { panic!("expected an instruction") };
        let InstrKind::Let(_, e) = &instr.kind else { panic!("expected a let") };
        assert_eq!(e.kind, ExprKind::Number(1.0));
        assert_eq!((e.span.start as usize, e.span.end as usize), (8, text.len()));
    });
}

#[test]
fn deeply_right_nested_sums() {
    with_big_stack(|| {
        let text = format!("let x = {}1{}", "1+(".repeat(DEPTH), ")".repeat(DEPTH));
        let program = parse_items(SourceId(0), &text).expect("parses");
        assert_eq!(program.items.len(), 1);
    });
}

#[test]
fn deeply_left_nested_sums() {
    with_big_stack(|| {
        let text = format!("let x = 1{}", "+1".repeat(DEPTH));
        assert!(parse_items(SourceId(0), &text).is_ok());
    });
}

#[test]
fn deeply_nested_negations_and_conditions() {
    with_big_stack(|| {
        let text = format!("let x = {}1", "-".repeat(DEPTH));
        assert!(parse_items(SourceId(0), &text).is_ok());
        let text = format!("if {}a < 1 then end", "!".repeat(DEPTH));
        assert!(parse_items(SourceId(0), &text).is_ok());
        let text = format!("if {}a < 1{} then end", "(".repeat(DEPTH), ")".repeat(DEPTH));
        assert!(parse_items(SourceId(0), &text).is_ok());
    });
}

#[test]
fn deeply_nested_objects_and_ifs() {
    with_big_stack(|| {
        let text = format!("put {}s{}", "group ".repeat(DEPTH), " end".repeat(DEPTH));
        assert!(parse_items(SourceId(0), &text).is_ok());
        let text = format!("put {}s{}", "scale ".repeat(DEPTH), " by 2 end".repeat(DEPTH));
        assert!(parse_items(SourceId(0), &text).is_ok());
        let text = format!("{}put s{}", "if a < 1 then ".repeat(DEPTH), " end".repeat(DEPTH));
        assert!(parse_items(SourceId(0), &text).is_ok());
    });
}

#[test]
fn deep_unclosed_nesting_is_a_clear_error() {
    with_big_stack(|| {
        let text = format!("let x = {}1", "(".repeat(DEPTH));
        let error = parse_items(SourceId(0), &text).expect_err("unclosed");
        assert!(error.message.starts_with("unexpected end of file"), "{}", error.message);
        assert!(is_incomplete(&text));
        let text = format!("put {}s", "group ".repeat(DEPTH));
        let error = parse_items(SourceId(0), &text).expect_err("unclosed");
        assert_eq!(error.message, "unexpected end of file: the `group` opened at line 1 is not closed with `end`");
        let text = format!("let x = {}1{}", "(".repeat(DEPTH), ")".repeat(DEPTH + 1));
        assert!(parse_items(SourceId(0), &text).is_err());
    });
}
