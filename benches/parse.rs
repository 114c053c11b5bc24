//! Parsing speed: a program of a million lines must parse in well under a
//! second (release build). Run with `cargo bench --bench parse`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rayrepl::lang::{SourceId, is_incomplete, parse_items};

/// `lines` lines of `let x = 1 + 2 * y`.
fn long_program(lines: usize) -> String {
    "let x = 1 + 2 * y\n".repeat(lines)
}

/// A scene-like program: procedures, objects and conditions.
fn scene_program(repeats: usize) -> String {
    let chunk = "proc ball(x, y)\n  if x < 10 & !(y = 0) then\n    put translate sphere center x, y, 0 radius 1 \
                 kd 0.5 ks 0.5 phong 10 color 255, 128, 0 end by 1, 2, 3 end\n  end\nend\nball(1, 2)\n";
    chunk.repeat(repeats)
}

fn parsing(c: &mut Criterion) {
    let million = long_program(1_000_000);
    let mut group = c.benchmark_group("parse");
    group.sample_size(10);
    group.bench_function("1M lines of `let x = 1 + 2 * y`", |b| {
        b.iter(|| parse_items(SourceId(0), black_box(&million)).map(|p| p.items.len()))
    });
    let scene = scene_program(100_000);
    group.bench_function("100k procedures with objects (700k lines)", |b| {
        b.iter(|| parse_items(SourceId(0), black_box(&scene)).map(|p| p.items.len()))
    });
    group.bench_function("is_incomplete on 1M lines", |b| b.iter(|| is_incomplete(black_box(&million))));
    group.finish();
}

criterion_group!(benches, parsing);
criterion_main!(benches);
