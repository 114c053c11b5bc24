//! Generates the parser from `grammar/scene.lalrpop` into `OUT_DIR`.

fn main() {
    println!("cargo:rerun-if-changed=grammar");
    lalrpop::Configuration::new()
        .set_in_dir("grammar")
        .use_cargo_dir_conventions()
        .process()
        .expect("the grammar in grammar/ must compile");
}
