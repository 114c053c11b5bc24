//! The documents stay in their places: every relative link of the README,
//! CONTRIBUTING.md, BENCHMARKS.md and `docs/` leads to a file of the
//! repository (and, for a heading, to a heading that exists there), and the
//! README and BENCHMARKS.md stay short enough to read (the guide and
//! `docs/perf/` take the rest).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The most lines the README may have: what rayrepl is and how to start,
/// in a screen or two.
const README_LINES: usize = 220;

/// The most lines BENCHMARKS.md may have: today's numbers and how to
/// reproduce them; investigations go in `docs/perf/`.
const BENCHMARKS_LINES: usize = 420;

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The Markdown files whose links are checked, relative to the repository.
fn documents() -> Vec<PathBuf> {
    let mut found = vec![PathBuf::from("README.md"), PathBuf::from("CONTRIBUTING.md"), PathBuf::from("BENCHMARKS.md")];
    let mut folders = vec![PathBuf::from("docs")];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(repository().join(&folder)).expect("a folder of docs/") {
            let name = folder.join(entry.expect("an entry").file_name());
            if repository().join(&name).is_dir() {
                folders.push(name);
            } else if name.extension().is_some_and(|extension| extension == "md") {
                found.push(name);
            }
        }
    }
    found.sort();
    found
}

/// The text outside fenced code blocks and inline code, where a link is a link.
fn prose(text: &str) -> String {
    let mut kept = String::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced {
            let outside_code = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
            kept.push_str(&outside_code);
            kept.push('\n');
        }
    }
    kept
}

/// The targets of the links `[text](target)` in a document's prose.
fn link_targets(text: &str) -> Vec<String> {
    let prose = prose(text);
    prose
        .match_indices("](")
        .filter_map(|(at, _)| {
            let rest = &prose[at + 2..];
            let end = rest.find([')', ' ', '\n'])?;
            Some(rest[..end].to_string())
        })
        .collect()
}

/// The anchors a forge gives a document's headings: lower case, spaces as
/// `-`, punctuation other than `-` and `_` dropped, a repeated one numbered.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if fenced || !(1..=6).contains(&hashes) || !line[hashes..].starts_with(' ') {
            continue;
        }
        let slug: String = line[hashes..]
            .trim()
            .to_lowercase()
            .chars()
            .filter(|&c| c.is_alphanumeric() || c == '-' || c == '_' || c == ' ')
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let mut numbered = slug.clone();
        let mut n = 0;
        while !found.insert(numbered.clone()) {
            n += 1;
            numbered = format!("{slug}-{n}");
        }
    }
    found
}

/// What is wrong with one link of `document`, if anything.
fn broken(document: &Path, target: &str) -> Option<String> {
    if target.contains("://") || target.starts_with("mailto:") {
        return None;
    }
    let (path, anchor) = target.split_once('#').unwrap_or((target, ""));
    let file = if path.is_empty() {
        document.to_path_buf()
    } else {
        let joined = document.parent().unwrap_or(Path::new("")).join(path);
        let mut normal = PathBuf::new();
        for part in joined.components() {
            match part {
                std::path::Component::ParentDir => {
                    if !normal.pop() {
                        return Some(format!("`{target}` leaves the repository"));
                    }
                }
                std::path::Component::CurDir => {}
                other => normal.push(other),
            }
        }
        normal
    };
    let full = repository().join(&file);
    if !full.exists() {
        return Some(format!("`{target}`: no file {}", file.display()));
    }
    if !anchor.is_empty() && file.extension().is_some_and(|extension| extension == "md") {
        let text = std::fs::read_to_string(&full).expect("a readable document");
        if !anchors(&text).contains(anchor) {
            return Some(format!("`{target}`: no heading #{anchor} in {}", file.display()));
        }
    }
    None
}

#[test]
fn every_relative_link_leads_to_a_file_and_a_heading() {
    let mut problems = Vec::new();
    let documents = documents();
    assert!(documents.iter().any(|document| document.starts_with("docs/guide")), "{documents:?}");
    for document in &documents {
        let text = std::fs::read_to_string(repository().join(document)).expect("a readable document");
        for target in link_targets(&text) {
            if let Some(problem) = broken(document, &target) {
                problems.push(format!("{}: {problem}", document.display()));
            }
        }
    }
    assert!(problems.is_empty(), "broken links:\n{}", problems.join("\n"));
}

#[test]
fn the_readme_and_the_benchmarks_stay_short() {
    for (document, most) in [("README.md", README_LINES), ("BENCHMARKS.md", BENCHMARKS_LINES)] {
        let lines = std::fs::read_to_string(repository().join(document)).expect("a readable document").lines().count();
        assert!(lines <= most, "{document} has {lines} lines, more than {most}: move the detail to docs/");
    }
}

#[test]
fn the_readme_says_what_rayrepl_is_before_anything_else() {
    let readme = std::fs::read_to_string(repository().join("README.md")).expect("the README");
    let first_paragraph = readme.split("\n\n").nth(1).expect("a paragraph after the title");
    assert!(first_paragraph.starts_with("rayrepl is "), "{first_paragraph}");
}

#[test]
fn the_anchors_are_those_a_forge_makes() {
    let text = "# The `.ray` language\n## 12. `print`: seeing values\n## Tried, not kept\n## Tried, not kept\n```\n# not a heading\n```\n";
    let expected = ["the-ray-language", "12-print-seeing-values", "tried-not-kept", "tried-not-kept-1"];
    assert_eq!(anchors(text), expected.iter().map(|anchor| anchor.to_string()).collect());
}
