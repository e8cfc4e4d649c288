//! The IFS front end: Fractint's libraries of iterated function systems
//! (`.ifs` files of many entries `Name { … }`, one map a line), read as
//! Fractint 19.6 reads them (`ifsload`), each entry lowered into an
//! object-instancing graph ([`crate::ir::graph`]): one symbol, one rule
//! `A -> w1(A) … wn(A)`, no geometry (Bekaert & Willems §2.3.1).
//!
//! `parser` (the library scanner, then each line's numbers) -> `ast` ->
//! `lower` (one [`crate::ir::System`] per entry). The library machinery
//! (choosing an entry, duplicates, the listing) is the one Fractint's
//! L-systems are read with ([`crate::front::library`]).

pub mod ast;
pub mod lower;
pub mod parser;

pub use lower::{is_3d, lower_entry, MAX_MAPS, NUMBERS_2D, NUMBERS_3D, SYMBOL};
pub use parser::parse;

use crate::diagnostics::{codes, Diagnostics};
use crate::front::{library, Confidence, Declaration, Front, Library, Read};
use crate::ir::{Lowered, Span};
use crate::source::SourceFile;

/// Fractint's IFS libraries in the registry.
pub struct Ifs;

impl Front for Ifs {
    fn name(&self) -> &'static str {
        "ifs"
    }
    fn title(&self) -> &'static str {
        "Fractint IFS"
    }
    fn extensions(&self) -> &'static [&'static str] {
        &["ifs"]
    }
    /// Certain when the first entry's first line is 7 or more numbers.
    fn detect(&self, text: &str) -> Confidence {
        if looks_ifs(text) {
            Confidence::Certain
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
        Some("`Name { … }` entries of maps")
    }
    fn describe(&self, _sys: Option<&crate::ir::System>) -> Option<String> {
        None
    }
    fn comment_spans(&self, src: &str) -> Vec<Span> {
        library::comment_spans(src)
    }
    fn declarations(&self, src: &str) -> Vec<Declaration> {
        let file = parse(src, &mut Diagnostics::default());
        library::declarations(src, file.entries, "IFS entry")
    }
}

/// A line `Name {` (or `Name (3D) {`) whose next line, or the rest of
/// its own, is 7 or more numbers and nothing else (`;` comments left out).
fn looks_ifs(text: &str) -> bool {
    let mut lines = text.lines().map(|l| l.split(';').next().unwrap_or(""));
    while let Some(line) = lines.next() {
        let Some((name, rest)) = line.split_once('{') else {
            continue;
        };
        if name.trim().is_empty() || name.contains(':') {
            continue;
        }
        let numbers = |l: &str| {
            let words: Vec<&str> = l.split_whitespace().collect();
            words.len() >= NUMBERS_2D && words.iter().all(|w| parser::number(w).is_some())
        };
        let rest = rest.trim().trim_end_matches('}');
        if !rest.trim().is_empty() {
            return numbers(rest);
        }
        return lines
            .find(|l| !l.trim().is_empty())
            .is_some_and(|l| numbers(l.trim().trim_end_matches('}')));
    }
    false
}

/// Reads an IFS library ([`library::read`]): every entry is lowered, so
/// each one's problems are its own.
fn read_library(
    text: &str,
    entry: Option<&str>,
    diags: &mut Diagnostics,
) -> (Library, Option<Lowered>) {
    let mut file_diags = Diagnostics::default();
    let ast = parse(text, &mut file_diags);
    let how = library::Reading {
        title: "Fractint IFS",
        no_entries: codes::IFS_NO_ENTRIES,
        duplicate: codes::IFS_DUPLICATE_ENTRY,
    };
    let lower = |e: &ast::Entry, d: &mut Diagnostics| lower::lower_graph(text, e, d);
    let (mut lib, graph) = library::read(&ast.entries, file_diags, entry, &how, lower, diags);
    let three_d = ast.entries.iter().filter(|e| is_3d(text, e)).count();
    lib.summary = format!(
        "Fractint IFS, {}; {three_d} of them 3D)",
        library::entries_summary(&lib)
    );
    (lib, graph.map(lower::lowered))
}

/// Reads the first entry of an IFS text that must be free of errors (for
/// tests and examples).
///
/// # Panics
/// When the text has no entry or errors; the message lists them.
pub fn read_ok(src: &str) -> crate::ir::System {
    crate::front::read_clean(|d| {
        let file = parse(src, d);
        lower_entry(src, file.entries.first().expect("an entry"), d)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ifs_text_is_told_by_its_numbers() {
        assert!(looks_ifs("fern {\n  0 0 0 .16 0 0 .01\n}\n"));
        assert!(looks_ifs(
            "; c\nt (3D) { ; c\n .5 0 0 0 .5 0 0 0 .5 0 0 1 1 }\n"
        ));
        assert!(!looks_ifs("Koch1 {\n  Angle 6\n  Axiom F\n}\n"));
        assert!(!looks_ifs("axiom: {F}\n1 2 3 4 5 6 7\n"));
    }

    #[test]
    fn a_library_lists_its_entries_and_their_dimension() {
        let src = "a {\n.5 0 0 .5 0 0 1\n}\nb (3D) {\n.5 0 0 0 .5 0 0 0 .5 0 0 1 1\n}\n";
        let mut d = Diagnostics::default();
        let (lib, lowered) = read_library(src, None, &mut d);
        assert!(d.is_empty(), "{d:#?}");
        assert!(lowered.is_none() && lib.needs_entry);
        assert_eq!(
            lib.summary,
            "Fractint IFS, 2 entries (choose one with FILE:NAME or --entry NAME; 1 of them 3D)"
        );
        let (_, lowered) = read_library(src, Some("B"), &mut d);
        assert!(!lowered.unwrap().system.graph.unwrap().is_planar());
        assert!(read_ok(src).graph.unwrap().is_planar());
    }
}
