//! Diagnostics: what every stage reports, and the one place that renders them.
//!
//! A [`Diagnostic`] has a stable [`Code`] (see [`codes`]), a severity, a
//! one-line message, a primary span, secondary labels, notes and a help line.
//! Stages collect them in a [`Diagnostics`] list and keep going (a parser that
//! never fails); the CLI renders them with ariadne (`render`) or as JSON.

pub mod codes;
mod render;

pub use codes::Code;
pub use render::{escaped, render_all, render_human, render_json, shortened, to_json, MAX_SHOWN};

use crate::ir::Span;
use crate::source::SourceFile;
use serde::Serialize;
use std::sync::Arc;

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Error,
    Warning,
}

/// A secondary place in the source, with a message.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    pub span: Span,
    pub message: String,
}

/// One problem found in one source file.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub code: Code,
    pub severity: Severity,
    pub message: String,
    /// The primary span; `None` for problems with no place in a file (e.g. a
    /// derivation too large for `--max-symbols` given on the command line).
    pub span: Option<Span>,
    /// The message shown at the primary span.
    pub label: Option<String>,
    pub labels: Vec<Label>,
    pub notes: Vec<String>,
    pub help: Option<String>,
    /// Set on the last diagnostic kept once a list is full ([`MAX_KEPT`]):
    /// what came after it and was counted, not kept.
    pub not_kept: Option<NotKept>,
    /// The file the spans point into when it is not the file being read:
    /// a side file (a cpfg view, function or surface file), so that the
    /// diagnostic is shown, and listed in JSON, as that file's.
    pub side: Option<Arc<SideFile>>,
    /// The replacement that fixes the problem, when it is known: the help
    /// line says it, and an editor offers it as a quick fix.
    pub fix: Option<Fix>,
}

/// A suggested edit: write `replacement` in place of `span`.
#[derive(Clone, Debug, PartialEq)]
pub struct Fix {
    pub span: Span,
    pub replacement: String,
}

/// A file read beside the one being read, as diagnostics quote it.
#[derive(Clone, Debug, PartialEq)]
pub struct SideFile {
    pub name: String,
    pub text: String,
}

/// Diagnostics found after a list was full ([`MAX_KEPT`]), counted only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NotKept {
    pub errors: usize,
    pub warnings: usize,
}

impl NotKept {
    pub fn total(&self) -> usize {
        self.errors + self.warnings
    }

    fn count(&mut self, d: &Diagnostic) {
        match d.severity {
            Severity::Error => self.errors += 1,
            Severity::Warning => self.warnings += 1,
        }
        if let Some(more) = d.not_kept {
            self.errors += more.errors;
            self.warnings += more.warnings;
        }
    }
}

/// The most diagnostics a list keeps: one long line of repeated mistakes
/// can hold millions, and each costs a few hundred bytes. Those after are
/// counted on the last one kept ([`Diagnostic::not_kept`]).
pub const MAX_KEPT: usize = 100_000;

/// The most characters a message, label, note or help keeps: a message
/// that quotes the input (an unknown header, an unexpected token) would
/// otherwise be as long as the input, in JSON as well as for people.
pub const MAX_TEXT_CHARS: usize = 1000;

/// `text` cut to [`MAX_TEXT_CHARS`]: its start and its end, `…` between.
fn bounded(text: String) -> String {
    if text.len() <= MAX_TEXT_CHARS {
        return text;
    }
    let n = text.chars().count();
    if n <= MAX_TEXT_CHARS {
        return text;
    }
    let tail = MAX_TEXT_CHARS / 3;
    let head: String = text.chars().take(MAX_TEXT_CHARS - tail - 1).collect();
    let end: String = text.chars().skip(n - tail).collect();
    format!("{head}…{end}")
}

impl Diagnostic {
    fn new(code: Code, message: impl Into<String>) -> Self {
        Diagnostic {
            code,
            severity: code.severity(),
            message: bounded(message.into()),
            span: None,
            label: None,
            labels: Vec::new(),
            notes: Vec::new(),
            help: None,
            not_kept: None,
            side: None,
            fix: None,
        }
    }

    /// A diagnostic with code `code` (its severity comes from the code).
    pub fn at(code: Code, span: Span, message: impl Into<String>) -> Self {
        let mut d = Diagnostic::new(code, message);
        d.span = Some(span);
        d
    }

    /// A diagnostic with no place in a file.
    pub fn global(code: Code, message: impl Into<String>) -> Self {
        Diagnostic::new(code, message)
    }

    pub fn with_label(mut self, message: impl Into<String>) -> Self {
        self.label = Some(bounded(message.into()));
        self
    }

    pub fn with_secondary(mut self, span: Span, message: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            message: bounded(message.into()),
        });
        self
    }

    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(bounded(note.into()));
        self
    }

    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(bounded(help.into()));
        self
    }

    /// "did you mean `replacement`?", and the fix that writes it over the
    /// primary span (the name mistyped): one value for the help line and
    /// the editor's quick fix.
    pub fn suggesting(self, replacement: impl std::fmt::Display) -> Self {
        let replacement = replacement.to_string();
        let help = format!("did you mean `{replacement}`?");
        match self.span.clone() {
            Some(span) => self.with_fix(span, replacement, help),
            None => self.with_help(help),
        }
    }

    /// The fix that writes `replacement` over `span`, with `help` saying it.
    pub fn with_fix(mut self, span: Span, replacement: String, help: String) -> Self {
        self.fix = Some(Fix { span, replacement });
        self.with_help(help)
    }

    /// The same diagnostic, its spans in `side` rather than in the file
    /// being read.
    pub fn in_side_file(mut self, side: Arc<SideFile>) -> Self {
        self.side = Some(side);
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// The notes, and for the last diagnostic kept of a full list, one
    /// that says how many more were found.
    pub fn all_notes(&self) -> impl Iterator<Item = std::borrow::Cow<'_, str>> {
        let more = self.not_kept.map(|n| {
            std::borrow::Cow::Owned(format!(
                "graftal keeps the first {MAX_KEPT} diagnostics of a file: {} more ({} errors, {} warnings) were found after them and not kept",
                n.total(),
                n.errors,
                n.warnings
            ))
        });
        self.notes
            .iter()
            .map(|n| std::borrow::Cow::Borrowed(n.as_str()))
            .chain(more)
    }
}

/// Diagnostics collected by a stage, in the order found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostics {
    /// Adds `d`, or counts it once [`MAX_KEPT`] are kept.
    pub fn push(&mut self, d: Diagnostic) {
        if self.0.len() < MAX_KEPT {
            self.0.push(d);
        } else {
            self.count_not_kept(d);
        }
    }

    /// Counts `d` on the last diagnostic kept. An error takes the place of
    /// a warning there, so a list with errors still has one.
    fn count_not_kept(&mut self, d: Diagnostic) {
        let Some(last) = self.0.last_mut() else {
            return self.0.push(d);
        };
        let mut counted = last.not_kept.take().unwrap_or_default();
        let dropped = if d.is_error() && !last.is_error() {
            std::mem::replace(last, d)
        } else {
            d
        };
        counted.count(&dropped);
        if let Some(more) = last.not_kept.take() {
            counted.errors += more.errors;
            counted.warnings += more.warnings;
        }
        last.not_kept = Some(counted);
    }

    /// Whether [`MAX_KEPT`] are kept: what is pushed now is only counted,
    /// so a stage may stop building diagnostics for repeated mistakes.
    pub fn is_full(&self) -> bool {
        self.0.len() >= MAX_KEPT
    }

    pub fn extend(&mut self, other: Diagnostics) {
        for d in other.0 {
            self.push(d);
        }
    }
    /// Reports the invalid character at `span` of `src` (E0001), merging it
    /// into the previous report when that one ends where this begins: a run
    /// of invalid characters is one problem.
    pub fn push_invalid_character(&mut self, src: &str, span: Span) {
        if let Some(last) = self.0.last_mut() {
            if last.code == codes::INVALID_CHARACTER
                && last.span.as_ref().is_some_and(|s| s.end == span.start)
            {
                let start = last.span.as_ref().map_or(span.start, |s| s.start);
                last.span = Some(start..span.end);
                last.message = "invalid characters".to_string();
                return;
            }
        }
        let ch = src[span.clone()].chars().next().unwrap_or('\0');
        self.push(
            Diagnostic::at(
                codes::INVALID_CHARACTER,
                span,
                format!("invalid character U+{:04X}", ch as u32),
            )
            .with_label("not a symbol")
            .with_help("remove this character; symbols are printable characters"),
        )
    }
    pub fn has_errors(&self) -> bool {
        self.0.iter().any(Diagnostic::is_error)
    }
    pub fn iter(&self) -> impl Iterator<Item = &Diagnostic> {
        self.0.iter()
    }
    pub fn len(&self) -> usize {
        self.0.len()
    }
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    /// Sorts by position (stable, so diagnostics at one place keep their
    /// order); global diagnostics and those of side files come last.
    pub fn sort(&mut self) {
        self.0.sort_by_key(|d| match (&d.span, &d.side) {
            (Some(s), None) => s.start,
            _ => usize::MAX,
        });
    }
    /// Renders all for people (see [`render_human`]).
    pub fn render(&self, file: &SourceFile, colour: bool) -> String {
        render_all(&self.0, file, colour)
    }
}

/// The Levenshtein distance between two strings (by characters).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        cur[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cost = usize::from(ca != cb);
            cur[j + 1] = (prev[j] + cost).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// The candidates nearest to `name` (case-insensitive), best first, if any is
/// close enough to be a likely misspelling.
pub fn nearest<'a>(name: &str, candidates: &[&'a str]) -> Vec<&'a str> {
    let lower = name.to_lowercase();
    let limit = (lower.chars().count() / 3).max(2);
    let mut scored: Vec<(usize, &str)> = candidates
        .iter()
        .map(|c| (edit_distance(&lower, &c.to_lowercase()), *c))
        .filter(|(d, _)| *d <= limit)
        .collect();
    scored.sort();
    let best = scored.first().map(|(d, _)| *d);
    scored
        .into_iter()
        .take_while(|(d, _)| Some(*d) == best)
        .map(|(_, c)| c)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texts_that_quote_the_input_are_cut_to_their_ends() {
        let token = format!("<{}>", "é".repeat(50_000));
        let d = Diagnostic::global(codes::SYNTAX, format!("unexpected `{token}`"))
            .with_label(token.clone())
            .with_note(token.clone())
            .with_help(token.clone())
            .with_secondary(0..1, token.clone());
        for text in [
            &d.message,
            d.label.as_ref().unwrap(),
            &d.notes[0],
            d.help.as_ref().unwrap(),
            &d.labels[0].message,
        ] {
            assert_eq!(text.chars().count(), MAX_TEXT_CHARS);
            assert!(text.contains('…'));
            assert!(
                text.ends_with(">`") || text.ends_with('>'),
                "{}",
                &text[text.len() - 8..]
            );
        }
        assert!(d.message.starts_with("unexpected `<é"));
        let short = Diagnostic::global(codes::SYNTAX, "unexpected `x`");
        assert_eq!(short.message, "unexpected `x`");
    }

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("axiom", "axiom"), 0);
        assert_eq!(edit_distance("axiim", "axiom"), 1);
        assert_eq!(edit_distance("angel factor", "angle factor"), 2);
        assert_eq!(edit_distance("", "abc"), 3);
    }

    #[test]
    fn nearest_suggests_close_keywords_only() {
        let keys = ["derivation length", "angle factor", "axiom"];
        assert_eq!(
            nearest("derivaton length", &keys),
            vec!["derivation length"]
        );
        assert_eq!(nearest("Axiom", &keys), vec!["axiom"]);
        assert!(nearest("colour table", &keys).is_empty());
    }

    fn warning(at: usize) -> Diagnostic {
        Diagnostic::at(codes::SHADOWED_PRODUCTION, at..at + 1, "shadowed")
    }

    #[test]
    fn a_full_list_counts_what_comes_after_and_keeps_an_error() {
        let mut list = Diagnostics::default();
        for i in 0..MAX_KEPT + 10 {
            list.push(warning(i));
        }
        assert_eq!(list.len(), MAX_KEPT);
        assert!(list.is_full());
        assert!(!list.has_errors());
        let last = list.0.last().unwrap();
        assert_eq!(last.span, Some(MAX_KEPT - 1..MAX_KEPT));
        assert_eq!(
            last.not_kept,
            Some(NotKept {
                errors: 0,
                warnings: 10
            })
        );
        // An error past the limit takes the last place: the list still
        // has errors.
        let error = Diagnostic::at(codes::SYNTAX, 7..8, "late error");
        list.push(error.clone());
        list.push(warning(0));
        assert_eq!(list.len(), MAX_KEPT);
        assert!(list.has_errors());
        let last = list.0.last().unwrap();
        assert_eq!(last.message, "late error");
        assert_eq!(
            last.not_kept,
            Some(NotKept {
                errors: 0,
                warnings: 12
            })
        );
        let note = last.all_notes().last().unwrap().into_owned();
        assert!(note.contains("12 more (0 errors, 12 warnings)"), "{note}");
        // Sorting and merging lists keep the count.
        list.sort();
        let mut merged = Diagnostics::default();
        merged.push(error);
        merged.extend(list);
        assert_eq!(merged.len(), MAX_KEPT);
        let counted: usize = merged
            .iter()
            .filter_map(|d| d.not_kept)
            .map(|n| n.total())
            .sum();
        assert_eq!(counted, 13);
    }
}
