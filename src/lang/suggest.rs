//! "Did you mean ...?": the closest known name to a misspelt one.

/// The longest name compared. The edit distance takes time in the product of
/// the two lengths, so two names of 100,000 letters would take a minute; a
/// name longer than this is not one a typo suggestion helps with.
const LONGEST_COMPARED: usize = 64;

/// The candidate closest to `word` by edit distance, if it is close enough to
/// be a likely typo (at most a third of the word's length, at least 1).
/// Candidates whose length differs by more than that are skipped unread,
/// and a `word` longer than [`LONGEST_COMPARED`] gets no suggestion.
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let length = word.chars().count();
    if length > LONGEST_COMPARED {
        return None;
    }
    let limit = (length / 3).max(1);
    let close_in_length = |c: &str| c.chars().take(length + limit + 1).count().abs_diff(length) <= limit;
    candidates
        .into_iter()
        .filter(|c| *c != word && close_in_length(c))
        .map(|c| (strsim::damerau_levenshtein(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, c)| (*d, *c))
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_close_keyword_and_rejects_far_ones() {
        let keywords = ["sphere", "plane", "box"];
        assert_eq!(closest("spehre", keywords), Some("sphere"));
        assert_eq!(closest("sphre", keywords), Some("sphere"));
        assert_eq!(closest("xyz", keywords), None);
    }

    #[test]
    fn long_names_still_get_suggestions() {
        let names = ["number_of_spheres_in_the_outer_ring", "radius"];
        assert_eq!(closest("number_of_spheres_in_the_outer_rign", names), Some(names[0]));
        assert_eq!(closest("radiuses", names), Some("radius"));
    }

    #[test]
    fn huge_names_are_not_compared() {
        let huge = "a".repeat(100_000);
        let other = format!("{}b", "a".repeat(99_999));
        assert_eq!(closest(&other, [huge.as_str()]), None);
        assert_eq!(closest("aaaa", [huge.as_str(), "aaab"]), Some("aaab"));
    }
}
