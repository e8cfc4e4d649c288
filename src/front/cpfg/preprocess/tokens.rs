//! The preprocessor's tokens: splitting a line into identifiers, numbers,
//! strings, punctuation and white space, with the hide set each carries.

use std::ops::Range;
use std::rc::Rc;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Ident,
    /// Numbers, strings, punctuation: anything not expanded.
    Other,
    /// Spaces, tabs, line breaks.
    Ws,
    /// A backslash-newline outside a directive (C line splicing): prints as
    /// nothing.
    Splice,
}

#[derive(Clone, Debug)]
pub(super) struct Tok {
    pub(super) kind: Kind,
    pub(super) text: Rc<str>,
    /// Where the token comes from in the file being read: its own bytes for
    /// a token of the file, the whole macro call for one made by expansion.
    pub(super) origin: Range<usize>,
    /// Still the file's own token (copied, not produced by an expansion).
    pub(super) own: bool,
    /// Macros this token may not expand (sorted ids).
    pub(super) hide: Rc<Vec<u32>>,
}

fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_'
}
fn is_ident_char(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// Splits `text` (starting at byte `base` of the file) into tokens. In a
/// directive (`directive`), backslash-newline is plain space.
pub(super) fn tokenize(text: &str, base: usize, directive: bool) -> Vec<Tok> {
    let b = text.as_bytes();
    let empty: Rc<Vec<u32>> = Rc::new(Vec::new());
    let mut toks = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let start = i;
        let c = b[i];
        let kind;
        if c == b'\\' && splice_len(b, i) > 0 {
            i += splice_len(b, i);
            if directive {
                // Spliced away: the lines join with nothing between them.
                toks.push(Tok {
                    kind: Kind::Ws,
                    text: Rc::from(""),
                    origin: base + start..base + i,
                    own: true,
                    hide: empty.clone(),
                });
                continue;
            }
            kind = Kind::Splice;
        } else if matches!(c, b' ' | b'\t' | b'\r' | b'\n' | 0x0b | 0x0c) {
            while i < b.len() && matches!(b[i], b' ' | b'\t' | b'\r' | b'\n' | 0x0b | 0x0c) {
                i += 1;
            }
            kind = Kind::Ws;
        } else if is_ident_start(c) {
            while i < b.len() && is_ident_char(b[i]) {
                i += 1;
            }
            kind = Kind::Ident;
        } else if c.is_ascii_digit() || (c == b'.' && b.get(i + 1).is_some_and(u8::is_ascii_digit))
        {
            i += 1;
            while i < b.len() {
                if matches!(b[i], b'e' | b'E' | b'p' | b'P')
                    && matches!(b.get(i + 1), Some(b'+' | b'-'))
                {
                    i += 2;
                } else if is_ident_char(b[i]) || b[i] == b'.' {
                    i += 1;
                } else {
                    break;
                }
            }
            kind = Kind::Other;
        } else if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                i += if b[i] == b'\\' && i + 1 < b.len() && b[i + 1] != b'\n' {
                    2
                } else {
                    1
                };
            }
            if i < b.len() && b[i] == b'"' {
                i += 1;
            }
            kind = Kind::Other;
        } else {
            i += 1;
            while i < b.len() && !text.is_char_boundary(i) {
                i += 1;
            }
            kind = Kind::Other;
        }
        let i_end = i.min(b.len());
        toks.push(Tok {
            kind,
            text: Rc::from(&text[start..i_end]),
            origin: base + start..base + i_end,
            own: true,
            hide: empty.clone(),
        });
        i = i_end;
    }
    toks
}

/// Whether a line (without its indentation) is a directive: `#` followed
/// by a name, or `#` alone. A `#` followed by anything else (`#(0.06)`, the
/// width module, on a continuation line of a production) is text: vlab's
/// cpfg models rely on that (11-CPFG-ArticulatedLamp, 11-CPFG-JumpingLamp),
/// although a strict C preprocessor rejects it.
pub(super) fn is_directive(line: &str) -> bool {
    let Some(rest) = line.strip_prefix('#') else {
        return false;
    };
    let rest = rest.trim_start_matches([' ', '\t']);
    rest.is_empty()
        || rest.starts_with(['\n', '\r'])
        || rest.as_bytes().first().copied().is_some_and(is_ident_start)
        || rest.starts_with("\\\n")
}

/// Length of a backslash-newline at `i` (`\` `\n` or `\` `\r` `\n`), or 0.
fn splice_len(b: &[u8], i: usize) -> usize {
    match (b.get(i), b.get(i + 1), b.get(i + 2)) {
        (Some(b'\\'), Some(b'\n'), _) => 2,
        (Some(b'\\'), Some(b'\r'), Some(b'\n')) => 3,
        _ => 0,
    }
}

pub(super) fn strip_ws(mut toks: Vec<Tok>) -> Vec<Tok> {
    while toks
        .last()
        .is_some_and(|t| matches!(t.kind, Kind::Ws | Kind::Splice))
    {
        toks.pop();
    }
    let lead = toks
        .iter()
        .take_while(|t| matches!(t.kind, Kind::Ws | Kind::Splice))
        .count();
    toks.drain(..lead);
    toks
}

pub(super) fn span_of(toks: &[Tok]) -> Option<Range<usize>> {
    let lo = toks.iter().map(|t| t.origin.start).min()?;
    let hi = toks.iter().map(|t| t.origin.end).max()?;
    Some(lo..hi)
}

pub(super) fn union(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut v: Vec<u32> = a.iter().chain(b).copied().collect();
    v.sort_unstable();
    v.dedup();
    v
}

// ---------------------------------------------------------------------------
// Comments

impl Tok {
    /// This token as made by the expansion of the call at `origin`.
    pub(super) fn made_by(&self, origin: &Range<usize>, hide: Rc<Vec<u32>>) -> Tok {
        Tok {
            kind: self.kind,
            text: self.text.clone(),
            origin: origin.clone(),
            own: false,
            hide,
        }
    }
}
