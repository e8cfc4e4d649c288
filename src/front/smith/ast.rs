//! The Smith abstract syntax tree: a file is `key: value` lines; the
//! values are kept as spans and read by [`super::lower`].

use crate::ir::Span;

/// A parsed file: its lines in order (lines that failed to parse are left
/// out; their diagnostics were reported).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct File {
    pub entries: Vec<Entry>,
}

/// `key: value`, e.g. `rules: 0.1[1].1.1.0.11.1.0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// The key, lowercased.
    pub key: String,
    pub key_span: Span,
    /// The value as written, without surrounding spaces.
    pub value: String,
    pub value_span: Span,
}
