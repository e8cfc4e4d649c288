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
    ("cpfg-polygons", false),
    ("colour", false),
    ("colour-step", false),
    ("view", false),
    ("seed", false),
    ("random", false),
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
    ("label", false),
    ("sub-lsystem", true),
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
    ("texture", false),
    ("surface", true),
    ("backdrop", true),
    ("contour", true),
    ("graph", true),
    ("environment", false),
];

/// The words that start a line of a `graph { … }` block (docs/gft.md
/// §13); any other line of the block is a rule `A -> …`.
pub const GRAPH_LINES: &[&str] = &["transform", "axiom", "symbol", "geometry", "alternative"];

/// The steps a transform of a `graph` block is composed of.
pub const TRANSFORMS: &[&str] = &["translate", "scale", "rotate", "shear", "matrix"];

/// The primitive shapes of a `graph` block's `geometry` lines.
pub const SHAPES: &[&str] = &[
    "sphere", "box", "cylinder", "cone", "disc", "triangle", "polygon",
];

/// The finish words after a shape, each followed by a number.
pub const FINISHES: &[&str] = &["ambient", "diffuse", "specular", "shininess"];

/// The axes of `rotate x|y|z` and `shear`.
pub const AXES: &[&str] = &["x", "y", "z"];

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
