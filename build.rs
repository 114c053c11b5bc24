//! Generates the parser from `grammar/scene.lalrpop` into `OUT_DIR`.

fn main() {
    println!("cargo:rerun-if-changed=grammar");
    // `use_cargo_dir_conventions` sets the input directory to `src`, so the
    // input directory must be set after it.
    lalrpop::Configuration::new()
        .use_cargo_dir_conventions()
        .set_in_dir("grammar")
        .process()
        .expect("the grammar in grammar/ must compile");
}
