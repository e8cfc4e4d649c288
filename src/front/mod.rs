//! Front ends: one folder per notation, each behind [`Front`], all listed in
//! [`FRONTS`]. A front end reads a source file into the one IR
//! ([`crate::ir::System`]) with its spans and diagnostics; nothing after it
//! knows which notation a system came from.
//!
//! Adding a notation is a folder here (lexer, parser, AST, lowering, and a
//! unit struct implementing [`Front`], which also answers what the language
//! server asks of the notation: keywords, comments, declared names, user
//! functions) and one line in [`FRONTS`]; the README ("How graftal is
//! built") lists the other places a notation touches. Choosing
//! the front for a file is [`detect`]: by extension where only one front
//! claims it, by content where several share it (`.l` is pfg, cpfg and
//! Fractint). The content rule, from the survey of the three `.l` dialects'
//! corpora: with `;` comments removed, a line `Name {` and no `-->`
//! anywhere is Fractint (pfg and cpfg productions always have `-->`,
//! Fractint never does); otherwise a line starting with `lsystem:`,
//! `endlsystem` or a `#define`/`#include`/`#if` directive is cpfg;
//! everything else is pfg, graftal's oldest front end.

pub mod comments;
pub mod cpfg;
pub mod declared;
pub mod depth;
pub mod fractint;
pub mod gft;
pub mod graph;
pub mod ifs;
pub mod library;
pub mod linf;
pub mod names;
pub mod parse;
pub mod pfg;
pub mod repeats;
pub mod smith;
pub mod stl;
pub mod suggest;

use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::{Lowered, Span, System, Word};
use crate::source::SourceFile;
pub use declared::{Declaration, DeclarationKind, FunctionSite};
use serde::Serialize;
use std::path::Path;

pub(crate) use comments::{
    block_comments, line_comments, skip_block_comment, strip_block_comments,
};
pub use parse::syntax_error;

/// Every notation graftal reads. The order breaks ties in [`detect`].
pub static FRONTS: &[&dyn Front] = &[
    &pfg::Pfg,
    &linf::Linf,
    &stl::Stl,
    &cpfg::Cpfg,
    &fractint::Fractint,
    &smith::Smith,
    &gft::Gft,
    &ifs::Ifs,
];

/// How sure a front end is that a text is in its notation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Confidence {
    /// Not this notation (or not told by content at all).
    No,
    /// This notation when no other claims the text.
    Fallback,
    /// Marks of this notation.
    Likely,
    /// Marks no other notation has.
    Certain,
}

/// A notation graftal reads.
pub trait Front: Sync {
    /// The name as the command line and the registry spell it (`pfg`,
    /// `linf`, …).
    fn name(&self) -> &'static str;
    /// The name shown to people (`LinF`, `STL`, `Fractint`, …).
    fn title(&self) -> &'static str;
    /// File extensions (lowercase, without the dot) of this notation.
    fn extensions(&self) -> &'static [&'static str];
    /// How sure this front end is, from the text alone, that `text` is its
    /// notation (only asked when several front ends share an extension,
    /// or none claims it).
    fn detect(&self, _text: &str) -> Confidence {
        Confidence::No
    }
    /// Reads `file` into the IR. `entry` chooses an entry of a library
    /// (only notations with [`Read::library`] have entries).
    fn read(&self, file: &SourceFile, entry: Option<&str>, diags: &mut Diagnostics) -> Read;
    /// A derived word as text in this notation: symbols side by side, and
    /// a module's parameters in parentheses.
    fn word_text(&self, sys: &System, word: &Word) -> String {
        word.display(&sys.symbols)
    }
    /// Whether [`Front::word_text`] is the symbols' names side by side, so
    /// that a word can be written name by name as it is derived.
    fn spells_words_by_name(&self) -> bool {
        true
    }
    /// The comments of a source text: (span, text without the delimiters),
    /// for emitters that carry comments over.
    fn comments(&self, _src: &str) -> Vec<(Span, String)> {
        Vec::new()
    }
    /// How a library of several systems is written in this notation, for
    /// a notation that has libraries (`Name { … }` entries in Fractint).
    fn library_form(&self) -> Option<&'static str> {
        None
    }
    /// What `check` says about a file of this notation beyond its
    /// diagnostics (after `FILE: dialect: `), if anything: by default,
    /// for a file read without errors, the notation and how many
    /// productions it has.
    fn describe(&self, sys: Option<&System>) -> Option<String> {
        let n = sys?.productions.len();
        Some(format!(
            "{}, {n} production{}",
            self.title(),
            if n == 1 { "" } else { "s" }
        ))
    }
    /// The turn divided into whole angle increments as the source states
    /// it (pfg's `angle factor`), which a translation keeps when it fits.
    fn angle_divisions(&self, _sys: &System) -> Option<u64> {
        None
    }

    // What the language server asks of a notation, so that it matches on
    // no notation's name: each front end answers for itself.

    /// The keywords of this notation, as its parser spells them (for
    /// completion).
    fn keywords(&self) -> Vec<&'static str> {
        Vec::new()
    }
    /// The spans of a source text's comments, in order, as this notation's
    /// lexer finds them: by default those of [`Front::comments`].
    fn comment_spans(&self, src: &str) -> Vec<Span> {
        self.comments(src)
            .into_iter()
            .map(|(span, _)| span)
            .collect()
    }
    /// The names a source text declares besides its symbols (rules,
    /// rotations, macros, library entries), comments included: the
    /// language server leaves out what a comment holds.
    fn declarations(&self, _src: &str) -> Vec<Declaration> {
        Vec::new()
    }
    /// Where a source text uses declared names, as its syntax tree says:
    /// each use's name and span. `None` (the default): every word outside
    /// comments spelt as a declared name is a use of it.
    fn declared_name_uses(&self, _src: &str) -> Option<Vec<(String, Span)>> {
        None
    }
    /// The user functions that the files beside the source at `path`
    /// declare, numbered as the source calls them.
    fn user_functions(&self, _path: &Path) -> Vec<FunctionSite> {
        Vec::new()
    }
    /// The number or name of the user function a source text calls at byte
    /// `at`, when `at` is on it (outside comments).
    fn user_function_called_at<'t>(&self, _src: &'t str, _at: usize) -> Option<&'t str> {
        None
    }
}

/// What a front end read: the system (`None` for a library whose entry
/// was not chosen, or when nothing could be lowered) and, for a library,
/// its entries.
pub struct Read {
    pub lowered: Option<Lowered>,
    pub library: Option<Library>,
}

impl From<Lowered> for Read {
    fn from(lowered: Lowered) -> Self {
        Read {
            lowered: Some(lowered),
            library: None,
        }
    }
}

/// A file of several systems (a Fractint library).
#[derive(Clone, Debug, Default)]
pub struct Library {
    pub entries: Vec<EntryInfo>,
    /// The entry read (an index into `entries`).
    pub chosen: Option<usize>,
    /// Several entries and none chosen: no system, and no error yet.
    pub needs_entry: bool,
    /// What `check` prints after `FILE: dialect: ` (the notation, the
    /// number of entries, how to choose).
    pub summary: String,
}

/// One entry of a library, as `check` lists it.
#[derive(Clone, Debug, Serialize)]
pub struct EntryInfo {
    pub name: String,
    /// The name's place in the file.
    pub span: Span,
    pub errors: usize,
    pub warnings: usize,
}

/// The front end for a file with extension `ext` (any case, without the
/// dot) and content `text`: the one front end that claims the extension,
/// else the most confident of those that share it (or, for an extension
/// none claims, of all), earlier in [`FRONTS`] on a tie.
pub fn detect(ext: &str, text: &str) -> &'static dyn Front {
    let ext = ext.to_ascii_lowercase();
    let claiming: Vec<&'static dyn Front> = FRONTS
        .iter()
        .copied()
        .filter(|f| f.extensions().contains(&ext.as_str()))
        .collect();
    if let [only] = claiming.as_slice() {
        return *only;
    }
    let candidates = if claiming.is_empty() {
        FRONTS.to_vec()
    } else {
        claiming
    };
    let mut best = candidates[0];
    let mut best_confidence = best.detect(text);
    for f in &candidates[1..] {
        let c = f.detect(text);
        if c > best_confidence {
            (best, best_confidence) = (*f, c);
        }
    }
    best
}

/// The largest file [`reads_badly`] considers for reading in another notation.
pub const GUESS_AT_MOST_BYTES: usize = 256 << 10;

/// How many errors make a reading worth trying in the other notations,
/// whatever lines they cover.
const SEVERAL_ERRORS: usize = 3;

/// Whether a reading of `file` failed badly enough that the file is more
/// likely in another notation: it has errors, and their spans cover at
/// least half of the file's non-blank lines (a LinF file read as pfg: 20
/// errors on its 22 lines; an STL file read as LinF: one error over 5 of
/// its 8 lines; a pfg file with a typo: one error on one line). An error
/// with no place (nothing found at all) counts as covering every line.
/// [`SEVERAL_ERRORS`] count as failing badly wherever they stand.
pub fn reads_badly(file: &SourceFile, diags: &Diagnostics) -> bool {
    // A file saved under the wrong extension is a hand-written model; a
    // bigger one is not read again in four more notations (a 4 MB line of
    // errors would take seconds).
    if !diags.has_errors() || file.text.len() > GUESS_AT_MOST_BYTES {
        return false;
    }
    // Several errors are reason enough to look: a LinF file read as a
    // Fractint library (its `{` looks like an entry) has errors at a few
    // names only, however wrong the whole reading is.
    if diags.iter().filter(|d| d.is_error()).count() >= SEVERAL_ERRORS {
        return true;
    }
    let lines: Vec<&str> = file.text.split('\n').collect();
    let mut covered = vec![false; lines.len()];
    for d in diags.iter().filter(|d| d.is_error()) {
        let Some(span) = &d.span else { return true };
        let first = file.line_col(span.start).0;
        let last = file.line_col(span.end.max(span.start + 1) - 1).0.max(first);
        for c in covered.iter_mut().take(last).skip(first - 1) {
            *c = true;
        }
    }
    let non_blank = lines.iter().filter(|l| !l.trim().is_empty()).count();
    let bad = lines
        .iter()
        .zip(&covered)
        .filter(|(l, &c)| c && !l.trim().is_empty())
        .count();
    2 * bad >= non_blank
}

/// The first front end other than `first` that reads `file` cleanly: no
/// errors, and an axiom or a production (or, for a library, an entry).
/// Tried in [`FRONTS`] order, each on its own diagnostics.
pub fn reads_cleanly_as(file: &SourceFile, first: &dyn Front) -> Option<&'static dyn Front> {
    FRONTS.iter().copied().find(|f| {
        if f.name() == first.name() {
            return false;
        }
        let mut d = Diagnostics::default();
        let read = f.read(file, None, &mut d);
        let something = read.library.as_ref().is_some_and(|l| !l.entries.is_empty())
            || read
                .lowered
                .as_ref()
                .is_some_and(|l| !l.system.productions.is_empty() || !l.system.axiom.is_empty());
        !d.has_errors() && something
    })
}

/// The one error for a file read as `first` (by its extension `ext`,
/// without the dot) that reads badly there (`diags`) and cleanly as
/// `other`: which notation was assumed, and how to read it as the other
/// (renaming it only when that gives the other notation its own
/// extension). It stands at the first error, which a note quotes.
pub fn other_notation(
    first: &dyn Front,
    ext: &str,
    other: &dyn Front,
    diags: &Diagnostics,
) -> Diagnostic {
    let own_ext = other
        .extensions()
        .iter()
        .find(|e| FRONTS.iter().filter(|f| f.extensions().contains(e)).count() == 1);
    let how = match own_ext {
        Some(e) if *e != ext => format!("rename it `.{e}` or pass `--notation {}`", other.name()),
        _ => format!("pass `--notation {}`", other.name()),
    };
    let message = format!(
        "this file reads as {}, not as {} (from `.{ext}`)",
        other.title(),
        first.title()
    );
    let errors: Vec<&Diagnostic> = diags.iter().filter(|d| d.is_error()).collect();
    let d = match errors.first().and_then(|e| e.span.clone()) {
        Some(span) => Diagnostic::at(codes::OTHER_NOTATION, span, message).with_label(format!(
            "read as {}, the first of {} errors is here",
            first.title(),
            errors.len()
        )),
        None => Diagnostic::global(codes::OTHER_NOTATION, message),
    };
    let d = match errors.first() {
        Some(e) => d.with_note(format!("as {}: [{}] {}", first.title(), e.code, e.message)),
        None => d,
    };
    d.with_help(how)
}

/// The front end registered as `name`.
pub fn by_name(name: &str) -> Option<&'static dyn Front> {
    FRONTS.iter().copied().find(|f| f.name() == name)
}

/// The error for a library whose entry was not chosen (see
/// [`Library::needs_entry`]), listing the entries.
pub fn choose_entry(file_name: &str, title: &str, lib: &Library) -> Diagnostic {
    let names: Vec<&str> = lib.entries.iter().map(|e| e.name.as_str()).collect();
    let first = names.first().copied().unwrap_or("NAME");
    Diagnostic::global(
        codes::FR_CHOOSE_ENTRY,
        format!(
            "`{file_name}` is a {title} library of {} entries: choose one",
            names.len()
        ),
    )
    .with_note(format!(
        "entries: {}",
        name_list(names.iter().copied(), false)
    ))
    .with_help(format!(
        "write `{file_name}:{first}` or add `--entry {first}`; `graftal check` lists the entries"
    ))
}

/// The most names a diagnostic lists (the entries of a library): a note
/// is one line, and a library may have 100,000 entries.
pub const LISTED_NAMES: usize = 20;

/// The most characters of names a list shows: a diagnostic's text is cut
/// in the middle past 200 characters, which would drop names from the
/// middle of the list without saying how many.
const LISTED_WIDTH: usize = 150;

/// `names` separated by commas (each in backticks when `quoted`), the
/// first [`LISTED_NAMES`] of them (fewer when long names would pass
/// [`LISTED_WIDTH`]), then how many more there are. Only those shown are
/// read from `names`.
pub fn name_list<'a, I>(names: I, quoted: bool) -> String
where
    I: IntoIterator<Item = &'a str>,
    I::IntoIter: ExactSizeIterator,
{
    let names = names.into_iter();
    let total = names.len();
    let mut shown: Vec<String> = Vec::new();
    let mut width = 0;
    for n in names.take(LISTED_NAMES) {
        let n = if quoted {
            format!("`{n}`")
        } else {
            n.to_string()
        };
        width += n.chars().count() + 2;
        // The first name is always shown, however long.
        if width > LISTED_WIDTH && !shown.is_empty() {
            break;
        }
        shown.push(n);
    }
    let more = total - shown.len();
    let shown = shown.join(", ");
    match more {
        0 => shown,
        more => format!("{shown}, … and {more} more"),
    }
}

/// The system `read` lowers from a text that must be free of errors (the
/// front ends' `read_ok`, for tests and examples).
///
/// # Panics
/// When reading reports an error; the message lists the diagnostics.
pub fn read_clean(read: impl FnOnce(&mut Diagnostics) -> Lowered) -> System {
    let mut d = Diagnostics::default();
    let l = read(&mut d);
    assert!(!d.has_errors(), "{d:#?}");
    l.system
}

#[cfg(test)]
mod tests {
    use super::*;

    fn named(ext: &str, text: &str) -> &'static str {
        detect(ext, text).name()
    }

    #[test]
    fn tells_the_l_dialects_apart_by_content() {
        let fr = "; comment\nKoch1 { ; by X\n  Angle 6\n  Axiom F--F--F\n  F=F+F--F+F\n}\n";
        assert_eq!(named("l", fr), "fractint");
        assert_eq!(named("l", "Lars1{\nangle 4\naxiom f\n}"), "fractint");
        let pfg = "derivation length: 2\naxiom: {f+f}F\nF --> F+F\n";
        assert_eq!(named("l", pfg), "pfg");
        // A pfg header with a brace in its value is not an entry.
        assert_eq!(named("l", "axiom: {F}\n"), "pfg");
        // Nor a brace in a pfg comment, in a file without productions.
        assert_eq!(named("l", "/* lines {\n */\naxiom: A\n"), "pfg");
        let cpfg = "#define N 3\nlsystem: 1\naxiom: A\nA --> B\nendlsystem\n";
        assert_eq!(named("l", cpfg), "cpfg");
        assert_eq!(named("l", "/* x */\nLsystem : 1\nA-->B\n"), "cpfg");
        // cpfg blocks `{ … }` come with productions.
        assert_eq!(
            named("l", "lsystem: 1\nA --> B\nS {\n}\nendlsystem\n"),
            "cpfg"
        );
        assert_eq!(named("linf", fr), "linf");
        assert_eq!(named("stl", fr), "stl");
        assert_eq!(named("l", ""), "pfg");
    }

    #[test]
    fn long_names_are_listed_whole_then_counted() {
        let long: Vec<String> = (0..30)
            .map(|i| format!("SomeRatherLongEntryName{i}"))
            .collect();
        let listed = name_list(long.iter().map(String::as_str), false);
        assert!(listed.chars().count() < 200, "{listed}");
        let shown = listed.matches("SomeRatherLongEntryName").count();
        assert!(
            listed.ends_with(&format!(", … and {} more", 30 - shown)),
            "{listed}"
        );
        // Each name shown is whole, in order from the first.
        for (k, name) in listed.split(", ").take(shown).enumerate() {
            assert_eq!(name, long[k]);
        }
    }

    #[test]
    fn name_lists_stop_after_a_few_names() {
        assert_eq!(name_list(["a", "b"], false), "a, b");
        assert_eq!(name_list(["a", "b"], true), "`a`, `b`");
        let many: Vec<String> = (0..LISTED_NAMES + 5).map(|i| format!("e{i}")).collect();
        let many: Vec<&str> = many.iter().map(String::as_str).collect();
        let listed = name_list(many.iter().copied(), false);
        assert!(listed.starts_with("e0, e1, "), "{listed}");
        assert!(listed.ends_with(&format!("e{}, … and 5 more", LISTED_NAMES - 1)));
        assert_eq!(
            name_list(many[..LISTED_NAMES].iter().copied(), false)
                .matches(", ")
                .count(),
            LISTED_NAMES - 1
        );
    }

    #[test]
    fn one_claiming_extension_decides() {
        assert_eq!(named("linf", "Koch1 {\n}\n"), "linf");
        assert_eq!(named("STL", "axiom: F\n"), "stl");
        // An extension nobody claims is told by content, as `.l` is.
        assert_eq!(named("txt", "axiom: F\nF --> F+F\n"), "pfg");
    }

    #[test]
    fn every_front_has_a_distinct_name_and_an_extension() {
        let mut names: Vec<&str> = FRONTS.iter().map(|f| f.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), FRONTS.len());
        for f in FRONTS {
            assert!(!f.extensions().is_empty(), "{}", f.name());
            assert_eq!(by_name(f.name()).map(|g| g.title()), Some(f.title()));
        }
    }
}
