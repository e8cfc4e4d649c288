//! The LinF front end: the language of Pereira, Rolla, Rezende & Carceroni
//! (2003), "The Language LinF for Fractal Specification", with the file
//! format fixed in SPEC.md and `grammar/linf.ebnf`.
//!
//! `lexer` (logos) -> `parser` (chumsky, recovering) -> `ast` -> `lower` (IR).

pub mod ast;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use lower::{lower, Lowered};
pub use parser::parse;

use crate::diagnostics::Diagnostics;

/// Parses and lowers LinF source text: the IR (usable only when `diags` got
/// no error) and its spans.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parse(src, diags);
    lower(&ast, diags)
}

/// Reads a LinF text that must be free of errors (for tests and examples).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    let mut d = Diagnostics::default();
    let l = read(src, &mut d);
    assert!(!d.has_errors(), "{d:#?}");
    l.system
}
