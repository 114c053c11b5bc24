//! Running whole programs for the integration tests.

use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};

/// The interpreter after running the file text `text` at `time`; the text
/// must parse and evaluate. `name` is the file's name in messages.
pub fn evaluated(name: &str, text: &str, time: f64) -> Interpreter {
    let mut sources = SourceMap::new();
    let id = sources.add(name, text, 0);
    let program = parse_file(id, &sources.get(id).text).unwrap_or_else(|e| panic!("{name} parses: {}", e.message));
    let mut interpreter = Interpreter::new(time, Limits::default());
    interpreter.run(&program).unwrap_or_else(|e| panic!("{name} evaluates: {}", e.message));
    interpreter
}
