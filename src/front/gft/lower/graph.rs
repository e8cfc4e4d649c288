//! A `graph { … }` block (docs/gft.md §13) lowered to the IR's
//! [`InstancingGraph`]: transform names resolved, symbols numbered in the
//! order the lines that introduce them come (a rule, a `geometry`, an
//! `alternative` or a `symbol` line; symbols only placed come after, in
//! the order they are placed), then the graph's own checks
//! ([`crate::front::graph::check`]) reported where each part was read.

use super::Cx;
use crate::common::gft_words::TRANSFORMS;
use crate::diagnostics::{codes, Diagnostic};
use crate::front::gft::ast::{Block, Couple, GraphLine, Keyword, Name, Placement, Step};
use crate::front::graph::{check, Place};
use crate::ir::graph::{Affine, Alternative, GraphSymbol, Instance, InstancingGraph};
use crate::ir::Span;
use std::collections::{HashMap, HashSet};

/// Where the parts of the graph were read, for its checks.
#[derive(Default)]
struct Spans {
    /// Where each symbol is introduced.
    introduced: Vec<Option<Span>>,
    /// Where each symbol is first placed.
    first_use: Vec<Option<Span>>,
    /// Each couple of the axiom: the couple and its transform.
    axiom: Vec<(Span, Span)>,
    /// Each couple of each symbol's rule.
    edges: Vec<Vec<(Span, Span)>>,
}

impl Spans {
    fn of(&self, place: Place) -> Option<Span> {
        let couple = |s: Option<usize>, k: usize| match s {
            None => self.axiom.get(k),
            Some(s) => self.edges.get(s).and_then(|e| e.get(k)),
        };
        match place {
            Place::Symbol(s) => self.introduced[s].clone().or(self.first_use[s].clone()),
            Place::Use(s) => self.first_use[s].clone(),
            Place::Couple(s, k) => couple(s, k).map(|c| c.0.clone()),
            Place::Transform(s, k) => couple(s, k).map(|c| c.1.clone()),
        }
    }
}

/// The transforms a block declares: resolved, or failed (reported).
#[derive(Default)]
struct Transforms {
    resolved: HashMap<String, Affine>,
    failed: HashSet<String>,
    /// Every declared name, resolved or not.
    declared: HashSet<String>,
}

/// The symbols of a graph being built, by name.
#[derive(Default)]
struct Symbols {
    graph: InstancingGraph,
    index: HashMap<String, usize>,
    spans: Spans,
}

impl Symbols {
    fn get_or_add(&mut self, name: &str) -> usize {
        if let Some(&s) = self.index.get(name) {
            return s;
        }
        let s = self.graph.symbols.len();
        self.graph.symbols.push(GraphSymbol {
            name: name.to_string(),
            geometry: Vec::new(),
            alternative: None,
            rule: None,
        });
        self.index.insert(name.to_string(), s);
        self.spans.introduced.push(None);
        self.spans.first_use.push(None);
        self.spans.edges.push(Vec::new());
        s
    }

    fn introduce(&mut self, name: &Name) -> usize {
        let s = self.get_or_add(&name.text);
        self.spans.introduced[s].get_or_insert(name.span.clone());
        s
    }
}

/// The span of a couple's transform (its symbol for the identity).
fn transform_span(c: &Couple) -> Span {
    match &c.placement {
        Placement::Identity => c.symbol.span.clone(),
        Placement::Named(n) => n.span.clone(),
        Placement::Steps(_, span) => span.clone(),
    }
}

impl Cx<'_> {
    /// Lowers a `graph` block into `sys.graph`.
    pub(super) fn graph(&mut self, k: &Keyword) {
        let Some(Block::Graph(lines)) = &k.block else {
            return;
        };
        let transforms = self.transforms(lines);
        let mut sy = Symbols::default();
        for line in lines {
            match line {
                GraphLine::Symbol { names, .. } => {
                    for n in names {
                        sy.introduce(n);
                    }
                }
                GraphLine::Rule { symbol, .. }
                | GraphLine::Geometry { symbol, .. }
                | GraphLine::Alternative { symbol, .. } => {
                    sy.introduce(symbol);
                }
                GraphLine::Unread { symbols, .. } => {
                    for n in symbols {
                        sy.introduce(n);
                    }
                }
                _ => {}
            }
        }
        let introduced = sy.graph.symbols.len();
        for line in lines {
            if let GraphLine::Axiom { couples, .. } | GraphLine::Rule { couples, .. } = line {
                for c in couples {
                    let s = sy.get_or_add(&c.symbol.text);
                    sy.spans.first_use[s].get_or_insert(c.symbol.span.clone());
                }
            }
        }
        let mut axiom_at: Option<Span> = None;
        let mut rule_at: HashMap<usize, Span> = HashMap::new();
        for line in lines {
            match line {
                GraphLine::Axiom { couples, span } => {
                    if let Some(first) = &axiom_at {
                        self.twice(
                            span,
                            first,
                            "the graph's `axiom` given twice",
                            "write one `axiom` line, with every couple the object starts from",
                        );
                        continue;
                    }
                    axiom_at = Some(span.clone());
                    let (instances, spans) = self.couples(couples, &transforms, &sy.index);
                    sy.graph.axiom = instances;
                    sy.spans.axiom = spans;
                }
                GraphLine::Rule {
                    symbol, couples, ..
                } => {
                    let s = sy.index[&symbol.text];
                    if let Some(first) = rule_at.get(&s) {
                        let message = format!("`{}` has two rules", symbol.text);
                        self.twice(
                            &symbol.span,
                            first,
                            &message,
                            &format!("write one rule with every couple: `{} -> …`", symbol.text),
                        );
                        continue;
                    }
                    rule_at.insert(s, symbol.span.clone());
                    let (instances, spans) = self.couples(couples, &transforms, &sy.index);
                    sy.graph.symbols[s].rule = Some(instances);
                    sy.spans.edges[s] = spans;
                }
                GraphLine::Geometry { symbol, shape, .. } => {
                    let s = sy.index[&symbol.text];
                    sy.graph.symbols[s].geometry.push(shape.clone());
                }
                GraphLine::Alternative {
                    symbol,
                    below,
                    shape,
                    ..
                } => {
                    let s = sy.index[&symbol.text];
                    let sym = &mut sy.graph.symbols[s];
                    match &mut sym.alternative {
                        None => {
                            sym.alternative = Some(Alternative {
                                shapes: vec![shape.clone()],
                                below_pixels: below.as_ref().map_or(1.0, |b| b.0),
                            });
                        }
                        Some(alt) => {
                            let differs = below
                                .as_ref()
                                .filter(|b| b.0.to_bits() != alt.below_pixels.to_bits());
                            if let Some((_, at)) = differs {
                                let message =
                                    format!("`{}`'s alternative given with two sizes", symbol.text);
                                self.diags.push(
                                    Diagnostic::at(codes::GRAPH_DEFINED_TWICE, at.clone(), message)
                                        .with_label("another size than its first line's")
                                        .with_help("give `below` once, on the first `alternative` line of the symbol"),
                                );
                                continue;
                            }
                            alt.shapes.push(shape.clone());
                        }
                    }
                }
                GraphLine::Transform { .. }
                | GraphLine::Symbol { .. }
                | GraphLine::Unread { .. } => {}
            }
        }
        if axiom_at.is_none() {
            self.diags.push(
                Diagnostic::at(
                    codes::GFT_NO_AXIOM,
                    k.span.clone(),
                    "a graph without an axiom",
                )
                .with_label("this graph places nothing")
                .with_help("add a line `axiom A` to the graph, naming the symbol the object is"),
            );
        }
        // A geometry line that did not read may have been the graph's.
        let unread_geometry =
            (lines.iter()).any(|l| matches!(l, GraphLine::Unread { geometry: true, .. }));
        if !sy.graph.has_geometry() && !unread_geometry {
            self.unknown_symbols(&sy, introduced);
        }
        let errors = self.diags.iter().any(|d| {
            d.is_error()
                && d.span
                    .as_ref()
                    .is_some_and(|s| s.start >= k.line.start && s.end <= k.line.end)
        });
        if !errors {
            let spans = &sy.spans;
            check(&sy.graph, &|p| spans.of(p), self.diags);
        }
        self.sys.graph = Some(sy.graph);
    }

    fn twice(&mut self, at: &Span, first: &Span, message: &str, help: &str) {
        self.diags.push(
            Diagnostic::at(codes::GRAPH_DEFINED_TWICE, at.clone(), message.to_string())
                .with_label("given again here")
                .with_secondary(first.clone(), "first given here")
                .with_help(help.to_string()),
        );
    }

    /// E0924 for the symbols placed that no line introduces (`from`
    /// on), in a graph without geometry (with one, E1002 says it).
    fn unknown_symbols(&mut self, sy: &Symbols, from: usize) {
        let known: Vec<&str> = sy.graph.symbols[..from]
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        // Any one letter is near any other: only a change of case is
        // suggested for one.
        let near = |cx: &mut Self, name: &str| -> Option<String> {
            let found = cx.suggester.nearest(name, &known);
            let one = name.chars().count() == 1;
            (found.into_iter())
                .find(|k| !one || k.eq_ignore_ascii_case(name))
                .map(str::to_string)
        };
        for s in from..sy.graph.symbols.len() {
            let name = &sy.graph.symbols[s].name;
            let Some(span) = sy.spans.first_use[s].clone() else {
                continue;
            };
            let d = Diagnostic::at(
                codes::GRAPH_UNKNOWN_SYMBOL,
                span,
                format!("unknown symbol `{name}`"),
            )
            .with_label("no rule, geometry or `symbol` line introduces it");
            let near = near(self, name);
            self.diags.push(match near {
                Some(n) => d.suggesting(n),
                None => d.with_help(format!(
                    "give it a rule `{name} -> …` or a `geometry` line, or declare it with `symbol {name}`"
                )),
            });
        }
    }

    /// Resolves the block's `transform` lines in order: each may use the
    /// transforms declared above it.
    fn transforms(&mut self, lines: &[GraphLine]) -> Transforms {
        let mut t = Transforms::default();
        let mut first: HashMap<&str, &Span> = HashMap::new();
        for line in lines {
            if let GraphLine::Unread {
                transform: Some(name),
                ..
            } = line
            {
                t.declared.insert(name.text.clone());
                t.failed.insert(name.text.clone());
            }
            if let GraphLine::Transform { name, .. } = line {
                if let Some(at) = first.get(name.text.as_str()) {
                    let message = format!("the transform `{}` declared twice", name.text);
                    self.twice(&name.span, at, &message, "give each transform its own name");
                } else {
                    first.insert(&name.text, &name.span);
                    t.declared.insert(name.text.clone());
                }
            }
        }
        let mut done: HashSet<&str> = HashSet::new();
        for line in lines {
            let GraphLine::Transform { name, steps, .. } = line else {
                continue;
            };
            if !done.insert(&name.text) {
                continue;
            }
            match self.steps(steps, &t, true) {
                Some(a) => {
                    t.resolved.insert(name.text.clone(), a);
                }
                None => {
                    t.failed.insert(name.text.clone());
                }
            }
        }
        t
    }

    /// The transform `steps` compose, or `None` (reported). `defining`:
    /// inside a `transform` line, where a name declared below is refused.
    fn steps(&mut self, steps: &[Step], t: &Transforms, defining: bool) -> Option<Affine> {
        let mut out = Vec::new();
        let mut ok = true;
        for step in steps {
            match step {
                Step::Affine(a, _) => out.push(*a),
                Step::Name(n) => match t.resolved.get(&n.text) {
                    Some(a) => out.push(*a),
                    None if t.failed.contains(&n.text) => ok = false,
                    None if defining && t.declared.contains(&n.text) => {
                        ok = false;
                        self.diags.push(
                            Diagnostic::at(
                                codes::GRAPH_UNKNOWN_NAME,
                                n.span.clone(),
                                format!("the transform `{}` is used before it is declared", n.text),
                            )
                            .with_label("declared below")
                            .with_help("a transform's definition uses only the transforms declared above it: move this line below"),
                        );
                    }
                    None => {
                        ok = false;
                        let d = Diagnostic::at(
                            codes::GRAPH_UNKNOWN_TRANSFORM,
                            n.span.clone(),
                            format!("unknown transform `{}`", n.text),
                        )
                        .with_label("neither a transform word nor a declared transform");
                        let mut words: Vec<&str> = t.resolved.keys().map(String::as_str).collect();
                        words.sort_unstable();
                        words.splice(0..0, TRANSFORMS.iter().copied());
                        let near = self.suggester.nearest(&n.text, &words);
                        self.diags.push(match near.first() {
                            Some(w) => d.suggesting(w),
                            None => d.with_help("a transform is `translate`, `scale`, `rotate`, `shear`, `matrix` or a name declared with `transform NAME = …`"),
                        });
                    }
                },
            }
        }
        ok.then(|| Affine::compose(&out))
    }

    /// The instances of couples, with the spans of each couple and its
    /// transform; couples whose transform is unknown are left out
    /// (reported).
    fn couples(
        &mut self,
        couples: &[Couple],
        t: &Transforms,
        index: &HashMap<String, usize>,
    ) -> (Vec<Instance>, Vec<(Span, Span)>) {
        let mut instances = Vec::new();
        let mut spans = Vec::new();
        for c in couples {
            let transform = match &c.placement {
                Placement::Identity => Some(Affine::IDENTITY),
                Placement::Steps(steps, _) => self.steps(steps, t, false),
                Placement::Named(n) => self.named(n, t),
            };
            if let Some(transform) = transform {
                instances.push(Instance {
                    transform,
                    symbol: index[&c.symbol.text],
                });
                spans.push((c.span.clone(), transform_span(c)));
            }
        }
        (instances, spans)
    }

    /// The transform `NAME` of a couple `NAME(B)`.
    fn named(&mut self, n: &Name, t: &Transforms) -> Option<Affine> {
        if let Some(a) = t.resolved.get(&n.text) {
            return Some(*a);
        }
        if t.failed.contains(&n.text) {
            return None;
        }
        let d = Diagnostic::at(
            codes::GRAPH_UNKNOWN_NAME,
            n.span.clone(),
            format!("no transform `{}`", n.text),
        )
        .with_label("not declared with `transform`");
        let mut names: Vec<&str> = t.resolved.keys().map(String::as_str).collect();
        names.sort_unstable();
        let near = self.suggester.nearest(&n.text, &names);
        self.diags.push(match near.first() {
            Some(w) => d.suggesting(w),
            None => d.with_help(format!(
                "declare it in the graph: `transform {} = scale 0.5`",
                n.text
            )),
        });
        None
    }
}

#[cfg(test)]
mod tests {
    use crate::diagnostics::Diagnostics;
    use crate::front::gft::read;

    fn codes(text: &str) -> Vec<&'static str> {
        let mut d = Diagnostics::default();
        read(text, &mut d);
        d.iter().map(|d| d.code.0).collect()
    }

    #[test]
    fn a_transform_uses_only_those_declared_above_it() {
        let above = "graph {\n  transform h = scale 0.5\n  transform t = h translate (1, 0, 0)\n  axiom A\n  A -> t(A) h(A)\n}\n";
        assert!(codes(above).is_empty());
        let below = "graph {\n  transform t = h translate (1, 0, 0)\n  transform h = scale 0.5\n  axiom A\n  A -> t(A) h(A)\n}\n";
        // Reported once: `t`, which failed, is not reported again where used.
        assert_eq!(codes(below), ["E0926"]);
    }

    #[test]
    fn a_line_that_does_not_read_is_not_reported_again_where_it_is_used() {
        // The broken `transform`, `geometry` and rule lines introduce their
        // names: no E0926 for `h`, no E0924 for `B` or `C`.
        let text = "graph {\n  transform h = scale (1, 2)\n  axiom A\n  A -> h(A) B C\n  geometry B = cube\n  C D -> h(C)\n}\n";
        assert_eq!(codes(text), ["E0922", "E0923", "E0920"]);
    }

    #[test]
    fn the_graph_checks_wait_for_a_block_without_errors() {
        // A rule dropped for its error would leave `B` unreached (W1004).
        let text =
            "graph {\n  axiom A\n  A -> [scale 0.5](A) [scal 0.5](B)\n  B -> [scale 0.5](B)\n}\n";
        assert_eq!(codes(text), ["E0921"]);
    }
}
