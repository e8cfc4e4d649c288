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

use crate::diagnostics::{codes, nearest, Diagnostic, Diagnostics};
use crate::front::{Confidence, Declaration, EntryInfo, Front, Library, Read};
pub use crate::ir::Lowered;
use crate::ir::Span;
use crate::source::SourceFile;
use ast::Entry;
use std::collections::HashMap;

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

/// Reads a Fractint library: every entry is lowered (so each one's
/// problems are its own); the diagnostics kept are the chosen entry's and
/// the file's, or every entry's when none is chosen. Linear in the number
/// of entries: a library of 100,000 is read in well under a second, and
/// only the chosen entry's system is kept.
fn read_library(
    text: &str,
    entry: Option<&str>,
    diags: &mut Diagnostics,
) -> (Library, Option<Lowered>) {
    let mut file_diags = Diagnostics::default();
    let ast = parse(text, &mut file_diags);
    report_duplicates(&ast.entries, diags);
    let mut lib = Library {
        chosen: choose(&ast.entries, entry, diags),
        ..Library::default()
    };
    let mut lowered = None;
    let mut per_entry: Vec<Diagnostics> = Vec::with_capacity(ast.entries.len());
    for (i, e) in ast.entries.iter().enumerate() {
        let mut d = Diagnostics::default();
        let l = lower_entry(e, &mut d);
        if lib.chosen == Some(i) {
            lowered = Some(l);
        }
        per_entry.push(d);
    }
    // The file's diagnostics belong to the entry they are in, if any.
    for d in file_diags.0 {
        match owner(&ast.entries, &d) {
            Some(i) => per_entry[i].push(d),
            None => diags.push(d),
        }
    }
    for (e, d) in ast.entries.iter().zip(&per_entry) {
        lib.entries.push(EntryInfo {
            name: e.name.clone(),
            span: e.name_span.clone(),
            errors: d.iter().filter(|d| d.is_error()).count(),
            warnings: d.iter().filter(|d| !d.is_error()).count(),
        });
    }
    if ast.entries.is_empty() {
        diags.push(
            Diagnostic::global(codes::FR_CHOOSE_ENTRY, "this Fractint file has no entries")
                .with_help("an entry is `Name {`, its lines, and a line `}`"),
        );
    }
    match lib.chosen {
        Some(i) => diags.extend(per_entry.swap_remove(i)),
        None => {
            lib.needs_entry = entry.is_none() && ast.entries.len() > 1;
            for d in per_entry {
                diags.extend(d);
            }
        }
    }
    // One entry is drawn without being chosen: nothing to ask for.
    let choose = match lib.entries.len() {
        1 => "drawn without choosing",
        _ => "choose one with FILE:NAME or --entry NAME",
    };
    lib.summary = format!(
        "Fractint, {} {} ({choose}; -n sets the order, default {} as in Fractint)",
        lib.entries.len(),
        if lib.entries.len() == 1 {
            "entry"
        } else {
            "entries"
        },
        DEFAULT_ORDER
    );
    (lib, lowered)
}

/// Warns about each entry named as an earlier one was (names compared
/// without regard to case), pointing at the first.
fn report_duplicates(entries: &[Entry], diags: &mut Diagnostics) {
    let mut first_named: HashMap<String, usize> = HashMap::with_capacity(entries.len());
    for (i, e) in entries.iter().enumerate() {
        let first = *first_named.entry(e.name.to_ascii_lowercase()).or_insert(i);
        if first == i {
            continue;
        }
        // About the file, whichever entry is chosen.
        diags.push(
            Diagnostic::at(
                codes::FR_DUPLICATE_ENTRY,
                e.name_span.clone(),
                format!("a second entry named `{}`", e.name),
            )
            .with_label("never chosen by name")
            .with_secondary(
                entries[first].name_span.clone(),
                "the first, which `FILE:NAME` finds",
            ),
        );
    }
}

/// The entry read: the first named `entry` (reported when there is none),
/// else the only one.
fn choose(entries: &[Entry], entry: Option<&str>, diags: &mut Diagnostics) -> Option<usize> {
    let Some(name) = entry else {
        return (entries.len() == 1).then_some(0);
    };
    let found = entries
        .iter()
        .position(|e| e.name.eq_ignore_ascii_case(name));
    if found.is_none() {
        let names: Vec<&str> = entries.iter().map(|e| e.name.as_str()).collect();
        let mut d = Diagnostic::global(
            codes::FR_UNKNOWN_ENTRY,
            format!("no entry `{name}` in this file"),
        )
        .with_note(format!(
            "entries: {}",
            crate::front::name_list(names.iter().copied(), false)
        ));
        if let Some(n) = nearest(name, &names).first() {
            d = d.with_help(format!("did you mean `{n}`?"));
        }
        diags.push(d);
    }
    found
}

/// The entry whose text holds the place of `d`, if any. Entries are in
/// the order of the file and do not overlap, so a binary search finds it.
fn owner(entries: &[Entry], d: &Diagnostic) -> Option<usize> {
    let at = d.span.as_ref()?.start;
    let i = entries
        .partition_point(|e| e.span.start <= at)
        .checked_sub(1)?;
    let e = &entries[i];
    (at < e.span.end.max(e.span.start + 1)).then_some(i)
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
