//! Reading a file (a path, `std:NAME`, `FILE:NAME` for a library's entry)
//! and compiling it to the IR with every diagnostic.

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::{self, Front, Library};
use crate::ir::{SpanTable, System, Word};
use crate::source::{NotText, SourceFile, MAX_SOURCE_BYTES};
use crate::stdlib;
use std::path::Path;

/// Why a file could not be read (a usage or I/O problem: exit status 2).
#[derive(Debug)]
pub enum LoadError {
    /// `std:NAME` names no stdlib entry: the message, with the names near
    /// it ([`stdlib::unknown`]).
    UnknownStdlib(String),
    /// The file could not be read.
    Unreadable { spec: String, error: std::io::Error },
}

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoadError::UnknownStdlib(message) => f.write_str(message),
            LoadError::Unreadable { spec, error } => write!(f, "cannot read `{spec}`: {error}"),
        }
    }
}

/// Reads `spec`: a path, or `std:NAME` for a stdlib entry.
pub fn load(spec: &str) -> Result<SourceFile, LoadError> {
    if let Some(name) = spec.strip_prefix("std:") {
        return match stdlib::get(name) {
            Some(e) => Ok(SourceFile::new(e.file, e.text)),
            None => Err(LoadError::UnknownStdlib(stdlib::unknown(name))),
        };
    }
    SourceFile::read(Path::new(spec)).map_err(|error| LoadError::Unreadable {
        spec: spec.to_string(),
        error,
    })
}

/// A file compiled to the IR. `system` is `None` when the file has errors
/// (what was read of it is `recovered`), or when it is a library of
/// several entries and none was chosen (`library.needs_entry`).
pub struct Compiled {
    pub file: SourceFile,
    pub system: Option<System>,
    pub spans: SpanTable,
    pub diagnostics: Diagnostics,
    /// The notation the file was read as.
    pub front: &'static dyn Front,
    /// A library's entries, and which was read.
    pub library: Option<Library>,
    /// What the front end lowered of a file with errors (`system` is then
    /// `None`): the parts that parse, with `spans`. For finding places (an
    /// editor's hover and definitions), never for deriving or drawing.
    pub recovered: Option<System>,
}

impl Compiled {
    /// Several entries and none chosen: `system` is `None` without errors.
    pub fn needs_entry(&self) -> bool {
        self.library.as_ref().is_some_and(|l| l.needs_entry)
    }

    /// The system as read, errors or not: `system`, else what was
    /// [`recovered`](Compiled::recovered) of a file with errors.
    pub fn system_or_recovered(&self) -> Option<&System> {
        self.system.as_ref().or(self.recovered.as_ref())
    }

    /// The derived word as text in the notation the file was read in.
    pub fn word_text(&self, sys: &System, word: &Word) -> String {
        self.front.word_text(sys, word)
    }
}

/// Splits `FILE:NAME` (a library entry) when `FILE` exists and the whole
/// does not; anything else is a path as it is.
pub fn split_entry(spec: &str) -> (String, Option<String>) {
    if !spec.starts_with("std:") && !Path::new(spec).exists() {
        if let Some((path, name)) = spec.rsplit_once(':') {
            if !name.is_empty() && !name.contains(['/', '\\']) && Path::new(path).is_file() {
                return (path.to_string(), Some(name.to_string()));
            }
        }
    }
    (spec.to_string(), None)
}

/// The error for a library whose entry was not chosen (see
/// [`Compiled::needs_entry`]), listing the entries.
pub fn choose_entry(c: &Compiled) -> Diagnostic {
    let empty = Library::default();
    let lib = c.library.as_ref().unwrap_or(&empty);
    front::choose_entry(&c.file.name, c.front.title(), lib)
}

/// Parses, lowers and validates `file`, collecting every diagnostic.
pub fn compile(file: SourceFile) -> Compiled {
    compile_entry(file, None)
}

/// [`compile`], choosing the entry `entry` of a library (names compared
/// without regard to case). Without a choice, a library of one entry gives
/// that entry; of several, every entry is checked and
/// [`Compiled::needs_entry`] holds.
pub fn compile_entry(file: SourceFile, entry: Option<&str>) -> Compiled {
    compile_as(file, entry, None)
}

/// [`compile_entry`] in the notation `notation` (`--notation`), else in
/// the one [`front::detect`] chooses; a file that reads badly in the
/// chosen one ([`front::reads_badly`]) and cleanly in another gets that one
/// error (E0015) instead of the reading's errors (a note on its one error,
/// when it has one).
pub fn compile_as(
    file: SourceFile,
    entry: Option<&str>,
    notation: Option<&'static dyn Front>,
) -> Compiled {
    let mut diags = Diagnostics::default();
    if let Some(refused) = refuse_unread(&file) {
        // Not read, so not told apart either: the first front end stands
        // for it.
        diags.push(refused);
        return Compiled {
            file,
            system: None,
            spans: SpanTable::default(),
            diagnostics: diags,
            front: front::FRONTS[0],
            library: None,
            recovered: None,
        };
    }
    let ext = file.extension().unwrap_or("l").to_ascii_lowercase();
    let front = notation.unwrap_or_else(|| front::detect(&ext, &file.text));
    if file.text.trim().is_empty() {
        // Every notation would say something different about nothing.
        diags.push(empty_file(&file));
        return Compiled {
            file,
            system: None,
            spans: SpanTable::default(),
            diagnostics: diags,
            front,
            library: None,
            recovered: None,
        };
    }
    let read = front.read(&file, entry, &mut diags);
    if entry.is_some() && read.library.is_none() {
        diags.push(
            Diagnostic::global(
                codes::FR_UNKNOWN_ENTRY,
                format!(
                    "an entry was chosen, but this file is {} and has no entries",
                    front.title()
                ),
            )
            .with_help(format!(
                "only libraries have entries to choose ({})",
                front::FRONTS
                    .iter()
                    .filter_map(|f| f
                        .library_form()
                        .map(|form| format!("{}: {form}", f.title())))
                    .collect::<Vec<_>>()
                    .join("; ")
            )),
        );
    }
    diags.sort();
    if notation.is_none() && front::reads_badly(&file, &diags) {
        if let Some(other) = front::reads_cleanly_as(&file, front) {
            let told = front::other_notation(front, &ext, other, &diags);
            let errors = diags.iter().filter(|d| d.is_error()).count();
            if errors > 1 {
                // One error that says what happened, not every error of a
                // reading that was never going to work.
                diags = Diagnostics(vec![told]);
            } else if let Some(only) = diags.0.iter_mut().find(|d| d.is_error()) {
                // One error may be the file's own slip: it stays, told
                // what else the file reads as.
                only.notes.push(format!(
                    "{}: {}",
                    told.message,
                    told.help.unwrap_or_default()
                ));
            }
        }
    }
    let (system, spans) = match read.lowered {
        Some(l) => (Some(l.system), l.spans),
        None => (None, SpanTable::default()),
    };
    // Kept aside rather than dropped: the language server finds symbols
    // in the parts of a file being typed that parse.
    let (system, recovered) = if diags.has_errors() {
        (None, system)
    } else {
        (system, None)
    };
    Compiled {
        file,
        system,
        spans,
        diagnostics: diags,
        front,
        library: read.library,
        recovered,
    }
}

/// The notations graftal reads, with their extensions: `pfg .l, …`.
pub fn notations() -> String {
    let each: Vec<String> = front::FRONTS
        .iter()
        .map(|f| format!("{} .{}", f.title(), f.extensions().join(" .")))
        .collect();
    each.join(", ")
}

/// The one diagnostic for a file of nothing but white space, the same
/// in every notation.
fn empty_file(file: &SourceFile) -> Diagnostic {
    Diagnostic::global(
        codes::EMPTY_FILE,
        format!("`{}` is empty: there is no L-system in it", file.name),
    )
    .with_help("write an axiom and productions; `graftal list` names examples to start from")
}

/// The one diagnostic for a file no front end reads: larger than
/// [`MAX_SOURCE_BYTES`], or not text (a picture, a program, random bytes),
/// which would otherwise give one diagnostic per byte.
fn refuse_unread(file: &SourceFile) -> Option<Diagnostic> {
    if let Some(over) = file.oversize() {
        let message = match over.size {
            Some(n) => {
                format!("the file has {n} bytes, more than the {MAX_SOURCE_BYTES} graftal reads")
            }
            // A pipe or a device: read no further than the limit.
            None => format!("the file has more than the {MAX_SOURCE_BYTES} bytes graftal reads"),
        };
        return Some(
            Diagnostic::global(codes::FILE_TOO_LARGE, message).with_help(
                "an L-system file holds rules, not derived words: write the axiom and productions",
            ),
        );
    }
    let why = match file.not_text()? {
        NotText::Nul(at) => {
            let (line, col) = file.line_col(at);
            format!("it holds a NUL byte (line {line}, column {col})")
        }
        NotText::Unprintable(percent) => {
            format!("{percent}% of its first characters are neither printable nor white space")
        }
    };
    Some(
        Diagnostic::global(
            codes::NOT_TEXT,
            format!("`{}` is not a text file", file.name),
        )
        .with_note(why)
        .with_help(format!(
            "graftal reads L-system files, which are plain text: {}",
            notations()
        )),
    )
}
