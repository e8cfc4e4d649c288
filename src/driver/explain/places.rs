//! Where a file writes each symbol of its system: in a production's
//! predecessor (a definition) or anywhere else (the axiom, a successor),
//! as its span table records them.

use crate::driver::Compiled;
use crate::ir::{Production, Span, SymbolId, System};

/// A place where a symbol is written.
pub(super) struct Occurrence {
    pub(super) span: Span,
    pub(super) symbol: SymbolId,
    /// Written as a production's predecessor.
    pub(super) defines: bool,
}

/// Every place a symbol of `c`'s system is written, as the span table
/// records it; predecessors are found in their production's text.
pub(super) fn find(c: &Compiled) -> Vec<Occurrence> {
    // A file with errors: the symbols of the parts that parse.
    let Some(sys) = c.system_or_recovered() else {
        return Vec::new();
    };
    let spans = &c.spans;
    let written = |symbol: SymbolId, span: &Span| Occurrence {
        span: span.clone(),
        symbol,
        defines: false,
    };
    let mut out: Vec<Occurrence> = (sys.axiom.0.iter().zip(&spans.axiom))
        .map(|(&symbol, span)| written(symbol, span))
        .collect();
    for (i, p) in sys.productions.iter().enumerate() {
        if let Some(span) = predecessor_span(sys, &c.file.text, spans.productions.get(i), p) {
            out.push(Occurrence {
                span,
                symbol: p.predecessor[0],
                defines: true,
            });
        }
        let per_alt = spans.successors.get(i).map(Vec::as_slice).unwrap_or(&[]);
        for (alt, alt_spans) in p.alternatives.iter().zip(per_alt) {
            let successor = alt.successor.0.iter().zip(alt_spans);
            out.extend(successor.map(|(&symbol, span)| written(symbol, span)));
        }
    }
    out
}

/// Where production `p`'s (first) predecessor symbol is written in its
/// production's span: after the left context's `<` when it has one.
fn predecessor_span(
    sys: &System,
    text: &str,
    production: Option<&Span>,
    p: &Production,
) -> Option<Span> {
    let span = production?;
    let line = text.get(span.clone())?;
    let name = sys.symbols.name(*p.predecessor.first()?);
    if name.is_empty() {
        return None;
    }
    let from = if p.left.is_empty() {
        0
    } else {
        line.find('<').map_or(0, |i| i + 1)
    };
    let at = span.start + from + line[from..].find(name)?;
    Some(at..at + name.len())
}

/// The occurrence written at byte `at` (or just before it, where a cursor
/// after a symbol stands).
pub(super) fn at(occ: &[Occurrence], at: usize) -> Option<&Occurrence> {
    let hit = |o: &&Occurrence| o.span.start <= at && at < o.span.end;
    let before = |o: &&Occurrence| o.span.end == at && at > 0;
    (occ.iter().find(hit)).or_else(|| occ.iter().find(before))
}
