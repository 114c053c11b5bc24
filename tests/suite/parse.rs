//! The grammar of SPEC 2: every rule, precedence and associativity, the `(`
//! ambiguity of conditions, the order of a file's parts, and the messages of
//! syntax errors with their line and column.

use rayrepl::lang::ast::{ExprKind, Instr, InstrKind, Item, Obj, ObjKind, Program, Texture, Triple};
use rayrepl::lang::{Diagnostic, Note, SourceId, SourceMap, parse_file, parse_items};

use crate::common::sexpr::{cond, expr};

// ---- Helpers: compact S-expressions of AST shapes --------------------------

fn triple(t: &Triple) -> String {
    format!("[{} {} {}]", expr(&t.parts[0]), expr(&t.parts[1]), expr(&t.parts[2]))
}

fn texture(t: &Texture) -> String {
    format!("(texture {} {} {} {})", expr(&t.kd), expr(&t.ks), expr(&t.phong), triple(&t.color))
}

fn obj(o: &Obj) -> String {
    match &o.kind {
        ObjKind::Var(name) => name.to_string(),
        ObjKind::Sphere { center, radius, texture: t } => {
            format!("(sphere {} {} {})", triple(center), expr(radius), texture(t))
        }
        ObjKind::Plane { rotation, shift, texture: t } => {
            format!("(plane {} {} {})", triple(rotation), expr(shift), texture(t))
        }
        ObjKind::Box { center, length, texture: t } => {
            format!("(box {} {} {})", triple(center), triple(length), texture(t))
        }
        ObjKind::Translate(o, v) => format!("(translate {} {})", obj(o), triple(v)),
        ObjKind::Rotate(o, r) => format!("(rotate {} {})", obj(o), triple(r)),
        ObjKind::Scale(o, k) => format!("(scale {} {})", obj(o), expr(k)),
        ObjKind::Group(members) => {
            let members: Vec<String> = members.iter().map(obj).collect();
            format!("(group{})", members.iter().map(|m| format!(" {m}")).collect::<String>())
        }
    }
}

fn block(instrs: &[Instr]) -> String {
    instrs.iter().map(|i| format!(" {}", instr(i))).collect()
}

fn instr(i: &Instr) -> String {
    match &i.kind {
        InstrKind::Let(name, e) => format!("(let {} {})", name.name, expr(e)),
        InstrKind::Object(name, o) => format!("(object {} {})", name.name, obj(o)),
        InstrKind::Call(name, args) => {
            format!("(call {}{})", name.name, args.iter().map(|a| format!(" {}", expr(a))).collect::<String>())
        }
        InstrKind::Put(o) => format!("(put {})", obj(o)),
        InstrKind::Print(values) => {
            format!("(print{})", values.iter().map(|v| format!(" {}", expr(v))).collect::<String>())
        }
        InstrKind::If(c, then, otherwise) => match otherwise {
            Some(otherwise) => format!("(if {} (then{}) (else{}))", cond(c), block(then), block(otherwise)),
            None => format!("(if {} (then{}))", cond(c), block(then)),
        },
    }
}

fn item(item: &Item) -> String {
    match item {
        Item::Camera(c) => format!("(camera {} {})", expr(&c.distance), expr(&c.angle)),
        Item::Ambient(a) => format!("(ambient {})", expr(&a.intensity)),
        Item::Light(l) => format!("(light {} {})", triple(&l.rotation), expr(&l.intensity)),
        Item::Proc(p) => {
            let params: Vec<&str> = p.params.iter().map(|p| &*p.name).collect();
            format!("(proc {} ({}){})", p.name.name, params.join(" "), block(&p.body))
        }
        Item::Instr(i) => instr(i),
    }
}

fn items(program: &Program) -> Vec<String> {
    program.items.iter().map(item).collect()
}

/// Parses a session input and returns its items as S-expressions.
fn session(text: &str) -> Vec<String> {
    match parse_items(SourceId(0), text) {
        Ok(program) => items(&program),
        Err(error) => panic!("{text:?} should parse, got: {}", error.message),
    }
}

/// The S-expression of the expression `text`.
fn parse_expr(text: &str) -> String {
    let program = parse_items(SourceId(0), &format!("let x = {text}")).expect("a valid expression");
    match &program.items[..] {
        [Item::Instr(Instr { kind: InstrKind::Let(_, e), .. })] => expr(e),
        other => panic!("unexpected items {other:?}"),
    }
}

/// The S-expression of the condition `text`.
fn parse_cond(text: &str) -> String {
    let program = match parse_items(SourceId(0), &format!("if {text} then end")) {
        Ok(program) => program,
        Err(error) => panic!("{text:?} should parse, got: {}", error.message),
    };
    match &program.items[..] {
        [Item::Instr(Instr { kind: InstrKind::If(c, _, _), .. })] => cond(c),
        other => panic!("unexpected items {other:?}"),
    }
}

/// A syntax error with its 1-based line and column.
struct Located {
    diagnostic: Diagnostic,
    line: usize,
    column: usize,
}

fn locate(text: &str, result: Result<Program, Diagnostic>) -> Located {
    let diagnostic = match result {
        Ok(_) => panic!("{text:?} should not parse"),
        Err(diagnostic) => diagnostic,
    };
    let mut map = SourceMap::new();
    let id = map.add("test.ray", text, 0);
    let (line, column) = map.get(id).line_col(diagnostic.span.start as usize);
    Located { diagnostic, line, column }
}

fn session_error(text: &str) -> Located {
    locate(text, parse_items(SourceId(0), text))
}

fn file_error(text: &str) -> Located {
    locate(text, parse_file(SourceId(0), text))
}

fn assert_error(located: &Located, message: &str, line: usize, column: usize) {
    assert_eq!(located.diagnostic.message, message);
    assert_eq!((located.line, located.column), (line, column), "position of {message:?}");
}

const HEADER: &str = "camera distance 10 angle 1 end\nambient 0.2\n";
const TEXTURE: &str = "kd 0.5 ks 0.5 phong 10 color 255, 0, 0";

// ---- Expressions ------------------------------------------------------------

#[test]
fn subtraction_and_division_are_left_associative() {
    assert_eq!(parse_expr("1-2-3"), "(- (- 1 2) 3)");
    assert_eq!(parse_expr("8/4/2"), "(/ (/ 8 4) 2)");
    assert_eq!(parse_expr("1+2-3+4"), "(+ (- (+ 1 2) 3) 4)");
}

#[test]
fn products_bind_tighter_than_sums() {
    assert_eq!(parse_expr("1+2*3"), "(+ 1 (* 2 3))");
    assert_eq!(parse_expr("1*2+3"), "(+ (* 1 2) 3)");
    assert_eq!(parse_expr("1-6/3*2"), "(- 1 (* (/ 6 3) 2))");
}

#[test]
fn unary_minus_binds_tightest_and_stays_a_node() {
    assert_eq!(parse_expr("-2*3"), "(* (neg 2) 3)");
    assert_eq!(parse_expr("2*-3"), "(* 2 (neg 3))");
    assert_eq!(parse_expr("--x"), "(neg (neg x))");
    assert_eq!(parse_expr("1 - -1"), "(- 1 (neg 1))");
    assert_eq!(parse_expr("-(1+2)"), "(neg (+ 1 2))");
}

#[test]
fn parentheses_group_without_a_node() {
    assert_eq!(parse_expr("(1+2)*3"), "(* (+ 1 2) 3)");
    assert_eq!(parse_expr("1-(2-3)"), "(- 1 (- 2 3))");
    assert_eq!(parse_expr("((((x))))"), "x");
}

#[test]
fn atoms_and_functions() {
    assert_eq!(parse_expr("sin(x) + cos(pi) * sqrt(2)"), "(+ (sin x) (* (cos pi) (sqrt 2)))");
    assert_eq!(parse_expr("time"), "time");
    assert_eq!(parse_expr("0.75"), "0.75");
    assert_eq!(parse_expr(".5"), "0.5");
    assert_eq!(parse_expr("1e3"), "1000");
    assert_eq!(parse_expr("sin(-x)"), "(sin (neg x))");
}

#[test]
fn spans_cover_the_whole_expression_and_its_parentheses() {
    let program = parse_items(SourceId(3), "let x = (1 + 2) * y").expect("valid");
    let Item::Instr(Instr { kind: InstrKind::Let(name, e), span }) = &program.items[0] else {
        panic!("expected a let");
    };
    assert_eq!((span.start, span.end), (0, 19));
    assert_eq!(span.source, SourceId(3));
    assert_eq!((name.span.start, name.span.end), (4, 5));
    assert_eq!((e.span.start, e.span.end), (8, 19));
    let ExprKind::Binary(_, left, right) = &e.kind else { panic!("expected a product") };
    assert_eq!((left.span.start, left.span.end), (8, 15), "the parentheses are in the span");
    assert_eq!((right.span.start, right.span.end), (18, 19));
}

// ---- Conditions -------------------------------------------------------------

#[test]
fn or_is_loosest_then_and_then_not() {
    assert_eq!(parse_cond("a<1 | b<2 & c<3"), "(or (< a 1) (and (< b 2) (< c 3)))");
    assert_eq!(parse_cond("a<1 & b<2 | c<3"), "(or (and (< a 1) (< b 2)) (< c 3))");
    assert_eq!(parse_cond("!a=1|b<2"), "(or (not (= a 1)) (< b 2))");
    assert_eq!(parse_cond("!a=1&b<2"), "(and (not (= a 1)) (< b 2))");
    assert_eq!(parse_cond("!!a<1"), "(not (not (< a 1)))");
}

#[test]
fn and_and_or_are_left_associative() {
    assert_eq!(parse_cond("a<1 & b<2 & c<3"), "(and (and (< a 1) (< b 2)) (< c 3))");
    assert_eq!(parse_cond("a<1 | b<2 | c<3"), "(or (or (< a 1) (< b 2)) (< c 3))");
}

#[test]
fn every_comparison_operator() {
    assert_eq!(parse_cond("a = b"), "(= a b)");
    assert_eq!(parse_cond("a != b"), "(!= a b)");
    assert_eq!(parse_cond("a < b"), "(< a b)");
    assert_eq!(parse_cond("a <= b"), "(<= a b)");
    assert_eq!(parse_cond("a > b"), "(> a b)");
    assert_eq!(parse_cond("a >= b"), "(>= a b)");
    assert_eq!(parse_cond("a + 1 < b * 2"), "(< (+ a 1) (* b 2))");
}

#[test]
fn a_parenthesis_may_open_a_condition_or_an_expression() {
    assert_eq!(parse_cond("(a + 1) * 2 < b"), "(< (* (+ a 1) 2) b)");
    assert_eq!(parse_cond("(a < b) & (c < d)"), "(and (< a b) (< c d))");
    assert_eq!(parse_cond("((a < b))"), "(< a b)");
    assert_eq!(parse_cond("!(a = 1) | b < 2"), "(or (not (= a 1)) (< b 2))");
    assert_eq!(parse_cond("(a) < (b)"), "(< a b)");
    assert_eq!(parse_cond("((a + 1)) < b"), "(< (+ a 1) b)");
    assert_eq!(parse_cond("(((a < b) | c < d) & e = f)"), "(and (or (< a b) (< c d)) (= e f))");
    assert_eq!(parse_cond("b < (a + 1) * 2"), "(< b (* (+ a 1) 2))");
    assert_eq!(parse_cond("(-(a) < 1)"), "(< (neg a) 1)");
}

#[test]
fn a_condition_span_includes_its_parentheses() {
    let program = parse_items(SourceId(0), "if ((a < b)) then end").expect("valid");
    let Item::Instr(Instr { kind: InstrKind::If(c, _, _), .. }) = &program.items[0] else { panic!("expected if") };
    assert_eq!((c.span.start, c.span.end), (3, 12));
}

#[test]
fn comparisons_do_not_chain() {
    let error = session_error("if a < b < c then end");
    assert_error(&error, "expected `then` after the condition of `if`", 1, 10);
}

#[test]
fn a_parenthesised_name_alone_is_not_a_condition() {
    let error = session_error("if (a) then end");
    assert!(error.diagnostic.message.starts_with("expected a comparison"), "{}", error.diagnostic.message);
}

// ---- Items, instructions, objects -----------------------------------------

#[test]
fn camera_ambient_and_both_light_spellings() {
    assert_eq!(
        session(
            "camera distance 10 angle pi / 3 end ambient 0.2 light vector 0, 0, 1 intensity 0.5 end \
             light rotation 1, 2, 3 intensity 1 end"
        ),
        vec!["(camera 10 (/ pi 3))", "(ambient 0.2)", "(light [0 0 1] 0.5)", "(light [1 2 3] 1)",]
    );
}

#[test]
fn procedures_with_zero_one_and_many_parameters() {
    assert_eq!(
        session("proc a() end proc b(x) put x end proc c(x, y, z) a() b(1) c(x, y + 1, -z) end"),
        vec!["(proc a ())", "(proc b (x) (put x))", "(proc c (x y z) (call a) (call b 1) (call c x (+ y 1) (neg z)))"]
    );
}

#[test]
fn every_instruction() {
    assert_eq!(
        session("let x = 1 object o = s put o p() p(1, 2) if x < 1 then put o end if x = 1 then else let y = 2 end"),
        vec![
            "(let x 1)",
            "(object o s)",
            "(put o)",
            "(call p)",
            "(call p 1 2)",
            "(if (< x 1) (then (put o)))",
            "(if (= x 1) (then) (else (let y 2)))",
        ]
    );
}

#[test]
fn nested_ifs() {
    assert_eq!(
        session("if a < 1 then if b < 1 then put x else put y end else put z end"),
        vec!["(if (< a 1) (then (if (< b 1) (then (put x)) (else (put y)))) (else (put z)))"]
    );
}

#[test]
fn every_object() {
    let texture = "(texture 0.5 0.5 10 [255 0 0])";
    let text = format!(
        "put sphere center 1, 2, 3 radius 4 {TEXTURE} end \
         put plane rotation 0, 0, 0 shift -1 {TEXTURE} end \
         put box center 0, 0, 0 length 1, 2, 3 {TEXTURE} end \
         put translate s by 1, 0, 0 end \
         put rotate s by 0, pi, 0 end \
         put scale s by 2 end \
         put group end \
         put group a translate b by 1, 1, 1 end c end"
    );
    assert_eq!(
        session(&text),
        vec![
            format!("(put (sphere [1 2 3] 4 {texture}))"),
            format!("(put (plane [0 0 0] (neg 1) {texture}))"),
            format!("(put (box [0 0 0] [1 2 3] {texture}))"),
            "(put (translate s [1 0 0]))".to_string(),
            "(put (rotate s [0 pi 0]))".to_string(),
            "(put (scale s 2))".to_string(),
            "(put (group))".to_string(),
            "(put (group a (translate b [1 1 1]) c))".to_string(),
        ]
    );
}

#[test]
fn objects_nest_inside_transformations() {
    assert_eq!(
        session("object o = scale rotate translate group a b end by 1, 2, 3 end by 0, 0, 1 end by 0.5 end"),
        vec!["(object o (scale (rotate (translate (group a b) [1 2 3]) [0 0 1]) 0.5))"]
    );
}

#[test]
fn a_session_input_may_be_empty_or_only_comments() {
    assert!(session("").is_empty());
    assert!(session("  # nothing here\n\n").is_empty());
}

#[test]
fn a_session_input_takes_items_in_any_order() {
    assert_eq!(
        session("put s light vector 0, 0, 0 intensity 1 end camera distance 1 angle 1 end proc p() end ambient 1"),
        vec!["(put s)", "(light [0 0 0] 1)", "(camera 1 1)", "(proc p ())", "(ambient 1)"]
    );
}

#[test]
fn item_spans_and_ids() {
    let program = parse_items(SourceId(7), "proc p(a)\n  put a\nend").expect("valid");
    let Item::Proc(proc) = &program.items[0] else { panic!("expected a proc") };
    assert_eq!((proc.span.start, proc.span.end), (0, 21));
    assert_eq!(proc.span.source, SourceId(7));
    assert_eq!((proc.params[0].span.start, proc.params[0].span.end), (7, 8));
    assert_eq!((proc.body[0].span.start, proc.body[0].span.end), (12, 17));
}

// ---- Files -------------------------------------------------------------------

#[test]
fn a_file_in_the_order_of_spec_2() {
    let text = format!(
        "# a scene\n{HEADER}light vector 0, 0, 0 intensity 1 end\nlight rotation 1, 0, 0 intensity 0.5 end\n\
         proc ball(x) put sphere center x, 0, 0 radius 1 {TEXTURE} end end\n\
         proc nothing() end\nball(1)\nlet y = 2\n"
    );
    let program = parse_file(SourceId(0), &text).expect("valid file");
    assert_eq!(program.items.len(), 8);
}

#[test]
fn a_minimal_file_has_camera_and_ambient() {
    assert_eq!(parse_file(SourceId(0), HEADER).expect("valid").items.len(), 2);
}

#[test]
fn a_file_must_start_with_the_camera() {
    assert_error(&file_error("put s\n"), "a scenario file must start with `camera ... end`", 1, 1);
    assert_error(&file_error("\n  ambient 1\n"), "a scenario file must start with `camera ... end`", 2, 3);
    assert_error(&file_error("  sphere"), "a scenario file must start with `camera ... end`", 1, 3);
    // The file ends just after its last character.
    assert_error(&file_error("# only a comment\n"), "a scenario file must start with `camera ... end`", 1, 17);
    assert_error(&file_error(""), "a scenario file must start with `camera ... end`", 1, 1);
}

#[test]
fn ambient_comes_right_after_the_camera() {
    let text = "camera distance 1 angle 1 end\nlight vector 0, 0, 0 intensity 1 end\n";
    assert_error(&file_error(text), "`ambient` must come right after the camera", 2, 1);
    let text = "camera distance 1 angle 1 end\n";
    assert_error(&file_error(text), "unexpected end of file: `ambient` must come right after the camera", 1, 30);
}

#[test]
fn lights_come_before_procedures_and_instructions() {
    let text = format!("{HEADER}put s\nlight vector 0, 0, 0 intensity 1 end\n");
    let error = file_error(&text);
    assert_error(&error, "a `light` must come before procedures and instructions", 4, 1);
    assert_eq!(error.diagnostic.related.len(), 1, "points at the first instruction");
    let text = format!("{HEADER}proc p() end\nlight rotation 0, 0, 0 intensity 1 end\n");
    assert_error(&file_error(&text), "a `light` must come before procedures and instructions", 4, 1);
}

#[test]
fn procedures_come_before_instructions() {
    let text = format!("{HEADER}let x = 1\nproc p() end\n");
    assert_error(&file_error(&text), "a `proc` must come before the instructions", 4, 1);
}

#[test]
fn a_file_has_one_camera_and_one_ambient() {
    let text = format!("{HEADER}camera distance 1 angle 1 end\n");
    assert_error(&file_error(&text), "a file has only one `camera`", 3, 1);
    let text = format!("{HEADER}ambient 1\n");
    assert_error(&file_error(&text), "a file has only one `ambient`", 3, 1);
}

// ---- Syntax errors -----------------------------------------------------------

#[test]
fn missing_end_names_the_open_construct() {
    let text = format!("let a = 1\nput sphere center 0, 0, 0 radius 1 {TEXTURE}\nput s\n");
    let error = session_error(&text);
    assert_error(&error, "expected `end` to close this `sphere`", 3, 1);
    let (span, label) = &error.diagnostic.related[0];
    assert_eq!((span.start, span.end), (14, 20), "related points at `sphere`");
    assert_eq!(label, "this `sphere` is not closed");
}

#[test]
fn missing_end_of_a_group() {
    let error = session_error("put group a b\nlet x = 1");
    assert_error(
        &error,
        "expected an object (`sphere`, `plane`, `box`, a name...) or `end` to close this `group`",
        2,
        1,
    );
}

#[test]
fn missing_expression() {
    let text = format!("put sphere center 0, 0, 0 radius {TEXTURE} end");
    let error = session_error(&text);
    assert_error(&error, "expected an expression (a number, a name, `(`...) after `radius`", 1, 34);
    let error = session_error("let x = 1 +\nput s");
    assert_error(&error, "expected an expression (a number, a name, `(`...) after `+`", 2, 1);
}

#[test]
fn missing_comma_in_a_triple() {
    let text = format!("put sphere center 0, 0 0 radius 1 {TEXTURE} end");
    assert_error(&session_error(&text), "expected `,` between the parts of the centre", 1, 24);
    let text = "put sphere center 0, 0, 0 radius 1 kd 1 ks 1 phong 1 color 1 2, 3 end";
    assert_error(&session_error(text), "expected `,` between the parts of the colour", 1, 62);
    let text = "light vector 1, 2 3 intensity 1 end";
    assert_error(&session_error(text), "expected `,` between the parts of the rotation", 1, 19);
    let text = "put translate s by 1 2, 3 end";
    assert_error(&session_error(text), "expected `,` between the parts of the vector", 1, 22);
    let text = "put box center 0, 0, 0 length 1, 2 3 kd 1 ks 1 phong 1 color 1, 2, 3 end";
    assert_error(&session_error(text), "expected `,` between the parts of the lengths", 1, 36);
}

#[test]
fn missing_then() {
    let error = session_error("if a < 1\n  put s\nend");
    assert_error(&error, "expected `then` after the condition of `if`", 2, 3);
}

#[test]
fn texture_out_of_order() {
    let text = "put sphere center 0, 0, 0 radius 1 ks 1 kd 1 phong 1 color 1, 2, 3 end";
    let missing_kd = "missing `kd`: a texture is `kd ... ks ... phong ... color r, g, b`, in this order";
    assert_error(&session_error(text), missing_kd, 1, 36);
    let expected = "the texture must be `kd ... ks ... phong ... color r, g, b` in this order";
    let text = "put sphere center 0, 0, 0 radius 1 kd 1 ks 1 kd 1 phong 1 color 1, 2, 3 end";
    assert_error(&session_error(text), expected, 1, 46);
}

#[test]
fn missing_texture() {
    let error = session_error("put sphere center 0, 0, 0 radius 1 end");
    assert_error(&error, "expected the texture `kd ... ks ... phong ... color r, g, b` after `1`", 1, 36);
}

#[test]
fn unexpected_end() {
    assert_error(&session_error("put s\nend"), "unexpected `end`: nothing is open here", 2, 1);
    assert_error(&session_error("proc p() end end"), "unexpected `end`: nothing is open here", 1, 14);
}

#[test]
fn unexpected_end_of_file_names_the_open_construct() {
    let error = session_error("let x = 1\n\nproc p(a)\n  put a\n");
    assert_error(&error, "unexpected end of file: expected `end` to close this `proc p`", 4, 8);
    let error = file_error(&format!("{HEADER}if x < 1 then\n  put s"));
    assert_error(&error, "unexpected end of file: expected `end` to close this `if`", 4, 8);
}

#[test]
fn unexpected_end_of_file_in_an_expression() {
    let error = session_error("let x =");
    assert_error(&error, "unexpected end of file: expected an expression (a number, a name, `(`...) after `=`", 1, 8);
}

#[test]
fn misspelt_keywords_get_a_suggestion() {
    for (text, keyword) in [
        ("put spher center 0, 0, 0 radius 1 kd 1 ks 1 phong 1 color 1, 2, 3 end", "sphere"),
        ("cemera distance 10 angle 1 end", "camera"),
        ("put rotaet s by 1, 2, 3 end", "rotate"),
        ("put sphere center 0, 0, 0 radius 1 kd 1 ks 1 phong 1 collor 1, 2, 3 end", "color"),
        ("light vectr 0, 0, 0 intensity 1 end", "vector"),
        ("if a < 1 thn put s end", "then"),
    ] {
        let error = session_error(text);
        assert_eq!(error.diagnostic.help, Some(format!("did you mean `{keyword}`?")), "{text}");
    }
}

#[test]
fn a_misspelt_keyword_where_a_keyword_is_expected_is_the_error_spot() {
    let text = "put sphere center 0, 0, 0 radius 1 kd 1 ks 1 phong 1 collor 1, 2, 3 end";
    let error = session_error(text);
    assert_error(&error, "expected `color` after `1`", 1, 54);
}

#[test]
fn an_object_where_an_instruction_is_expected() {
    let error = session_error("sphere center 0, 0, 0 radius 1 kd 1 ks 1 phong 1 color 1, 2, 3 end");
    assert_error(&error, "expected an instruction, found the object `sphere`", 1, 1);
    assert!(error.diagnostic.help.is_some());
}

#[test]
fn unclosed_parenthesis() {
    let error = session_error("let x = (1 + 2\nput s");
    assert_error(&error, "expected `)` to close the parenthesis", 2, 1);
    assert_eq!(error.diagnostic.related[0].0.start, 8);
}

#[test]
fn lexing_errors_are_reported_at_the_character() {
    let error = session_error("let x = 1\nlet y = 2 $ 3");
    assert_error(&error, "unexpected character `$`", 2, 11);
    assert_eq!(error.diagnostic.span.end - error.diagnostic.span.start, 1);
}

#[test]
fn stray_else() {
    assert!(session_error("else").diagnostic.message.starts_with("unexpected `else`"));
    assert!(session_error("proc p() else end").diagnostic.message.starts_with("unexpected `else`"));
}

#[test]
fn missing_name_or_equals() {
    assert_error(&session_error("let = 3"), "expected a name after `let`", 1, 5);
    assert_error(&session_error("let x 3"), "expected `=` after `x`", 1, 7);
    assert_error(&session_error("object o sphere"), "expected `=` after `o`", 1, 10);
}

#[test]
fn error_messages_never_list_raw_token_names() {
    let texts = [
        "let x = )",
        "put )",
        "proc 3",
        "proc p(3)",
        "if then",
        "camera 3",
        "light 3",
        "p(1 2)",
        "let x = 1 2 3",
        "put scale s by",
        "put group 3",
        "if a < 1 then else else",
        "ambient",
        "(",
        ")",
        ",",
        "=",
    ];
    for text in texts {
        let message = match parse_items(SourceId(0), text) {
            Ok(_) => panic!("{text:?} should not parse"),
            Err(error) => error.message,
        };
        for raw in ["NAME", "NUMBER", "\"", "Token", "EOF"] {
            assert!(!message.contains(raw), "{text:?} gave {message:?}");
        }
    }
}

#[test]
fn hints_for_common_mistakes() {
    let help = |text: &str| session_error(text).diagnostic.help.unwrap_or_default();
    assert_eq!(help("if x == 1 then end"), "a comparison is written with a single `=`");
    assert_eq!(help("let x = 2(3)"), "to multiply, write `*`, like `2 * (x + 1)`");
    assert_eq!(help("ambient = 0.5"), "write the value right after `ambient`, without `=`");
    assert_eq!(help("let x = sqrt(2, 3)"), "`sqrt` takes a single number");
    assert_eq!(
        help("light vector (0, 0, 1) intensity 1 end"),
        "write the three parts without parentheses, like `0, 0, 1`"
    );
    assert_eq!(
        help("let pi = 3"),
        "`pi` is a reserved word of the language (the number pi, half a turn in radians); choose another name"
    );
    assert_eq!(
        help("proc p(a, end) end"),
        "`end` is a reserved word of the language (closes the construct opened last); choose another name"
    );
    assert_eq!(help("end"), "", "no hint where none applies");
    assert!(help("let x = 1;").contains("`;`"));
    assert!(help("let café = 1").contains("without accents"));
}

#[test]
fn print_is_an_instruction_wherever_one_may_be() {
    assert_eq!(
        session("print a, b + 1 proc p(x) print x if x < 1 then print 1 else print 2 end end"),
        ["(print a (+ b 1))", "(proc p (x) (print x) (if (< x 1) (then (print 1)) (else (print 2))))"]
    );
    // One instruction ends where the next begins, as after `ambient`.
    assert_eq!(session("print a p(1)"), ["(print a)", "(call p 1)"]);
}

// ---- Missing `end`s: which construct is blamed ------------------------------

/// The related places of an error, as (source text, label).
fn related(text: &str, located: &Located) -> Vec<(String, String)> {
    let slice = |span: &rayrepl::lang::Span| text[span.start as usize..span.end as usize].to_string();
    located.diagnostic.related.iter().map(|(span, label)| (slice(span), label.clone())).collect()
}

#[test]
fn a_missing_end_of_an_if_inside_a_proc_is_blamed_on_the_if() {
    let text = "proc p(n)\n  if n < 1 then\n    put s\nend\nproc q()\n  p(0)\nend\n";
    let error = session_error(text);
    assert_error(&error, "expected `end` to close this `if`", 5, 1);
    assert_eq!(error.diagnostic.label.as_deref(), Some("`proc p` is still open here"));
    assert_eq!(
        related(text, &error),
        [
            ("if".to_string(), "this `if` is not closed".to_string()),
            ("end".to_string(), "this `end`, lined up with `proc p`, closed the `if`".to_string()),
        ]
    );
    assert_eq!(error.diagnostic.notes, [Note::from("so the lines after that `end` were read as the body of `proc p`")]);
}

#[test]
fn the_body_of_an_unclosed_if_ends_at_the_first_line_lined_up_with_it() {
    let text = "proc p(n)\n  if n < 1 then\n    put s\n  put t\nend\np(1)\n";
    let error = session_error(text);
    assert_error(&error, "unexpected end of file: expected `end` to close this `if`", 6, 5);
    let related = related(text, &error);
    assert_eq!(related[2], ("put".to_string(), "the `if`'s body seems to end before this line".to_string()));
}

#[test]
fn an_end_lined_up_with_its_own_construct_blames_the_innermost_open_one() {
    // The `if` is closed where it should be: the `proc` lacks its `end`.
    let error = session_error("proc p(n)\n  if n < 1 then\n    put s\n  end\n");
    assert_error(&error, "unexpected end of file: expected `end` to close this `proc p`", 4, 6);
}

#[test]
fn a_missing_end_of_a_sphere_inside_a_group() {
    let text = format!(
        "object g = group\n  sphere center 0, 0, 0 radius 1 {TEXTURE}\n  sphere center 1, 0, 0 radius 1 {TEXTURE} end\nend\n"
    );
    let error = session_error(&text);
    assert_error(&error, "expected `end` to close this `sphere`", 3, 3);
    assert_eq!(related(&text, &error), [("sphere".to_string(), "this `sphere` is not closed".to_string())]);
}

#[test]
fn a_missing_end_of_a_proc_before_another_proc() {
    let text = format!("{HEADER}proc a()\n  put s\n\nproc b()\n  a()\nend\n");
    let error = file_error(&text);
    assert_eq!((error.line, error.column), (6, 1));
    assert!(error.diagnostic.message.ends_with("or `end` to close this `proc a`"), "{}", error.diagnostic.message);
    assert_eq!(related(&text, &error), [("proc".to_string(), "this `proc a` is not closed".to_string())]);
}

#[test]
fn else_if_needs_its_own_end() {
    let text = "if x < 1 then\n  put s\nelse if x < 2 then\n  put t\nend\n";
    let error = session_error(text);
    assert_error(&error, "unexpected end of file: expected `end` to close this `if`", 5, 4);
    assert!(error.diagnostic.help.is_some_and(|help| help.contains("each `if` needs its own `end`")));
}

#[test]
fn no_message_names_a_line() {
    let texts = [
        "proc p(n)\n  if n < 1 then\n    put s\nend\nproc q()\nend\n",
        "put sphere center 0, 0, 0 radius 1 kd 1 ks 1 phong 1 color 1, 2, 3\nput s",
        "let x = (1 +\n2",
        "camera distance 1 angle 1 end\nambient 1\ncamera distance 1 angle 1 end\n",
    ];
    for text in texts {
        let mut map = SourceMap::new();
        let id = map.add("scene.ray", text.to_string(), 0);
        let error = parse_file(id, text).expect_err("invalid");
        let mut words = vec![error.message.clone()];
        words.extend(error.label.clone());
        words.extend(error.related.iter().map(|(_, label)| label.clone()));
        words.extend(error.notes.iter().map(|note| note.display(&map, id)));
        for said in words {
            assert!(!said.contains("line "), "{text:?} gave {said:?}");
        }
    }
}

// ---- Hints for beginners ------------------------------------------------------

#[test]
fn hints_for_words_from_elsewhere() {
    let help = |text: &str| session_error(text).diagnostic.help.unwrap_or_default();
    assert_eq!(help("CAMERA distance 1 angle 1 end"), "keywords are written in lower case: `camera`");
    assert_eq!(help("Put Sphere center 0, 0, 0"), "keywords are written in lower case: `put`, `sphere`");
    assert_eq!(
        help("put sphere centre 0, 0, 0"),
        "`centre` is the French and British spelling: the keyword is `center`"
    );
    assert_eq!(help("put boîte center 0, 0, 0"), "`boîte` is French: the keyword is `box`");
    assert_eq!(help("si x < 1 alors put s fin"), "`si` is French: the keyword is `if`");
    assert_eq!(help("let x = exp(1)"), "there is no function `exp`; the functions are `sin`, `cos` and `sqrt`");
    let error = session_error("let y = 2 * tan(x)");
    assert_error(&error, "unknown function `tan`", 1, 13);
}

#[test]
fn hints_for_typing_habits() {
    let help = |text: &str| session_error(text).diagnostic.help.unwrap_or_default();
    assert_eq!(help("let x = 0,25"), "decimal numbers are written with a point: `0.25`");
    assert_eq!(help("put sphere center 1,5, 2,5, 0 radius 1"), "decimal numbers are written with a point: `2.5`");
    assert_eq!(help("let x = 1 \u{2013} 2"), "this is a Unicode dash; type `-`");
    assert_eq!(help("/* a ball */"), "comments start with `#` and run to the end of the line");
    assert_eq!(
        help("put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color #0f8\nput s"),
        "`#` starts a comment; colours are three numbers from 0 to 255: `color 0, 255, 136`"
    );
    let error = session_error("let x\u{200b} = 1");
    assert_error(&error, "invisible character U+200B", 1, 6);
}

#[test]
fn a_missing_texture_part_is_reported_missing() {
    let text = "put sphere center 0, 0, 0 radius 1 kd 1 phong 1 color 1, 2, 3 end";
    assert_error(
        &session_error(text),
        "missing `ks`: a texture is `kd ... ks ... phong ... color r, g, b`, in this order",
        1,
        41,
    );
    let text = "put sphere center 0, 0, 0 radius 1 kd 1 ks 1 phong 1 end";
    assert_error(
        &session_error(text),
        "missing `color`: a texture is `kd ... ks ... phong ... color r, g, b`, in this order",
        1,
        54,
    );
}

#[test]
fn a_byte_order_mark_at_the_start_is_accepted() {
    assert!(parse_file(SourceId(0), &format!("\u{feff}{HEADER}put s\n")).is_ok());
    let error = session_error("let x = 1\n\u{feff}");
    assert_eq!(error.diagnostic.message, "invisible character U+FEFF");
}
