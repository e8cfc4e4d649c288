//! The IFS AST: a library file's entries, each a list of maps, one line
//! of numbers each.

use crate::ir::Span;

/// A library file: its entries in file order (`comment { … }` blocks and
/// nameless `{ … }` blocks are not entries).
#[derive(Clone, Debug, Default)]
pub struct File {
    pub entries: Vec<Entry>,
}

/// One entry `Name { … }` (`Name (3D) { … }`) and its lines.
pub type Entry = crate::front::library::Entry<Line>;

/// One line of an entry: a map's numbers, as far as they read.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// From its first word to its last.
    pub span: Span,
    /// The words that are numbers, in order.
    pub numbers: Vec<Number>,
    /// Whether a word of the line is not a number (reported): the line
    /// is no map.
    pub broken: bool,
}

/// A number and where it is written.
#[derive(Clone, Debug, PartialEq)]
pub struct Number {
    pub value: f64,
    pub span: Span,
}
