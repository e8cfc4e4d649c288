//! An STL system as bracketed productions, for the pfg and LinF emitters.
//!
//! The STL front end keeps the file's structure (rules, the seed's
//! branching terms, the layout, stem levels) and expands it into the axiom
//! word. Here the structure becomes a production system that derives the
//! same word:
//!
//! * each distinct branching term at each level, `R1{R1, ~, R2{,}}`,
//!   becomes a symbol (named after its rule) whose production is the rule's
//!   body with each entry's term symbol placed at the end of its branch,
//!   a failed branch (`~`) left out;
//! * the axiom is the seed, with a term symbol where the seed has a term;
//! * the derivation length is the depth of the deepest term, so that after
//!   it every term is expanded: an Outline Description's grown tree comes
//!   out as its explicit tree (or, when pfg's alphabet is too small for
//!   the distinct terms, the axiom is that tree, with no productions);
//! * stem levels become length factors: the seed's length (`L`) is the
//!   step length (the coordinates stay STL's), each term's
//!   production starts with the ratio of its level's length to its
//!   parent's, and a seed term followed by more of the seed is followed by
//!   the inverse ratio (a branch's `]` restores the length by itself).
//!   Stem broadness has no equivalent: unless every stem is 1 wide, that
//!   is reported, as is a layout.

use super::{Kind, Problem};
use crate::ir::{BranchEntry, BranchTerm, SeedItem, Structure, SymbolId, System, TurtleOp, Word};
use std::collections::HashMap;

struct Builder<'a> {
    st: &'a Structure,
    out: System,
    lengths: Vec<f64>,
    terms: HashMap<(String, u32), SymbolId>,
    taken: HashMap<String, u32>,
    /// Expand terms in place: the axiom is the explicit tree.
    explicit: bool,
}

// The walks over terms below recurse as deep as the terms nest, which the
// STL front end (the only one that makes them) keeps within
// `ir::MAX_NESTING`: braces in the seed, and growth counted from the seed.

fn key(t: &BranchTerm) -> String {
    let mut s = format!("{}{{", t.rule.0);
    for e in &t.entries {
        match e {
            BranchEntry::Empty => s.push(','),
            BranchEntry::Failed => s.push_str("~,"),
            BranchEntry::Term(c) => {
                s.push_str(&key(c));
                s.push(',');
            }
        }
    }
    s.push('}');
    s
}

fn depth(t: &BranchTerm) -> u32 {
    1 + t
        .entries
        .iter()
        .map(|e| match e {
            BranchEntry::Term(c) => depth(c),
            _ => 0,
        })
        .max()
        .unwrap_or(0)
}

impl Builder<'_> {
    fn scale(&mut self, ratio: f64) -> Option<SymbolId> {
        if ratio == 1.0 || !ratio.is_finite() {
            return None;
        }
        let id = self.out.intern(&format!("{}@", super::number(ratio)));
        self.out
            .set_interpretation(id, TurtleOp::ScaleLength(ratio));
        Some(id)
    }

    fn length(&self, level: u32) -> f64 {
        self.lengths.get(level as usize).copied().unwrap_or(1.0)
    }

    /// The symbol of term `t` at `level`, defining its production.
    fn term(&mut self, t: &BranchTerm, level: u32) -> SymbolId {
        let k = (key(t), level);
        if let Some(&id) = self.terms.get(&k) {
            return id;
        }
        let rule = &self.st.rules[t.rule.0 as usize];
        let n = self.taken.entry(rule.name.clone()).or_insert(0);
        *n += 1;
        let name = if *n == 1 {
            rule.name.clone()
        } else {
            format!("{}_{}", rule.name, n)
        };
        let id = self.out.intern(&name);
        self.terms.insert(k, id);
        // The parent's production comes before its children's.
        let slot = self.out.productions.len();
        self.out.productions.push(crate::ir::Production::new(
            Vec::new(),
            vec![id],
            Vec::new(),
            vec![crate::ir::Alternative::new(1.0, Word::default())],
        ));
        let succ = self.expand(t, level);
        self.out.productions[slot].alternatives[0].successor = Word::from(succ);
        id
    }

    /// What term `t` at `level` stands for: its rule's body with the
    /// entries at the branch ends, as term symbols, or expanded in place
    /// when `self.explicit`.
    fn expand(&mut self, t: &BranchTerm, level: u32) -> Vec<SymbolId> {
        let rule = &self.st.rules[t.rule.0 as usize];
        let body = rule.body.0.clone();
        let mut succ = Vec::with_capacity(body.len() + 4);
        let ratio = self.length(level) / self.length(level.saturating_sub(1));
        succ.extend(self.scale(ratio));
        let mut i = 0;
        let mut branch = 0;
        while i < body.len() {
            if body[i] == SymbolId::OPEN {
                let mut d = 0;
                let mut j = i;
                while j < body.len() {
                    if body[j] == SymbolId::OPEN {
                        d += 1;
                    } else if body[j] == SymbolId::CLOSE {
                        d -= 1;
                        if d == 0 {
                            break;
                        }
                    }
                    j += 1;
                }
                let j = j.min(body.len() - 1);
                match t.entries.get(branch) {
                    Some(BranchEntry::Failed) => {}
                    Some(BranchEntry::Term(c)) => {
                        succ.extend_from_slice(&body[i..j]);
                        if self.explicit {
                            let inner = self.expand(c, level + 1);
                            succ.extend(inner);
                        } else {
                            let child = self.term(c, level + 1);
                            succ.push(child);
                        }
                        succ.push(SymbolId::CLOSE);
                    }
                    _ => succ.extend_from_slice(&body[i..=j]),
                }
                branch += 1;
                i = j + 1;
            } else {
                succ.push(body[i]);
                i += 1;
            }
        }
        let out = &self.out;
        succ.retain(|s| !out.symbols.name(*s).is_empty());
        succ
    }
}

/// How many distinct (term, level) pairs the seed has: the symbols
/// [`productions`] needs.
pub fn term_count(sys: &System) -> usize {
    fn walk(t: &BranchTerm, level: u32, seen: &mut std::collections::HashSet<(String, u32)>) {
        if seen.insert((key(t), level)) {
            for e in &t.entries {
                if let BranchEntry::Term(c) = e {
                    walk(c, level + 1, seen);
                }
            }
        }
    }
    let mut seen = std::collections::HashSet::new();
    if let Some(st) = &sys.structure {
        for i in &st.seed {
            if let SeedItem::Term(t) = i {
                walk(t, 1, &mut seen);
            }
        }
    }
    seen.len()
}

/// The production system of an STL system, and what pfg and LinF cannot
/// express of it (layout, stem broadness). With `explicit`, there are no
/// productions: the axiom is the whole tree (for pfg, whose alphabet is
/// too small for a big grown outline's distinct terms).
pub fn productions(sys: &System, explicit: bool) -> (System, Vec<Problem>) {
    let mut problems = Vec::new();
    let mut out = sys.clone();
    out.productions.clear();
    out.structure = None;
    out.settings.step = 1.0;
    out.settings.width = 1.0;
    let silent = |s: &SymbolId| sys.symbols.name(*s).is_empty();
    let Some(st) = &sys.structure else {
        out.axiom = Word::from(
            sys.axiom
                .0
                .iter()
                .copied()
                .filter(|s| !silent(s))
                .collect::<Vec<_>>(),
        );
        out.settings.steps = Some(0);
        return (out, problems);
    };
    out.axiom = Word::default();
    if !st.constraint.outline.is_empty() {
        problems.push(Problem {
            kind: Kind::Layout,
            span: None,
            what: format!(
                "the layout ({} shape{}): only STL draws shapes",
                st.constraint.outline.len(),
                if st.constraint.outline.len() == 1 {
                    ""
                } else {
                    "s"
                }
            ),
            change: "the shapes are dropped; the grown tree is kept".into(),
        });
    }
    let max_depth = st
        .seed
        .iter()
        .map(|i| match i {
            SeedItem::Term(t) => depth(t),
            SeedItem::Word(_) => 0,
        })
        .max()
        .unwrap_or(0);
    let (mut lengths, _) = Structure::per_level(st.stems.length.0, st.stems.length.1, max_depth);
    // The seed's length is the step length, so that a constant `L` needs
    // no factor per level and the coordinates stay STL's (a translation
    // that says it is exact draws the same numbers, not only the same
    // shape fitted to a frame).
    let l0 = lengths.first().copied().unwrap_or(1.0);
    if l0 > 0.0 && l0.is_finite() {
        lengths.iter_mut().for_each(|l| *l /= l0);
        out.settings.step = l0;
    }
    let (widths, _) = Structure::per_level(st.stems.broadness.0, st.stems.broadness.1, max_depth);
    if widths
        .iter()
        .any(|&w| w.min(Structure::MAX_DRAWN_WIDTH) != 1.0)
    {
        problems.push(Problem {
            kind: Kind::Attribute,
            span: None,
            what: format!(
                "the stem broadness B = {} ({}): the target has no per-stem widths",
                super::number(st.stems.broadness.0),
                super::number(st.stems.broadness.1)
            ),
            change: "every stem is drawn 1 wide".into(),
        });
    }
    let mut b = Builder {
        st,
        out,
        lengths,
        terms: HashMap::new(),
        taken: HashMap::new(),
        explicit,
    };
    let mut axiom = Vec::new();
    for (i, item) in st.seed.iter().enumerate() {
        match item {
            SeedItem::Word(w) => axiom.extend(w.0.iter().copied().filter(|s| !silent(s))),
            SeedItem::Term(t) => {
                if explicit {
                    let inner = b.expand(t, 1);
                    axiom.extend(inner);
                } else {
                    let id = b.term(t, 1);
                    axiom.push(id);
                }
                if i + 1 < st.seed.len() {
                    let back = b.length(0) / b.length(1);
                    axiom.extend(b.scale(back));
                }
            }
        }
    }
    let mut out = b.out;
    out.axiom = Word::from(axiom);
    out.settings.steps = Some(if explicit { 0 } else { max_depth as u64 });
    (out, problems)
}
