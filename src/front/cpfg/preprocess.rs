//! The C preprocessor pass cpfg runs over an L-system file.
//!
//! cpfg hands the `.l` file to the C preprocessor before reading it, so cpfg
//! files use `#define` (object-like and function-like, with `\` continuation
//! lines), `#undef`, `#include "file"`, `#if`/`#ifdef`/`#ifndef`/`#elif`/
//! `#else`/`#endif` and C comments. This module is that pass:
//!
//! - comments (`/* */`, `//`) become spaces (their line breaks stay), so
//!   columns and lines stay put; nothing inside a comment or a `"…"` string
//!   is expanded;
//! - macros expand as in C: arguments are expanded first, the result is
//!   rescanned, and a macro is not expanded again inside its own expansion
//!   (hide sets, after Prosser's algorithm). The stringizing `#` and pasting
//!   `##` operators are *not* implemented: in cpfg `#` is a module (line
//!   width), and no cpfg file uses either;
//! - directives become empty lines, so a line of the output is the same line
//!   of the input wherever possible (a macro call spanning lines, a `\`
//!   continuation outside a directive, or an included file shift the lines
//!   after it until the next line break of the original, where the missing
//!   breaks are put back);
//! - [`SourceMap`] sends any output range back to the original text: copied
//!   bytes to themselves, bytes made by an expansion to the whole macro call
//!   (name and arguments), bytes of an included file to the `#include` line;
//!   [`SourceMap::locate`] sends them into the included file itself.
//!
//! It never panics and always ends: output is capped at 8 MiB and expansion
//! at 20 million steps ([`codes::CPFG_EXPANSION_LIMIT`]); macro calls in
//! arguments and `#if` conditions nest at most [`MAX_NESTING`] deep (E0013,
//! graftal's one depth limit), since both are followed by recursion.

use crate::diagnostics::{codes, nearest, Diagnostic, Diagnostics, SideFile};
use crate::front::depth::too_deep;
use crate::ir::MAX_NESTING;
use std::collections::{HashMap, VecDeque};
use std::ops::Range;
use std::rc::Rc;
use std::sync::Arc;

/// Output larger than this is cut off.
pub const MAX_OUTPUT: usize = 8 << 20;
const MAX_STEPS: u64 = 20_000_000;
const MAX_PENDING_TOKENS: usize = 2_000_000;
const MAX_INCLUDE_DEPTH: usize = 16;

/// The preprocessed text, its map back to the original, and what went wrong.
#[derive(Clone, Debug)]
pub struct Preprocessed {
    pub text: String,
    pub map: SourceMap,
    pub diagnostics: Diagnostics,
    /// Expansion stopped at macro calls nested past the depth limit
    /// (reported): the rest of the text is left as written, nesting and all.
    pub stopped_too_deep: bool,
}

/// Maps byte ranges of the preprocessed text to byte ranges of the original
/// main file, or of the file `#include`d there.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    segs: Vec<Seg>,
    src_len: usize,
    /// The included files' text in the output, each with its own map.
    included: Vec<Included>,
}

/// An included file's place in the output (bytes `out`), how its own
/// output maps into it, and the note that says where it was included.
#[derive(Clone, Debug)]
struct Included {
    file: Arc<SideFile>,
    out: Range<usize>,
    map: SourceMap,
    note: String,
}

/// Where output bytes come from when they come from an included file: that
/// file (the innermost one), and the notes that say where each file on the
/// way was included, innermost first.
pub type IncludedFrom = (Arc<SideFile>, Vec<String>);

#[derive(Clone, Debug, PartialEq)]
struct Seg {
    out: Range<usize>,
    src: Range<usize>,
    /// Bytes copied from the original (byte i of `out` is byte i of `src`);
    /// otherwise the whole of `out` comes from `src` (a macro call, an
    /// `#include` line).
    identity: bool,
}

impl SourceMap {
    /// The byte range of the original main file that produced the output
    /// bytes `out`: copied bytes map to themselves, expanded bytes to the
    /// whole macro call, included bytes to the `#include` directive. An
    /// empty range maps to the place it stands at.
    pub fn to_source(&self, out: Range<usize>) -> Range<usize> {
        let (a, b) = (out.start, out.end.max(out.start));
        if self.segs.is_empty() {
            return a.min(self.src_len)..a.min(self.src_len);
        }
        // First segment whose end is beyond `a` (or that contains the point a).
        let first = self.segs.partition_point(|s| s.out.end <= a);
        if a == b {
            let s = self
                .segs
                .get(first)
                .unwrap_or(&self.segs[self.segs.len() - 1]);
            return if s.identity {
                let p = (s.src.start + a.saturating_sub(s.out.start)).min(s.src.end);
                let p = if a >= s.out.end { s.src.end } else { p };
                p..p
            } else {
                s.src.clone()
            };
        }
        let mut lo = usize::MAX;
        let mut hi = 0;
        for s in &self.segs[first.min(self.segs.len())..] {
            if s.out.start >= b {
                break;
            }
            let (x, y) = if s.identity {
                let x = s.src.start + a.max(s.out.start) - s.out.start;
                let y = s.src.start + b.min(s.out.end) - s.out.start;
                (x, y)
            } else {
                (s.src.start, s.src.end)
            };
            lo = lo.min(x);
            hi = hi.max(y);
        }
        if lo == usize::MAX {
            let end = self.segs.last().map_or(0, |s| s.src.end.max(s.src.start));
            return end..end;
        }
        lo..hi
    }

    /// [`Self::to_source`], but output bytes that come from an included
    /// file map into that file (a mistake is shown where it is written,
    /// as rustc shows one inside a macro of another file).
    pub fn locate(&self, out: Range<usize>) -> (Range<usize>, Option<IncludedFrom>) {
        let inside = |i: &&Included| {
            i.out.start <= out.start && out.end <= i.out.end && out.start < i.out.end
        };
        let Some(inc) = self.included.iter().find(inside) else {
            return (self.to_source(out), None);
        };
        let shifted = out.start - inc.out.start..out.end - inc.out.start;
        let (span, deeper) = inc.map.locate(shifted);
        let (file, mut notes) = deeper.unwrap_or_else(|| (inc.file.clone(), Vec::new()));
        notes.push(inc.note.clone());
        (span, Some((file, notes)))
    }
}

/// Runs the preprocessor over `text` (the main file). `include` is called
/// with the name written in an `#include` and returns that file's text, or
/// `None` when there is no such file.
pub fn preprocess(text: &str, include: &mut dyn FnMut(&str) -> Option<String>) -> Preprocessed {
    preprocess_with_defines(text, &[], include)
}

/// [`preprocess`] with macros defined beforehand, as `cpp -D NAME=body`
/// does. cpfg defines one per user function (`-D FUNCNAME=id`, manual
/// §8.1.6), so a file can write `func(FUNCNAME, x)`.
pub fn preprocess_with_defines(
    text: &str,
    defines: &[(String, String)],
    include: &mut dyn FnMut(&str) -> Option<String>,
) -> Preprocessed {
    let mut pp = Pp {
        macros: HashMap::new(),
        names: Vec::new(),
        include,
        steps: 0,
        aborted: false,
        too_deep: false,
        stack: Vec::new(),
        texts: vec![Rc::from(text)],
        diags: Diagnostics::default(),
    };
    for (name, body) in defines {
        let toks = tokenize(body, 0, false);
        let body = strip_ws(toks);
        let id = pp.intern(name);
        pp.macros.insert(
            name.clone(),
            Macro {
                id,
                params: None,
                variadic: false,
                body,
                def: None,
            },
        );
    }
    let mut out = Out::default();
    pp.run(text, &mut out, true);
    out.flush_pending(text.len());
    let diagnostics = pp.diags;
    Preprocessed {
        text: out.text,
        map: SourceMap {
            segs: out.segs,
            src_len: text.len(),
            included: out.included,
        },
        diagnostics,
        stopped_too_deep: pp.too_deep,
    }
}

// ---------------------------------------------------------------------------
// Tokens

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
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
struct Tok {
    kind: Kind,
    text: Rc<str>,
    /// Where the token comes from in the file being read: its own bytes for
    /// a token of the file, the whole macro call for one made by expansion.
    origin: Range<usize>,
    /// Still the file's own token (copied, not produced by an expansion).
    own: bool,
    /// Macros this token may not expand (sorted ids).
    hide: Rc<Vec<u32>>,
}

fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_'
}
fn is_ident_char(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// Splits `text` (starting at byte `base` of the file) into tokens. In a
/// directive (`directive`), backslash-newline is plain space.
fn tokenize(text: &str, base: usize, directive: bool) -> Vec<Tok> {
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
fn is_directive(line: &str) -> bool {
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

fn strip_ws(mut toks: Vec<Tok>) -> Vec<Tok> {
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

fn span_of(toks: &[Tok]) -> Option<Range<usize>> {
    let lo = toks.iter().map(|t| t.origin.start).min()?;
    let hi = toks.iter().map(|t| t.origin.end).max()?;
    Some(lo..hi)
}

fn union(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut v: Vec<u32> = a.iter().chain(b).copied().collect();
    v.sort_unstable();
    v.dedup();
    v
}

// ---------------------------------------------------------------------------
// Comments

/// The text with comments replaced by spaces (line breaks kept), byte for
/// byte, and whether each line break lies inside a comment.
fn strip_comments(text: &str, diags: &mut Diagnostics) -> (String, Vec<bool>) {
    let b = text.as_bytes();
    let mut out = b.to_vec();
    let mut nl_in_comment = vec![false; b.len()];
    let mut i = 0;
    let blank = |out: &mut Vec<u8>, nl: &mut Vec<bool>, r: Range<usize>| {
        for j in r {
            if b[j] == b'\n' {
                nl[j] = true;
            } else if b[j] != b'\r' {
                out[j] = b' ';
            }
        }
    };
    while i < b.len() {
        match b[i] {
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                    i += if b[i] == b'\\' && i + 1 < b.len() && b[i + 1] != b'\n' {
                        2
                    } else {
                        1
                    };
                }
                i += 1;
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                let start = i;
                let end = text[i + 2..].find("*/").map(|k| i + 2 + k + 2);
                match end {
                    Some(e) => {
                        blank(&mut out, &mut nl_in_comment, start..e);
                        i = e;
                    }
                    None => {
                        diags.push(
                            Diagnostic::at(
                                codes::CPFG_UNTERMINATED_COMMENT,
                                start..start + 2,
                                "comment never closed",
                            )
                            .with_label("this comment runs to the end of the file")
                            .with_help("close it with `*/`"),
                        );
                        blank(&mut out, &mut nl_in_comment, start..b.len());
                        // A line break of an unclosed comment still ends lines.
                        nl_in_comment.iter_mut().for_each(|x| *x = false);
                        i = b.len();
                    }
                }
            }
            b'/' if b.get(i + 1) == Some(&b'/') => {
                let start = i;
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
                blank(&mut out, &mut nl_in_comment, start..i);
            }
            _ => i += 1,
        }
    }
    // Only ASCII bytes were replaced by ASCII spaces, and every byte of a
    // multi-byte character inside a comment was replaced: still UTF-8.
    let s = String::from_utf8(out)
        .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned());
    (s, nl_in_comment)
}

// ---------------------------------------------------------------------------
// Output

#[derive(Default)]
struct Out {
    text: String,
    segs: Vec<Seg>,
    /// Line breaks swallowed (by a call spanning lines, a splice) that are
    /// put back at the next line break.
    pending: usize,
    /// The furthest source byte accounted for.
    src_hi: usize,
    full: bool,
    /// The included files whose text is in `text`.
    included: Vec<Included>,
}

impl Out {
    fn push_seg(&mut self, text: &str, src: Range<usize>, identity: bool) -> bool {
        if text.is_empty() {
            return true;
        }
        if self.text.len() + text.len() > MAX_OUTPUT {
            self.full = true;
            return false;
        }
        let start = self.text.len();
        self.text.push_str(text);
        let end = self.text.len();
        if let Some(last) = self.segs.last_mut() {
            if identity && last.identity && last.out.end == start && last.src.end == src.start {
                last.out.end = end;
                last.src.end = src.end;
                return true;
            }
            if !identity && !last.identity && last.src == src && last.out.end == start {
                last.out.end = end;
                return true;
            }
        }
        self.segs.push(Seg {
            out: start..end,
            src,
            identity,
        });
        true
    }

    /// Copies the file's own text `text` found at `src`.
    fn copy(&mut self, text: &str, src: Range<usize>) {
        let mut at = 0;
        while let Some(k) = text[at..].find('\n') {
            let nl = at + k;
            self.push_seg(&text[at..=nl], src.start + at..src.start + nl + 1, true);
            self.flush_pending(src.start + nl);
            at = nl + 1;
        }
        self.push_seg(&text[at..], src.start + at..src.end, true);
        self.src_hi = self.src_hi.max(src.end);
    }

    /// Emits text made by an expansion of the call at `origin`; its line
    /// breaks become spaces (the call's own are put back later).
    fn generated(&mut self, text: &str, origin: Range<usize>, clean: &str) {
        if origin.end > self.src_hi {
            let from = self.src_hi.max(origin.start).min(clean.len());
            let to = origin.end.min(clean.len());
            if from < to {
                self.pending += clean.as_bytes()[from..to]
                    .iter()
                    .filter(|&&c| c == b'\n')
                    .count();
            }
            self.src_hi = origin.end;
        }
        if text.contains('\n') {
            self.push_seg(&text.replace('\n', " "), origin, false);
        } else {
            self.push_seg(text, origin, false);
        }
    }

    fn flush_pending(&mut self, at: usize) {
        while self.pending > 0 {
            self.pending -= 1;
            if !self.push_seg("\n", at..at, false) {
                self.pending = 0;
            }
        }
    }
}

// ---------------------------------------------------------------------------
// The preprocessor

#[derive(Clone, Debug)]
struct Macro {
    id: u32,
    params: Option<Vec<String>>,
    variadic: bool,
    body: Vec<Tok>,
    /// The definition's span when it is in the main file.
    def: Option<Range<usize>>,
}

impl Macro {
    fn same_as(&self, other: &Macro) -> bool {
        let norm = |b: &[Tok]| -> Vec<String> {
            b.iter()
                .map(|t| {
                    if t.kind == Kind::Ws {
                        " ".to_string()
                    } else {
                        t.text.to_string()
                    }
                })
                .collect()
        };
        self.params == other.params
            && self.variadic == other.variadic
            && norm(&self.body) == norm(&other.body)
    }
}

impl Tok {
    /// This token as made by the expansion of the call at `origin`.
    fn made_by(&self, origin: &Range<usize>, hide: Rc<Vec<u32>>) -> Tok {
        Tok {
            kind: self.kind,
            text: self.text.clone(),
            origin: origin.clone(),
            own: false,
            hide,
        }
    }
}

/// The index in `input` of the `)` that closes the `(` at `open`.
fn matching_paren(input: &VecDeque<Tok>, open: usize) -> Option<usize> {
    let mut level = 0usize;
    for (j, x) in input.iter().enumerate().skip(open) {
        match &*x.text {
            "(" if x.kind == Kind::Other => level += 1,
            ")" if x.kind == Kind::Other => {
                level -= 1;
                if level == 0 {
                    return Some(j);
                }
            }
            _ => {}
        }
    }
    None
}

/// The arguments between a call's parentheses, split at the commas outside
/// nested parentheses, without surrounding blanks. `f()` has no argument
/// when `f` takes none.
fn call_arguments(
    inner: &[Tok],
    n_params: usize,
    variadic: bool,
    name_origin: &Range<usize>,
) -> Vec<Vec<Tok>> {
    let mut args: Vec<Vec<Tok>> = vec![Vec::new()];
    let mut level = 0usize;
    for x in inner {
        if x.kind == Kind::Other {
            match &*x.text {
                "(" => level += 1,
                ")" => level = level.saturating_sub(1),
                "," if level == 0 => {
                    args.push(Vec::new());
                    continue;
                }
                _ => {}
            }
        }
        if let Some(a) = args.last_mut() {
            a.push(x.clone());
        }
    }
    let mut args: Vec<Vec<Tok>> = args.into_iter().map(strip_ws).collect();
    if n_params == 0 && args.len() == 1 && args[0].is_empty() {
        args.clear();
    }
    if variadic {
        fit_variadic(&mut args, n_params, name_origin);
    }
    args
}

/// Joins the arguments of a variadic macro past its named parameters into
/// the last one (with the commas between them), or gives it an empty one.
fn fit_variadic(args: &mut Vec<Vec<Tok>>, n_params: usize, name_origin: &Range<usize>) {
    if args.len() > n_params {
        let rest = args.split_off(n_params - 1);
        let mut joined = Vec::new();
        for (i, a) in rest.into_iter().enumerate() {
            if i > 0 {
                joined.push(Tok {
                    kind: Kind::Other,
                    text: Rc::from(","),
                    origin: name_origin.clone(),
                    own: false,
                    hide: Rc::new(Vec::new()),
                });
            }
            joined.extend(a);
        }
        args.push(joined);
    } else if args.len() + 1 == n_params {
        args.push(Vec::new());
    }
}

/// A function-like macro's body with each parameter replaced by its
/// expanded argument, every token made by the call at `origin`.
fn substitute(
    body: &[Tok],
    params: &[String],
    args: &[Vec<Tok>],
    origin: &Range<usize>,
    hide: &Rc<Vec<u32>>,
) -> Vec<Tok> {
    let mut repl: Vec<Tok> = Vec::new();
    for bt in body {
        let p = if bt.kind == Kind::Ident {
            params.iter().position(|p| **p == *bt.text)
        } else {
            None
        };
        match p {
            Some(p) => {
                for at in &args[p] {
                    repl.push(at.made_by(origin, Rc::new(union(&at.hide, hide))));
                }
            }
            None => repl.push(bt.made_by(origin, hide.clone())),
        }
    }
    repl
}

struct Cond {
    /// This group's text is kept.
    active: bool,
    /// A group of this `#if` chain was kept already.
    taken: bool,
    /// The enclosing text is kept.
    parent: bool,
    seen_else: bool,
    span: Range<usize>,
}

/// A directive line taken apart.
struct Directive<'a> {
    name: &'a str,
    /// The tokens after the name.
    rest: Vec<Tok>,
    /// `rest` without its surrounding blanks (the point after the name when
    /// there is nothing).
    rest_span: Range<usize>,
    name_span: Range<usize>,
    /// From the `#` to the end of the line's text.
    line_span: Range<usize>,
}

struct Pp<'a> {
    macros: HashMap<String, Macro>,
    names: Vec<String>,
    include: &'a mut dyn FnMut(&str) -> Option<String>,
    steps: u64,
    aborted: bool,
    /// Expansion stopped at calls nested past the depth limit.
    too_deep: bool,
    /// Names of the files being included (for recursion).
    stack: Vec<String>,
    /// The text of the main file, then of each file in `stack`: where the
    /// notes find the line of an `#include`.
    texts: Vec<Rc<str>>,
    diags: Diagnostics,
}

impl Pp<'_> {
    fn intern(&mut self, name: &str) -> u32 {
        if let Some(i) = self.names.iter().position(|n| n == name) {
            return i as u32;
        }
        self.names.push(name.to_string());
        (self.names.len() - 1) as u32
    }

    fn abort(&mut self, span: Range<usize>, what: &str) {
        if !self.aborted {
            self.aborted = true;
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_EXPANSION_LIMIT,
                    span,
                    format!("macro expansion stopped: {what}"),
                )
                .with_label("expanding this")
                .with_help("look for macros that expand into several copies of each other"),
            );
        }
    }

    /// Preprocesses one file's text into `out`. Diagnostics have spans in
    /// this text.
    fn run(&mut self, text: &str, out: &mut Out, main: bool) {
        let (clean, nl_in_comment) = strip_comments(text, &mut self.diags);
        let b = clean.as_bytes();
        let mut conds: Vec<Cond> = Vec::new();
        let mut pos = 0;
        let mut region: Option<usize> = None; // start of pending text lines
        while pos < b.len() {
            // The logical line: up to a line break that is neither escaped
            // nor inside a comment.
            let mut end = pos;
            loop {
                match clean[end..].find('\n') {
                    None => {
                        end = b.len();
                        break;
                    }
                    Some(k) => {
                        let nl = end + k;
                        let escaped = (nl >= 1 && b[nl - 1] == b'\\')
                            || (nl >= 2 && b[nl - 1] == b'\r' && b[nl - 2] == b'\\');
                        if escaped || nl_in_comment[nl] {
                            end = nl + 1;
                            continue;
                        }
                        end = nl + 1;
                        break;
                    }
                }
            }
            let line = &clean[pos..end];
            let trimmed = line.trim_start_matches([' ', '\t', '\x0b', '\x0c', '\r']);
            let active = conds.last().is_none_or(|c| c.active);
            if is_directive(trimmed) {
                if let Some(r) = region.take() {
                    self.text_region(&clean, r..pos, out);
                }
                let hash = pos + (line.len() - trimmed.len());
                self.directive(&clean, hash, end, &mut conds, out, active, main);
                // The directive's lines become empty lines.
                for (k, &c) in b[pos..end].iter().enumerate() {
                    if c == b'\n' {
                        out.copy("\n", pos + k..pos + k + 1);
                    }
                }
                out.src_hi = out.src_hi.max(end);
            } else if active {
                region.get_or_insert(pos);
            } else {
                for (k, &c) in b[pos..end].iter().enumerate() {
                    if c == b'\n' {
                        out.copy("\n", pos + k..pos + k + 1);
                    }
                }
                out.src_hi = out.src_hi.max(end);
            }
            pos = end;
            if out.full {
                break;
            }
        }
        if let Some(r) = region.take() {
            self.text_region(&clean, r..b.len(), out);
        }
        if out.full {
            self.abort(0..0, "the output passed 8 MiB");
        }
        for c in conds {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_UNTERMINATED_IF,
                    c.span,
                    "conditional block never closed",
                )
                .with_label("opened here")
                .with_help("add `#endif` where the conditional text ends"),
            );
        }
    }

    /// Expands and writes the text lines `range` of `clean`.
    fn text_region(&mut self, clean: &str, range: Range<usize>, out: &mut Out) {
        if out.full {
            return;
        }
        let toks = tokenize(&clean[range.clone()], range.start, false);
        let expanded = self.expand(toks.into(), 0);
        for t in expanded {
            if out.full {
                break;
            }
            if t.own {
                if t.kind == Kind::Splice {
                    out.pending += 1;
                    out.src_hi = out.src_hi.max(t.origin.end);
                } else {
                    out.copy(&t.text, t.origin.clone());
                }
            } else {
                out.generated(&t.text, t.origin.clone(), clean);
            }
        }
    }

    /// Expands a token list (Prosser's algorithm, iteratively).
    fn expand(&mut self, mut input: VecDeque<Tok>, depth: usize) -> Vec<Tok> {
        let mut output = Vec::with_capacity(input.len());
        // What expansion adds is bounded, not the text given: a file of a
        // million plain tokens is no runaway expansion.
        let most_pending = input.len().saturating_add(MAX_PENDING_TOKENS);
        while let Some(t) = input.pop_front() {
            self.steps += 1;
            if self.steps > MAX_STEPS || input.len() > most_pending {
                self.abort(t.origin.clone(), "too many expansion steps");
            }
            if self.aborted || t.kind != Kind::Ident {
                output.push(t);
                continue;
            }
            let Some(m) = self.macros.get(&*t.text) else {
                output.push(t);
                continue;
            };
            if t.hide.contains(&m.id) {
                output.push(t);
                continue;
            }
            let m = m.clone();
            match &m.params {
                None => {
                    // The body replaces the name, to be rescanned.
                    let hide = Rc::new(union(&t.hide, &[m.id]));
                    for bt in m.body.iter().rev() {
                        input.push_front(bt.made_by(&t.origin, hide.clone()));
                    }
                }
                Some(params) => self.expand_call(t, &m, params, &mut input, &mut output, depth),
            }
        }
        output
    }

    /// Expands the call of the function-like macro `m` whose name is `t` and
    /// whose arguments follow in `input`: the replacement goes back to the
    /// front of `input`, to be rescanned. A name without `(` goes to `output`
    /// as it is, and so does a call that is unclosed, has the wrong number
    /// of arguments or is nested too deep (with a diagnostic).
    fn expand_call(
        &mut self,
        t: Tok,
        m: &Macro,
        params: &[String],
        input: &mut VecDeque<Tok>,
        output: &mut Vec<Tok>,
        depth: usize,
    ) {
        // Is the next non-space token `(`?
        let k = input
            .iter()
            .position(|x| !matches!(x.kind, Kind::Ws | Kind::Splice));
        let Some(k) = k.filter(|&k| &*input[k].text == "(") else {
            output.push(t);
            return;
        };
        let Some(close) = matching_paren(input, k) else {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_UNTERMINATED_CALL,
                    t.origin.clone(),
                    format!("call of macro `{}` is never closed", t.text),
                )
                .with_label("this call has no closing `)`")
                .with_help("add the missing `)`; a call cannot run past the next directive"),
            );
            output.push(t);
            return;
        };
        let call: Vec<Tok> = input.drain(..=close).collect();
        let rparen_hide = call[close].hide.clone();
        let args = call_arguments(&call[k + 1..close], params.len(), m.variadic, &t.origin);
        let mut origin = t.origin.clone();
        if let Some(s) = span_of(&call) {
            origin = origin.start.min(s.start)..origin.end.max(s.end);
        }
        // Arguments are expanded by recursion, one level per call, each
        // level holding the arguments of the levels inside it: the calls
        // written nested are counted first, in one pass, rather than found
        // too deep after that much work. (Calls that expansion makes are
        // counted as they are expanded.)
        let too_deep_at = match depth {
            0 => self.first_call_too_deep(&call[k + 1..close], MAX_NESTING),
            _ => None,
        }
        .or((depth >= MAX_NESTING).then_some(&t))
        .map(|x| x.origin.clone());
        let refused = if args.len() != params.len() {
            self.wrong_argument_count(&t, m, params, args.len(), origin.clone());
            true
        } else if let Some(at) = too_deep_at {
            if !std::mem::replace(&mut self.aborted, true) {
                self.too_deep = true;
                self.diags.push(too_deep(
                    at,
                    "call fewer macros inside the arguments of macros",
                ));
            }
            true
        } else {
            false
        };
        if refused {
            // Leave the call as it is.
            output.push(t);
            output.extend(call);
            return;
        }
        let expanded_args: Vec<Vec<Tok>> = args
            .into_iter()
            .map(|a| self.expand(a.into(), depth + 1))
            .collect();
        // The tokens made hide what both the name and the closing `)` hide,
        // and the macro itself.
        let inter: Vec<u32> = t
            .hide
            .iter()
            .filter(|h| rparen_hide.contains(h))
            .copied()
            .collect();
        let hide = Rc::new(union(&inter, &[m.id]));
        let repl = substitute(&m.body, params, &expanded_args, &origin, &hide);
        for x in repl.into_iter().rev() {
            input.push_front(x);
        }
    }

    /// The first call of a function-like macro in `toks` that is the
    /// `room`th or deeper nested in the arguments of others there.
    fn first_call_too_deep<'t>(&self, toks: &'t [Tok], room: usize) -> Option<&'t Tok> {
        let mut calls = 0usize;
        // Per open parenthesis: whether it holds the arguments of a call.
        let mut open: Vec<bool> = Vec::new();
        let mut name: Option<&Tok> = None;
        for x in toks {
            match (x.kind, &*x.text) {
                (Kind::Ws | Kind::Splice, _) => continue,
                (Kind::Ident, n) if self.macros.get(n).is_some_and(|m| m.params.is_some()) => {
                    name = Some(x);
                    continue;
                }
                (Kind::Other, "(") => {
                    if name.is_some() {
                        if calls + 1 >= room {
                            return name;
                        }
                        calls += 1;
                    }
                    open.push(name.is_some());
                }
                (Kind::Other, ")") if open.pop() == Some(true) => calls -= 1,
                _ => {}
            }
            name = None;
        }
        None
    }

    fn wrong_argument_count(
        &mut self,
        t: &Tok,
        m: &Macro,
        params: &[String],
        given: usize,
        origin: Range<usize>,
    ) {
        let mut d = Diagnostic::at(
            codes::CPFG_MACRO_ARGUMENTS,
            origin,
            format!(
                "macro `{}` takes {} argument{} but is given {}",
                t.text,
                params.len(),
                if params.len() == 1 { "" } else { "s" },
                given
            ),
        )
        .with_label("this call")
        .with_help(format!("call it as `{}({})`", t.text, params.join(", ")));
        if let Some(def) = &m.def {
            d = d.with_secondary(def.clone(), "defined here");
        }
        self.diags.push(d);
    }

    /// Reads the directive whose `#` is at `hash` and whose logical line ends
    /// at `end`. In skipped text (not `active`) only the conditionals are
    /// followed.
    #[allow(clippy::too_many_arguments)]
    fn directive(
        &mut self,
        clean: &str,
        hash: usize,
        end: usize,
        conds: &mut Vec<Cond>,
        out: &mut Out,
        active: bool,
        main: bool,
    ) {
        let toks = tokenize(&clean[hash + 1..end], hash + 1, true);
        let mut it = toks.iter().filter(|t| t.kind != Kind::Ws).peekable();
        let line_span = hash..clean[..end].trim_end().len().max(hash + 1);
        let Some(name_tok) = it.next() else {
            return; // the null directive `#`
        };
        let name = &*name_tok.text;
        let name_span = name_tok.origin.clone();
        // The tokens after the directive's name.
        let rest: Vec<Tok> = {
            let idx = toks
                .iter()
                .position(|t| std::ptr::eq(t, name_tok))
                .unwrap_or(0);
            toks[idx + 1..].to_vec()
        };
        let rest_span = span_of(&strip_ws(rest.clone())).unwrap_or(name_span.end..name_span.end);
        let dir = Directive {
            name,
            rest,
            rest_span,
            name_span,
            line_span,
        };
        match name {
            "if" | "ifdef" | "ifndef" => {
                let value = active && self.condition(&dir);
                conds.push(Cond {
                    active: active && value,
                    taken: value,
                    parent: active,
                    seen_else: false,
                    span: dir.line_span,
                });
            }
            "elif" | "else" | "endif" => self.next_group(dir, conds),
            _ if !active => {} // other directives of skipped text are not read
            "define" => self.define(dir.rest, dir.line_span, main),
            "undef" => {
                if let Some(m) = self.macro_operand(&dir) {
                    self.macros.remove(&*m);
                }
            }
            "include" => self.include_directive(dir.rest, dir.line_span, out),
            "error" => {
                let msg = clean[dir.rest_span.clone()].trim().to_string();
                self.diags.push(
                    Diagnostic::at(
                        codes::CPFG_ERROR_DIRECTIVE,
                        dir.line_span,
                        format!("#error {msg}"),
                    )
                    .with_label("the file stops itself here"),
                );
            }
            "pragma" | "line" | "warning" | "ident" | "sccs" => {}
            _ => self.unknown_directive(name_tok, hash),
        }
    }

    /// The value of an `#if`, `#ifdef` or `#ifndef` in kept text.
    fn condition(&mut self, dir: &Directive) -> bool {
        if dir.name == "if" {
            return self.eval_if(&dir.rest, dir.rest_span.clone(), dir.name_span.clone());
        }
        self.macro_operand(dir)
            .is_some_and(|m| self.macros.contains_key(&*m) == (dir.name == "ifdef"))
    }

    /// The macro name an `#ifdef`, `#ifndef` or `#undef` is about: text after
    /// it is reported as ignored, and a line without it as a bad directive.
    fn macro_operand(&mut self, dir: &Directive) -> Option<Rc<str>> {
        let words = strip_ws(dir.rest.clone());
        match words.first() {
            Some(w) if w.kind == Kind::Ident => {
                self.extra_tokens(&words[1..], dir.name);
                Some(w.text.clone())
            }
            _ => {
                self.bad_directive(
                    dir.line_span.clone(),
                    format!("`#{}` needs a macro name", dir.name),
                );
                None
            }
        }
    }

    /// `#elif`, `#else` or `#endif`: ends the current group of the innermost
    /// `#if` and, but for `#endif`, starts the next one.
    fn next_group(&mut self, dir: Directive, conds: &mut Vec<Cond>) {
        let name = dir.name;
        let Some(c) = conds.last_mut() else {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_STRAY_CONDITIONAL,
                    dir.line_span,
                    format!("`#{name}` without `#if`"),
                )
                .with_label("no conditional block is open here")
                .with_help("remove it, or add the `#if` it belongs to"),
            );
            return;
        };
        if name == "endif" {
            self.extra_tokens(&strip_ws(dir.rest), name);
            conds.pop();
            return;
        }
        if c.seen_else {
            let first = c.span.clone();
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_STRAY_CONDITIONAL,
                    dir.line_span,
                    format!("`#{name}` after `#else`"),
                )
                .with_secondary(first, "in the block opened here")
                .with_label("the block already had its `#else`")
                .with_help("a block has at most one `#else`, after every `#elif`"),
            );
            return;
        }
        if name == "else" {
            self.extra_tokens(&strip_ws(dir.rest), name);
            c.seen_else = true;
            c.active = c.parent && !c.taken;
            c.taken = true;
        } else {
            let (parent, taken) = (c.parent, c.taken);
            let value = if parent && !taken {
                self.eval_if(&dir.rest, dir.rest_span, dir.name_span)
            } else {
                false
            };
            if let Some(c) = conds.last_mut() {
                c.active = parent && !taken && value;
                c.taken = taken || value;
            }
        }
    }

    /// A `#` line that is no directive cpfg's preprocessor knows.
    fn unknown_directive(&mut self, name_tok: &Tok, hash: usize) {
        let name = &*name_tok.text;
        let known = [
            "define", "undef", "include", "if", "ifdef", "ifndef", "elif", "else", "endif",
            "error", "pragma", "line",
        ];
        let mut d = Diagnostic::at(
            codes::CPFG_UNKNOWN_DIRECTIVE,
            hash..name_tok.origin.end,
            format!("unknown preprocessor directive `#{name}`"),
        )
        .with_label("not a directive");
        let suggestion = if name_tok.kind == Kind::Ident {
            nearest(name, &known).first().copied()
        } else {
            None
        };
        if let Some(n) = suggestion {
            d = d.suggesting(format!("#{n}"));
        } else {
            d = d.with_help(
                "a line cannot start with `#` in cpfg (the preprocessor reads it as a directive); \
                 put something before the module, e.g. `* < #(w)` as a context",
            );
        }
        self.diags.push(d);
    }

    fn bad_directive(&mut self, span: Range<usize>, msg: String) {
        self.diags
            .push(Diagnostic::at(codes::CPFG_BAD_DIRECTIVE, span, msg).with_label("here"));
    }

    fn extra_tokens(&mut self, words: &[Tok], name: &str) {
        if let Some(s) = span_of(&strip_ws(words.to_vec())) {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_EXTRA_TOKENS,
                    s,
                    format!("extra text after `#{name}` is ignored"),
                )
                .with_label("ignored"),
            );
        }
    }

    fn define(&mut self, rest: Vec<Tok>, line_span: Range<usize>, main: bool) {
        let lead = rest.iter().take_while(|t| t.kind == Kind::Ws).count();
        let Some(name) = rest.get(lead).filter(|t| t.kind == Kind::Ident) else {
            self.bad_directive(line_span, "`#define` needs a macro name".to_string());
            return;
        };
        let mut i = lead + 1;
        let mut params = None;
        let mut variadic = false;
        // A `(` right after the name makes a function-like macro.
        if rest
            .get(i)
            .is_some_and(|t| &*t.text == "(" && t.origin.start == name.origin.end)
        {
            i += 1;
            let mut ps: Vec<String> = Vec::new();
            let mut ok = false;
            let mut expect_name = true;
            while let Some(t) = rest.get(i) {
                i += 1;
                match (t.kind, &*t.text) {
                    (Kind::Ws, _) => {}
                    (Kind::Other, ")") if !expect_name || ps.is_empty() => {
                        ok = true;
                        break;
                    }
                    (Kind::Ident, p) if expect_name => {
                        ps.push(p.to_string());
                        expect_name = false;
                    }
                    (Kind::Other, ".")
                        if expect_name && rest.get(i).is_some_and(|x| &*x.text == ".") =>
                    {
                        // `...`
                        i += 2;
                        ps.push("__VA_ARGS__".to_string());
                        variadic = true;
                        expect_name = false;
                    }
                    (Kind::Other, ",") if !expect_name && !variadic => expect_name = true,
                    _ => break,
                }
            }
            if !ok {
                self.bad_directive(
                    line_span,
                    format!("malformed parameter list of macro `{}`", name.text),
                );
                return;
            }
            params = Some(ps);
        }
        let mut body: Vec<Tok> = Vec::new();
        let raw = &rest[i.min(rest.len())..];
        for (k, t) in raw.iter().enumerate() {
            // `\\` at the end of a line: the first backslash would stay.
            if &*t.text == "\\"
                && t.kind == Kind::Other
                && raw
                    .get(k + 1)
                    .is_some_and(|n| n.kind == Kind::Ws && n.text.is_empty())
            {
                self.diags.push(
                    Diagnostic::at(
                        codes::CPFG_STRAY_BACKSLASH,
                        t.origin.clone(),
                        "backslash before the line continuation is dropped",
                    )
                    .with_label("this `\\` would stay in the macro's text")
                    .with_help("end the line with a single `\\`"),
                );
                continue;
            }
            body.push(t.clone());
        }
        let body = strip_ws(body);
        let name_s = name.text.to_string();
        let id = self.intern(&name_s);
        let m = Macro {
            id,
            params,
            variadic,
            body,
            def: if main { Some(line_span.clone()) } else { None },
        };
        if let Some(old) = self.macros.get(&name_s) {
            if !old.same_as(&m) {
                let mut d = Diagnostic::at(
                    codes::CPFG_MACRO_REDEFINED,
                    line_span,
                    format!("macro `{name_s}` redefined; this definition is used from here on"),
                )
                .with_label("new definition");
                if let Some(def) = &old.def {
                    d = d.with_secondary(def.clone(), "previous definition");
                }
                self.diags.push(
                    d.with_help(format!("write `#undef {name_s}` first if this is intended")),
                );
            }
        }
        self.macros.insert(name_s, m);
    }

    fn include_directive(&mut self, rest: Vec<Tok>, line_span: Range<usize>, out: &mut Out) {
        let words = strip_ws(rest);
        let (file, file_span, after) = match words.first() {
            Some(t) if t.text.starts_with('"') && t.text.len() >= 2 && t.text.ends_with('"') => {
                (t.text[1..t.text.len() - 1].to_string(), t.origin.clone(), 1)
            }
            Some(t) if &*t.text == "<" => match words.iter().position(|x| &*x.text == ">") {
                Some(k) if k > 1 => {
                    let name: String = words[1..k].iter().map(|x| &*x.text).collect();
                    (name, t.origin.start..words[k].origin.end, k + 1)
                }
                _ => {
                    self.bad_directive(line_span, "`#include` needs a file name".to_string());
                    return;
                }
            },
            _ => {
                self.bad_directive(
                    line_span,
                    "`#include` needs a file name in quotes".to_string(),
                );
                return;
            }
        };
        self.extra_tokens(&words[after..], "include");
        if self.stack.len() >= MAX_INCLUDE_DEPTH || self.stack.contains(&file) {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_RECURSIVE_INCLUDE,
                    file_span,
                    if self.stack.contains(&file) {
                        format!("`{file}` includes itself")
                    } else {
                        format!("includes nested more than {MAX_INCLUDE_DEPTH} deep")
                    },
                )
                .with_label("not included again")
                .with_note(format!("include chain: {}", self.stack.join(" -> "))),
            );
            return;
        }
        let Some(text) = (self.include)(&file) else {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_MISSING_INCLUDE,
                    file_span,
                    format!("cannot read included file `{file}`"),
                )
                .with_label("no such file beside the L-system file")
                .with_help("check the name; included files are looked for in the object's folder"),
            );
            return;
        };
        let note = self.included_note(&file, &line_span);
        let side = Arc::new(SideFile {
            name: file.clone(),
            text: text.clone(),
        });
        self.stack.push(file);
        self.texts.push(Rc::from(text.as_str()));
        let saved = std::mem::take(&mut self.diags);
        let mut sub = Out::default();
        self.run(&text, &mut sub, false);
        let inner = std::mem::replace(&mut self.diags, saved);
        self.texts.pop();
        self.stack.pop();
        // Diagnostics inside the included file are shown there, with a
        // note at the `#include` (those of a file it includes already are).
        for d in inner.0 {
            let mut d = match d.side {
                Some(_) => d,
                None => d.in_side_file(side.clone()),
            };
            d.notes.push(note.clone());
            self.diags.push(d);
        }
        // The included text (with its own line breaks) maps to the directive.
        let mut t = sub.text;
        if !t.ends_with('\n') && !t.is_empty() {
            t.push('\n');
        }
        let start = out.text.len();
        if !out.push_seg(&t, line_span, false) {
            out.full = true;
            return;
        }
        out.included.push(Included {
            file: side,
            out: start..out.text.len(),
            map: SourceMap {
                segs: sub.segs,
                src_len: text.len(),
                included: sub.included,
            },
            note,
        });
    }

    /// "`file` is included at line N of …": where the `#include` at `at`
    /// of the file being read stands.
    fn included_note(&self, file: &str, at: &Range<usize>) -> String {
        let including = self.texts.last().map_or("", |t| t);
        let before = including.get(..at.start).unwrap_or(including);
        let line = 1 + before.bytes().filter(|&c| c == b'\n').count();
        match self.stack.last() {
            Some(parent) => format!("`{file}` is included at line {line} of `{parent}`"),
            None => format!("`{file}` is included at line {line} of the L-system file"),
        }
    }

    /// Evaluates an `#if`/`#elif` condition.
    fn eval_if(&mut self, rest: &[Tok], span: Range<usize>, name_span: Range<usize>) -> bool {
        // `defined X` / `defined(X)` first, then macro expansion.
        let mut toks: Vec<Tok> = Vec::new();
        let mut i = 0;
        let sig = |k: &mut usize| {
            while *k < rest.len() && rest[*k].kind == Kind::Ws {
                *k += 1;
            }
        };
        while i < rest.len() {
            let t = &rest[i];
            if t.kind == Kind::Ident && &*t.text == "defined" {
                let mut k = i + 1;
                sig(&mut k);
                let paren = rest.get(k).is_some_and(|x| &*x.text == "(");
                if paren {
                    k += 1;
                    sig(&mut k);
                }
                let name = rest.get(k).filter(|x| x.kind == Kind::Ident);
                let Some(name) = name else {
                    self.bad_directive(span, "`defined` needs a macro name".to_string());
                    return false;
                };
                let v = self.macros.contains_key(&*name.text);
                k += 1;
                if paren {
                    sig(&mut k);
                    if rest.get(k).is_none_or(|x| &*x.text != ")") {
                        self.bad_directive(span, "`defined(` is not closed".to_string());
                        return false;
                    }
                    k += 1;
                }
                let mut t2 = t.clone();
                t2.kind = Kind::Other;
                t2.text = Rc::from(if v { "1" } else { "0" });
                toks.push(t2);
                i = k;
            } else {
                toks.push(t.clone());
                i += 1;
            }
        }
        let expanded = self.expand(toks.into(), 0);
        let words: Vec<&Tok> = expanded
            .iter()
            .filter(|t| !matches!(t.kind, Kind::Ws | Kind::Splice))
            .collect();
        if words.is_empty() {
            self.bad_directive(name_span, "`#if` needs a condition".to_string());
            return false;
        }
        let mut p = Expr {
            toks: &words,
            pos: 0,
            err: None,
            too_deep: None,
        };
        let v = p.ternary(0);
        if p.err.is_none() && p.pos < words.len() {
            p.err = Some(format!("unexpected `{}`", words[p.pos].text));
        }
        if let Some(at) = p.too_deep {
            self.diags.push(too_deep(
                at,
                "write the condition with fewer parentheses, signs and `?:`",
            ));
            return false;
        }
        match p.err {
            Some(e) => {
                self.diags.push(
                    Diagnostic::at(
                        codes::CPFG_BAD_DIRECTIVE,
                        span,
                        format!("cannot evaluate the condition: {e}"),
                    )
                    .with_label("this condition")
                    .with_help(
                        "`#if` takes an integer expression; names that are not macros count as 0",
                    ),
                );
                false
            }
            None => v != 0,
        }
    }
}

/// The integer expressions of `#if`.
struct Expr<'a> {
    toks: &'a [&'a Tok],
    pos: usize,
    err: Option<String>,
    /// The token that went past [`MAX_NESTING`], if one did.
    too_deep: Option<Range<usize>>,
}

impl Expr<'_> {
    fn peek(&self) -> &str {
        self.toks.get(self.pos).map_or("", |t| &t.text)
    }
    fn peek2(&self) -> String {
        let a = self.peek();
        match self.toks.get(self.pos + 1) {
            Some(b) if b.origin.start == self.toks[self.pos].origin.end || !b.own => {
                format!("{a}{}", b.text)
            }
            _ => a.to_string(),
        }
    }
    fn fail(&mut self, msg: String) -> i64 {
        if self.err.is_none() {
            self.err = Some(msg);
        }
        self.pos = self.toks.len();
        0
    }

    /// Whether `depth` (the levels of parentheses, signs and `?:` around
    /// the token at `pos`) is past the limit; if so, evaluation stops there
    /// and the token that opened the level is kept to be reported.
    fn past_limit(&mut self, depth: usize) -> bool {
        if depth <= MAX_NESTING {
            return false;
        }
        let opener = self.toks.get(self.pos.saturating_sub(1));
        self.too_deep = opener.map(|t| t.origin.clone());
        self.fail("nested too deeply".to_string());
        true
    }

    fn ternary(&mut self, depth: usize) -> i64 {
        if self.past_limit(depth) {
            return 0;
        }
        let c = self.binary(0, depth);
        if self.peek() == "?" {
            self.pos += 1;
            let a = self.ternary(depth + 1);
            if self.peek() != ":" {
                return self.fail("`?` without `:`".to_string());
            }
            self.pos += 1;
            let b = self.ternary(depth + 1);
            return if c != 0 { a } else { b };
        }
        c
    }

    /// Binary operators by precedence level (0 = `||`).
    fn binary(&mut self, level: usize, depth: usize) -> i64 {
        const LEVELS: &[&[&str]] = &[
            &["||"],
            &["&&"],
            &["|"],
            &["^"],
            &["&"],
            &["==", "!="],
            &["<=", ">=", "<", ">"],
            &["<<", ">>"],
            &["+", "-"],
            &["*", "/", "%"],
        ];
        if level == LEVELS.len() {
            return self.unary(depth);
        }
        let mut l = self.binary(level + 1, depth);
        loop {
            if self.err.is_some() {
                return 0;
            }
            let two = self.peek2();
            let op = if LEVELS[level].contains(&two.as_str()) && two.len() == 2 {
                two
            } else if LEVELS[level].contains(&self.peek()) {
                // A one-character operator that is not the start of a longer one.
                let one = self.peek().to_string();
                if two.len() == 2
                    && ["||", "&&", "==", "!=", "<=", ">=", "<<", ">>"].contains(&two.as_str())
                {
                    return l;
                }
                one
            } else {
                return l;
            };
            self.pos += if op.len() == 2 && self.peek().len() == 1 {
                2
            } else {
                1
            };
            let r = self.binary(level + 1, depth);
            l = match op.as_str() {
                "||" => i64::from(l != 0 || r != 0),
                "&&" => i64::from(l != 0 && r != 0),
                "|" => l | r,
                "^" => l ^ r,
                "&" => l & r,
                "==" => i64::from(l == r),
                "!=" => i64::from(l != r),
                "<" => i64::from(l < r),
                ">" => i64::from(l > r),
                "<=" => i64::from(l <= r),
                ">=" => i64::from(l >= r),
                "<<" => l.wrapping_shl(r as u32),
                ">>" => l.wrapping_shr(r as u32),
                "+" => l.wrapping_add(r),
                "-" => l.wrapping_sub(r),
                "*" => l.wrapping_mul(r),
                "/" | "%" if r == 0 => return self.fail("division by zero".to_string()),
                "/" => l.wrapping_div(r),
                _ => l.wrapping_rem(r),
            };
        }
    }

    fn unary(&mut self, depth: usize) -> i64 {
        if self.past_limit(depth) {
            return 0;
        }
        let Some(t) = self.toks.get(self.pos) else {
            return self.fail("the condition ends too early".to_string());
        };
        let text = t.text.clone();
        self.pos += 1;
        match &*text {
            "-" => self.unary(depth + 1).wrapping_neg(),
            "+" => self.unary(depth + 1),
            "!" => i64::from(self.unary(depth + 1) == 0),
            "~" => !self.unary(depth + 1),
            "(" => {
                let v = self.ternary(depth + 1);
                if self.peek() != ")" {
                    return self.fail("`(` without `)`".to_string());
                }
                self.pos += 1;
                v
            }
            // Names left after expansion are 0, as in C.
            _ if t.kind == Kind::Ident => 0,
            s if s.as_bytes()[0].is_ascii_digit() => match parse_int(s) {
                Some(v) => v,
                None => self.fail(format!("`{s}` is not an integer")),
            },
            s => self.fail(format!("unexpected `{s}`")),
        }
    }
}

fn parse_int(s: &str) -> Option<i64> {
    let s = s.trim_end_matches(['u', 'U', 'l', 'L']);
    let (digits, radix) = if let Some(h) = s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        (h, 16)
    } else if s.len() > 1 && s.starts_with('0') {
        (&s[1..], 8)
    } else {
        (s, 10)
    };
    u64::from_str_radix(digits, radix).ok().map(|v| v as i64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn pp(text: &str) -> Preprocessed {
        preprocess(text, &mut |_| None)
    }
    fn codes_of(p: &Preprocessed) -> Vec<&'static str> {
        p.diagnostics.iter().map(|d| d.code.0).collect()
    }

    #[test]
    fn object_macros_expand_and_lines_stay() {
        let src =
            "#define RATE 1.02 /* growth */\n#define N 3\naxiom: A(RATE)\nA(x) --> A(x*RATE)B(N)\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        assert_eq!(p.text, "\n\naxiom: A(1.02)\nA(x) --> A(x*1.02)B(3)\n");
        assert_eq!(p.text.lines().count(), src.lines().count());
    }

    #[test]
    fn function_like_macros_nest_and_rescan() {
        let src =
            "#define MAX(a,b) (((a)>(b))?(a):(b))\n#define W(x) MAX(x,1)\nA --> F(W(MAX(2,3)))\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        let y = "(((2)>(3))?(2):(3))";
        assert_eq!(p.text.trim(), format!("A --> F(((({y})>(1))?({y}):(1)))"));
    }

    #[test]
    fn a_name_without_parenthesis_is_not_a_call() {
        let p = pp("#define f(x) g\nA --> f + f(1)\n");
        assert_eq!(p.text, "\nA --> f + g\n");
    }

    #[test]
    fn no_self_recursion() {
        let p = pp("#define A A+B\n#define B A*2\nx: A\n");
        assert!(p.diagnostics.is_empty());
        assert_eq!(p.text, "\n\nx: A+A*2\n");
        let p = pp("#define f(x) f(x+1)\nf(f(0))\n");
        assert_eq!(p.text, "\nf(f(0+1)+1)\n");
    }

    #[test]
    fn continuation_lines_join_the_definition_and_keep_line_count() {
        let src = "#define LEAF(a) [+F(a)\\\n   -F(a)]\nA --> LEAF(2)\nB\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        assert_eq!(p.text, "\n\nA --> [+F(2)   -F(2)]\nB\n");
    }

    #[test]
    fn double_backslash_is_dropped_with_a_warning() {
        let p = pp("#define f(x) \\\\\n\t(x*2)\nA --> F(f(3))\n");
        assert_eq!(codes_of(&p), ["W0802"]);
        assert_eq!(p.text, "\n\nA --> F((3*2))\n");
    }

    #[test]
    fn no_expansion_in_comments_or_strings() {
        let p = pp("#define N 5\n/* N */ printf(\"N=%d\", N); // N\n");
        assert_eq!(p.text, "\n        printf(\"N=%d\", 5);     \n");
    }

    #[test]
    fn multi_line_comment_inside_a_define() {
        let src = "#define LM (8/8)  /* amount\n   maintained */\nA --> F(LM)\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty());
        assert_eq!(p.text, "\n\nA --> F((8/8))\n");
    }

    #[test]
    fn conditionals() {
        let src = "#define LEAVES 2\n#if LEAVES==1\none\n#elif LEAVES>1 && defined(LEAVES)\ntwo\n#else\nthree\n#endif\n#ifdef NOPE\nx\n#endif\n#ifndef NOPE\ny\n#endif\n";
        let p = pp(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        assert_eq!(p.text.split_whitespace().collect::<Vec<_>>(), ["two", "y"]);
        assert_eq!(p.text.lines().count(), src.lines().count());
        // Nested, with arithmetic and the ternary.
        let p = pp("#if (7 % 4) * 2 - 6 == 0 ? !0 : 0\n#if 1 < 0 || (2 <= 2 && 3 >= 4)\nno\n#else\nyes\n#endif\n#endif\n");
        assert_eq!(p.text.trim(), "yes");
    }

    #[test]
    fn map_sends_expansions_back_to_the_call() {
        let src = "#define W(x) #(x*2)\naxiom: F W(3) G\n";
        let p = pp(src);
        let at = p.text.find("#(3*2)").unwrap();
        let call = src.find("W(3)").unwrap();
        assert_eq!(p.map.to_source(at + 2..at + 3), call..call + 4);
        // Copied text maps to itself.
        let g = p.text.find('G').unwrap();
        let gs = src.rfind('G').unwrap();
        assert_eq!(p.map.to_source(g..g + 1), gs..gs + 1);
        let a = p.text.find("axiom").unwrap();
        assert_eq!(&src[p.map.to_source(a..a + 5)], "axiom");
    }

    #[test]
    fn calls_spanning_lines_put_the_line_breaks_back() {
        let src = "#define P(a,b) a+b\nA --> P(1,\n 2) B\nC\n";
        let p = pp(src);
        assert_eq!(p.text, "\nA --> 1+2 B\n\nC\n");
        let c = p.text.find('C').unwrap();
        assert_eq!(
            p.map.to_source(c..c + 1),
            src.find('C').map(|i| i..i + 1).unwrap()
        );
    }

    #[test]
    fn includes() {
        let mut files = |n: &str| match n {
            "leaf.l" => Some("#define LW 2\nleaf --> F(LW)\n".to_string()),
            "self.l" => Some("#include \"self.l\"\n".to_string()),
            _ => None,
        };
        let src = "#include \"leaf.l\"\nA --> LW\n#include \"nope.l\"\n#include \"self.l\"\n";
        let p = preprocess(src, &mut files);
        assert!(p.text.contains("leaf --> F(2)"));
        assert!(p.text.contains("A --> 2"));
        assert_eq!(codes_of(&p), ["E0806", "E0807"]);
        let missing = &p.diagnostics.0[0];
        assert_eq!(&src[missing.span.clone().unwrap()], "\"nope.l\"");
        // Included text maps to the directive.
        let at = p.text.find("leaf -->").unwrap();
        assert_eq!(&src[p.map.to_source(at..at + 4)], "#include \"leaf.l\"");
        // Recursion is reported at the directive, naming the file.
        assert!(p.diagnostics.0[1]
            .notes
            .iter()
            .any(|n| n.contains("self.l")));
    }

    #[test]
    fn errors_with_spans() {
        let src = "/* open\nA";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0801"]);
        assert_eq!(p.diagnostics.0[0].span, Some(0..2));

        let p = pp("#if 1\nA\n");
        assert_eq!(codes_of(&p), ["E0802"]);
        let p = pp("A\n#endif\n#else\n");
        assert_eq!(codes_of(&p), ["E0803", "E0803"]);
        let p = pp("#if 0\n#else\n#else\n#endif\n");
        assert_eq!(codes_of(&p), ["E0803"]);

        let src = "#define M(a,b) a\nA --> M(1)\n";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0804"]);
        assert_eq!(&src[p.diagnostics.0[0].span.clone().unwrap()], "M(1)");
        assert_eq!(p.diagnostics.0[0].labels[0].span, 0..16);

        let src = "x\n#w(d) --> #(d*2)\n";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0805"]);
        assert_eq!(&src[p.diagnostics.0[0].span.clone().unwrap()], "#w");
        // `#` before something that is not a name is text, as vlab reads it.
        let p = pp("A -->\n\t#(0.06) F\n");
        assert!(p.diagnostics.is_empty());
        assert_eq!(p.text, "A -->\n\t#(0.06) F\n");
        let p = pp("#defin X 1\n");
        assert_eq!(
            p.diagnostics.0[0].help.as_deref(),
            Some("did you mean `#define`?")
        );

        let src = "#define M(a) a\nA --> M(1\n";
        let p = pp(src);
        assert_eq!(codes_of(&p), ["E0808"]);
        assert_eq!(&src[p.diagnostics.0[0].span.clone().unwrap()], "M");

        let p = pp("#if 1/0\n#endif\n#if 2 +\n#endif\n#define\n#include nope\n");
        assert_eq!(codes_of(&p), ["E0809", "E0809", "E0809", "E0809"]);
    }

    #[test]
    fn predefined_function_names() {
        let p = preprocess_with_defines(
            "x = func(LEAF_WIDTH, 0.5);\n",
            &[("LEAF_WIDTH".into(), "2".into())],
            &mut |_| None,
        );
        assert_eq!(p.text, "x = func(2, 0.5);\n");
    }

    #[test]
    fn exponential_macros_are_cut_off() {
        let mut src = String::new();
        for i in 0..40 {
            src.push_str(&format!("#define M{i} M{} M{}\n", i + 1, i + 1));
        }
        src.push_str("M0\n");
        let p = pp(&src);
        assert!(codes_of(&p).contains(&"E0810"));
        assert!(p.text.len() <= MAX_OUTPUT);
    }

    #[test]
    fn redefinition_warns_only_when_different() {
        let p = pp("#define A 1\n#define A 1\n#define A 2\nA\n");
        assert_eq!(codes_of(&p), ["W0801"]);
        assert_eq!(p.text.trim(), "2");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        #[test]
        fn never_panics_and_maps_into_the_source(
            parts in proptest::collection::vec(
                prop_oneof![
                    Just("#define ".to_string()), Just("#if ".to_string()), Just("#endif\n".to_string()),
                    Just("#else\n".to_string()), Just("#include \"a\"\n".to_string()), Just("(".to_string()),
                    Just(")".to_string()), Just(",".to_string()), Just("\\\n".to_string()), Just("/*".to_string()),
                    Just("*/".to_string()), Just("//".to_string()), Just("\"".to_string()), Just("\n".to_string()),
                    Just("A".to_string()), Just("B(x)".to_string()), Just(" A B ".to_string()), Just("é".to_string()),
                    Just("defined".to_string()), Just("1".to_string()), Just("==".to_string()), Just("#".to_string()),
                    "[ -~]{0,6}",
                ],
                0..40,
            )
        ) {
            let src: String = parts.concat();
            let p = preprocess(&src, &mut |n| (n == "a").then(|| "A\n#include \"a\"\n".to_string()));
            prop_assert!(p.text.len() <= MAX_OUTPUT);
            for s in [0..p.text.len(), 0..0, p.text.len() / 2..p.text.len()] {
                let r = p.map.to_source(s);
                prop_assert!(r.start <= r.end && r.end <= src.len(), "{r:?}");
            }
            for d in p.diagnostics.iter() {
                let s = d.span.clone().unwrap_or(0..0);
                prop_assert!(s.start <= s.end && s.end <= shown_in(d, &src).len());
            }
        }
    }

    /// The text a diagnostic's span points into: the included file it is
    /// reported on, else the main file.
    fn shown_in<'a>(d: &'a crate::diagnostics::Diagnostic, main: &'a str) -> &'a str {
        d.side.as_ref().map_or(main, |f| f.text.as_str())
    }

    /// A file that includes itself is reported on that file, at the name
    /// in its own `#include` (the case the property above first found).
    #[test]
    fn a_file_including_itself_is_reported_where_it_does() {
        let inner = "A\n#include \"a\"\n";
        let src = "#include \"a\"\n";
        let p = preprocess(src, &mut |n| (n == "a").then(|| inner.to_string()));
        let on_a: Vec<_> = (p.diagnostics.iter())
            .filter(|d| d.side.as_ref().is_some_and(|f| f.name == "a"))
            .collect();
        assert!(!on_a.is_empty(), "{:?}", p.diagnostics);
        for d in on_a {
            let s = d.span.clone().expect("a place");
            assert_eq!(&shown_in(d, src)[s], "\"a\"");
        }
    }
}
