//! Libraries: files of many named entries `Name { … }`, as Fractint keeps
//! its L-systems (`.l`) and its IFS codes (`.ifs`). Fractint finds the
//! entries of both with one scanner (`find_file_item`), and graftal reads
//! them with one too; each notation says only what an entry's lines are.
//!
//! - [`Token`] (logos): what the structure needs of a file: line ends,
//!   `;` comments, `{`, `}`, `=` and runs of other characters;
//! - [`scan`]: the entries and their lines ([`Lines`] reads each line);
//! - [`read`]: every entry lowered (each one's problems its own), the one
//!   chosen kept, duplicates and unknown names reported, the listing
//!   `check` prints;
//! - [`declarations`]: the entries, for the language server.

use crate::diagnostics::{codes, nearest, Code, Diagnostic, Diagnostics};
use crate::front::{Declaration, DeclarationKind, EntryInfo, Library};
use crate::ir::Span;
use logos::Logos;
use std::collections::HashMap;

/// The tokens of a library's structure. Words are separated by spaces and
/// tabs only, so a run is anything else. Control characters are errors.
#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq)]
#[logos(skip r"[ \t\x0b\x0c]+")]
pub enum Token<'src> {
    /// LF, CR LF, or a lone CR.
    #[regex(r"\r\n|\n|\r")]
    Newline,
    #[regex(r";[^\r\n]*", allow_greedy = true)]
    Comment,
    #[token("{")]
    Open,
    #[token("}")]
    Close,
    #[token("=")]
    Eq,
    #[regex(r"[^ \t\x0b\x0c\r\n;{}=\x00-\x08\x0e-\x1f\x7f]+")]
    Text(&'src str),
}

impl std::fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Token::Newline => f.write_str("end of line"),
            Token::Comment => f.write_str("comment"),
            Token::Open => f.write_str("`{`"),
            Token::Close => f.write_str("`}`"),
            Token::Eq => f.write_str("`=`"),
            Token::Text(s) => write!(f, "`{s}`"),
        }
    }
}

/// A token and its place.
pub type Tok<'src> = (Token<'src>, Span);

/// The tokens of `src` without comments; invalid characters are reported
/// (E0001) and left out.
pub fn lex<'src>(src: &'src str, diags: &mut Diagnostics) -> Vec<Tok<'src>> {
    let mut out = Vec::new();
    for (tok, span) in Token::lexer(src).spanned() {
        match tok {
            Ok(Token::Comment) => {}
            Ok(t) => out.push((t, span)),
            Err(()) => diags.push_invalid_character(src, span),
        }
    }
    out
}

/// The spans of `src`'s `;` comments, as [`Token`] finds them.
pub fn comment_spans(src: &str) -> Vec<Span> {
    (Token::lexer(src).spanned())
        .filter(|(t, _)| *t == Ok(Token::Comment))
        .map(|(_, span)| span)
        .collect()
}

/// One entry `Name { … }`, its lines as its notation reads them.
#[derive(Clone, Debug)]
pub struct Entry<L> {
    /// As written (Fractint compares names without regard to case).
    pub name: String,
    pub name_span: Span,
    /// From the name to the closing `}` (or to where the entry was cut off).
    pub span: Span,
    /// What stands between the name and `{` (an IFS entry's `(3D)`), when
    /// anything does.
    pub header: Option<Span>,
    /// Whether a `}` closed it.
    pub closed: bool,
    pub lines: Vec<L>,
}

/// What a notation says of its entries' lines, for [`scan`].
pub trait Lines {
    /// One line as the notation reads it.
    type Line;
    /// The code of an entry without its `}`.
    const UNCLOSED: Code;
    /// Whether a `}` anywhere on a line closes the entry (Fractint's IFS
    /// reader reads tokens, not lines), not only one that starts a line.
    const CLOSES_WITHIN_A_LINE: bool = false;
    /// Whether a line inside an entry that names `name` before a `{`
    /// opens the next entry (the `}` before it missing).
    fn opens_entry(&self, name: &str, line: &[Tok<'_>]) -> bool;
    /// Reads `src[span]`, a line of an entry without its comment; `first`
    /// when it is the rest of the line of `{`.
    fn line(
        &mut self,
        src: &str,
        span: Span,
        first: bool,
        diags: &mut Diagnostics,
    ) -> Option<Self::Line>;
}

/// What [`scan`] found: the entries in file order, and the lines outside
/// any entry or block (which Fractint skips).
#[derive(Clone, Debug)]
pub struct Scanned<L> {
    pub entries: Vec<Entry<L>>,
    pub outside: Vec<Span>,
}

enum State<L> {
    Outside,
    Block,
    Entry(Entry<L>),
}

/// The entries of a library (Fractint's entry scanner): a line `Name {`
/// (the name ends at a blank, `(` or `{`) opens an entry and the rest of
/// that line is its first line; a line whose first token is `}` closes it
/// (with [`Lines::CLOSES_WITHIN_A_LINE`], a `}` anywhere). `comment { … }`
/// blocks and nameless `{ … }` blocks are not entries: they end at the
/// first `}`. A line inside an entry that opens another entry means the
/// `}` is missing ([`Lines::UNCLOSED`]): the entry ends there, so the
/// next one still reads. The lines are slices of the tokens: nothing is
/// allocated per line, so a library of 100,000 entries reads in a fraction
/// of a second.
pub fn scan<R: Lines>(src: &str, reader: &mut R, diags: &mut Diagnostics) -> Scanned<R::Line> {
    let tokens = lex(src, diags);
    let mut out = Scanned {
        entries: Vec::new(),
        outside: Vec::new(),
    };
    let mut state = State::Outside;
    let mut last_end = 0;
    for line in tokens.split(|t| t.0 == Token::Newline) {
        let (Some(first), Some(last)) = (line.first(), line.last()) else {
            continue;
        };
        let (start, end) = (first.1.start, last.1.end);
        let close = line.iter().position(|t| t.0 == Token::Close);
        state = match state {
            State::Block if close.is_some() => State::Outside,
            State::Block => State::Block,
            State::Entry(e) if close == Some(0) => {
                finish(e, first.1.end, &mut out);
                State::Outside
            }
            State::Entry(e)
                if opening(line).is_some_and(|(n, _, _)| reader.opens_entry(&n, line)) =>
            {
                let d = unclosed::<R>(&e)
                    .with_secondary(start..end, "the next entry starts here")
                    .with_help("end the entry with a line `}`");
                diags.push(d);
                finish_open(e, last_end, &mut out);
                open_block(src, line, reader, &mut out, diags)
            }
            State::Entry(mut e) => match close.filter(|_| R::CLOSES_WITHIN_A_LINE) {
                Some(k) => {
                    e.lines
                        .extend(reader.line(src, start..line[k - 1].1.end, false, diags));
                    finish(e, line[k].1.end, &mut out);
                    State::Outside
                }
                None => {
                    e.lines.extend(reader.line(src, start..end, false, diags));
                    State::Entry(e)
                }
            },
            State::Outside => {
                if opening(line).is_none() {
                    out.outside.push(start..end);
                }
                open_block(src, line, reader, &mut out, diags)
            }
        };
        last_end = end;
    }
    if let State::Entry(e) = state {
        let d = unclosed::<R>(&e).with_help("the file ends first: end the entry with a line `}`");
        diags.push(d);
        finish_open(e, last_end, &mut out);
    }
    out
}

/// The name of a line that opens a block (`None` when no `{` opens one;
/// an empty name for a nameless block), with its span and the index of
/// the `{`.
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

/// The error for an entry without its `}`.
fn unclosed<R: Lines>(e: &Entry<R::Line>) -> Diagnostic {
    Diagnostic::at(
        R::UNCLOSED,
        e.name_span.clone(),
        format!("the entry `{}` is not closed with `}}`", e.name),
    )
    .with_label("this entry has no `}`")
}

/// Ends an entry closed by a `}` ending at `end`.
fn finish<L>(mut e: Entry<L>, end: usize, out: &mut Scanned<L>) {
    e.closed = true;
    e.span.end = end;
    out.entries.push(e);
}

/// Ends an unclosed entry at `end`.
fn finish_open<L>(mut e: Entry<L>, end: usize, out: &mut Scanned<L>) {
    e.span.end = end;
    out.entries.push(e);
}

/// A line outside entries: opens an entry, a block, or is skipped (as
/// Fractint's scanner skips lines without `{`).
fn open_block<R: Lines>(
    src: &str,
    line: &[Tok<'_>],
    reader: &mut R,
    out: &mut Scanned<R::Line>,
    diags: &mut Diagnostics,
) -> State<R::Line> {
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
    let header_start = name_span.end;
    let header_end = line[open].1.start;
    let header =
        (!src[header_start..header_end].trim().is_empty()).then_some(header_start..header_end);
    let mut e = Entry {
        name,
        span: name_span.start..line[open].1.end,
        name_span,
        header,
        closed: false,
        lines: Vec::new(),
    };
    let rest = &line[open + 1..];
    let close = rest.iter().position(|t| t.0 == Token::Close);
    match close {
        // `Name { }`: an entry of no lines.
        Some(0) if rest.len() == 1 || R::CLOSES_WITHIN_A_LINE => {
            finish(e, rest[0].1.end, out);
            return State::Outside;
        }
        Some(k) if R::CLOSES_WITHIN_A_LINE => {
            let span = rest[0].1.start..rest[k - 1].1.end;
            e.lines.extend(reader.line(src, span, true, diags));
            finish(e, rest[k].1.end, out);
            return State::Outside;
        }
        _ => {}
    }
    // The rest of the line after `{` is the entry's first line.
    if let (Some(a), Some(b)) = (rest.first(), rest.last()) {
        e.lines
            .extend(reader.line(src, a.1.start..b.1.end, true, diags));
    }
    State::Entry(e)
}

/// The codes and words a notation's library is read with by [`read`].
pub struct Reading {
    /// The notation's name for people (`Fractint`, `Fractint IFS`).
    pub title: &'static str,
    /// A file without entries.
    pub no_entries: Code,
    /// An entry named as an earlier one was.
    pub duplicate: Code,
}

/// Reads a library's `entries` (found by [`scan`], with the scan's
/// diagnostics `file_diags`): every entry is lowered with `lower` (so
/// each one's problems are its own); the diagnostics kept are the chosen
/// entry's and the file's, or every entry's when none is chosen. Linear
/// in the number of entries: only the chosen entry's lowering is kept (a
/// system, or what a notation makes one of). The library's summary is
/// left for the notation to write.
pub fn read<L, T>(
    entries: &[Entry<L>],
    file_diags: Diagnostics,
    entry: Option<&str>,
    how: &Reading,
    mut lower: impl FnMut(&Entry<L>, &mut Diagnostics) -> T,
    diags: &mut Diagnostics,
) -> (Library, Option<T>) {
    report_duplicates(entries, how.duplicate, diags);
    let mut lib = Library {
        chosen: choose(entries, entry, diags),
        ..Library::default()
    };
    let mut lowered = None;
    let mut per_entry: Vec<Diagnostics> = Vec::with_capacity(entries.len());
    for (i, e) in entries.iter().enumerate() {
        let mut d = Diagnostics::default();
        let l = lower(e, &mut d);
        if lib.chosen == Some(i) {
            lowered = Some(l);
        }
        per_entry.push(d);
    }
    // The file's diagnostics belong to the entry they are in, if any.
    for d in file_diags.0 {
        match owner(entries, &d) {
            Some(i) => per_entry[i].push(d),
            None => diags.push(d),
        }
    }
    for (e, d) in entries.iter().zip(&per_entry) {
        lib.entries.push(EntryInfo {
            name: e.name.clone(),
            span: e.name_span.clone(),
            errors: d.iter().filter(|d| d.is_error()).count(),
            warnings: d.iter().filter(|d| !d.is_error()).count(),
        });
    }
    if entries.is_empty() {
        diags.push(
            Diagnostic::global(
                how.no_entries,
                format!("this {} file has no entries", how.title),
            )
            .with_help("an entry is `Name {`, its lines, and a line `}`"),
        );
    }
    match lib.chosen {
        Some(i) => diags.extend(per_entry.swap_remove(i)),
        None => {
            lib.needs_entry = entry.is_none() && entries.len() > 1;
            for d in per_entry {
                diags.extend(d);
            }
        }
    }
    (lib, lowered)
}

/// `N entries (drawn without choosing)` or `N entries (choose one …`:
/// the start of a library's summary, for `check`.
pub fn entries_summary(lib: &Library) -> String {
    let n = lib.entries.len();
    // One entry is drawn without being chosen: nothing to ask for.
    let choose = match n {
        1 => "drawn without choosing",
        _ => "choose one with FILE:NAME or --entry NAME",
    };
    let entries = if n == 1 { "entry" } else { "entries" };
    format!("{n} {entries} ({choose}")
}

/// Reports each entry named as an earlier one was (names compared without
/// regard to case), pointing at the first.
fn report_duplicates<L>(entries: &[Entry<L>], code: Code, diags: &mut Diagnostics) {
    let mut first_named: HashMap<String, usize> = HashMap::with_capacity(entries.len());
    for (i, e) in entries.iter().enumerate() {
        let first = *first_named.entry(e.name.to_ascii_lowercase()).or_insert(i);
        if first == i {
            continue;
        }
        // About the file, whichever entry is chosen.
        diags.push(
            Diagnostic::at(
                code,
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
fn choose<L>(entries: &[Entry<L>], entry: Option<&str>, diags: &mut Diagnostics) -> Option<usize> {
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
fn owner<L>(entries: &[Entry<L>], d: &Diagnostic) -> Option<usize> {
    let at = d.span.as_ref()?.start;
    let i = entries
        .partition_point(|e| e.span.start <= at)
        .checked_sub(1)?;
    let e = &entries[i];
    (at < e.span.end.max(e.span.start + 1)).then_some(i)
}

/// The entries of `text` for the language server, each with its first
/// lines: `what` says what an entry is (`Fractint entry`).
pub fn declarations<L>(text: &str, entries: Vec<Entry<L>>, what: &str) -> Vec<Declaration> {
    (entries.into_iter())
        .filter(|e| !e.name.is_empty())
        .map(|e| {
            let lines = (e.span.end - e.span.start).min(300);
            let shown = text.get(e.span.start..e.span.start + lines).unwrap_or("");
            Declaration {
                about: format!("{what} `{}`\n\n```\n{shown}\n```", e.name),
                name: e.name,
                span: e.name_span,
                kind: DeclarationKind::Module,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lines as their text, closed mid-line or not.
    struct Words<const MID: bool>;

    impl<const MID: bool> Lines for Words<MID> {
        type Line = String;
        const UNCLOSED: Code = codes::FR_UNCLOSED_ENTRY;
        const CLOSES_WITHIN_A_LINE: bool = MID;
        fn opens_entry(&self, name: &str, _: &[Tok<'_>]) -> bool {
            name.len() > 1
        }
        fn line(&mut self, src: &str, span: Span, _: bool, _: &mut Diagnostics) -> Option<String> {
            Some(src[span].to_string())
        }
    }

    fn scanned<const MID: bool>(src: &str) -> (Scanned<String>, Diagnostics) {
        let mut d = Diagnostics::default();
        let s = scan(src, &mut Words::<MID>, &mut d);
        (s, d)
    }

    #[test]
    fn entries_blocks_and_lines_outside() {
        let src = "{ credits\n text }\ncomment {\n x }\n;c\nA1 (3D) { x\n y\n}\nstray\nB{}\n";
        let (s, d) = scanned::<false>(src);
        assert!(d.is_empty(), "{d:#?}");
        let names: Vec<&str> = s.entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["A1", "B"]);
        assert_eq!(s.entries[0].lines, ["x", "y"]);
        assert_eq!(&src[s.entries[0].header.clone().unwrap()], " (3D) ");
        assert_eq!(s.entries[1].header, None);
        assert!(s.entries.iter().all(|e| e.closed));
        assert_eq!(
            s.outside
                .iter()
                .map(|o| &src[o.clone()])
                .collect::<Vec<_>>(),
            ["stray"]
        );
    }

    #[test]
    fn a_brace_within_a_line_closes_only_where_the_notation_says() {
        let src = "A {\n 1 2 }\nBb { 3 }\n";
        let (s, d) = scanned::<true>(src);
        assert!(d.is_empty(), "{d:#?}");
        assert_eq!(s.entries[0].lines, ["1 2"]);
        assert_eq!(s.entries[1].lines, ["3"]);
        assert_eq!(&src[s.entries[0].span.clone()], "A {\n 1 2 }");
        // Not so for Fractint's L-systems: the next entry finds it open.
        let (s, d) = scanned::<false>(src);
        assert_eq!(d.len(), 2, "{d:#?}");
        assert_eq!(s.entries[0].lines, ["1 2 }"]);
        assert!(!s.entries[0].closed);
    }
}
