//! The Fractint front end: the L-system libraries of Fractint (`.l` files
//! of many entries `Name { … }`), read as Fractint 19 reads them
//! (`lsys.c`), with the tolerance of Fractint 16 for old files.
//!
//! `lexer` (logos: the file's tokens, and the commands of a string) ->
//! `parser` (chumsky lines, then entries and their lines) -> `ast` ->
//! `lower` (one [`crate::ir::System`] per entry).

pub mod ast;
pub mod declared;
pub mod lexer;
pub mod lower;
pub mod parser;

pub use lower::{lower_entry, palette, DEFAULT_ORDER, RESERVED};
pub use parser::parse;

use crate::diagnostics::{codes, Diagnostics};
use crate::front::{library, Confidence, Declaration, Front, Library, Read};
pub use crate::ir::Lowered;
use crate::ir::Span;
use crate::source::SourceFile;

/// Fractint's L-system libraries in the registry.
pub struct Fractint;

impl Front for Fractint {
    fn name(&self) -> &'static str {
        "fractint"
    }
    fn title(&self) -> &'static str {
        "Fractint"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["l"]
    }
    /// A line `Name {` and no `-->` (`;` comments left out).
    fn detect(&self, text: &str) -> Confidence {
        if looks_fractint(text) {
            Confidence::Likely
        } else {
            Confidence::No
        }
    }
    fn read(&self, file: &SourceFile, entry: Option<&str>, diags: &mut Diagnostics) -> Read {
        let (library, lowered) = read_library(&file.text, entry, diags);
        Read {
            lowered,
            library: Some(library),
        }
    }
    fn library_form(&self) -> Option<&'static str> {
        Some("`Name { … }` entries")
    }
    fn keywords(&self) -> Vec<&'static str> {
        parser::KEYWORDS.to_vec()
    }
    fn comment_spans(&self, src: &str) -> Vec<Span> {
        lexer::comment_spans(src)
    }
    fn declarations(&self, src: &str) -> Vec<Declaration> {
        declared::entries(src)
    }
    // The comments of a library belong to its many entries, not to the
    // one translated: none are carried over (the default).
}

/// A `Name {` line and no `-->`, `;` comments left out.
fn looks_fractint(text: &str) -> bool {
    let mut header = false;
    for line in text.lines() {
        let line = line.split(';').next().unwrap_or("");
        if line.contains("-->") {
            return false;
        }
        if !header {
            let t = line.trim_start();
            let name_end = t
                .find(|c: char| c.is_whitespace() || c == '(' || c == '{')
                .unwrap_or(t.len());
            let (name, rest) = t.split_at(name_end);
            header = !name.is_empty() && !name.contains(':') && rest.contains('{');
        }
    }
    header
}

/// Reads a Fractint library ([`library::read`]): every entry is lowered,
/// so each one's problems are its own.
fn read_library(
    text: &str,
    entry: Option<&str>,
    diags: &mut Diagnostics,
) -> (Library, Option<Lowered>) {
    let mut file_diags = Diagnostics::default();
    let ast = parse(text, &mut file_diags);
    let how = library::Reading {
        title: "Fractint",
        no_entries: codes::FR_CHOOSE_ENTRY,
        duplicate: codes::FR_DUPLICATE_ENTRY,
    };
    let (mut lib, lowered) =
        library::read(&ast.entries, file_diags, entry, &how, lower_entry, diags);
    lib.summary = format!(
        "Fractint, {}; -n sets the order, default {} as in Fractint)",
        library::entries_summary(&lib),
        DEFAULT_ORDER
    );
    (lib, lowered)
}

/// Reads the first entry of a Fractint text that must be free of errors
/// (for tests and examples).
///
/// # Panics
/// When the text has no entry or errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    crate::front::read_clean(|d| {
        let file = parse(src, d);
        lower_entry(file.entries.first().expect("an entry"), d)
    })
}
