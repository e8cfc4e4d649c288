//! Guarded symbols (`p?s`): their probability and base, checked once
//! every rule is known.

use super::strings::{push_pieces, split, StringOut};
use super::{Cx, Role};
use crate::diagnostics::{codes, Diagnostic};
use crate::front::linf::ast::Item;
use crate::ir::{Span, SymbolId};

/// `p?s`: returns the index of the item after `s`.
pub(super) fn lower_guard(
    cx: &mut Cx<'_>,
    out: &mut StringOut,
    items: &[Item],
    i: usize,
    p: f64,
    number: &Span,
    question: &Span,
) -> usize {
    let valid = p > 0.0 && p < 1.0;
    if !valid {
        cx.report(codes::LINF_PROBABILITY, |_| {
            Diagnostic::at(
                codes::LINF_PROBABILITY,
                number.clone(),
                format!("probability {p} is not between 0 and 1"),
            )
            .with_label("must be greater than 0 and less than 1")
            .with_help("`p?s` expands `s` with probability p, 0 < p < 1; to always expand it, write `s` alone")
        });
    }
    let Some(Item::Name(n)) = items.get(i + 2) else {
        cx.report(codes::LINF_GUARD_TARGET, |_| {
            Diagnostic::at(
                codes::LINF_GUARD_TARGET,
                question.clone(),
                "`?` is not followed by a symbol",
            )
            .with_label("guards nothing")
            .with_help("write the symbol right after `?`: `0.5?j`")
        });
        return i + 2;
    };
    let mut pieces = split(cx, &n.text, n.span.start);
    match pieces.first() {
        Some((Ok(Role::Angle(_)), _, _)) | Some((Err(()), _, _)) => {}
        Some((Ok(_), text, span)) => {
            let base = cx.sys.intern(text);
            if valid {
                let id = cx.sys.symbols.intern_guarded(p, base);
                cx.sys.intern(cx.sys.symbols.name(id).to_string().as_str());
                out.push(id, number.start..span.end);
            }
            let _ = pieces.remove(0);
        }
        None => {}
    }
    push_pieces(cx, out, &pieces, &n.text);
    i + 3
}

/// Warns about guards on symbols that have no rule.
pub(super) fn check_guards(cx: &mut Cx<'_>) {
    let mut warned = std::collections::HashSet::new();
    let guarded: Vec<(SymbolId, f64, SymbolId)> = cx
        .sys
        .symbols
        .iter()
        .filter_map(|(id, info)| info.guard.map(|g| (id, g.probability, g.base)))
        .collect();
    for (id, p, base) in guarded {
        let name = cx.sys.symbols.name(base).to_string();
        if cx.has_rule.contains_key(&name) || !warned.insert(base) {
            continue;
        }
        let span = cx
            .spans
            .successors
            .iter()
            .flatten()
            .flatten()
            .zip(
                cx.sys
                    .productions
                    .iter()
                    .flat_map(|p| p.alternatives.iter())
                    .flat_map(|a| a.successor.0.iter()),
            )
            .find(|(_, s)| **s == id)
            .map(|(sp, _)| sp.clone())
            .or_else(|| {
                cx.sys
                    .axiom
                    .0
                    .iter()
                    .zip(&cx.spans.axiom)
                    .find(|(s, _)| **s == id)
                    .map(|(_, sp)| sp.clone())
            });
        let d = Diagnostic::global(
            codes::LINF_GUARD_NO_RULE,
            format!("`{p}?{name}` guards `{name}`, which has no rule: the guard changes nothing"),
        )
        .with_help(format!(
            "give `{name}` a rule (`{name} = …`) or drop `{p}?`"
        ));
        cx.diags.push(match span {
            Some(s) => Diagnostic { span: Some(s), ..d },
            None => d,
        });
    }
}
