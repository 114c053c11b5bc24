//! Items as they were written: the text of a definition taken from the
//! source it came from, with its comments, for `:write` and `:show`.

use crate::lang::{SourceMap, Span};

/// Where `span` starts, as `scene.ray:12` or `<input 3>:1`.
pub(crate) fn location(sources: &SourceMap, span: Span) -> String {
    let source = sources.get(span.source);
    format!("{}:{}", source.name, source.line_col(span.start as usize).0)
}

/// The text of `span`, exactly as written.
pub(crate) fn raw(sources: &SourceMap, span: Span) -> &str {
    let text = &sources.get(span.source).text;
    text.get(span.start as usize..span.end as usize).unwrap_or_default()
}

/// The text of the item spanning `span` as its author wrote it: the comment
/// lines right above it (when it starts its line), the item itself, and a
/// comment ending its last line, without the indentation they share, so
/// that it reads the same anywhere it is printed.
pub(crate) fn item_text(sources: &SourceMap, span: Span) -> String {
    let text = &*sources.get(span.source).text;
    let (start, end) = (span.start as usize, span.end as usize);
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let starts_its_line = text[line_start..start].trim().is_empty();
    let from = if starts_its_line { comments_above(text, line_start) } else { start };
    let line_end = text[end..].find('\n').map_or(text.len(), |i| end + i);
    let rest = text[end..line_end].trim_start();
    let to = if rest.is_empty() || rest.starts_with('#') { line_end } else { end };
    dedent(&text[from..to])
}

/// Where the block of whole-line comments right above the line starting at
/// `line_start` begins (`line_start` itself when there is none).
fn comments_above(text: &str, line_start: usize) -> usize {
    let mut from = line_start;
    while from > 0 {
        let previous = text[..from - 1].rfind('\n').map_or(0, |i| i + 1);
        if !text[previous..from - 1].trim_start().starts_with('#') {
            break;
        }
        from = previous;
    }
    from
}

/// `text` without the indentation all its non-blank lines share, and
/// without blanks at the ends of lines.
fn dedent(text: &str) -> String {
    let indent = |line: &str| line.len() - line.trim_start().len();
    let common = text.lines().filter(|line| !line.trim().is_empty()).map(indent).min().unwrap_or(0);
    let lines: Vec<&str> =
        text.lines().map(|line| line.get(common.min(indent(line))..).unwrap_or(line).trim_end()).collect();
    lines.join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn excerpt(text: &str, item: &str) -> String {
        let mut sources = SourceMap::new();
        let id = sources.add("a.ray", text, 0);
        let start = text.find(item).expect("the item is in the text");
        item_text(&sources, Span::new(id, start, start + item.len()))
    }

    #[test]
    fn an_item_keeps_the_comments_above_and_after_it() {
        let text = "let a = 1\n\n  # the ball\n  # of the scene\n  put ball # red\nlet b = 2\n";
        assert_eq!(excerpt(text, "put ball"), "# the ball\n# of the scene\nput ball # red");
        assert_eq!(excerpt(text, "let a = 1"), "let a = 1");
    }

    #[test]
    fn an_item_shares_its_line_with_no_other() {
        let text = "# two\nlet a = 1 let b = 2 # b\n";
        assert_eq!(excerpt(text, "let a = 1"), "# two\nlet a = 1");
        assert_eq!(excerpt(text, "let b = 2"), "let b = 2 # b");
    }

    #[test]
    fn lines_of_an_indented_item_keep_their_own_indentation() {
        let text = "if 1 < 2 then\n    proc p()\n      put ball\n    end\nend";
        assert_eq!(excerpt(text, "proc p()\n      put ball\n    end"), "proc p()\n  put ball\nend");
    }

    #[test]
    fn locations_name_the_source_and_line() {
        let mut sources = SourceMap::new();
        let id = sources.add("<stdin>", "\nlet a = 1", 16);
        assert_eq!(location(&sources, Span::new(id, 1, 10)), "<stdin>:18");
        assert_eq!(raw(&sources, Span::new(id, 1, 4)), "let");
    }
}
