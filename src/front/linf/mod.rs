//! The LinF front end: the language of Pereira, Rolla, Rezende & Carceroni
//! (2003), "The Language LinF for Fractal Specification", with the file
//! format fixed in `grammar/linf.ebnf`.
//!
//! `lexer` (logos) -> `parser` (chumsky, recovering) -> `ast` -> `lower` (IR).

pub mod ast;
pub mod declared;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use crate::ir::Lowered;
pub use lower::lower;
pub use parser::parse;

use crate::diagnostics::Diagnostics;
use crate::front::{line_comments, Declaration, Front, Read};
use crate::ir::{Span, System, Word};
use crate::source::SourceFile;

/// The LinF notation in the registry.
pub struct Linf;

impl Front for Linf {
    fn name(&self) -> &'static str {
        "linf"
    }
    fn title(&self) -> &'static str {
        "LinF"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["linf"]
    }
    fn read(&self, file: &SourceFile, _entry: Option<&str>, diags: &mut Diagnostics) -> Read {
        read(&file.text, diags).into()
    }
    fn word_text(&self, sys: &System, word: &Word) -> String {
        display(sys, word)
    }
    /// Names of several characters are set apart by spaces.
    fn spells_words_by_name(&self) -> bool {
        false
    }
    /// `#` to the end of the line; `#:` lines are directives, not comments.
    fn comments(&self, src: &str) -> Vec<(Span, String)> {
        line_comments(src, Some(':'))
    }
    fn keywords(&self) -> Vec<&'static str> {
        (lexer::BlockKind::ALL.iter())
            .map(|k| k.keyword())
            .collect()
    }
    fn declarations(&self, src: &str) -> Vec<Declaration> {
        declared::names(src)
    }
}

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
    crate::front::read_clean(|d| read(src, d))
}

/// A word as LinF text that reads back as the same symbols. Names are
/// written side by side (`f+f--f+f`) when every name-like symbol of the
/// system is one character, since the longest-name split then gives them
/// back; otherwise adjacent names are separated by a space (`stem leaf`).
/// A space also separates a name from a following number (`f 0.5@`), which
/// would otherwise lex as one name.
pub fn display(sys: &crate::ir::System, word: &crate::ir::Word) -> String {
    let is_name_char = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let starts_name = |n: &str| n.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_');
    let all_short =
        sys.symbols.iter().all(|(_, info)| {
            info.guard.is_some() || !starts_name(&info.name) || info.name.len() == 1
        }) && sys.rotations.iter().all(|r| r.name.len() <= 1);
    let mut out = String::with_capacity(word.len() * 2);
    let mut prev_ends_name = false;
    for &id in &word.0 {
        let name = sys.symbols.name(id);
        let first = name.chars().next().unwrap_or(' ');
        if prev_ends_name
            && (first.is_ascii_digit() || first == '.' || (!all_short && is_name_char(first)))
        {
            out.push(' ');
        }
        out.push_str(name);
        prev_ends_name = name.ends_with(is_name_char);
    }
    out
}
