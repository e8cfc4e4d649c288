//! The graftal notation (`.gft`, docs/gft.md): the toolchain's own
//! language, which says everything the IR holds.
//!
//! `lexer` (logos) -> `parser` (logical lines; chumsky for expressions and
//! statements, recovering line by line; `graph` for the lines of a
//! `graph { … }` block) -> `ast` -> `lower` (IR).

pub mod ast;
pub mod graph;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use crate::ir::Lowered;

use crate::diagnostics::Diagnostics;
use crate::front::{block_comments, Front, Read};
use crate::ir::{Span, System};
use crate::source::SourceFile;

/// The `.gft` notation in the registry.
pub struct Gft;

impl Front for Gft {
    fn keywords(&self) -> Vec<&'static str> {
        parser::KEYWORDS.iter().map(|(k, _)| *k).collect()
    }
    fn name(&self) -> &'static str {
        "gft"
    }
    fn title(&self) -> &'static str {
        "graftal"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["gft"]
    }
    fn read(&self, file: &SourceFile, _entry: Option<&str>, diags: &mut Diagnostics) -> Read {
        // Texture images are named relative to the file's folder.
        let folder = std::path::Path::new(&file.name).parent();
        let ast = parser::parse(&file.text, diags);
        lower::lower_in(&ast, folder, diags).into()
    }
    fn comments(&self, src: &str) -> Vec<(Span, String)> {
        block_comments(src)
    }
    /// The turn the file's `angle` divides into, when it divides it
    /// whole: what the file states, as pfg's `angle factor` does, so that
    /// a translation keeps it even where no symbol turns.
    fn angle_divisions(&self, sys: &System) -> Option<u64> {
        sys.settings.whole_divisions()
    }
}

/// Parses and lowers `.gft` text: the IR (usable only when `diags` got no
/// error) and its spans.
pub fn read(src: &str, diags: &mut Diagnostics) -> Lowered {
    let ast = parser::parse(src, diags);
    lower::lower(&ast, diags)
}

/// Reads a `.gft` text that must be free of errors (tests and examples).
///
/// # Panics
/// When the text has errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    crate::front::read_clean(|d| read(src, d))
}
