//! Growing an Outline Description: each growth point of the seed grows
//! within the layout, and the grown terms replace it.

use super::header::Settings;
use super::{Ctx, Part, RuleSrc, State, Term, TermEntry};
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::stl::ast::Str;
use crate::front::stl::growth;
use crate::front::stl::growth::{Grown, Point, UnitGeom};
use crate::front::stl::layout;
use crate::front::stl::layout::Outline;
use crate::ir::{Shape, Span, MAX_NESTING};

pub(super) fn no_growth(diags: &mut Diagnostics, layout_span: &Span) {
    diags.push(
        Diagnostic::at(
            codes::STL_NO_GROWTH,
            layout_span.clone(),
            "this layout has nothing to grow",
        )
        .with_label("an Outline Description grows the seed's rules")
        .with_help("name a rule with branches in the seed, without `{…}`, e.g. `F R1`"),
    );
}

/// Grows the outline: replaces each growth point of `parts` by the grown
/// terms (adding a rule `NAME_unit` for each counted rule `[I n string]`
/// grown). Returns whether there was any growth point.
pub(super) fn grow_outline(
    ctx: &mut Ctx<'_>,
    parts: &mut [Part],
    st: &Settings,
    shapes: &[Shape],
    bw: &[f64],
    lw: &[f64],
) -> bool {
    let events = ctx.seed_events(parts);
    let mut growth_points: Vec<(usize, usize)> = Vec::new();
    collect_growth(parts, &mut growth_points);
    if growth_points.is_empty() {
        return false;
    }
    let growth_terms: Vec<usize> = growth_points.iter().map(|&(r, _)| r).collect();
    let unit_of = ctx.unit_rules(&growth_terms);
    // Each growth point grows its unit rule for as many levels as its
    // rule's count allows, or LEVELS; and no deeper than the depth limit,
    // counted from the seed (each level is a term nested in the one
    // before, and the code that reads terms recurses).
    let growing: Vec<(usize, u32)> = growth_points
        .iter()
        .map(|&(r, depth)| {
            let room = (MAX_NESTING + 1).saturating_sub(depth) as u32;
            let levels = ctx.count[r].unwrap_or(st.levels).min(room);
            (unit_of[r].unwrap_or(r), levels)
        })
        .collect();
    let defaults = (st.l.0, st.b.0);
    let (stems, points) =
        growth::walk_seed(&events, &growing, st.angle.to_radians(), defaults, bw, lw);
    let delta = st.angle.to_radians();
    let units: Vec<UnitGeom> = ctx.full.iter().map(|c| UnitGeom::new(c, delta)).collect();
    let params = growth::Params {
        delta,
        depth_first: st.depth_first,
        broadness: bw.to_vec(),
        length: lw.to_vec(),
        max_stems: growth::MAX_STEMS,
    };
    let outline = Outline::new(shapes);
    let bounds = layout::bounds(shapes).unwrap_or([0.0, 0.0, 1.0, 1.0]);
    // Growth points with no budget (`[I 0 X]`) grow nothing.
    let out = growth::grow(&units, &outline, bounds, &params, &stems, &points);
    if out.truncated {
        ctx.diags.push(
            Diagnostic::global(
                codes::STL_TOO_DEEP,
                format!("growth stopped at {} stems", growth::MAX_STEMS),
            )
            .with_help("use fewer LEVELS, a larger broadness B or a smaller layout"),
        );
    }
    // Replace the growth points by the grown terms.
    let mut next = 0;
    fill_growth(parts, &out.nodes, &points, &mut next);
    true
}

impl Ctx<'_> {
    /// The unit rule each rule of `growth_terms` grows by: the rule itself,
    /// the rule named in `[I n Rk]`, or a new rule holding the string of
    /// `[I n string]`. Indexed by rule.
    fn unit_rules(&mut self, growth_terms: &[usize]) -> Vec<Option<usize>> {
        let mut unit_of: Vec<Option<usize>> = vec![None; self.rules.len()];
        for &r in growth_terms {
            if unit_of[r].is_some() {
                continue;
            }
            let unit = match (self.count[r], self.unit_ref[r]) {
                (None, _) => r,
                (Some(_), Some(k)) => k,
                (Some(_), None) => self.add_unit_rule(r),
            };
            if self.count[r].is_some() {
                self.grown_units.insert(r, unit);
            }
            unit_of[r] = Some(unit);
        }
        unit_of
    }

    /// Adds the rule `NAME_unit` holding the string of rule `r`'s
    /// `[I n string]`, a rule of its own so the grown terms can name it.
    fn add_unit_rule(&mut self, r: usize) -> usize {
        let mut name = format!("{}_unit", self.rules[r].name);
        while self.by_name.contains_key(&name) {
            name.push('_');
        }
        let unit = self.unit[r].clone();
        let id = self.rules.len();
        self.rules.push(RuleSrc {
            name: name.clone(),
            name_span: self.rules[r].name_span.clone(),
            span: self.rules[r].span.clone(),
            body: Str::default(),
        });
        self.by_name.insert(name, id);
        self.state.push(State::Done);
        self.full.push(unit.clone());
        self.unit.push(unit);
        self.count.push(None);
        self.unit_ref.push(None);
        id
    }
}

/// The growth points of `parts`, in order: each one's rule and how deep
/// its term is (1 for a term of the seed).
fn collect_growth(parts: &[Part], out: &mut Vec<(usize, usize)>) {
    fn term(t: &Term, depth: usize, out: &mut Vec<(usize, usize)>) {
        if t.growth {
            out.push((t.rule, depth));
        }
        for e in &t.entries {
            if let TermEntry::Term(c) = e {
                term(c, depth + 1, out);
            }
        }
    }
    for p in parts {
        if let Part::Term(t) = p {
            term(t, 1, out);
        }
    }
}

fn fill_growth(parts: &mut [Part], nodes: &[growth::Node], points: &[Point], next: &mut usize) {
    fn node_term(nodes: &[growth::Node], i: usize) -> Term {
        Term {
            rule: nodes[i].rule,
            entries: nodes[i]
                .entries
                .iter()
                .map(|e| match *e {
                    Grown::Empty => TermEntry::Empty,
                    Grown::Failed => TermEntry::Failed,
                    Grown::Node(c) => TermEntry::Term(node_term(nodes, c)),
                })
                .collect(),
            growth: false,
        }
    }
    fn term(t: &mut Term, nodes: &[growth::Node], points: &[Point], next: &mut usize) {
        if t.growth {
            if *next < points.len() {
                *t = node_term(nodes, *next);
            }
            *next += 1;
            return;
        }
        for e in &mut t.entries {
            if let TermEntry::Term(c) = e {
                term(c, nodes, points, next);
            }
        }
    }
    for p in parts {
        if let Part::Term(t) = p {
            term(t, nodes, points, next);
        }
    }
}
