//! Strings (axioms and rule bodies): splitting names by the longest
//! declared one, numbers after names, and the symbols they become.

use super::guards::lower_guard;
use super::nesting::Nesting;
use super::signs::lower_signs;
use super::{Cx, Role};
use crate::common::vocabulary;
use crate::common::vocabulary::TurtleSet;
use crate::diagnostics::{codes, nearest, Diagnostic};
use crate::front::linf::ast::{Item, Name};
use crate::front::names::LongestNames;
use crate::ir::{Span, SymbolId, TurtleOp};
use std::borrow::Cow;

/// Splits a run of name characters into declared names, longest first.
/// Undeclared stretches come back as `Err` pieces.
pub(super) fn split<'n>(
    cx: &Cx<'_>,
    text: &'n str,
    start: usize,
) -> Vec<(Result<Role, ()>, &'n str, Span)> {
    let built;
    let index = match &cx.name_index {
        Some(index) => index,
        None => {
            built = LongestNames::new(cx.roles.keys().map(String::as_str));
            &built
        }
    };
    let longest = index.longest_at(text);
    let mut out: Vec<(Result<Role, ()>, &str, Span)> = Vec::new();
    let mut p = 0;
    while p < text.len() {
        let len = longest[p];
        let found = (len > 0)
            .then(|| cx.roles.get(&text[p..p + len]).map(|(r, _)| (*r, len)))
            .flatten();
        match found {
            Some((role, len)) => {
                out.push((Ok(role), &text[p..p + len], start + p..start + p + len));
                p += len;
            }
            None => {
                // Names are ASCII; extend an unknown stretch by one byte.
                match out.last_mut() {
                    Some((Err(()), _, span)) if span.end == start + p => {
                        span.end += 1;
                        let s = span.start - start;
                        out.last_mut().expect("just matched").1 = &text[s..p + 1];
                    }
                    _ => out.push((Err(()), &text[p..p + 1], start + p..start + p + 1)),
                }
                p += 1;
            }
        }
    }
    out
}

pub(super) struct StringOut {
    pub(super) word: Vec<SymbolId>,
    pub(super) spans: Vec<Span>,
}

impl StringOut {
    pub(super) fn push(&mut self, id: SymbolId, span: Span) {
        self.word.push(id);
        self.spans.push(span);
    }
}

fn undeclared(cx: &mut Cx<'_>, text: &str, span: Span, whole: &str) {
    cx.report(codes::LINF_UNDECLARED, |cx| {
        undeclared_name(cx, text, span, whole)
    });
}

fn undeclared_name(cx: &mut Cx<'_>, text: &str, span: Span, whole: &str) -> Diagnostic {
    // Angles are not suggested: alone in a string they would be wrong too.
    let affordable = cx
        .suggester
        .afford(text.len() + whole.len(), cx.roles.len(), cx.longest);
    let names = if affordable {
        cx.names(false)
    } else {
        Vec::new()
    };
    let mut near = nearest(text, &names);
    if near.is_empty() && whole != text {
        near = nearest(whole, &names);
    }
    near.sort();
    // With one-letter names everything is one edit away: no guess then.
    if near.len() > 3 {
        near.clear();
    }
    let d = Diagnostic::at(
        codes::LINF_UNDECLARED,
        span,
        format!("`{text}` is not declared"),
    )
    .with_label("not a line, blank, angle or rule head");
    match near.as_slice() {
        [] => d.with_help(format!(
            "declare it: `lines {text}` to draw it, `blanks {text}` to move without drawing, or give it a rule `{text} = …`"
        )),
        [one] => d.suggesting(one),
        many => d.with_help(format!(
            "did you mean one of {}?",
            many.iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Appends the pieces of a name (already split) to `out`.
pub(super) fn push_pieces(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    pieces: &[(Result<Role, ()>, &str, Span)],
    whole: &str,
) {
    for (role, text, span) in pieces {
        match role {
            Err(()) => undeclared(cx, text, span.clone(), whole),
            Ok(Role::Angle(_)) => cx.report(codes::LINF_BARE_ANGLE, |_| {
                Diagnostic::at(
                    codes::LINF_BARE_ANGLE,
                    span.clone(),
                    format!("the angle `{text}` is used without a sign"),
                )
                .with_label("an angle name must follow `+` or `-`")
                .with_help(format!(
                    "write `+{text}` or `-{text}` (no space) to rotate by it"
                ))
            }),
            Ok(_) => {
                let id = cx.sys.intern(text);
                out.push(id, span.clone());
            }
        }
    }
}

/// Names may end in digits (`f1`), so `f0.5?j` and `f2@` lex as the name
/// `f0` or `f2` and what follows. When the trailing digits of such a name
/// are no declared name, and a number, `?` or `@` follows, they are the
/// number: `f0.5?j` is `f 0.5?j`, `f2@` is `f 2@`.
fn detach_numbers<'i>(cx: &Cx<'_>, items: &'i [Item]) -> Cow<'i, [Item]> {
    // Most strings have no name ending in digits: they are not copied.
    let ends_in_digit =
        |i: &Item| matches!(i, Item::Name(n) if n.text.ends_with(|c: char| c.is_ascii_digit()));
    if !items.iter().any(ends_in_digit) {
        return Cow::Borrowed(items);
    }
    let mut out: Vec<Item> = Vec::with_capacity(items.len());
    let mut i = 0;
    while i < items.len() {
        let (Item::Name(n), Some(next)) = (&items[i], items.get(i + 1)) else {
            out.push(items[i].clone());
            i += 1;
            continue;
        };
        let fraction = match next {
            Item::Number { text, span, .. }
                if text.starts_with('.') && span.start == n.span.end =>
            {
                Some((text.as_str(), span.end))
            }
            Item::Question(s) | Item::At(s) if s.start == n.span.end => None,
            _ => {
                out.push(items[i].clone());
                i += 1;
                continue;
            }
        };
        let digits = n.text.len() - n.text.trim_end_matches(|c: char| c.is_ascii_digit()).len();
        let unknown_tail =
            matches!(split(cx, &n.text, 0).last(), Some((Err(()), t, _)) if t.len() >= digits);
        if digits == 0 || digits == n.text.len() || !unknown_tail {
            out.push(items[i].clone());
            i += 1;
            continue;
        }
        let cut = n.span.end - digits;
        out.push(Item::Name(Name {
            text: n.text[..n.text.len() - digits].to_string(),
            span: n.span.start..cut,
        }));
        let digit_text = &n.text[n.text.len() - digits..];
        let (text, end) = match fraction {
            Some((f, end)) => (format!("{digit_text}{f}"), end),
            None => (digit_text.to_string(), n.span.end),
        };
        out.push(Item::Number {
            value: text.parse().unwrap_or(f64::NAN),
            text,
            span: cut..end,
        });
        i += if fraction.is_some() { 2 } else { 1 };
    }
    Cow::Owned(out)
}

/// Interns `name` with the turtle meaning `op` and appends it.
pub(super) fn push_op(cx: &mut Cx<'_>, out: &mut StringOut, name: &str, op: TurtleOp, span: Span) {
    let id = cx.sys.intern(name);
    cx.sys.set_interpretation(id, op);
    out.push(id, span);
}

pub(super) fn lower_string(cx: &mut Cx<'_>, items: &[Item]) -> (Vec<SymbolId>, Vec<Span>) {
    let items = &detach_numbers(cx, items)[..];
    let mut out = StringOut {
        word: Vec::new(),
        spans: Vec::new(),
    };
    let mut nesting = Nesting::new();
    let mut i = 0;
    while i < items.len() {
        i = match &items[i] {
            Item::Name(n) => {
                let pieces = split(cx, &n.text, n.span.start);
                push_pieces(cx, &mut out, &pieces, &n.text);
                i + 1
            }
            Item::Sign { .. } => lower_signs(cx, &mut out, items, i),
            Item::Number { value, text, span } => {
                lower_number(cx, &mut out, items, i, (*value, text), span)
            }
            Item::Question(span) => {
                missing_number(cx, span, "?", "`0.5?j` expands `j` with probability 0.5");
                i + 1
            }
            Item::At(span) => {
                missing_number(cx, span, "@", "`0.5@` halves the length");
                i + 1
            }
            Item::Open(span) => {
                nesting.open(span);
                out.push(SymbolId::OPEN, span.clone());
                i + 1
            }
            Item::Close(span) => {
                nesting.close(cx, span);
                out.push(SymbolId::CLOSE, span.clone());
                i + 1
            }
            Item::NextColour(span) => {
                nesting.next_colour(span);
                push_op(cx, &mut out, "{", linf_op("{"), span.clone());
                i + 1
            }
            Item::PreviousColour(span) => {
                nesting.previous_colour(cx, span);
                push_op(cx, &mut out, "}", linf_op("}"), span.clone());
                i + 1
            }
            Item::Swap(span) => {
                push_op(cx, &mut out, "!", linf_op("!"), span.clone());
                i + 1
            }
        };
    }
    nesting.check_closed(cx);
    cx.repeats.end_item(cx.diags, "in this string");
    // The first place each symbol is written (for diagnostics elsewhere,
    // e.g. translation).
    for (id, span) in out.word.iter().zip(&out.spans) {
        cx.spans.symbols.entry(*id).or_insert_with(|| span.clone());
    }
    (out.word, out.spans)
}

/// What LinF's fixed symbol `name` does ([`vocabulary`]'s LinF set).
fn linf_op(name: &str) -> TurtleOp {
    vocabulary::op(TurtleSet::Linf, name).unwrap_or(TurtleOp::Push)
}

/// A number, as written: `x@` scales the length, `p?s` guards `s`; any
/// other number is reported. Returns the index of the next item.
fn lower_number(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    items: &[Item],
    i: usize,
    (value, text): (f64, &str),
    span: &Span,
) -> usize {
    match items.get(i + 1) {
        Some(Item::At(at)) => {
            let op = TurtleOp::ScaleLength(value);
            push_op(cx, out, &format!("{text}@"), op, span.start..at.end);
            i + 2
        }
        Some(Item::Question(q)) => lower_guard(cx, out, items, i, value, span, q),
        _ => {
            cx.report(codes::LINF_STRAY_NUMBER, |_| {
                Diagnostic::at(
                    codes::LINF_STRAY_NUMBER,
                    span.clone(),
                    format!("the number `{text}` is not followed by `?` or `@`"),
                )
                .with_label("a number in a string must say what it is for")
                .with_help(format!(
                    "`{text}@` multiplies the length; `{text}?s` expands `s` with probability {text}"
                ))
            });
            i + 1
        }
    }
}

/// `?` or `@` (`mark`) with no number before it.
fn missing_number(cx: &mut Cx<'_>, span: &Span, mark: &str, example: &str) {
    cx.report(codes::LINF_MISSING_NUMBER, |_| {
        Diagnostic::at(
            codes::LINF_MISSING_NUMBER,
            span.clone(),
            format!("`{mark}` without a number before it"),
        )
        .with_label("needs a number right before it")
        .with_help(format!("write the number first: {example}"))
    });
}
