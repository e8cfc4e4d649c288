//! What a file declares besides its symbols, as a front end tells the
//! language server: its declared names ([`Declaration`]: STL rules, LinF
//! rotations and declared names, cpfg macros, Fractint entries) and the
//! user functions it calls from side files ([`FunctionSite`]). Each front
//! end answers for its own notation through [`super::Front`], so the
//! language server matches on no notation's name.

use crate::ir::Span;

/// A declared name: where it is written in its declaration, what kind of
/// thing it is, and what hovering it shows (Markdown).
#[derive(Clone, Debug, PartialEq)]
pub struct Declaration {
    pub name: String,
    pub span: Span,
    pub kind: DeclarationKind,
    pub about: String,
}

/// What kind of thing a declared name is, as an editor's outline shows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeclarationKind {
    /// Something applied to arguments or expanded in place: an STL rule,
    /// a function-like macro.
    Function,
    /// A fixed value: a named rotation, an object-like macro.
    Constant,
    /// A name a file declares for its symbols (LinF's `lines`, `blanks`).
    Variable,
    /// A whole system of a library (a Fractint entry).
    Module,
}

/// A user function where the files beside a source declare it: what the
/// source calls by number (`func(k, x)`) or by name (`func(NAME, x)`).
pub struct FunctionSite {
    /// k, from 1, in the order the notation numbers them.
    pub number: usize,
    /// `NAME`, as the source calls it.
    pub name: Option<String>,
    /// The file that declares it, and its text.
    pub path: std::path::PathBuf,
    pub text: String,
    /// Where its name is written there (its file's start when unnamed).
    pub span: Span,
    /// Its control points, after multiplicities are expanded.
    pub points: Vec<[f64; 2]>,
    /// How many samples of it are computed in advance (0: none).
    pub samples: usize,
}

/// `text[span]`, cut to a line's worth for a hover.
pub fn quoted(text: &str, span: &Span) -> String {
    crate::diagnostics::shortened(text.get(span.clone()).unwrap_or("").trim(), 200).into_owned()
}

/// Whether `c` may be part of a declared name: letters, digits and `_`.
pub fn is_name_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The word (letters, digits, `_`) around byte `at` of `text`.
pub fn word_at(text: &str, at: usize) -> Option<&str> {
    word_span(text, at).map(|s| &text[s])
}

/// Where the word (letters, digits, `_`) around byte `at` of `text` is.
pub fn word_span(text: &str, at: usize) -> Option<Span> {
    let at = at.min(text.len());
    let start = text
        .get(..at)?
        .rfind(|c| !is_name_char(c))
        .map_or(0, |i| i + 1);
    let end = text
        .get(at..)?
        .find(|c| !is_name_char(c))
        .map_or(text.len(), |i| at + i);
    (start < end).then_some(start..end)
}
