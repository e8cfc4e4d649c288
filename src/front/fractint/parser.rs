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

use super::ast::{Body, Entry, File, Line, LineKind};
use super::lexer::{lex, Token};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::ir::Span;

type Tok<'src> = (Token<'src>, Span);

/// The keywords of an entry.
pub const KEYWORDS: [&str; 2] = ["axiom", "angle"];

/// Parses a Fractint library. Never fails: problems are pushed to `diags`.
pub fn parse(src: &str, diags: &mut Diagnostics) -> File {
    let tokens: Vec<Tok<'_>> = lex(src, diags);
    // The lines are slices of the tokens: nothing is allocated per line, so
    // a library of 100,000 entries reads in a fraction of a second.
    build(src, tokens.split(|t| t.0 == Token::Newline), diags)
}

enum State {
    Outside,
    Block,
    Entry(Entry),
}

/// The name of a line that opens a block (`None` when no `{` opens one),
/// with its span and the index of the `{`.
fn opening(line: &[Tok<'_>]) -> Option<(String, Span, usize)> {
    let open = line.iter().position(|t| t.0 == Token::Open)?;
    match line.first() {
        Some((Token::Text(t), span)) if open > 0 => {
            let name = t.split('(').next().unwrap_or("");
            let span = span.start..span.start + name.len();
            Some((name.to_string(), span, open))
        }
        _ => Some((String::new(), 0..0, open)),
    }
}

/// Whether a line inside an entry opens the next entry (its `}` missing).
fn opens_entry(line: &[Tok<'_>]) -> bool {
    let Some((name, _, open)) = opening(line) else {
        return false;
    };
    name.chars().count() > 1
        && !KEYWORDS.contains(&name.to_ascii_lowercase().as_str())
        && !line[..open].iter().any(|t| t.0 == Token::Eq)
}

fn build<'t, 's: 't>(
    src: &str,
    lines: impl Iterator<Item = &'t [Tok<'s>]>,
    diags: &mut Diagnostics,
) -> File {
    let mut file = File::default();
    let mut state = State::Outside;
    let mut last_end = 0;
    for line in lines {
        let (Some(first), Some(last)) = (line.first(), line.last()) else {
            continue;
        };
        let (start, end) = (first.1.start, last.1.end);
        state = match state {
            State::Block => {
                if line.iter().any(|t| t.0 == Token::Close) {
                    State::Outside
                } else {
                    State::Block
                }
            }
            State::Entry(mut e) if first.0 == Token::Close => {
                e.closed = true;
                e.span.end = first.1.end;
                file.entries.push(e);
                State::Outside
            }
            State::Entry(e) if opens_entry(line) => {
                let d = unclosed(&e)
                    .with_secondary(start..end, "the next entry starts here")
                    .with_help("end the entry with a line `}`");
                cut_off(e, last_end, d, &mut file, diags);
                open_block(src, line, &mut file)
            }
            State::Entry(mut e) => {
                long_line(src, start, diags);
                e.lines.extend(parse_line(src, start, end));
                State::Entry(e)
            }
            State::Outside => open_block(src, line, &mut file),
        };
        last_end = end;
    }
    if let State::Entry(e) = state {
        let d = unclosed(&e).with_help("the file ends first: end the entry with a line `}`");
        cut_off(e, last_end, d, &mut file, diags);
    }
    file
}

/// E0701 for an entry without its `}`.
fn unclosed(e: &Entry) -> Diagnostic {
    Diagnostic::at(
        codes::FR_UNCLOSED_ENTRY,
        e.name_span.clone(),
        format!("the entry `{}` is not closed with `}}`", e.name),
    )
    .with_label("this entry has no `}`")
}

/// Ends an unclosed entry at `end`, reporting `d`.
fn cut_off(mut e: Entry, end: usize, d: Diagnostic, file: &mut File, diags: &mut Diagnostics) {
    diags.push(d);
    e.span.end = end;
    file.entries.push(e);
}

/// A line outside entries: opens an entry, a block, or is ignored (as
/// Fractint's scanner ignores lines without `{`).
fn open_block(src: &str, line: &[Tok<'_>], file: &mut File) -> State {
    let Some((name, name_span, open)) = opening(line) else {
        return State::Outside;
    };
    if name.is_empty() || name.eq_ignore_ascii_case("comment") {
        return if line[open..].iter().any(|t| t.0 == Token::Close) {
            State::Outside
        } else {
            State::Block
        };
    }
    let mut e = Entry {
        name,
        span: name_span.start..line[open].1.end,
        name_span,
        closed: false,
        lines: Vec::new(),
    };
    // The rest of the line after `{` is the entry's first line.
    if let (Some(a), Some(b)) = (line.get(open + 1), line.last()) {
        if a.0 == Token::Close && line.len() == open + 2 {
            e.closed = true;
            e.span.end = a.1.end;
            file.entries.push(e);
            return State::Outside;
        }
        e.lines.extend(parse_line(src, a.1.start, b.1.end));
    }
    State::Entry(e)
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
