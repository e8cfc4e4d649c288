//! The checks of an object-instancing graph ([`crate::ir::graph`]) as
//! diagnostics, for every front end that reads one (`.gft` `graph`
//! blocks, Fractint's `.ifs` libraries): the IR finds the problems, the
//! front end says where each part was read from through a [`Place`] →
//! span function, and [`check`] words them the same for every notation.
//!
//! E1001 a cycle whose composed transform does not shrink, E1002 a
//! terminal without a geometry in a graph that has geometries, W1003 a
//! singular transform, W1004 a symbol the axiom never reaches.

use crate::diagnostics::{codes, Code, Diagnostic, Diagnostics};
use crate::ir::graph::InstancingGraph;
use crate::ir::Span;

/// A part of a graph, for which a front end gives the span it was read
/// from (or none).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Place {
    /// Where symbol `s` is introduced: its rule, its geometry, its
    /// declaration.
    Symbol(usize),
    /// Where symbol `s` is first placed (in the axiom or a rule).
    Use(usize),
    /// Couple `k` of symbol `s`'s rule (`Some(s)`) or of the axiom (`None`).
    Couple(Option<usize>, usize),
    /// The transform of that couple.
    Transform(Option<usize>, usize),
}

fn at(code: Code, span: Option<Span>, message: String) -> Diagnostic {
    match span {
        Some(s) => Diagnostic::at(code, s, message),
        None => Diagnostic::global(code, message),
    }
}

/// How much a cycle stretches, in words: "stretches by 1.25".
pub fn stretch(factor: f64) -> String {
    if !factor.is_finite() {
        return "stretches without bound".to_string();
    }
    if (factor - 1.0).abs() < 1e-9 {
        return "keeps its size (factor 1)".to_string();
    }
    let short = format!("{factor:.3}");
    let short = short.trim_end_matches('0').trim_end_matches('.');
    if short == "1" {
        format!("stretches by {}", crate::number::readable(factor))
    } else {
        format!("stretches by {short}")
    }
}

/// Reports the graph's problems (E1001, E1002, W1003, W1004) into
/// `diags`, each at the span `span` gives for its place.
pub fn check(
    graph: &InstancingGraph,
    span: &dyn Fn(Place) -> Option<Span>,
    diags: &mut Diagnostics,
) {
    let name = |s: usize| graph.symbols[s].name.as_str();
    for d in graph.divergent_cycles() {
        let Some(&(first, k)) = d.edges.first() else {
            continue;
        };
        let mut names: Vec<&str> = d.edges.iter().map(|&(s, _)| name(s)).collect();
        names.push(name(first));
        let cycle = names.join(" -> ");
        diags.push(
            at(
                codes::GRAPH_DIVERGENT,
                span(Place::Couple(Some(first), k)),
                format!(
                    "the cycle `{cycle}` does not shrink: it {}",
                    stretch(d.factor)
                ),
            )
            .with_label("the cycle leaves here")
            .with_note(
                "each cycle must shrink what it places (Bekaert & Willems §2.1): \
                 otherwise its copies grow without end and the object has no limit",
            )
            .with_help("scale the transforms along the cycle below 1, e.g. with `scale 0.5`"),
        );
    }
    for s in graph.bare_terminals() {
        let place = span(Place::Use(s)).or_else(|| span(Place::Symbol(s)));
        diags.push(
            at(
                codes::GRAPH_BARE_TERMINAL,
                place,
                format!("`{}` has no rule and no geometry", name(s)),
            )
            .with_label("a terminal without a geometry")
            .with_note("the graph has geometries, so each of its terminals is drawn as one")
            .with_help(format!(
                "give it a `geometry` line (`geometry {} = …`) or a rule",
                name(s)
            )),
        );
    }
    for (s, k) in graph.singular_transforms() {
        diags.push(
            at(
                codes::GRAPH_SINGULAR,
                span(Place::Transform(s, k)),
                "a singular transform".to_string(),
            )
            .with_label("this transform flattens what it places")
            .with_note(
                "what it places is flat; the ray tracer thickens it to 1/1000 of its largest extent",
            ),
        );
    }
    if graph.axiom.is_empty() {
        return;
    }
    for (s, reached) in graph.reachable().into_iter().enumerate() {
        if !reached {
            diags.push(
                at(
                    codes::GRAPH_UNREACHABLE,
                    span(Place::Symbol(s)),
                    format!("`{}` is never placed", name(s)),
                )
                .with_label("no rule leads here from the axiom")
                .with_help("place it in the axiom or a rule, or remove it"),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::graph::{Affine, GraphSymbol, Instance};

    fn symbol(name: &str, rule: Vec<Instance>) -> GraphSymbol {
        GraphSymbol {
            name: name.into(),
            geometry: Vec::new(),
            alternative: None,
            rule: Some(rule),
        }
    }

    #[test]
    fn a_two_symbol_cycle_that_stretches_is_named_with_its_factor() {
        let half = Affine::scale([0.5; 3]);
        let big = Affine::scale([2.5; 3]);
        let g = InstancingGraph {
            symbols: vec![
                symbol(
                    "A",
                    vec![Instance {
                        transform: half,
                        symbol: 1,
                    }],
                ),
                symbol(
                    "B",
                    vec![Instance {
                        transform: big,
                        symbol: 0,
                    }],
                ),
            ],
            axiom: vec![Instance {
                transform: Affine::IDENTITY,
                symbol: 0,
            }],
        };
        let mut diags = Diagnostics::default();
        check(
            &g,
            &|p| (p == Place::Couple(Some(0), 0)).then_some(3..7),
            &mut diags,
        );
        let d: Vec<_> = diags.iter().collect();
        assert_eq!(d.len(), 1, "{d:#?}");
        assert_eq!(d[0].code, codes::GRAPH_DIVERGENT);
        assert_eq!(d[0].span, Some(3..7));
        assert_eq!(
            d[0].message,
            "the cycle `A -> B -> A` does not shrink: it stretches by 1.25"
        );
    }

    #[test]
    fn stretches_are_told_in_few_digits() {
        assert_eq!(stretch(1.25), "stretches by 1.25");
        assert_eq!(stretch(2.0), "stretches by 2");
        assert_eq!(stretch(1.0), "keeps its size (factor 1)");
        assert_eq!(stretch(1.000_000_1), "stretches by 1.0000001");
    }
}
