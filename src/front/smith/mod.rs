//! Smith's bracketed 2L-systems (Alvy Ray Smith, "Plants, fractals, and
//! formal languages", SIGGRAPH 1984): a system over {0, 1} written as the
//! eight images of the binary triples, `rules: 0.1[1].1.1.0.11.1.0`, with
//! an axiom and the settings of Smith's program Gene (`.smith` files;
//! grammar in `grammar/smith.ebnf`).
//!
//! `lexer` (logos) -> `parser` (chumsky, recovering) -> `ast` -> `lower` (IR).

pub mod ast;
pub mod lexer;
pub mod lower;
pub mod parser;

use crate::diagnostics::Diagnostics;
use crate::front::{Front, Read};
use crate::ir::{Lowered, SymbolId, System, Word};
use crate::source::SourceFile;

/// Smith's notation in the registry.
pub struct Smith;

impl Front for Smith {
    fn keywords(&self) -> Vec<&'static str> {
        lower::KEYS.to_vec()
    }
    fn name(&self) -> &'static str {
        "smith"
    }
    fn title(&self) -> &'static str {
        "Smith"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["smith"]
    }
    fn read(&self, file: &SourceFile, _entry: Option<&str>, diags: &mut Diagnostics) -> Read {
        read(&file.text, diags).into()
    }
    /// The word as Smith prints it: 0, 1 and brackets, without the turns
    /// and leaves added for drawing.
    fn word_text(&self, sys: &System, word: &Word) -> String {
        smith_text(sys, word.symbols())
    }
    fn spells_words_by_name(&self) -> bool {
        false
    }
}

/// `symbols` as Smith writes them: only 0, 1, `[` and `]`.
pub fn smith_text(sys: &System, symbols: &[SymbolId]) -> String {
    symbols
        .iter()
        .map(|&s| sys.symbols.name(s))
        .filter(|n| matches!(*n, "0" | "1" | "[" | "]"))
        .collect()
}

/// Parses and lowers Smith source text.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parser::parse(src, diags);
    lower::lower(&ast, diags)
}

/// Reads a Smith text that must be free of errors (for tests and examples).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> System {
    crate::front::read_clean(|d| read(src, d))
}
