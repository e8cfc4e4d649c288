//! The Fractint parser: the tokens cut at line ends into lines; the entry
//! structure and each line's meaning follow Fractint's reader.
//!
//! Entries (Fractint's entry scanner): a line `Name {` (the name ends at a
//! blank, `(` or `{`) opens an entry and the rest of that line is its first
//! line; a line whose first token is `}` closes it. `comment { … }` blocks
//! and nameless `{ … }` blocks are not entries: they end at the first `}`.
//! A line inside an entry that opens another entry means the `}` is missing
//! (E0701): the entry ends there, so the next one still reads.
//!
//! Lines (Fractint's `readLSystemFile`, after cutting the `;` comment and
//! lowercasing): the first word ends at a blank or `=`; its string is the
//! next run of non-blank characters after that one delimiter; anything
//! after the string is extra text. So `x=-FX`, `axiom=FX` and `Angle 6`
//! read, and `x = -FX` gives the string `=` and extra text.

use super::ast::{Body, File, Line, LineKind};
use crate::diagnostics::{codes, Code, Diagnostic, Diagnostics};
use crate::front::library::{self, Tok, Token};
use crate::ir::Span;

/// The keywords of an entry.
pub const KEYWORDS: [&str; 2] = ["axiom", "angle"];

/// Parses a Fractint library. Never fails: problems are pushed to `diags`.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let scanned = library::scan(src, &mut EntryLines, diags);
    File {
        entries: scanned.entries,
    }
}

/// An L-system entry's lines, for the library scanner.
struct EntryLines;

impl library::Lines for EntryLines {
    type Line = Line;
    const UNCLOSED: Code = codes::FR_UNCLOSED_ENTRY;

    /// A line naming something of more than one character, not a keyword,
    /// with no `=` before its `{`.
    fn opens_entry(&self, name: &str, line: &[Tok<'_>]) -> bool {
        let open = line.iter().position(|t| t.0 == Token::Open);
        name.chars().count() > 1
            && !KEYWORDS.contains(&name.to_ascii_lowercase().as_str())
            && !line[..open.unwrap_or(0)].iter().any(|t| t.0 == Token::Eq)
    }

    fn line(
        &mut self,
        src: &str,
        span: Span,
        first: bool,
        diags: &mut Diagnostics,
    ) -> Option<Line> {
        if !first {
            long_line(src, span.start, diags);
        }
        parse_line(src, span.start, span.end)
    }
}

/// Fractint's limit: lines of 160 characters and more are cut (W0704).
pub const MAX_LINE: usize = 159;

/// Warns when the line holding `at` is longer than Fractint reads.
fn long_line(src: &str, at: usize, diags: &mut Diagnostics) {
    let start = src[..at].rfind(['\n', '\r']).map_or(0, |i| i + 1);
    let end = src[at..].find(['\n', '\r']).map_or(src.len(), |i| at + i);
    let line = &src[start..end];
    if line.chars().count() > MAX_LINE {
        let cut = start
            + line
                .char_indices()
                .nth(MAX_LINE)
                .map_or(line.len(), |(i, _)| i);
        diags.push(
            Diagnostic::at(
                codes::FR_LONG_LINE,
                cut..end,
                format!("a line of {} characters", line.chars().count()),
            )
            .with_label("Fractint reads this part as a line of its own")
            .with_help("split a long rule into several rules for the same character"),
        );
    }
}

fn is_blank(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\x0b' | '\x0c')
}

/// One line of an entry, `src[start..end]` (its comment already cut), read
/// as Fractint's `strtok` calls read it.
pub fn parse_line(src: &str, start: usize, end: usize) -> Option<Line> {
    let s = &src[start..end];
    let n = s.len();
    let sep = |c: char| is_blank(c) || c == '=';
    let ws = s.find(|c: char| !sep(c))?;
    let we = ws + s[ws..].find(sep).unwrap_or(n - ws);
    let word = s[ws..we].to_ascii_lowercase();
    let followed_by_eq = s[we..].starts_with('=');
    // strtok ends the word at one delimiter, which it consumes.
    let p = if we < n { we + 1 } else { we };
    let bs = p + s[p..].find(|c: char| !is_blank(c)).unwrap_or(n - p);
    let be = bs + s[bs..].find(is_blank).unwrap_or(n - bs);
    let body = (bs < be).then(|| Body {
        text: s[bs..be].to_ascii_lowercase(),
        span: start + bs..start + be,
    });
    let xs = be + s[be..].find(|c: char| !is_blank(c)).unwrap_or(n - be);
    let extra = (xs < n).then(|| start + xs..start + s.trim_end_matches(is_blank).len());
    let keyword = start + ws..start + we;
    let kind = match word.as_str() {
        "axiom" => LineKind::Axiom { keyword, body },
        "angle" => LineKind::Angle {
            keyword,
            value: body,
        },
        w if w.chars().count() == 1 => LineKind::Rule {
            head: word.clone(),
            head_span: keyword,
            body,
        },
        _ => {
            return Some(Line {
                kind: LineKind::Unknown {
                    word: s[ws..we].to_string(),
                    span: keyword,
                    rule: followed_by_eq,
                },
                extra: None,
            })
        }
    };
    Some(Line { kind, extra })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(s: &str) -> Line {
        parse_line(s, 0, s.len()).unwrap()
    }

    #[test]
    fn lines_read_as_strtok_reads_them() {
        let l = line("x=-FX");
        assert_eq!(
            l.kind,
            LineKind::Rule {
                head: "x".into(),
                head_span: 0..1,
                body: Some(Body {
                    text: "-fx".into(),
                    span: 2..5
                })
            }
        );
        assert_eq!(l.extra, None);
        let l = line("x = -FX");
        let LineKind::Rule { body, .. } = l.kind else {
            panic!()
        };
        assert_eq!(body.unwrap().text, "=");
        assert_eq!(l.extra, Some(4..7));
        assert!(
            matches!(line("angle=6").kind, LineKind::Angle { value: Some(ref v), .. } if v.text == "6")
        );
        assert!(matches!(line("F=").kind, LineKind::Rule { body: None, .. }));
        assert!(matches!(
            line("Axoim F").kind,
            LineKind::Unknown { rule: false, .. }
        ));
        assert!(matches!(
            line("xy=F").kind,
            LineKind::Unknown { rule: true, .. }
        ));
    }

    #[test]
    fn entries_comments_and_nameless_blocks() {
        let src = "{ credits\n text }\ncomment {\n x }\n;c\nA1 { ; x\n angle 4\n}\nB{axiom f\n}\n";
        let mut d = Diagnostics::default();
        let f = parse(src, &mut d);
        assert!(d.is_empty(), "{d:#?}");
        let names: Vec<&str> = f.entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["A1", "B"]);
        assert_eq!(f.entries[1].lines.len(), 1);
        assert!(f.entries.iter().all(|e| e.closed));
    }
}
