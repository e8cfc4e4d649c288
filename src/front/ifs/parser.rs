//! The IFS parser: entries found as Fractint finds them (the library
//! scanner, [`crate::front::library::scan`]), each line of an entry read
//! as a map's numbers.
//!
//! Fractint's `ifsload` reads an entry's numbers one word after the other
//! with C's `%f` until a word that starts with `}`, so a `}` closes the
//! entry wherever it stands; graftal reads the same numbers line by line,
//! so that a line of the wrong length is reported where it is. Words are
//! separated by blanks (space, tab, vertical tab, form feed); `;` starts a
//! comment.

use super::ast::{File, Line, Number};
use crate::diagnostics::{codes, Code, Diagnostic, Diagnostics};
use crate::front::library::{self, Tok};
use crate::ir::Span;

/// Parses an IFS library. Never fails: problems are pushed to `diags`.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let scanned = library::scan(src, &mut MapLines, diags);
    outside_entries(src, &scanned, diags);
    File {
        entries: scanned.entries,
    }
}

/// An IFS entry's lines, for the library scanner.
struct MapLines;

impl library::Lines for MapLines {
    type Line = Line;
    const UNCLOSED: Code = codes::IFS_UNCLOSED_ENTRY;
    const CLOSES_WITHIN_A_LINE: bool = true;

    /// A line `Name {` whose name is not a number.
    fn opens_entry(&self, name: &str, _: &[Tok<'_>]) -> bool {
        number(name).is_none()
    }

    fn line(&mut self, src: &str, span: Span, _: bool, diags: &mut Diagnostics) -> Option<Line> {
        Some(read_line(src, span, diags))
    }
}

/// A blank, or a control character (reported by the lexer, E0001), which
/// parts words as a blank does.
fn is_blank(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\x0b' | '\x0c') || c.is_control()
}

/// The words of `src[span]` with their spans.
fn words(src: &str, span: Span) -> impl Iterator<Item = (&str, Span)> {
    let start = span.start;
    let text = &src[span];
    text.split(is_blank)
        .filter(|w| !w.is_empty())
        .map(move |w| {
            let at = start + (w.as_ptr() as usize - text.as_ptr() as usize);
            (w, at..at + w.len())
        })
}

/// A word read as a number, as C's `%f` reads a whole word: a finite
/// decimal (`0.5`, `.5`, `-.04`, `1e-3`).
pub fn number(word: &str) -> Option<f64> {
    let starts_well = word
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_digit() || matches!(c, '+' | '-' | '.'));
    let v: f64 = word.parse().ok().filter(|_| starts_well)?;
    v.is_finite().then_some(v)
}

/// One line of an entry: its numbers; the first word that is not one is
/// reported (E1103), with how many more the line has.
pub fn read_line(src: &str, span: Span, diags: &mut Diagnostics) -> Line {
    let mut numbers = Vec::new();
    let mut bad: Vec<(&str, Span)> = Vec::new();
    for (w, at) in words(src, span.clone()) {
        match number(w) {
            Some(value) => numbers.push(Number { value, span: at }),
            None => bad.push((w, at)),
        }
    }
    if let Some((w, at)) = bad.first() {
        let mut d = not_a_number(w, at.clone());
        if bad.len() > 1 {
            d = d.with_note(format!(
                "{} more words of this line are not numbers either",
                bad.len() - 1
            ));
        }
        diags.push(d);
    }
    Line {
        span,
        numbers,
        broken: !bad.is_empty(),
    }
}

/// E1103 for the word `w`.
fn not_a_number(w: &str, at: Span) -> Diagnostic {
    let shown = crate::diagnostics::shortened(w, 40);
    let d = Diagnostic::at(
        codes::IFS_NOT_A_NUMBER,
        at,
        format!("`{shown}` is not a number"),
    );
    let parses = w.parse::<f64>().is_ok_and(|v| !v.is_finite());
    let trimmed = w.trim_end_matches([',', ';']);
    if parses && w.bytes().any(|b| b.is_ascii_digit()) {
        d.with_label("too large for a number")
            .with_help("a map's numbers are decimals within floating point, such as `0.5`")
    } else if trimmed != w && number(trimmed).is_some() {
        d.with_label("a number and a comma")
            .with_help("numbers are separated by spaces only: drop the comma")
    } else {
        d.with_label("a map is a line of numbers only")
            .with_help("write decimal numbers such as `0.5` or `-.04`, separated by spaces")
    }
}

/// E1102 for lines of numbers outside every entry: once for each run of
/// them, pointing at the line before it when that may be the name of an
/// entry whose `{` is missing.
fn outside_entries(src: &str, scanned: &library::Scanned<Line>, diags: &mut Diagnostics) {
    let numeric = |span: &Span| {
        let mut any = false;
        for (w, _) in words(src, span.clone()) {
            if number(w).is_none() {
                return false;
            }
            any = true;
        }
        any
    };
    // Whether an entry lies between two places.
    let entry_between = |a: usize, b: usize| {
        let i = scanned.entries.partition_point(|e| e.span.start < a);
        scanned.entries.get(i).is_some_and(|e| e.span.start < b)
    };
    let mut before: Option<(&Span, bool)> = None;
    for span in &scanned.outside {
        let is_numeric = numeric(span);
        let continues = before.is_some_and(|(b, n)| n && !entry_between(b.end, span.start));
        if is_numeric && !continues {
            let name = before
                .filter(|(b, n)| !n && !entry_between(b.end, span.start))
                .map(|(b, _)| b.clone());
            let d = Diagnostic::at(
                codes::IFS_OUTSIDE_ENTRY,
                span.clone(),
                "numbers outside every entry",
            )
            .with_label("this map belongs to no entry");
            let d = match name {
                Some(b) => {
                    let shown = crate::diagnostics::shortened(src[b.clone()].trim(), 40);
                    d.with_secondary(b, "an entry's name without its `{`?")
                        .with_help(format!("open the entry with `{shown} {{`"))
                }
                None => d.with_help("open an entry with `Name {` before its maps"),
            };
            diags.push(d);
        }
        before = Some((span, is_numeric));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::parse::{parse_clean, parse_codes};

    #[test]
    fn numbers_read_as_percent_f_reads_whole_words() {
        for (w, v) in [
            (".5", 0.5),
            ("-.04", -0.04),
            ("1e-3", 1e-3),
            ("+2", 2.0),
            ("5.", 5.0),
        ] {
            assert_eq!(number(w), Some(v), "{w}");
        }
        for w in [
            "inf", "NaN", "1e400", "0.5,", "a", "{", "=", "--1", "infinity",
        ] {
            assert_eq!(number(w), None, "{w}");
        }
    }

    #[test]
    fn entries_lines_and_the_3d_mark() {
        let src = " t (3D) { ; c\n .5 0 0 0 .5 0 0 0 .5 0 0 1 1\n}\nu {\n.5 0 0 .5 0 0 1 }\n";
        let f = parse_clean(parse, src);
        assert_eq!(f.entries.len(), 2);
        let t = &f.entries[0];
        assert_eq!(&src[t.header.clone().unwrap()].trim(), &"(3D)");
        assert_eq!(t.lines.len(), 1);
        assert_eq!(t.lines[0].numbers.len(), 13);
        assert_eq!(f.entries[1].lines[0].numbers.len(), 7);
        assert!(f.entries[1].closed);
    }

    #[test]
    fn a_word_that_is_not_a_number_is_reported_once_a_line() {
        let mut d = Diagnostics::default();
        let f = parse("e {\n .5, 0 x 0 y\n}\n", &mut d);
        assert_eq!(d.len(), 1);
        assert_eq!(d.0[0].code, codes::IFS_NOT_A_NUMBER);
        assert_eq!(d.0[0].span, Some(5..8));
        assert!(d.0[0].help.as_deref().unwrap().contains("comma"));
        assert!(d.0[0].notes[0].starts_with("2 more"));
        assert!(f.entries[0].lines[0].broken);
    }

    #[test]
    fn maps_outside_entries_are_reported_once_a_run() {
        let src = "fern\n 0 0 0 .16 0 0 .01\n .85 .04 -.04 .85 0 1.6 .85\n}\n";
        let mut d = Diagnostics::default();
        parse(src, &mut d);
        assert_eq!(d.len(), 1, "{d:#?}");
        assert_eq!(d.0[0].code, codes::IFS_OUTSIDE_ENTRY);
        assert_eq!(&src[d.0[0].span.clone().unwrap()], "0 0 0 .16 0 0 .01");
        assert_eq!(d.0[0].help.as_deref(), Some("open the entry with `fern {`"));
        assert_eq!(parse_codes(parse, "a { 1 }\n1 2\n"), ["E1102"]);
        // Prose outside entries is skipped, as Fractint skips it.
        assert!(parse_codes(parse, "IFS codes by someone\na { 1 }\n").is_empty());
    }
}
