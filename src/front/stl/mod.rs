//! The STL front end: the Structural Tree Language of Yeh, Chien & Lee
//! (drawing components, growth rules, self-resemblance counts, stem
//! parameters, branching syntax, layouts), in the file format that
//! `grammar/stl.ebnf` fixes normatively (the paper leaves it open).
//!
//! `lexer` (logos) -> `parser` (chumsky, recovering) -> `ast` -> `lower`
//! (the paper's Language Analyzer; for an Outline Description it runs
//! `growth`, the Graphics Developer, over the `layout` shapes) -> IR. The
//! lowered seed is always a Branch-Expansion Description, which
//! [`crate::back::stl`] writes back out.

pub mod ast;
pub mod declared;
pub mod layout;

/// Outline growth is the IR's: the front end asks it, walking no turtle of
/// its own.
pub use crate::layout::growth;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use crate::ir::Lowered;
pub use lower::lower;
pub use parser::parse;

use crate::diagnostics::Diagnostics;
use crate::front::{line_comments, Declaration, Front, Read};
use crate::ir::Span;
use crate::source::SourceFile;

/// The STL notation in the registry.
pub struct Stl;

impl Front for Stl {
    fn name(&self) -> &'static str {
        "stl"
    }
    fn title(&self) -> &'static str {
        "STL"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["stl"]
    }
    fn read(&self, file: &SourceFile, _entry: Option<&str>, diags: &mut Diagnostics) -> Read {
        read(&file.text, diags).into()
    }
    fn comments(&self, src: &str) -> Vec<(Span, String)> {
        line_comments(src, None)
    }
    fn keywords(&self) -> Vec<&'static str> {
        parser::KEYWORDS.to_vec()
    }
    fn declarations(&self, src: &str) -> Vec<Declaration> {
        declared::rules(src)
    }
    fn declared_name_uses(&self, src: &str) -> Option<Vec<(String, Span)>> {
        Some(declared::rule_uses(src))
    }
}

/// Parses and lowers STL source text: the IR (usable only when `diags` got
/// no error) and its spans.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parse(src, diags);
    lower(&ast, src.len(), diags)
}

/// Reads an STL text that must be free of errors (for tests and examples).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    crate::front::read_clean(|d| read(src, d))
}
