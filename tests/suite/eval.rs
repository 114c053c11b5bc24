//! Evaluation of whole programs (SPEC 3 and 4): scoping, errors with their
//! line and column, the geometry baked into primitives, `time` dependence,
//! atomic runs and the resource limits.

use std::f64::consts::PI;

use glam::{DMat3, DVec3};
use rayrepl::lang::{Diagnostic, Interpreter, Limits, Severity, SourceMap, parse_file, parse_items};
use rayrepl::scene::{Primitive, Scene, Shape};

use crate::common::limited::run_limited;

/// A texture that raises no warning.
const TEX: &str = "kd 0.5 ks 0.5 phong 10 color 255, 0, 51";

/// Session-style source (items in any order), with `$T` replaced by [`TEX`].
fn source(text: &str) -> String {
    text.replace("$T", TEX)
}

/// Parses `text` as session items and runs it at `time`.
fn run_at(text: &str, time: f64, limits: Limits) -> (Interpreter, Result<(), Diagnostic>, SourceMap) {
    let mut sources = SourceMap::new();
    let text = source(text);
    let id = sources.add("test.ray", text.clone(), 0);
    let program = parse_items(id, &text).unwrap_or_else(|d| panic!("syntax error: {}\n{text}", d.message));
    let mut interpreter = Interpreter::new(time, limits);
    let result = interpreter.run(&program);
    (interpreter, result, sources)
}

/// The scene of a program that must succeed.
fn scene(text: &str) -> Scene {
    let (interpreter, result, _) = run_at(text, 0.0, Limits::default());
    if let Err(d) = result {
        panic!("unexpected error: {}", d.message);
    }
    interpreter.into_scene()
}

/// The error of a program that must fail, with its 1-based line and column.
fn error(text: &str) -> (Diagnostic, usize, usize) {
    error_with(text, Limits::default())
}

fn error_with(text: &str, limits: Limits) -> (Diagnostic, usize, usize) {
    let (_, result, sources) = run_at(text, 0.0, limits);
    let d = result.expect_err("the program should fail");
    let (line, col) = sources.get(d.span.source).line_col(d.span.start as usize);
    (d, line, col)
}

/// The notes of the error of a program that must fail, as a person reads them.
fn notes(text: &str, limits: Limits) -> Vec<String> {
    let (_, result, sources) = run_at(text, 0.0, limits);
    let d = result.expect_err("the program should fail");
    d.notes.iter().map(|note| note.display(&sources, d.span.source)).collect()
}

/// Where a diagnostic points, as (line, column, spanned text).
fn spot(sources: &SourceMap, d: &Diagnostic) -> (usize, usize, String) {
    let file = sources.get(d.span.source);
    let (line, col) = file.line_col(d.span.start as usize);
    (line, col, file.text[d.span.start as usize..d.span.end as usize].to_string())
}

fn sphere_centers(primitives: &[Primitive]) -> Vec<DVec3> {
    primitives
        .iter()
        .map(|p| match p.shape {
            Shape::Sphere { center, .. } => center,
            other => panic!("expected a sphere, got {other:?}"),
        })
        .collect()
}

/// The x coordinate of each sphere put, in order.
fn xs(text: &str) -> Vec<f64> {
    sphere_centers(&scene(text).primitives).iter().map(|c| c.x).collect()
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element() < 1e-12
}

fn close_mat(a: DMat3, b: DMat3) -> bool {
    close(a.x_axis, b.x_axis) && close(a.y_axis, b.y_axis) && close(a.z_axis, b.z_axis)
}

// ---------------------------------------------------------------- scoping

#[test]
fn a_procedure_sees_the_globals_as_they_are_at_the_call() {
    let text = "
        let a = 1
        proc p() put sphere center a, 0, 0 radius 1 $T end end
        p()
        let a = 2
        p()";
    assert_eq!(xs(text), [1.0, 2.0]);
}

#[test]
fn a_procedure_sees_objects_bound_after_its_definition() {
    let text = "
        proc p() put o end
        object o = sphere center 7, 0, 0 radius 1 $T end
        p()";
    assert_eq!(xs(text), [7.0]);
}

#[test]
fn a_callee_does_not_see_its_callers_locals() {
    let text = "
        proc q() put sphere center x, 0, 0 radius 1 $T end end
        proc p() let x = 1 q() end
        p()";
    let (d, line, col) = error(text);
    assert_eq!(d.message, "unknown variable `x`");
    assert_eq!((line, col), (2, 36));
}

#[test]
fn a_callee_does_not_see_its_callers_parameters() {
    let text = "
        proc q() let y = n end
        proc p(n) q() end
        p(1)";
    let (d, line, _) = error(text);
    assert_eq!(d.message, "unknown variable `n`");
    assert_eq!(line, 2);
}

#[test]
fn a_local_shadows_a_global_only_inside_the_call() {
    let text = "
        let x = 1
        proc p() let x = 5 put sphere center x, 0, 0 radius 1 $T end end
        p()
        put sphere center x, 0, 0 radius 1 $T end";
    assert_eq!(xs(text), [5.0, 1.0]);
}

#[test]
fn a_parameter_shadows_a_global() {
    let text = "
        let x = 1
        proc p(x) put sphere center x, 0, 0 radius 1 $T end end
        p(9)
        put sphere center x, 0, 0 radius 1 $T end";
    assert_eq!(xs(text), [9.0, 1.0]);
}

#[test]
fn a_procedure_cannot_change_a_global() {
    let text = "
        let x = 1
        object o = sphere center 1, 0, 0 radius 1 $T end
        proc p()
          let x = 2
          object o = sphere center 2, 0, 0 radius 1 $T end
          let fresh = 3
        end
        p()
        put sphere center x, 0, 0 radius 1 $T end
        put o";
    assert_eq!(xs(text), [1.0, 1.0]);
    let (d, _, _) = error("proc p() let fresh = 3 end p() let y = fresh");
    assert_eq!(d.message, "unknown variable `fresh`");
}

#[test]
fn a_local_can_be_rebound_within_its_call() {
    let text = "
        proc p() let x = 1 let x = x + 1 put sphere center x, 0, 0 radius 1 $T end end
        p()";
    assert_eq!(xs(text), [2.0]);
}

#[test]
fn locals_do_not_survive_between_calls() {
    let text = "
        proc p(first) if first = 1 then let x = 4 end put sphere center x, 0, 0 radius 1 $T end end
        p(1)
        p(0)";
    let (d, line, _) = error(text);
    assert_eq!(d.message, "unknown variable `x`");
    assert_eq!(line, 2);
}

#[test]
fn if_has_no_scope() {
    let text = "
        if 1 = 1 then let x = 3 else let x = 4 end
        put sphere center x, 0, 0 radius 1 $T end
        proc p() if 0 < 1 then let y = 6 end put sphere center y, 0, 0 radius 1 $T end end
        p()";
    assert_eq!(xs(text), [3.0, 6.0]);
}

#[test]
fn top_level_lets_inside_an_if_are_globals() {
    let text = "
        if 1 = 1 then let g = 8 end
        proc p() put sphere center g, 0, 0 radius 1 $T end end
        p()";
    assert_eq!(xs(text), [8.0]);
}

#[test]
fn procedures_may_call_procedures_defined_later_and_redefinition_replaces() {
    let text = "
        proc a() b() end
        proc b() put sphere center 1, 0, 0 radius 1 $T end end
        a()
        proc b() put sphere center 2, 0, 0 radius 1 $T end end
        a()";
    assert_eq!(xs(text), [1.0, 2.0]);
}

#[test]
fn recursion_works() {
    let text = "
        proc row(n) if 0 < n then put sphere center n, 0, 0 radius 0.5 $T end row(n - 1) end end
        row(4)";
    assert_eq!(xs(text), [4.0, 3.0, 2.0, 1.0]);
}

#[test]
fn arguments_are_evaluated_in_the_callers_frame() {
    let text = "
        let b = 100
        proc p(a, b) put sphere center a, b, 0 radius 1 $T end end
        proc q(a) p(a + 1, a) end
        q(5)";
    let s = scene(text);
    assert_eq!(sphere_centers(&s.primitives), [DVec3::new(6.0, 5.0, 0.0)]);
}

// ---------------------------------------------------------------- numbers and conditions

#[test]
fn arithmetic_functions_and_constants() {
    let text = "
        let a = 2 + 3 * 4 - 10 / 4
        let b = -2 * 3
        let c = sqrt(16) + cos(0) + sin(0)
        let d = pi
        put sphere center a, b, c radius d $T end";
    let s = scene(text);
    let Shape::Sphere { center, radius } = s.primitives[0].shape else { panic!() };
    assert_eq!(center, DVec3::new(11.5, -6.0, 5.0));
    assert_eq!(radius, PI);
}

#[test]
fn comparisons_and_connectives() {
    let cases = [
        ("0.1 + 0.2 = 0.3", false),
        ("0.5 + 0.25 = 0.75", true),
        ("1 < 2", true),
        ("2 < 2", false),
        ("2 <= 2", true),
        ("3 > 2", true),
        ("2 >= 3", false),
        ("1 != 1", false),
        ("1 = 1 & 2 < 1", false),
        ("1 = 1 | 2 < 1", true),
        ("!(1 = 1)", false),
        ("!(1 = 2) & (2 < 1 | 3 = 3)", true),
    ];
    for (cond, expected) in cases {
        let text = format!("if {cond} then let r = 1 else let r = 0 end put sphere center r, 0, 0 radius 1 $T end");
        assert_eq!(xs(&text), [if expected { 1.0 } else { 0.0 }], "{cond}");
    }
}

#[test]
fn and_and_or_stop_early() {
    // The right side would divide by zero.
    assert_eq!(
        xs("if 1 = 2 & 1 / 0 = 1 then let r = 1 else let r = 0 end put sphere center r, 0, 0 radius 1 $T end"),
        [0.0]
    );
    assert_eq!(
        xs("if 1 = 1 | 1 / 0 = 1 then let r = 1 else let r = 0 end put sphere center r, 0, 0 radius 1 $T end"),
        [1.0]
    );
}

#[test]
fn time_is_predefined_and_can_be_rebound() {
    let (i, result, _) = run_at("put sphere center time, 0, 0 radius 1 $T end", 3.0, Limits::default());
    result.unwrap();
    assert_eq!(sphere_centers(&i.scene().timed_primitives)[0].x, 3.0);
    assert_eq!(xs("let time = 5 put sphere center time, 0, 0 radius 1 $T end"), [5.0]);
    assert_eq!(xs("put sphere center time, 0, 0 radius 1 $T end").len(), 0, "time-dependent: not static");
}

// ---------------------------------------------------------------- camera, ambient, lights

#[test]
fn camera_and_ambient_replace_lights_add() {
    let text = "
        camera distance 10 angle 1 end
        ambient 0.2
        light vector 0, 0, 0 intensity 0.5 end
        light rotation pi / 2, 0, 0 intensity 0.25 end
        camera distance 20 angle 0.5 end
        ambient 0.4
        light vector 0, 0, -pi / 2 intensity 1 end";
    let (i, result, _) = run_at(text, 0.0, Limits::default());
    result.unwrap();
    assert!(i.has_camera() && i.has_ambient());
    let s = i.scene();
    assert_eq!((s.camera.distance, s.camera.angle), (20.0, 0.5));
    assert_eq!(s.ambient, 0.4);
    assert_eq!(s.lights.len(), 3);
    assert!(close(s.lights[0].direction, DVec3::Y));
    assert!(close(s.lights[1].direction, DVec3::Z));
    assert!(close(s.lights[2].direction, DVec3::X));
    assert_eq!(s.lights[1].intensity, 0.25);
    assert_eq!(s.counts().lights, 3);
}

#[test]
fn no_camera_means_defaults_and_a_flag() {
    let (i, result, _) = run_at("let x = 1", 0.0, Limits::default());
    result.unwrap();
    assert!(!i.has_camera() && !i.has_ambient());
    assert_eq!(i.scene().camera, rayrepl::lang::eval::DEFAULT_CAMERA);
}

#[test]
fn a_whole_file_in_spec_order_evaluates() {
    let text = source(
        "# a file
camera distance 12 angle pi / 3 end
ambient 0.3
light vector 0.5, 0, 0 intensity 0.8 end
proc pair(x) put sphere center x, 0, 0 radius 1 $T end put sphere center -x, 0, 0 radius 1 $T end end
pair(2)
put plane rotation 0, 0, 0 shift -1 $T end
put box center 0, 2, 0 length 1, 1, 1 $T end
",
    );
    let mut sources = SourceMap::new();
    let id = sources.add("file.ray", text.clone(), 0);
    let program = parse_file(id, &text).unwrap_or_else(|d| panic!("{}", d.message));
    let mut i = Interpreter::new(0.0, Limits::default());
    i.run(&program).unwrap();
    let counts = i.scene().counts();
    assert_eq!((counts.spheres, counts.planes, counts.boxes, counts.lights), (2, 1, 1, 1));
    assert!(!i.has_time_reads());
    assert!(!i.scene().depends_on_time());
}

// ---------------------------------------------------------------- errors, with line and column

#[test]
fn unknown_variable_suggests_a_visible_name() {
    let (d, line, col) = error("let radius2 = 1\nproc p(width) let a = widht end\np(1)");
    assert_eq!(d.message, "unknown variable `widht`");
    assert_eq!((line, col), (2, 23));
    assert_eq!(d.help.as_deref(), Some("did you mean `width`?"));
    let (d, _, _) = error("let angle1 = 1\nlet b = angle2");
    assert_eq!(d.help.as_deref(), Some("did you mean `angle1`?"));
}

#[test]
fn unknown_procedure_suggests_a_defined_one() {
    let (d, line, col) = error("proc orbit(x, y, r) end\n\n  orbt(1, 2, 3)");
    assert_eq!(d.message, "unknown procedure `orbt`");
    assert_eq!((line, col), (3, 3));
    assert_eq!(d.help.as_deref(), Some("did you mean `orbit`?"));
}

#[test]
fn wrong_arity_names_the_parameters() {
    let (d, line, col) = error("proc orbit(x, y, r) end\norbit(1, 2)");
    assert_eq!(d.message, "`orbit` takes 3 arguments (x, y, r) but was given 2");
    assert_eq!((line, col), (2, 1));
    assert_eq!(d.related.len(), 1, "points at the definition too");
}

#[test]
fn wrong_kinds_name_both_kinds() {
    let (d, line, col) = error("let x = 1\nput x");
    assert_eq!(d.message, "`x` is a number, but an object is needed here");
    assert_eq!((line, col), (2, 5));
    let (d, line, col) = error("object o = sphere center 0, 0, 0 radius 1 $T end\nlet y = 2 * o");
    assert_eq!(d.message, "`o` is an object, but a number is needed here");
    assert_eq!((line, col), (2, 13));
}

#[test]
fn errors_inside_procedures_point_into_the_body_and_name_the_call() {
    let (d, line, col) = error("proc p(a)\n  let b = 1 / a\nend\np(2)\np(0)");
    assert_eq!(d.message, "division by zero");
    assert_eq!((line, col), (2, 11));
    assert_eq!(d.related.len(), 1);
    assert_eq!(d.related[0].1, "in this call of `p`");
}

#[test]
fn non_finite_numbers_are_errors_at_the_operation() {
    let (_, result, sources) = run_at("let a = 2\nlet b = (a + 1) / (a - 2)", 0.0, Limits::default());
    let d = result.unwrap_err();
    assert_eq!(d.message, "division by zero");
    assert_eq!(spot(&sources, &d), (2, 9, "(a + 1) / (a - 2)".to_string()));

    let (_, result, sources) = run_at("let a = 1 - sqrt(2 - 6)", 0.0, Limits::default());
    let d = result.unwrap_err();
    assert_eq!(d.message, "square root of a negative number (-4)");
    assert_eq!(spot(&sources, &d), (1, 13, "sqrt(2 - 6)".to_string()));

    let big = "1".repeat(200);
    let (d, line, col) = error(&format!("let a = {big}\nlet b = a * a"));
    assert!(d.message.contains("overflows"), "{}", d.message);
    assert_eq!((line, col), (2, 9));
}

#[test]
fn sizes_must_be_positive() {
    let (d, line, col) = error("put sphere center 0, 0, 0 radius 0 $T end");
    assert_eq!(d.message, "a sphere's radius must be positive, but it is 0");
    assert_eq!((line, col), (1, 34));
    let (d, line, col) = error("put box center 0, 0, 0 length 1, -2, 1 $T end");
    assert_eq!(d.message, "a box's length must be positive, but it is -2");
    assert_eq!((line, col), (1, 34));
    let (d, line, col) = error("\nput sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 0 color 1, 1, 1 end");
    assert_eq!(d.message, "`phong` must be positive, but it is 0");
    assert_eq!((line, col), (2, 52));
    let (d, line, col) = error("object o = sphere center 0, 0, 0 radius 1 $T end\nput scale o by 1 - 1 end");
    assert_eq!(d.message, "cannot scale by 0");
    assert_eq!((line, col), (2, 16));
}

#[test]
fn transformations_that_overflow_are_errors() {
    let big = "9".repeat(308);
    let (d, line, _) = error(&format!(
        "put translate translate sphere center 0, 0, 0 radius 1 $T end by {big}, 0, 0 end by {big}, 0, 0 end"
    ));
    assert_eq!(d.message, "this transformation moves the object out of range");
    assert_eq!(line, 1);
}

#[test]
fn errors_in_any_construct_name_the_spot() {
    // Each program fails at `bad`, a name never defined.
    let programs = [
        "camera distance bad angle 1 end",
        "ambient bad",
        "light vector 0, bad, 0 intensity 1 end",
        "put plane rotation 0, 0, 0 shift bad $T end",
        "put rotate sphere center 0, 0, 0 radius 1 $T end by 0, 0, bad end",
        "put group sphere center 0, 0, 0 radius 1 $T end bad end",
        "if bad < 1 then end",
        "put sphere center 0, 0, 0 radius 1 kd 1 ks 0 phong 1 color 1, 1, bad end",
    ];
    for program in programs {
        let (_, result, sources) = run_at(program, 0.0, Limits::default());
        let d = result.expect_err(program);
        assert_eq!(d.message, "unknown variable `bad`", "{program}");
        assert_eq!(spot(&sources, &d).2, "bad", "{program}");
    }
}

// ---------------------------------------------------------------- warnings

#[test]
fn out_of_range_colours_and_coefficients_are_clamped_with_a_warning() {
    let text = "put sphere center 0, 0, 0 radius 1 kd 1.5 ks -0.5 phong 3 color 300, -5, 51 end";
    let (mut i, result, sources) = run_at(text, 0.0, Limits::default());
    result.unwrap();
    let m = i.scene().primitives[0].material;
    assert_eq!((m.kd, m.ks, m.phong), (1.0, 0.0, 3.0));
    assert_eq!(m.color, DVec3::new(1.0, 0.0, 0.2));
    let warnings = i.take_warnings();
    assert_eq!(warnings.len(), 4);
    assert!(warnings.iter().all(|w| w.severity == Severity::Warning));
    let spots: Vec<String> = warnings.iter().map(|w| spot(&sources, w).2).collect();
    assert_eq!(spots, ["1.5", "-0.5", "300", "-5"]);
    assert_eq!(warnings[0].message, "`kd` should be between 0 and 1, but it is 1.5; 1 is used");
    assert_eq!(warnings[2].message, "a colour component should be between 0 and 255, but it is 300; 255 is used");
    assert!(i.take_warnings().is_empty(), "taken");
}

#[test]
fn a_spot_warns_once_however_often_it_runs() {
    let text = "
        proc p(n) if 0 < n then put sphere center n, 0, 0 radius 1 kd 2 ks 0 phong 1 color n, 0, 0 end p(n - 1) end end
        p(1000)";
    let (mut i, result, _) = run_at(text, 0.0, Limits::default());
    result.unwrap();
    assert_eq!(i.scene().primitives.len(), 1000);
    let warnings = i.take_warnings();
    assert_eq!(warnings.len(), 2, "kd once, the colour once (from n = 256 on)");
}

// ---------------------------------------------------------------- geometry (SPEC 4)

#[test]
fn primitives_are_built_as_spec_4_says() {
    let s = scene(
        "put sphere center 1, 2, 3 radius 4 $T end
         put plane rotation pi / 2, 0, 0 shift -1 $T end
         put box center 1, 2, 3 length 2, 4, 6 $T end",
    );
    assert_eq!(s.primitives[0].shape, Shape::Sphere { center: DVec3::new(1.0, 2.0, 3.0), radius: 4.0 });
    let Shape::Plane { normal, shift } = s.primitives[1].shape else { panic!() };
    assert!(close(normal, DVec3::Z));
    assert_eq!(shift, -1.0);
    assert_eq!(
        s.primitives[2].shape,
        Shape::Box { center: DVec3::new(1.0, 2.0, 3.0), half: DVec3::new(1.0, 2.0, 3.0), axes: DMat3::IDENTITY }
    );
    let m = s.primitives[0].material;
    assert_eq!((m.kd, m.ks, m.phong, m.color), (0.5, 0.5, 10.0, DVec3::new(1.0, 0.0, 0.2)));
}

#[test]
fn transformations_are_baked_in_order() {
    let s = scene(
        "object g = group
           sphere center 1, 0, 0 radius 1 $T end
           plane rotation 0, 0, 0 shift 2 $T end
           box center 0, 1, 0 length 2, 2, 4 $T end
         end
         put translate g by 1, 2, 3 end
         put rotate g by 0, 0, pi / 2 end
         put scale g by 3 end
         put scale g by -2 end
         put translate rotate scale g by 2 end by pi / 2, 0, 0 end by 0, 0, 1 end",
    );
    let p: Vec<Shape> = s.primitives.iter().map(|p| p.shape).collect();
    assert_eq!(p.len(), 15);
    // translate by (1, 2, 3)
    assert_eq!(p[0], Shape::Sphere { center: DVec3::new(2.0, 2.0, 3.0), radius: 1.0 });
    assert_eq!(p[1], Shape::Plane { normal: DVec3::Y, shift: 4.0 });
    assert_eq!(
        p[2],
        Shape::Box { center: DVec3::new(1.0, 3.0, 3.0), half: DVec3::new(1.0, 1.0, 2.0), axes: DMat3::IDENTITY }
    );
    // rotate by 90° about z: x -> y, y -> -x
    let Shape::Sphere { center, .. } = p[3] else { panic!() };
    assert!(close(center, DVec3::Y));
    let Shape::Plane { normal, shift } = p[4] else { panic!() };
    assert!(close(normal, -DVec3::X) && shift == 2.0);
    let Shape::Box { center, half, axes } = p[5] else { panic!() };
    assert!(close(center, -DVec3::X));
    assert_eq!(half, DVec3::new(1.0, 1.0, 2.0));
    assert!(close_mat(axes, DMat3::from_cols(DVec3::Y, -DVec3::X, DVec3::Z)));
    // scale by 3
    assert_eq!(p[6], Shape::Sphere { center: DVec3::new(3.0, 0.0, 0.0), radius: 3.0 });
    assert_eq!(p[7], Shape::Plane { normal: DVec3::Y, shift: 6.0 });
    assert_eq!(
        p[8],
        Shape::Box { center: DVec3::new(0.0, 3.0, 0.0), half: DVec3::new(3.0, 3.0, 6.0), axes: DMat3::IDENTITY }
    );
    // scale by -2: a point reflection; the plane y = 2 (solid below) becomes -y = 4 (solid above y = -4)
    assert_eq!(p[9], Shape::Sphere { center: DVec3::new(-2.0, 0.0, 0.0), radius: 2.0 });
    assert_eq!(p[10], Shape::Plane { normal: -DVec3::Y, shift: 4.0 });
    assert_eq!(
        p[11],
        Shape::Box { center: DVec3::new(0.0, -2.0, 0.0), half: DVec3::new(2.0, 2.0, 4.0), axes: DMat3::IDENTITY }
    );
    // scale by 2, then rotate 90° about x (y -> z, z -> -y), then translate by (0, 0, 1)
    let Shape::Sphere { center, radius } = p[12] else { panic!() };
    assert!(close(center, DVec3::new(2.0, 0.0, 1.0)) && radius == 2.0);
    let Shape::Plane { normal, shift } = p[13] else { panic!() };
    assert!(close(normal, DVec3::Z));
    assert!((shift - 5.0).abs() < 1e-12, "4 after scaling, + (0,0,1)·z");
    let Shape::Box { center, half, axes } = p[14] else { panic!() };
    assert!(close(center, DVec3::new(0.0, 0.0, 3.0)));
    assert_eq!(half, DVec3::new(2.0, 2.0, 4.0));
    assert!(close_mat(axes, DMat3::from_cols(DVec3::X, DVec3::Z, -DVec3::Y)));
}

#[test]
fn objects_are_values_transformations_make_new_ones() {
    let s = scene(
        "object a = sphere center 1, 0, 0 radius 1 $T end
         object b = translate a by 1, 0, 0 end
         put a put b put group a b b end",
    );
    let x: Vec<f64> = sphere_centers(&s.primitives).iter().map(|c| c.x).collect();
    assert_eq!(x, [1.0, 2.0, 1.0, 2.0, 2.0]);
}

// ---------------------------------------------------------------- time dependence

#[test]
fn only_what_depends_on_time_is_timed() {
    let text = "
        put sphere center 0, 0, 0 radius 1 $T end
        put sphere center time, 0, 0 radius 1 $T end
        put plane rotation 0, 0, 0 shift -1 $T end
        object moving = translate sphere center 0, 0, 0 radius 1 $T end by 0, time, 0 end
        object still = box center 0, 0, 0 length 1, 1, 1 $T end
        put group still end";
    let (i, result, _) = run_at(text, 2.0, Limits::default());
    result.unwrap();
    let s = i.scene();
    assert_eq!(s.primitives.len(), 3);
    assert_eq!(s.timed_primitives.len(), 1);
    assert_eq!(sphere_centers(&s.timed_primitives), [DVec3::new(2.0, 0.0, 0.0)]);
    assert!(i.has_time_reads());
    assert!(s.depends_on_time());
}

#[test]
fn a_group_with_one_timed_member_is_timed() {
    let text = "
        object moving = sphere center 0, time, 0 radius 1 $T end
        put group box center 0, 0, 0 length 1, 1, 1 $T end moving end";
    let s = scene(text);
    assert_eq!((s.primitives.len(), s.timed_primitives.len()), (0, 2));
}

#[test]
fn puts_under_a_time_condition_are_timed() {
    let text = "
        object s = sphere center 0, 0, 0 radius 1 $T end
        if time < 5 then put s end
        if 1 < 5 then put s end";
    let s = scene(text);
    assert_eq!((s.primitives.len(), s.timed_primitives.len()), (1, 1));
}

#[test]
fn values_bound_under_a_time_condition_are_timed() {
    let text = "
        if time < 5 then let x = 1 object o = sphere center 0, 0, 0 radius 1 $T end end
        put sphere center x, 0, 0 radius 1 $T end
        put o";
    let s = scene(text);
    assert_eq!((s.primitives.len(), s.timed_primitives.len()), (0, 2));
}

#[test]
fn variables_a_time_condition_may_rebind_are_timed_even_when_it_does_not() {
    // At time 1 the branch is not taken, yet `x` must count as depending on
    // `time`: at time 6 it is 1, so the sphere cannot be built once for all frames.
    let text = "
        let x = 0
        object o = sphere center 0, 0, 0 radius 1 $T end
        let other = 0
        if time > 5 then if 1 = 1 then let x = 1 end else object o = sphere center 1, 0, 0 radius 1 $T end end
        put sphere center x, 0, 0 radius 1 $T end
        put o
        put sphere center other, 0, 0 radius 1 $T end
        proc p() let y = 0 if time > 5 then let y = 1 end put sphere center y, 0, 0 radius 1 $T end end
        p()";
    let (i, result, _) = run_at(text, 1.0, Limits::default());
    result.unwrap();
    assert_eq!((i.scene().primitives.len(), i.scene().timed_primitives.len()), (1, 3));
    assert_eq!(sphere_centers(&i.scene().primitives), [DVec3::ZERO]);
}

#[test]
fn parameters_of_calls_under_a_time_condition_are_timed() {
    // `p` is untainted as a value, but the call happens only when time < 5,
    // and inside, `n` may be rebound under another time condition.
    let text = "
        proc g(n) if time > 5 then let n = 1 end put sphere center n, 0, 0 radius 1 $T end end
        if time < 5 then g(0) end";
    let (i, result, _) = run_at(text, 1.0, Limits::default());
    result.unwrap();
    assert_eq!((i.scene().primitives.len(), i.scene().timed_primitives.len()), (0, 1));
}

#[test]
fn nested_time_conditions_stay_linear() {
    let depth = 20_000;
    let text = format!(
        "let x = 0 {} let x = 1 {} put sphere center x, 0, 0 radius 1 {TEX} end",
        "if time < 5 then ".repeat(depth),
        "end ".repeat(depth)
    );
    let mut sources = SourceMap::new();
    let id = sources.add("nested.ray", text.clone(), 0);
    let program = parse_items(id, &text).unwrap();
    let mut i = Interpreter::new(1.0, Limits::default());
    i.run(&program).unwrap();
    assert_eq!(i.scene().timed_primitives.len(), 1);
}

#[test]
fn time_flows_through_procedure_arguments_and_recursion() {
    let text = "
        proc f(t) if 0 < t then put sphere center t, 0, 0 radius 1 $T end f(t - 1) end end
        proc g(n) put sphere center n, 0, 0 radius 1 $T end end
        f(time)
        g(1)
        let copy = time
        g(copy)";
    let (i, result, _) = run_at(text, 3.0, Limits::default());
    result.unwrap();
    let s = i.scene();
    assert_eq!(s.primitives.len(), 1);
    assert_eq!(s.timed_primitives.len(), 4);
}

#[test]
fn calls_under_a_time_condition_put_timed_primitives() {
    let text = "
        proc g() put sphere center 0, 0, 0 radius 1 $T end end
        if time = 0 then g() end";
    let s = scene(text);
    assert_eq!((s.primitives.len(), s.timed_primitives.len()), (0, 1));
}

#[test]
fn camera_ambient_and_lights_record_their_time_use() {
    let s = scene("camera distance 10 + time angle 1 end ambient 0.1 light vector 0, 0, 0 intensity 1 end");
    assert_eq!((s.time_use.camera, s.time_use.ambient, s.time_use.lights), (true, false, false));
    let s = scene("camera distance 10 angle 1 end ambient time / 10 light vector 0, time, 0 intensity 1 end");
    assert_eq!((s.time_use.camera, s.time_use.ambient, s.time_use.lights), (false, true, true));
    let s = scene("camera distance 10 + time angle 1 end camera distance 10 angle 1 end");
    assert!(!s.time_use.camera, "the later camera replaces the earlier");
}

#[test]
fn rebinding_time_to_a_constant_removes_the_dependence() {
    let s = scene("let time = 4 put sphere center time, 0, 0 radius 1 $T end");
    assert_eq!((s.primitives.len(), s.timed_primitives.len()), (1, 0));
}

#[test]
fn a_program_that_never_reads_time_says_so() {
    let (i, result, _) = run_at("proc p() let a = time end let b = 1", 0.0, Limits::default());
    result.unwrap();
    assert!(!i.has_time_reads());
    let (i, result, _) = run_at("let b = time", 0.0, Limits::default());
    result.unwrap();
    assert!(i.has_time_reads());
}

#[test]
fn later_frames_can_skip_static_primitives() {
    let text = source(
        "put sphere center 0, 0, 0 radius 1 $T end
         put sphere center time, 0, 0 radius 1 $T end
         if time < 10 then put box center 0, 0, 0 length 1, 1, 1 $T end end",
    );
    let mut sources = SourceMap::new();
    let id = sources.add("anim.ray", text.clone(), 0);
    let program = parse_items(id, &text).unwrap();
    let mut first = Interpreter::new(1.0, Limits::default());
    first.run(&program).unwrap();
    let mut later = Interpreter::new(2.0, Limits::default()).skip_static(true);
    later.run(&program).unwrap();
    assert_eq!((first.scene().primitives.len(), first.scene().timed_primitives.len()), (1, 2));
    assert_eq!((later.scene().primitives.len(), later.scene().timed_primitives.len()), (0, 2));
    assert_eq!(sphere_centers(&later.scene().timed_primitives[..1]), [DVec3::new(2.0, 0.0, 0.0)]);
}

// ---------------------------------------------------------------- atomicity (SPEC 7)

/// Everything observable about an interpreter.
fn observe(i: &Interpreter) -> String {
    let names: Vec<String> = i
        .global_names()
        .iter()
        .map(|n| format!("{n}={:?}/{:?}", i.global_number(n), i.global_object(n).map(<[_]>::len)))
        .collect();
    // The places in the program of every part of the scene (camera,
    // ambient, lights, puts, objects): source positions too must come back
    // as they were.
    let o = i.origins();
    let objects: Vec<_> = o.objects.iter().collect();
    let places = format!(
        "{:?} {:?} {:?} {:?} {:?} {objects:?} {}",
        o.camera, o.ambient, o.lights, o.primitives, o.timed_primitives, o.branched_on_time
    );
    format!(
        "{:?} {:?} {} {} {} {:?} {places}",
        i.scene(),
        names,
        i.procedure_names().iter().map(|name| name.as_str()).collect::<Vec<_>>().join(","),
        i.has_camera(),
        i.has_ambient(),
        i.has_time_reads()
    )
}

fn run_session_input(i: &mut Interpreter, sources: &mut SourceMap, text: &str) -> Result<(), Diagnostic> {
    let text = source(text);
    let id = sources.add("<input>", text.clone(), 0);
    let program = parse_items(id, &text).unwrap_or_else(|d| panic!("{}", d.message));
    i.run(&program)
}

#[test]
fn a_failed_input_changes_nothing() {
    let mut i = Interpreter::new(0.0, Limits::default());
    let mut sources = SourceMap::new();
    run_session_input(
        &mut i,
        &mut sources,
        "camera distance 5 angle 1 end ambient 0.5 light vector 0, 0, 0 intensity 1 end
         let g = 1 object o = sphere center 0, 0, 0 radius 1 $T end
         proc keep() put o end
         put sphere center 0, time, 0 radius 1 kd 2 ks 0 phong 1 color 0, 0, 0 end",
    )
    .unwrap();
    assert_eq!(i.take_warnings().len(), 1);
    let before = observe(&i);
    let failing = "
        camera distance 50 angle 1 + time end ambient 0.9
        light vector 1, 0, 0 intensity time end
        let g = 2 let new = 3 object o = box center 0, 0, 0 length 1, 1, 1 $T end
        proc keep() end
        proc extra() end
        proc half(n)
          put sphere center n, 0, 0 radius 1 kd 3 ks 0 phong 1 color 0, 0, 0 end
          if time < 1 then put o end
          let x = 1 / (n - 3)
        end
        half(1) half(2) half(3)";
    let d = run_session_input(&mut i, &mut sources, failing).unwrap_err();
    assert_eq!(d.message, "division by zero");
    assert_eq!(observe(&i), before);
    assert!(i.take_warnings().is_empty(), "warnings of the failed input are dropped");
    // The session goes on from the state before the failure.
    run_session_input(&mut i, &mut sources, "keep()").unwrap();
    assert_eq!(i.global_number("g"), Some(1.0));
    assert_eq!(i.global_number("new"), None);
    assert_eq!(i.scene().counts().spheres, 2);
}

#[test]
fn a_failed_input_gives_back_the_primitives_its_objects_held() {
    let mut i = Interpreter::new(0.0, Limits { max_primitives: 4, ..Limits::default() });
    let mut sources = SourceMap::new();
    run_session_input(&mut i, &mut sources, "object o = sphere center 0, 0, 0 radius 1 $T end").unwrap();
    let failing = "object o = group o o o end let x = 1 / 0";
    assert_eq!(run_session_input(&mut i, &mut sources, failing).unwrap_err().message, "division by zero");
    assert_eq!(i.global_object("o").map(<[_]>::len), Some(1));
    // 1 held by `o` and 2 in `p`: within the limit only if the failed `o` of 3 is forgotten.
    run_session_input(&mut i, &mut sources, "object p = group o o end").unwrap();
    let two_more = "object q = group o o end";
    assert!(run_session_input(&mut i, &mut sources, two_more).is_err(), "5 primitives are over the limit");
}

#[test]
fn a_spot_that_warned_in_a_failed_run_warns_again_when_it_succeeds() {
    let text = source("put sphere center 0, 0, 0 radius 1 kd 3 ks 0 phong 1 color 0, 0, 0 end let z = 1 / d");
    let mut sources = SourceMap::new();
    let id = sources.add("<input>", text.clone(), 0);
    let program = parse_items(id, &text).unwrap();
    let mut i = Interpreter::new(0.0, Limits::default());
    i.run(&parse_items(id, "let d = 0").unwrap()).unwrap();
    assert!(i.run(&program).is_err());
    assert!(i.take_warnings().is_empty());
    i.run(&parse_items(id, "let d = 1").unwrap()).unwrap();
    i.run(&program).unwrap();
    assert_eq!(i.take_warnings().len(), 1);
    i.run(&program).unwrap();
    assert!(i.take_warnings().is_empty(), "once per spot");
}

#[test]
fn a_failed_input_keeps_earlier_procedures_and_its_error_comes_from_the_state_before() {
    let mut i = Interpreter::new(0.0, Limits::default());
    let mut sources = SourceMap::new();
    run_session_input(&mut i, &mut sources, "proc p(n) put sphere center n, 0, 0 radius 1 $T end end").unwrap();
    assert!(run_session_input(&mut i, &mut sources, "proc p() end p(1, 2)").is_err());
    run_session_input(&mut i, &mut sources, "p(3)").unwrap();
    assert_eq!(sphere_centers(&i.scene().primitives), [DVec3::new(3.0, 0.0, 0.0)]);
}

#[test]
fn huge_misspelt_names_fail_without_a_suggestion() {
    let name = "a".repeat(100_000);
    let misspelt = format!("{}b{}", "a".repeat(50_000), "a".repeat(49_999));
    let (d, line, col) = error(&format!("let {name} = 1\nlet y = {misspelt}"));
    assert!(d.message.starts_with("unknown variable `aaa"), "{}", &d.message[..40]);
    assert_eq!((line, col, d.help), (2, 9, None));
}

// ---------------------------------------------------------------- limits

#[test]
fn ten_thousand_nested_calls_work() {
    let text =
        "proc down(n) if 0 < n then down(n - 1) else put sphere center n, 0, 0 radius 1 $T end end end down(10000)";
    assert_eq!(xs(text), [0.0]);
}

#[test]
fn a_hundred_thousand_nested_calls_work_on_a_small_stack() {
    std::thread::Builder::new()
        .stack_size(512 * 1024)
        .spawn(|| {
            let text = "proc down(n) if 0 < n then down(n - 1) else put sphere center n, 0, 0 radius 1 $T end end end
                        down(99999)";
            assert_eq!(xs(text), [0.0]);
        })
        .unwrap()
        .join()
        .unwrap();
}

#[test]
fn recursion_past_the_limit_is_an_error_with_the_call_chain() {
    let text = "proc f(n)
  let m = n + 1
  f(m)
end
f(0)";
    let (d, line, col) = error(text);
    assert_eq!(d.message, "recursion deeper than 100000 calls");
    assert_eq!((line, col), (3, 3));
    assert_eq!(
        notes(text, Limits::default()),
        ["call chain: f (line 5) -> f (line 3) -> ... `f (line 3)` repeated 99999 more times"]
    );
    assert!(d.help.is_some());
}

#[test]
fn the_call_limit_is_configurable_and_mutual_recursion_is_summarised() {
    let limits = Limits { max_call_depth: 50, ..Limits::default() };
    let text = "proc even() odd() end\nproc odd() even() end\neven()";
    let (d, line, _) = error_with(text, limits);
    assert_eq!(d.message, "recursion deeper than 50 calls");
    assert_eq!(line, 2);
    assert_eq!(
        notes(text, limits),
        [
            "call chain: even (line 3) -> odd (line 1) -> even (line 2) -> ... the cycle `odd (line 1) -> even (line 2)` repeated 24 more times"
        ]
    );
    // 50 calls are fine.
    let (_, result, _) = run_at("proc f(n) if 1 < n then f(n - 1) end end f(50)", 0.0, limits);
    result.unwrap();
}

#[test]
fn deeply_nested_expressions_evaluate() {
    let depth = 100_000;
    let text = format!("let x = {}1{}", "1 + (".repeat(depth), ")".repeat(depth));
    let mut sources = SourceMap::new();
    let id = sources.add("deep.ray", text.clone(), 0);
    let program = parse_items(id, &text).unwrap();
    let mut i = Interpreter::new(0.0, Limits::default());
    i.run(&program).unwrap();
    assert_eq!(i.global_number("x"), Some((depth + 1) as f64));
    // Nested groups and conditions too.
    let text = format!(
        "put {}sphere center 0, 0, 0 radius 1 {TEX} end{} if {}1 = 1{} then let y = 1 end",
        "group ".repeat(depth),
        " end".repeat(depth),
        "!(".repeat(depth),
        ")".repeat(depth)
    );
    let id = sources.add("deep2.ray", text.clone(), 0);
    let program = parse_items(id, &text).unwrap();
    let mut i = Interpreter::new(0.0, Limits::default());
    i.run(&program).unwrap();
    assert_eq!(i.scene().primitives.len(), 1);
    assert_eq!(i.global_number("y"), Some(1.0));
}

#[test]
fn deeply_nested_expressions_evaluate_on_a_small_stack() {
    let depth = 100_000;
    let text = format!("let x = {}1{}", "1 + (".repeat(depth), ")".repeat(depth));
    let x = std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(move || {
            let mut sources = SourceMap::new();
            let id = sources.add("deep.ray", text.clone(), 0);
            let program = parse_items(id, &text).unwrap();
            let mut i = Interpreter::new(0.0, Limits::default());
            i.run(&program).unwrap();
            // The AST is dropped here too, without recursion.
            drop(program);
            i.global_number("x")
        })
        .unwrap()
        .join()
        .unwrap();
    assert_eq!(x, Some((depth + 1) as f64));
}

#[test]
fn the_primitive_cap_stops_runaway_programs() {
    let limits = Limits { max_primitives: 1000, ..Limits::default() };
    let (d, line, col) = error_with(
        "proc p(n) if 0 < n then put sphere center n, 0, 0 radius 1 $T end p(n - 1) end end\np(2000)",
        limits,
    );
    assert_eq!(d.message, "this makes more than 1000 primitives, the most a scene may have");
    assert_eq!((line, col), (1, 29));
    let (_, result, _) = run_at(
        "proc p(n) if 0 < n then put sphere center n, 0, 0 radius 1 $T end p(n - 1) end end\np(1000)",
        0.0,
        limits,
    );
    result.unwrap();
}

#[test]
fn the_primitive_cap_stops_exponential_doubling() {
    let mut text = String::from("object a0 = sphere center 0, 0, 0 radius 1 $T end\n");
    for k in 1..=60 {
        text.push_str(&format!("object a{k} = group a{} a{} end\n", k - 1, k - 1));
    }
    text.push_str("put a60\n");
    let (d, line, col) = error_with(&text, Limits { max_primitives: 1 << 20, ..Limits::default() });
    assert!(d.message.starts_with("this makes more than 1048576 primitives"), "{}", d.message);
    // a0..a19 hold 2^20 - 1 primitives in all; a20's first copy of a19 crosses.
    assert_eq!((line, col), (21, 20));
}

/// A file for the binary: the header SPEC 2 requires, then `body`.
fn scene_file(body: &str) -> String {
    format!("camera distance 10 angle 1 end\nambient 0.2\n{}", source(body))
}

/// Runs the binary on `text` (from stdin) with a cap on its memory: it must
/// stop with status 1 and the primitive limit's diagnostic, pointing at
/// `line` and showing `shown` from its source line.
fn assert_stopped_by_the_default_cap(text: &str, line: usize, shown: &str) {
    let output = run_limited(&["--check", "-"], text);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    let limit = Limits::default().max_primitives;
    assert!(stderr.contains(&format!("error: this makes more than {limit} primitives")), "{stderr}");
    assert!(stderr.contains(&format!(":{line}:")), "{stderr}");
    assert!(stderr.contains(shown) && stderr.contains('^'), "{stderr}");
}

#[test]
fn the_default_cap_stops_doubling_before_memory_runs_out() {
    let body = "object o = sphere center 0, 0, 0 radius 1 $T end\n".to_string()
        + &"object o = group o o end\n".repeat(60)
        + "put o\n";
    // `o` and its first 22 doublings make 2^23 - 1 primitives; the 23rd
    // (line 26) would bring them to 2^24 - 1, past 10 million.
    assert_stopped_by_the_default_cap(&scene_file(&body), 26, "object o = group o o end");
}

#[test]
fn the_default_cap_stops_two_to_the_forty_spheres() {
    let body = "proc p(n)\n  if n < 1 then put sphere center 0, 0, 0 radius 1 $T end\n  \
                else p(n - 1) p(n - 1) end\nend\np(40)\n";
    assert_stopped_by_the_default_cap(&scene_file(body), 4, "put sphere");
}

#[test]
fn the_cap_counts_what_a_session_already_holds() {
    let limits = Limits { max_primitives: 10, ..Limits::default() };
    let mut i = Interpreter::new(0.0, limits);
    let mut sources = SourceMap::new();
    let put5 = "put group $S $S $S $S $S end".replace("$S", "sphere center 0, 0, 0 radius 1 $T end");
    run_session_input(&mut i, &mut sources, &put5).unwrap();
    run_session_input(&mut i, &mut sources, &put5).unwrap();
    let d = run_session_input(&mut i, &mut sources, &put5).unwrap_err();
    assert!(d.message.contains("more than 10 primitives"));
    assert_eq!(i.scene().primitives.len(), 10);
}

mod random_programs {
    use super::*;
    use proptest::prelude::*;

    /// Random numeric expressions over `x`, `a` and `time`, with every operator
    /// and function, and values that provoke divisions by zero, negative
    /// roots, overflows and out-of-range textures.
    fn expr() -> impl Strategy<Value = String> {
        let leaf = prop_oneof![
            Just("0".to_string()),
            Just("1".to_string()),
            Just("2.5".to_string()),
            Just("300".to_string()),
            Just("1000000000000000000000000000000000000000000000000000000000000000000000000000000000000".to_string()),
            Just("time".to_string()),
            Just("a".to_string()),
            Just("x".to_string()),
            Just("pi".to_string()),
        ];
        leaf.prop_recursive(4, 24, 2, |inner| {
            prop_oneof![
                (inner.clone(), prop_oneof![Just("+"), Just("-"), Just("*"), Just("/")], inner.clone())
                    .prop_map(|(a, op, b)| format!("({a} {op} {b})")),
                inner.clone().prop_map(|a| format!("-{a}")),
                (prop_oneof![Just("sin"), Just("cos"), Just("sqrt")], inner).prop_map(|(f, a)| format!("{f}({a})")),
            ]
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

        /// Whatever the numbers, evaluation returns a scene or an error, and a
        /// scene only holds finite, in-range primitives.
        #[test]
        fn evaluation_never_panics_and_scenes_are_sane(e in proptest::collection::vec(expr(), 10)) {
            let text = format!(
                "let a = 1
                 let x = {}
                 proc p(a, n)
                   if n > 0 & {} < {} then
                     put sphere center {}, a, 0 radius {} kd {} ks 0.5 phong {} color {}, 0, 0 end
                     p(a + 1, n - 1)
                   end
                 end
                 p({}, 3)
                 put scale translate box center 0, 0, 0 length {}, 1, 1 {TEX} end by {}, 0, 0 end by {} end",
                e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], e[8], e[9], e[0], e[1]
            );
            let mut sources = SourceMap::new();
            let id = sources.add("random.ray", text.clone(), 0);
            let program = parse_items(id, &text).unwrap();
            let mut i = Interpreter::new(2.0, Limits::default());
            if i.run(&program).is_ok() {
                for p in i.scene().all_primitives() {
                    prop_assert!(p.shape.is_finite(), "{text}");
                    let m = p.material;
                    prop_assert!((0.0..=1.0).contains(&m.kd) && (0.0..=1.0).contains(&m.ks) && m.phong > 0.0);
                    prop_assert!(m.color.min_element() >= 0.0 && m.color.max_element() <= 1.0);
                    match p.shape {
                        Shape::Sphere { radius, .. } => prop_assert!(radius > 0.0),
                        Shape::Box { half, .. } => prop_assert!(half.min_element() > 0.0),
                        Shape::Plane { .. } => {}
                    }
                }
            } else {
                prop_assert_eq!(i.scene().all_primitives().count(), 0, "a failed run leaves nothing");
            }
        }
    }
}
