//! Evaluation speed: a Menger sponge (many calls, many boxes) and a deep
//! arithmetic recursion.

use criterion::{Criterion, criterion_group, criterion_main};
use rayrepl::lang::{Interpreter, Limits, SourceMap, ast::Program, parse_file, parse_items};

/// The sponge scene of `benches/scenes/menger.ray`, called at depth 5 there.
const MENGER: &str = include_str!("scenes/menger.ray");

fn program(text: &str, file: bool) -> Program {
    let mut sources = SourceMap::new();
    let id = sources.add("bench.ray", text, 0);
    let parsed = if file { parse_file(id, text) } else { parse_items(id, text) };
    parsed.unwrap_or_else(|d| panic!("the bench scene must parse: {}", d.message))
}

fn run(program: &Program) -> usize {
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    interpreter.run(program).unwrap_or_else(|d| panic!("the bench scene must run: {}", d.message));
    interpreter.scene().primitives.len()
}

fn menger(c: &mut Criterion) {
    let mut group = c.benchmark_group("menger");
    group.sample_size(10);
    for depth in [3, 4, 5] {
        let text = MENGER.replace("menger(0, 0, 0, 3, 5)", &format!("menger(0, 0, 0, 3, {depth})"));
        let program = program(&text, true);
        group.bench_function(format!("depth {depth}"), |b| b.iter(|| run(&program)));
    }
    group.finish();
}

fn recursion(c: &mut Criterion) {
    let text = "proc down(n, acc) if 0 < n then down(n - 1, acc + sin(n) * 2) end end down(99999, 0)";
    let program = program(text, false);
    c.bench_function("recursion 100000 calls deep", |b| b.iter(|| run(&program)));
}

criterion_group!(benches, menger, recursion);
criterion_main!(benches);
