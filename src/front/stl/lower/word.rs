//! The lowered seed and rules as IR: the word with its stem-level markers,
//! the drawing components' symbols, the rules' and terms' IR forms, and the
//! warning where a decrement clamps a stem.

use super::header::Settings;
use super::{Ctx, Ev, Part, Term, TermEntry};
use crate::common::vocabulary;
use crate::common::vocabulary::TurtleSet;
use crate::diagnostics::{codes, Diagnostic, Diagnostics};
use crate::front::stl::growth::Comp;
use crate::ir::{
    BranchEntry, BranchTerm, SeedItem, Structure, StructureRule, StructureRuleId, SymbolId, System,
    TurtleOp, Word,
};
use crate::number::readable;
use std::collections::HashMap;

impl Ctx<'_> {
    /// The rules in the IR: each one's expansion and count.
    pub(super) fn ir_rules(&self, comp_ids: &ComponentIds) -> Vec<StructureRule> {
        self.rules
            .iter()
            .enumerate()
            .map(|(r, src)| StructureRule {
                name: src.name.clone(),
                body: ir_word(&self.full[r], comp_ids),
                resemblance: self.count[r],
                unit: (self.grown_units.get(&r)).map(|&u| StructureRuleId(u as u32)),
            })
            .collect()
    }
}

/// The word of the expanded seed, with a silent stem-level marker wherever
/// the level changes; and the deepest level marked.
pub(super) fn level_word(
    system: &mut System,
    events: &[Ev],
    comp_ids: &ComponentIds,
    st: &Settings,
    bw: &[f64],
    lw: &[f64],
) -> (Vec<SymbolId>, u32) {
    let mut word = Vec::with_capacity(events.len());
    let mut max_seen = 0u32;
    let mut markers: HashMap<u32, SymbolId> = HashMap::new();
    let mut last_level = None;
    for e in events {
        match *e {
            Ev::Component(c) => word.push(comp_ids[c as usize]),
            Ev::Level(k) if last_level != Some(k) => {
                last_level = Some(k);
                max_seen = max_seen.max(k);
                let id = *markers
                    .entry(k)
                    .or_insert_with(|| level_marker(system, st, bw, lw, k));
                // A marker right before another marker is dead: replace it.
                if let Some(&prev) = word.last() {
                    if markers.values().any(|&m| m == prev) {
                        word.pop();
                    }
                }
                word.push(id);
            }
            Ev::Level(_) | Ev::Growth(_) => {}
        }
    }
    (word, max_seen)
}

/// A new silent symbol that sets the stem of level `k`.
fn level_marker(system: &mut System, st: &Settings, bw: &[f64], lw: &[f64], k: u32) -> SymbolId {
    let id = system.intern_silent(&format!("stl-level-{k}"));
    system.set_interpretation(
        id,
        TurtleOp::Stem {
            width: at_level(bw, st.b, k).min(Structure::MAX_DRAWN_WIDTH),
            length: at_level(lw, st.l, k),
        },
    );
    id
}

/// The value at level `k` of a table of `Structure::per_level(base, dec, …)`, computed
/// when `k` is past its end.
fn at_level(table: &[f64], (base, dec): (f64, f64), k: u32) -> f64 {
    let kk = k as usize;
    table
        .get(kk)
        .copied()
        .unwrap_or_else(|| Structure::per_level(base, dec, k).0[kk])
}

/// Warns where a decrement makes B or L non-positive. Only levels with
/// stems count: `max_seen` is the deepest.
pub(super) fn warn_clamped(diags: &mut Diagnostics, st: &Settings, max_seen: u32) {
    for (which, (base, dec), span) in [
        ("B", st.b, st.b_span.clone()),
        ("L", st.l, st.l_span.clone()),
    ] {
        let (_, first) = Structure::per_level(base, dec, max_seen);
        if let (Some(k), Some(span)) = (first, span) {
            let what = if which == "B" { "broadness" } else { "length" };
            diags.push(
                Diagnostic::at(
                    codes::STL_CLAMPED,
                    span,
                    format!(
                        "the stem {what} {which} reaches {} at level {k}; clamped to {}",
                        readable(base - dec * k as f64),
                        readable(base * 0.1)
                    ),
                )
                .with_label(format!("this decrement makes {which} non-positive"))
                .with_note(format!("the tree has {max_seen} levels"))
                .with_help(format!(
                    "use a smaller decrement, e.g. `({})`",
                    fmt_num(base / (max_seen as f64 + 1.0))
                )),
            );
        }
    }
}

/// Components as a word of the IR.
fn ir_word(cs: &[Comp], comp_ids: &ComponentIds) -> Word {
    Word::from(cs.iter().map(|&c| comp_ids[c as usize]).collect::<Vec<_>>())
}

pub(super) fn ir_seed_item(p: &Part, comp_ids: &ComponentIds) -> SeedItem {
    match p {
        Part::Comps(cs) => SeedItem::Word(ir_word(cs, comp_ids)),
        Part::Term(t) => SeedItem::Term(ir_term(t)),
    }
}

fn fmt_num(x: f64) -> String {
    let s = format!("{x:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn ir_term(t: &Term) -> BranchTerm {
    BranchTerm {
        rule: StructureRuleId(t.rule as u32),
        entries: t
            .entries
            .iter()
            .map(|e| match e {
                TermEntry::Empty => BranchEntry::Empty,
                TermEntry::Failed => BranchEntry::Failed,
                TermEntry::Term(c) => BranchEntry::Term(ir_term(c)),
            })
            .collect(),
        grows: t.growth,
    }
}

/// The drawing components as symbols, indexed by `Comp as usize`.
pub(super) type ComponentIds = [SymbolId; 7];

/// Interns the drawing components with their turtle meaning.
pub(super) fn intern_components(sys: &mut System) -> ComponentIds {
    let mut ids = [crate::ir::SymbolId::OPEN; 7];
    for (c, name) in [
        (Comp::F, "F"),
        (Comp::L, "L"),
        (Comp::R, "R"),
        (Comp::Plus, "+"),
        (Comp::Minus, "-"),
    ] {
        let Some(op) = vocabulary::op(TurtleSet::Stl, name) else {
            continue;
        };
        let id = sys.intern(name);
        sys.set_interpretation(id, op);
        ids[c as usize] = id;
    }
    ids[Comp::Open as usize] = crate::ir::SymbolId::OPEN;
    ids[Comp::Close as usize] = crate::ir::SymbolId::CLOSE;
    ids
}
