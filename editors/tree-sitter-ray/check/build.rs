//! Compiles the committed parser (../src/parser.c), as editors do.

fn main() {
    let src = std::path::Path::new("../src");
    println!("cargo::rerun-if-changed=../src/parser.c");
    cc::Build::new().include(src).file(src.join("parser.c")).warnings(false).compile("tree-sitter-ray");
}
