//! The Fractint AST: a library file's entries and their lines.

use crate::ir::Span;

/// A library file: its entries in file order (`comment { … }` blocks and
/// nameless `{ … }` blocks are not entries).
#[derive(Clone, Debug, Default)]
pub struct File {
    pub entries: Vec<Entry>,
}

/// One entry `Name { … }` and its lines.
pub type Entry = crate::front::library::Entry<Line>;

/// A string (axiom or rule body): lowercased, as Fractint reads it.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    pub text: String,
    pub span: Span,
}

/// One line of an entry.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    pub kind: LineKind,
    /// Text after the command's string (Fractint: "Extra text").
    pub extra: Option<Span>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum LineKind {
    Axiom {
        keyword: Span,
        body: Option<Body>,
    },
    Angle {
        keyword: Span,
        value: Option<Body>,
    },
    /// `x=body`; `x=` and `x` alone have no body (a deletion).
    Rule {
        head: String,
        head_span: Span,
        body: Option<Body>,
    },
    /// A word of several characters that is not a keyword; `rule` when it
    /// was followed by `=` (a multi-character rule head).
    Unknown {
        word: String,
        span: Span,
        rule: bool,
    },
}
