//! The pfg front end: the 1988 plant and fractal generator format of
//! Prusinkiewicz & Hanan (Appendix A), with the extensions of SPEC.md.
//!
//! `lexer` (logos) -> `parser` (chumsky, recovering) -> `ast` -> `lower` (IR).

pub mod ast;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use lower::{lower, Lowered};
pub use parser::parse;

use crate::diagnostics::Diagnostics;

/// Parses and lowers pfg source text: the IR (usable only when `diags` got
/// no error) and its spans.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parse(src, diags);
    lower(&ast, diags)
}

/// Reads a pfg text that must be free of errors (for tests and examples).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    let mut d = Diagnostics::default();
    let l = read(src, &mut d);
    assert!(!d.has_errors(), "{d:#?}");
    l.system
}
