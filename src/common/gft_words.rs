//! The keywords of the `.gft` notation (docs/gft.md), in one list that
//! both its front end (which reads them) and its emitter (which must
//! backquote a symbol spelt like one) import: neither may import the other.

/// Every keyword, with whether it takes a `{ }` block.
pub const KEYWORDS: &[(&str, bool)] = &[
    ("turtle", false),
    ("symbol", false),
    ("silent", false),
    ("steps", false),
    ("angle", false),
    ("length", false),
    ("scale", false),
    ("width", false),
    ("width-factor", false),
    ("width-step", false),
    ("widths", false),
    ("colour", false),
    ("colour-step", false),
    ("view", false),
    ("seed", false),
    ("choose", false),
    ("ignore", false),
    ("consider", false),
    ("ring", false),
    ("cut", false),
    ("axiom", false),
    ("rotation", false),
    ("colours", false),
    ("globals", false),
    ("array", false),
    ("decomposition", true),
    ("homomorphism", true),
    ("start", true),
    ("start-each", true),
    ("end-each", true),
    ("end", true),
    ("function", false),
    ("tropism", false),
    ("rule", false),
    ("stems", false),
    ("outline", true),
    ("growth", false),
    ("background", false),
    ("camera", false),
    ("lighting", false),
    ("light", false),
    ("material", false),
    ("surface", true),
    ("contour", true),
];

/// Whether `name` is a keyword.
pub fn is_keyword(name: &str) -> bool {
    KEYWORDS.iter().any(|(k, _)| *k == name)
}

/// Whether `name` is a keyword that takes a `{ }` block.
pub fn takes_block(name: &str) -> bool {
    KEYWORDS.iter().any(|(k, b)| *k == name && *b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_are_distinct_lowercase_words_joined_by_dashes() {
        let mut names: Vec<&str> = KEYWORDS.iter().map(|(k, _)| *k).collect();
        for k in &names {
            assert!(
                k.split('-')
                    .all(|w| !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase())),
                "{k}"
            );
        }
        names.sort_unstable();
        let n = names.len();
        names.dedup();
        assert_eq!(names.len(), n, "a keyword listed twice");
        assert!(is_keyword("axiom") && !is_keyword("axoim"));
        assert!(takes_block("start-each") && !takes_block("axiom"));
    }
}
