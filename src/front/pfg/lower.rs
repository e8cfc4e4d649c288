//! Lowering a pfg AST to the IR, with the checks the 1988 format implies.

use super::ast::{File, Header, Item, Production as AstProduction, Symbols};
use super::parser::HEADERS;
use crate::common::vocabulary::{self, TurtleSet};
use crate::diagnostics::{codes, nearest, Diagnostic, Diagnostics};
use crate::front::repeats::push_lazily;
use crate::ir::{
    Alternative, ContextFilter, Production, Span, SpanTable, SymbolId, System, TurtleOp, Word,
};
use std::collections::HashMap;

pub use crate::ir::Lowered;

struct Ctx<'a> {
    sys: System,
    spans: SpanTable,
    diags: &'a mut Diagnostics,
}

impl Ctx<'_> {
    fn intern(&mut self, name: &str, span: &Span) -> SymbolId {
        let id = self.sys.intern(name);
        self.spans.symbols.entry(id).or_insert_with(|| span.clone());
        id
    }

    fn word(&mut self, s: &Symbols) -> (Word, Vec<Span>) {
        let mut ids = Vec::with_capacity(s.chars.len());
        let mut spans = Vec::with_capacity(s.chars.len());
        for (c, span) in &s.chars {
            ids.push(self.intern(c, span));
            spans.push(span.clone());
        }
        (Word::from(ids), spans)
    }
}

/// Lowers a parsed file. Problems are pushed to `diags`; the result is
/// usable only if no error was pushed.
pub fn lower(file: &File, diags: &mut Diagnostics) -> Lowered {
    let mut sys = System::new();
    for name in TurtleSet::Pfg.names() {
        if let Some(op) = vocabulary::op(TurtleSet::Pfg, name) {
            let id = sys.intern(name);
            sys.set_interpretation(id, op);
        }
    }
    let mut cx = Ctx {
        sys,
        spans: SpanTable::default(),
        diags,
    };
    let headers: Vec<&Header> = file
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Header(h) => Some(h),
            _ => None,
        })
        .collect();
    let productions: Vec<&AstProduction> = file
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Production(p) => Some(p),
            _ => None,
        })
        .collect();
    let seen = lower_headers(&mut cx, &headers);
    if !seen[3] {
        let at = file
            .items
            .first()
            .map(|i| match i {
                Item::Header(h) => h.span.start..h.span.start,
                Item::Production(p) => p.span.start..p.span.start,
            })
            .unwrap_or(0..0);
        cx.diags.push(
            Diagnostic::at(codes::MISSING_AXIOM, at, "missing axiom")
                .with_label("this file has no `axiom:` line")
                .with_help(
                    "add the start word, e.g. `axiom: F+F+F+F`, after the angle and scale factors",
                ),
        );
    }
    lower_productions(&mut cx, &productions);
    if !seen[1] && uses_turns(&cx.sys) {
        let at = headers.first().map_or(0..0, |h| h.span.start..h.span.start);
        cx.diags.push(
            Diagnostic::at(
                codes::MISSING_HEADER,
                at,
                "no `angle factor`: turning by 90°",
            )
            .with_label("the headers start here")
            .with_help("add `angle factor: N` for an angle increment of 360°/N"),
        );
    }
    Lowered {
        system: cx.sys,
        spans: cx.spans,
    }
}

fn uses_turns(sys: &System) -> bool {
    let turns = |w: &Word| {
        w.0.iter()
            .any(|&s| matches!(sys.op(s), Some(TurtleOp::Rotate { .. })))
    };
    turns(&sys.axiom)
        || sys
            .productions
            .iter()
            .flat_map(|p| &p.alternatives)
            .any(|a| turns(&a.successor))
}

/// Lowers the headers; returns which of [`HEADERS`] were seen.
fn lower_headers(cx: &mut Ctx<'_>, headers: &[&Header]) -> [bool; 5] {
    let mut seen: [Option<Span>; 5] = Default::default();
    let mut last: Option<(usize, Span)> = None;
    for h in headers {
        let key = h.key.to_lowercase();
        let Some(idx) = HEADERS.iter().position(|k| *k == key) else {
            push_lazily(cx.diags, codes::UNKNOWN_HEADER, || {
                let d = Diagnostic::at(
                    codes::UNKNOWN_HEADER,
                    h.key_span.clone(),
                    format!("unknown header `{}`", h.key),
                )
                .with_label("not a pfg header");
                match nearest(&h.key, &HEADERS).first() {
                    Some(k) => d.suggesting(k),
                    None => d.with_help(format!(
                        "pfg headers are: {}",
                        HEADERS.map(|k| format!("`{k}:`")).join(", ")
                    )),
                }
            });
            continue;
        };
        if let Some(first) = &seen[idx] {
            cx.diags.push(
                Diagnostic::at(
                    codes::DUPLICATE_HEADER,
                    h.key_span.clone(),
                    format!("`{}` is given twice", HEADERS[idx]),
                )
                .with_label("this value is used")
                .with_secondary(first.clone(), "first given here"),
            );
        }
        if let Some((prev, prev_span)) = &last {
            if idx < *prev {
                cx.diags.push(
                    Diagnostic::at(
                        codes::HEADER_ORDER,
                        h.key_span.clone(),
                        format!("`{}` comes after `{}`", HEADERS[idx], HEADERS[*prev]),
                    )
                    .with_label("out of the listing's order")
                    .with_secondary(prev_span.clone(), "should come after this")
                    .with_note("the Appendix A program reads: derivation length, angle factor, scale factor, axiom, ignore"),
                );
            }
        }
        if last.as_ref().is_none_or(|(p, _)| idx > *p) {
            last = Some((idx, h.key_span.clone()));
        }
        seen[idx] = Some(h.key_span.clone());
        lower_header(cx, idx, h);
    }
    seen.map(|s| s.is_some())
}

fn value_span(h: &Header) -> Span {
    if h.value.chars.is_empty() {
        h.key_span.end..h.span.end
    } else {
        h.value.span.clone()
    }
}

fn lower_header(cx: &mut Ctx<'_>, idx: usize, h: &Header) {
    let text = h.value.text();
    let span = value_span(h);
    let int = text.parse::<i64>();
    match idx {
        0 => match int {
            Ok(n) if n >= 0 => cx.sys.settings.steps = Some(n as u64),
            Ok(_) => cx.diags.push(
                Diagnostic::at(codes::NEGATIVE_STEPS, span, "negative derivation length")
                    .with_label(format!("{text} steps"))
                    .with_help("the derivation length counts steps: use 0 or more"),
            ),
            Err(e) if *e.kind() == std::num::IntErrorKind::PosOverflow => cx.diags.push(
                Diagnostic::at(
                    codes::BAD_HEADER_VALUE,
                    span,
                    format!("derivation length {text} is too large"),
                )
                .with_label(format!("at most {}", i64::MAX))
                .with_help(
                    "no system needs that many steps; `--max-symbols` would stop it long before",
                ),
            ),
            Err(_) => cx
                .diags
                .push(bad_value(span, &text, "a whole number of steps")),
        },
        1 => match int {
            Ok(n) if n > 0 => cx.sys.settings.delta = (360.0 / n as f64).to_radians(),
            _ => {
                let mut d = Diagnostic::at(
                    codes::BAD_ANGLE_FACTOR,
                    span,
                    format!("angle factor `{text}` is not a positive integer"),
                )
                .with_label("the angle increment is 360°/(angle factor)");
                if let Ok(x) = text.parse::<f64>() {
                    if x > 0.0 {
                        let n = x.round().max(1.0);
                        d = d.with_help(format!(
                            "write a whole number, e.g. `{n}` (δ = {:.4}°)",
                            360.0 / n
                        ));
                    }
                }
                if text.is_empty() {
                    d = d.with_help("write a whole number, e.g. `angle factor: 4` for 90°");
                }
                cx.diags.push(d);
            }
        },
        2 => match text.parse::<f64>() {
            Ok(s) if (0.0..=100.0).contains(&s) => cx.sys.settings.scale = s,
            Ok(s) if !s.is_nan() => {
                cx.sys.settings.scale = s.clamp(0.0, 100.0);
                cx.diags.push(
                    Diagnostic::at(
                        codes::SCALE_RANGE,
                        span,
                        format!("scale factor {text} is outside 0..100"),
                    )
                    .with_label(format!("used as {}", cx.sys.settings.scale)),
                );
            }
            _ => cx
                .diags
                .push(bad_value(span, &text, "a number from 0 to 100")),
        },
        3 => {
            if h.value.is_empty() {
                cx.diags.push(
                    Diagnostic::at(codes::BAD_HEADER_VALUE, span, "empty axiom")
                        .with_label("expected the start word here")
                        .with_help("write the axiom's symbols, e.g. `axiom: F+F+F+F`"),
                );
                return;
            }
            check_brackets(cx, &h.value, codes::UNBALANCED_AXIOM, "axiom");
            let (w, spans) = cx.word(&h.value);
            cx.sys.axiom = w;
            cx.spans.axiom = spans;
        }
        _ => {
            if let Some((c, bspan)) = h.value.chars.iter().find(|(c, _)| c == "[" || c == "]") {
                cx.diags.push(
                    Diagnostic::at(codes::BRACKET_IGNORED, bspan.clone(), format!("`{c}` cannot be ignored"))
                        .with_label("dropped from the ignore list")
                        .with_note("context matching always skips branches; the listing's behaviour for ignored brackets enters or leaves branches inconsistently")
                        .with_help("remove the brackets from `ignore:`"),
                );
            }
            let (w, _) = cx.word(&h.value);
            let mut set: Vec<SymbolId> =
                w.0.into_iter()
                    .filter(|&s| s != SymbolId::OPEN && s != SymbolId::CLOSE)
                    .collect();
            set.sort();
            set.dedup();
            cx.sys.context = ContextFilter::Ignore(set);
        }
    }
}

fn bad_value(span: Span, text: &str, expected: &str) -> Diagnostic {
    let msg = if text.is_empty() {
        "missing header value".to_string()
    } else {
        format!("`{text}` is not {expected}")
    };
    Diagnostic::at(codes::BAD_HEADER_VALUE, span, msg).with_label(format!("expected {expected}"))
}

/// Reports the first bracket that does not balance in `s`.
fn check_brackets(
    cx: &mut Ctx<'_>,
    s: &Symbols,
    code: crate::diagnostics::Code,
    what: &str,
) -> bool {
    let mut open: Vec<&Span> = Vec::new();
    for (c, span) in &s.chars {
        match c.as_str() {
            "[" => open.push(span),
            "]" if open.pop().is_none() => {
                cx.diags.push(
                    Diagnostic::at(code, span.clone(), format!("unbalanced `]` in the {what}"))
                        .with_label("this `]` closes no branch")
                        .with_help("remove it, or add the `[` that opens its branch"),
                );
                return false;
            }
            _ => {}
        }
    }
    if let Some(span) = open.last() {
        cx.diags.push(
            Diagnostic::at(code, (*span).clone(), format!("unclosed `[` in the {what}"))
                .with_label("this branch is never closed")
                .with_secondary(s.span.end..s.span.end, "expected `]` before here")
                .with_help("add the `]` that ends this branch"),
        );
        return false;
    }
    true
}

/// (left, predecessor, right) of a production: productions with the same
/// key are alternatives of one stochastic choice, or shadow each other.
type ProductionKey = (Vec<SymbolId>, Vec<SymbolId>, Vec<SymbolId>);

fn lower_productions(cx: &mut Ctx<'_>, prods: &[&AstProduction]) {
    // For each lowered production: whether it carried a weight, its span.
    let mut keys: Vec<(bool, Span)> = Vec::new();
    // The index of the first production with each key.
    let mut first_of: HashMap<ProductionKey, usize> = HashMap::new();
    for p in prods {
        let mut ok = true;
        for part in [p.left.as_ref(), Some(&p.predecessor), p.right.as_ref()]
            .into_iter()
            .flatten()
        {
            if let Some((c, span)) = part.chars.iter().find(|(c, _)| c == "[" || c == "]") {
                let role = if std::ptr::eq(part, &p.predecessor) {
                    "predecessor"
                } else {
                    "context"
                };
                cx.diags.push(
                    Diagnostic::at(
                        codes::BRACKET_IN_PREDECESSOR,
                        span.clone(),
                        format!("`{c}` in a {role}"),
                    )
                    .with_label("brackets may appear only in successors")
                    .with_note("context matching skips whole branches by itself")
                    .with_help("remove the brackets from the predecessor and contexts"),
                );
                ok = false;
            }
        }
        ok &= check_brackets(cx, &p.successor, codes::UNBALANCED_SUCCESSOR, "successor");
        if !ok {
            continue;
        }
        let left = p.left.as_ref().map(|s| cx.word(s).0).unwrap_or_default().0;
        let (pred, _) = cx.word(&p.predecessor);
        let right = p.right.as_ref().map(|s| cx.word(s).0).unwrap_or_default().0;
        let (succ, succ_spans) = cx.word(&p.successor);
        let weighted = p.weight.is_some();
        let existing = first_of
            .get(&(left.clone(), pred.0.clone(), right.clone()))
            .copied();
        if let Some(i) = existing {
            let (first_weighted, first_span) = keys[i].clone();
            match (first_weighted, weighted) {
                (true, true) => {
                    let prod = &mut cx.sys.productions[i];
                    prod.alternatives.push(Alternative::new(
                        p.weight.as_ref().map_or(1.0, |w| w.0),
                        succ,
                    ));
                    cx.spans.successors[i].push(succ_spans);
                    continue;
                }
                (false, false) => {
                    cx.diags.push(
                        Diagnostic::at(
                            codes::SHADOWED_PRODUCTION,
                            p.span.clone(),
                            "this production can never apply",
                        )
                        .with_label("shadowed by an earlier production")
                        .with_secondary(first_span, "this one always matches first")
                        .with_help("give both a weight (`: 0.5`) to choose between them at random"),
                    );
                }
                _ => {
                    let (at, other) = if weighted {
                        (first_span, p.span.clone())
                    } else {
                        (p.span.clone(), first_span)
                    };
                    cx.diags.push(
                        Diagnostic::at(
                            codes::MISSING_WEIGHT,
                            at,
                            "stochastic production without a weight",
                        )
                        .with_label("no weight")
                        .with_secondary(other, "this alternative has one")
                        .with_help(
                            "give every production with this predecessor a weight, e.g. `: 0.5`",
                        ),
                    );
                    continue;
                }
            }
        }
        first_of
            .entry((left.clone(), pred.0.clone(), right.clone()))
            .or_insert(keys.len());
        keys.push((weighted, p.span.clone()));
        cx.sys.productions.push(Production::new(
            left,
            pred.0,
            right,
            vec![Alternative::new(
                p.weight.as_ref().map_or(1.0, |w| w.0),
                succ,
            )],
        ));
        cx.spans.productions.push(p.span.clone());
        cx.spans.successors.push(vec![succ_spans]);
    }
    // Normalise the weights of each stochastic choice.
    for prod in &mut cx.sys.productions {
        let total: f64 = prod.alternatives.iter().map(|a| a.weight).sum();
        for a in &mut prod.alternatives {
            a.weight /= total;
        }
    }
}
