//! The pfg abstract syntax tree: what a `.l` file says, item by item, with
//! spans. Lowering ([`super::lower`]) turns it into the IR.

use crate::ir::Span;

/// A parsed file: its items in order. Lines that failed to parse are left
/// out (their diagnostics were reported).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct File {
    pub items: Vec<Item>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Header(Header),
    Production(Production),
}

/// `key: value`, e.g. `angle factor: 16`.
#[derive(Clone, Debug, PartialEq)]
pub struct Header {
    /// The key as written, with internal spaces normalised to one.
    pub key: String,
    pub key_span: Span,
    /// The value's symbols (each one character, with its span).
    pub value: Symbols,
    /// The whole line.
    pub span: Span,
}

/// A string of one-character symbols as written. `star` is set when it was
/// written as `*` (the empty string).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Symbols {
    pub chars: Vec<(String, Span)>,
    pub star: bool,
    pub span: Span,
}

impl Symbols {
    pub fn text(&self) -> String {
        self.chars.iter().map(|(c, _)| c.as_str()).collect()
    }
    pub fn is_empty(&self) -> bool {
        self.chars.is_empty()
    }
}

/// `lc < pred > rc --> succ : weight`.
#[derive(Clone, Debug, PartialEq)]
pub struct Production {
    pub left: Option<Symbols>,
    pub predecessor: Symbols,
    pub right: Option<Symbols>,
    pub successor: Symbols,
    /// The weight and the span of its number.
    pub weight: Option<(f64, Span)>,
    pub arrow: Span,
    /// The whole line.
    pub span: Span,
}
