//! The pfg front end: the 1988 plant and fractal generator format of
//! Prusinkiewicz & Hanan (Appendix A), with the extensions of SPEC.md.
//!
//! `lexer` (logos) -> `parser` (chumsky, recovering) -> `ast` -> `lower` (IR).

pub mod ast;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use lower::lower;
pub use parser::parse;
