//! The Fractint front end: the L-system libraries of Fractint (`.l` files
//! of many entries `Name { … }`), read as Fractint 19 reads them
//! (`lsys.c`), with the tolerance of Fractint 16 for old files.
//!
//! `lexer` (logos: the file's tokens, and the commands of a string) ->
//! `parser` (chumsky lines, then entries and their lines) -> `ast` ->
//! `lower` (one [`crate::ir::System`] per entry).

pub mod ast;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use lower::{lower_entry, palette, Lowered, DEFAULT_ORDER, RESERVED};
pub use parser::parse;

use crate::diagnostics::Diagnostics;

/// Reads the first entry of a Fractint text that must be free of errors
/// (for tests and examples).
///
/// # Panics
/// When the text has no entry or errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    let mut d = Diagnostics::default();
    let file = parse(src, &mut d);
    let entry = file.entries.first().expect("an entry");
    let l = lower_entry(entry, &mut d);
    assert!(!d.has_errors(), "{d:#?}");
    l.system
}
