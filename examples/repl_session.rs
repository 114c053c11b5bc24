//! Runs the session entry point, as `main` will: `cargo run --example repl_session`.
fn main() {
    let options = rayrepl::repl::SessionOptions::default();
    std::process::exit(rayrepl::repl::run(&options));
}
