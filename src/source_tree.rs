//! The crate's own source files, for the tests that hold the code to a
//! rule (every diagnostic code is listed, the time is read in one place).

use std::path::{Path, PathBuf};

/// Every `.rs` file under `src/`, with its text.
pub(crate) fn rust_sources() -> Vec<(PathBuf, String)> {
    let mut found = Vec::new();
    let mut folders = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("src")];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).expect("src is readable") {
            let path = entry.expect("an entry of src").path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|extension| extension == "rs") {
                let text = std::fs::read_to_string(&path).expect("a source file is text");
                found.push((path, text));
            }
        }
    }
    found
}

/// The crate's top-level modules by layer, the lowest first (ARCHITECTURE.md
/// says what each layer does). A module imports only modules of its own
/// layer or below, and the modules of one layer import each other without
/// a circle.
const LAYERS: [&[&str]; 10] = [
    &["clock", "data_dir", "scene"],
    &["lang"],
    &["render", "warned"],
    &["animation", "compare", "explain", "lessons", "lint", "output", "pipeline", "playback", "pov", "settings"],
    &["ide"],
    &["process"],
    &["session"],
    &["presentation"],
    &["jupyter", "lsp", "terminal"],
    &["app", "cli", "job"],
];

/// The top-level module a file under `src/` belongs to (`src/lang/eval.rs`
/// and `src/lang.rs` belong to `lang`).
fn top_module(path: &Path) -> String {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let relative = path.strip_prefix(&src).expect("a file under src");
    let first = relative.components().next().expect("a file has a name");
    Path::new(first.as_os_str()).file_stem().expect("a name").to_string_lossy().into_owned()
}

/// The top-level modules `text` imports (`crate::name`), outside comments
/// and its tests (which may build what they test from anywhere).
fn imports(text: &str) -> std::collections::BTreeSet<String> {
    let code = text.split("#[cfg(test)]\nmod tests").next().unwrap_or_default();
    let code = code.lines().filter(|line| !line.trim_start().starts_with("//"));
    let mut found = std::collections::BTreeSet::new();
    for line in code {
        for (at, _) in line.match_indices("crate::") {
            let rest = &line[at + "crate::".len()..];
            let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
            if !name.is_empty() && !line[..at].ends_with('$') {
                found.insert(name);
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, BTreeSet};

    use super::*;

    /// Every top-level module is in one layer, imports nothing above it,
    /// and the module graph has no circle.
    #[test]
    fn the_layers_hold_and_the_module_graph_has_no_circle() {
        let layer_of = |name: &str| LAYERS.iter().position(|layer| layer.contains(&name));
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (path, text) in rust_sources() {
            let module = top_module(&path);
            if ["lib", "main", "source_tree"].contains(&module.as_str()) {
                continue;
            }
            let here = layer_of(&module).unwrap_or_else(|| panic!("`{module}` is in no layer of LAYERS"));
            for imported in imports(&text).into_iter().filter(|name| *name != module && name != "source_tree") {
                let there = layer_of(&imported).unwrap_or_else(|| panic!("`{imported}` is in no layer of LAYERS"));
                assert!(there <= here, "{} imports `{imported}`, a layer above `{module}`", path.display());
                graph.entry(module.clone()).or_default().insert(imported);
            }
        }
        // Kahn's algorithm: a graph whose modules can all be taken away,
        // each once nothing left imports it, has no circle.
        let mut left = graph.clone();
        loop {
            let free: Vec<String> =
                left.keys().filter(|m| !left.values().any(|imported| imported.contains(*m))).cloned().collect();
            if free.is_empty() {
                break;
            }
            for module in free {
                left.remove(&module);
            }
        }
        assert!(left.is_empty(), "these modules import each other in a circle: {:?}", left.keys());
        assert!(!graph["lsp"].contains("session"), "the language server uses the IDE layer, not the session");
    }

    #[test]
    fn imports_are_found_outside_comments() {
        let text = "use crate::lang::Span;\n// crate::session\nfn f() { crate::process::failure::tell_line(1); }\n\
                    #[cfg(test)]\nmod tests {\n    use crate::lint::Check;\n}\n";
        assert_eq!(imports(text), BTreeSet::from(["lang".to_string(), "process".to_string()]));
    }
}
