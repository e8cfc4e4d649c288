//! An STL structure's seed as the word it draws, and an outline's planted
//! seed grown ([`super::growth`]): what a front end that reads a
//! [`Structure`] written out (rules, seed, stems, outline) does to get the
//! axiom, the same way the STL front end does from its own source.
//!
//! The seed's stems are level 0, a term's stems one level below the term
//! that holds it; a silent marker `stl-level-K` (a stem of that level's
//! broadness and length) stands wherever the level changes.

use super::growth::{self, Comp, Grown, SeedEvent, UnitGeom};
use super::shapes::{self, Outline};
use crate::ir::{
    BranchEntry, BranchTerm, SeedItem, Structure, SymbolId, System, TurtleOp, Word, MAX_NESTING,
};

/// What expanding a seed met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Ev {
    Symbol(SymbolId),
    Level(u32),
    /// A growth point (of a planted seed).
    Growth,
}

/// The seed could not be expanded within [`Structure::MAX_EXPANSION`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooLarge;

/// The top-level branches of a rule's body (brackets are all that count).
fn body_branches(body: &[SymbolId]) -> Vec<(usize, usize)> {
    let comps: Vec<Comp> = (body.iter())
        .map(|&s| match s {
            SymbolId::OPEN => Comp::Open,
            SymbolId::CLOSE => Comp::Close,
            _ => Comp::F,
        })
        .collect();
    growth::branches(&comps)
}

struct Expander<'a> {
    st: &'a Structure,
    out: Vec<Ev>,
    /// Per event, when its stems appeared in growth (with [`Appeared`]).
    keys: Vec<u32>,
    key: u32,
}

impl Expander<'_> {
    fn emit(&mut self, e: Ev) {
        self.out.push(e);
        self.keys.push(self.key);
    }

    fn emit_all(&mut self, body: &[SymbolId]) {
        for &s in body {
            self.emit(Ev::Symbol(s));
        }
    }

    /// Term `t` at `level`: the rule's body, each top-level branch
    /// extended by its entry (a failed one left out); `at` says when its
    /// parts appeared, if it grew. Recurses as deep as the term nests:
    /// readers keep terms within [`MAX_NESTING`].
    fn term(&mut self, t: &BranchTerm, level: u32, at: Option<&Appeared>) -> Result<(), TooLarge> {
        let Some(rule) = self.st.rules.get(t.rule.0 as usize) else {
            return Ok(());
        };
        let trunk = at.map_or(self.key, |a| a.trunk);
        self.key = trunk;
        self.emit(Ev::Level(level));
        if t.grows {
            self.emit(Ev::Growth);
            return Ok(());
        }
        let body = &rule.body.0;
        let mut branches = body_branches(body)
            .into_iter()
            .zip(&t.entries)
            .enumerate()
            .peekable();
        let mut i = 0;
        while i < body.len() {
            let Some((k, ((open, close), entry))) = branches.next_if(|b| b.1 .0 .0 == i) else {
                self.key = trunk;
                self.emit(Ev::Symbol(body[i]));
                i += 1;
                continue;
            };
            let (key, child_at) = (at.and_then(|a| a.entries.get(k)))
                .map_or((trunk, None), |(key, c)| (*key, c.as_ref()));
            self.key = key;
            match entry {
                BranchEntry::Failed => {}
                BranchEntry::Term(child) => {
                    self.emit_all(&body[open..close]);
                    self.term(child, level + 1, child_at)?;
                    self.key = key;
                    self.emit(Ev::Level(level));
                    self.emit(Ev::Symbol(SymbolId::CLOSE));
                }
                BranchEntry::Empty => self.emit_all(&body[open..=close]),
            }
            self.key = trunk;
            i = close + 1;
            if self.out.len() > Structure::MAX_EXPANSION {
                return Err(TooLarge);
            }
        }
        Ok(())
    }
}

/// The events of `seed` expanded over the structure's rules, and per event
/// when it appeared in growth (`appeared`, one per term of `seed`; 0
/// without).
fn events(
    st: &Structure,
    seed: &[SeedItem],
    appeared: &[Appeared],
) -> Result<(Vec<Ev>, Vec<u32>), TooLarge> {
    let mut x = Expander {
        st,
        out: vec![Ev::Level(0)],
        keys: vec![0],
        key: 0,
    };
    let mut terms = appeared.iter();
    for item in seed {
        x.key = 0;
        match item {
            SeedItem::Word(w) => x.emit_all(&w.0),
            SeedItem::Term(t) => {
                x.term(t, 1, terms.next())?;
                x.key = 0;
                x.emit(Ev::Level(0));
            }
        }
        if x.out.len() > Structure::MAX_EXPANSION {
            return Err(TooLarge);
        }
    }
    Ok((x.out, x.keys))
}

/// Broadness or length at level `k` (an element of [`Structure::per_level`]).
fn at_level((base, dec): (f64, f64), k: u32) -> f64 {
    let x = base - dec * k as f64;
    if x <= 0.0 && base > 0.0 {
        base * 0.1
    } else {
        x.max(0.0)
    }
}

/// The word `seed` draws, with a stem-level marker wherever the level
/// changes (interned in `sys`, given its stem unless it has an operation).
pub fn word(sys: &mut System, st: &Structure, seed: &[SeedItem]) -> Result<Word, TooLarge> {
    Ok(word_keyed(sys, st, seed, &[])?.0)
}

/// [`word`], with per symbol when it appeared in growth (`appeared`, one
/// per term of `seed`).
fn word_keyed(
    sys: &mut System,
    st: &Structure,
    seed: &[SeedItem],
    appeared: &[Appeared],
) -> Result<(Word, Vec<u32>), TooLarge> {
    let mut word = Vec::new();
    let mut keys = Vec::new();
    let mut markers: Vec<SymbolId> = Vec::new();
    let mut last = None;
    let (events, at) = events(st, seed, appeared)?;
    for (e, at) in events.into_iter().zip(at) {
        match e {
            Ev::Symbol(s) => {
                word.push(s);
                keys.push(at);
            }
            Ev::Level(k) if last != Some(k) => {
                last = Some(k);
                let id = sys.intern_silent(&format!("stl-level-{k}"));
                if sys.op(id).is_none() {
                    let width = at_level(st.stems.broadness, k).min(Structure::MAX_DRAWN_WIDTH);
                    let length = at_level(st.stems.length, k);
                    sys.set_interpretation(id, TurtleOp::Stem { width, length });
                }
                markers.push(id);
                // A marker right before another marker is dead: replace it.
                if word.last().is_some_and(|p| markers.contains(p)) {
                    word.pop();
                    keys.pop();
                }
                word.push(id);
                keys.push(at);
            }
            Ev::Level(_) | Ev::Growth => {}
        }
    }
    Ok((Word::from(word), keys))
}

/// The word a grown structure draws ([`word`] of the grown seed) and the
/// order its stems appeared in while growing: what an animation of the
/// growth replays.
pub struct GrowthOrder {
    pub word: Word,
    /// Per symbol of `word`: how many stems growth had made before the
    /// stems it belongs to (0 for the seed as written; `u32::MAX` for
    /// what growth did not draw).
    pub appeared: Vec<u32>,
    /// How many stems growth made in all (the seed's included).
    pub stems: u32,
}

/// The growth order of `st`'s planted seed, grown inside its outline;
/// `None` for a structure without an outline (nothing grows).
pub fn growth_order(sys: &mut System, st: &Structure) -> Result<Option<GrowthOrder>, TooLarge> {
    if st.constraint.outline.is_empty() {
        return Ok(None);
    }
    let grown = grow(sys, st)?;
    let (word, appeared) = word_keyed(sys, st, &grown.seed, &grown.appeared)?;
    Ok(Some(GrowthOrder {
        word,
        appeared,
        stems: grown.stems,
    }))
}

/// The growth points of `seed` in order: each one's rule, and how deep its
/// term is (1 for a term of the seed).
fn growth_points(seed: &[SeedItem]) -> Vec<(usize, usize)> {
    fn term(t: &BranchTerm, depth: usize, out: &mut Vec<(usize, usize)>) {
        if t.grows {
            out.push((t.rule.0 as usize, depth));
        }
        for e in &t.entries {
            if let BranchEntry::Term(c) = e {
                term(c, depth + 1, out);
            }
        }
    }
    let mut out = Vec::new();
    for item in seed {
        if let SeedItem::Term(t) = item {
            term(t, 1, &mut out);
        }
    }
    out
}

/// What growth gave: the grown seed, and whether growth stopped at
/// [`growth::MAX_STEMS`].
pub struct Outgrowth {
    pub seed: Vec<SeedItem>,
    pub truncated: bool,
    /// How many stems growth made (the seed's included).
    pub stems: u32,
    /// Per term of `seed`, when its parts appeared.
    appeared: Vec<Appeared>,
}

/// When the parts of a term appeared in growth: how many stems were made
/// before its trunk, and per entry before its branch (with what grew from
/// it). The seed as written appeared at 0.
#[derive(Clone, Debug, Default)]
struct Appeared {
    trunk: u32,
    entries: Vec<(u32, Option<Appeared>)>,
}

/// Grows the structure's planted seed inside its outline: the planted seed
/// with each growth point replaced by the tree grown there.
pub fn grow(sys: &System, st: &Structure) -> Result<Outgrowth, TooLarge> {
    let comp = |s: &SymbolId| match *s {
        SymbolId::OPEN => Some(Comp::Open),
        SymbolId::CLOSE => Some(Comp::Close),
        s => match sys.symbols.name(s) {
            "F" => Some(Comp::F),
            "L" => Some(Comp::L),
            "R" => Some(Comp::R),
            "+" => Some(Comp::Plus),
            "-" => Some(Comp::Minus),
            _ => None,
        },
    };
    let seed_events: Vec<SeedEvent> = (events(st, &st.planted, &[])?.0.iter())
        .filter_map(|e| match e {
            Ev::Symbol(s) => comp(s).map(SeedEvent::Component),
            Ev::Level(k) => Some(SeedEvent::Level(*k)),
            Ev::Growth => Some(SeedEvent::Growth(usize::MAX)),
        })
        .collect();
    let c = &st.constraint;
    // Each growth point grows its unit rule for as many levels as its
    // count allows, or `levels`; no deeper than the nesting limit.
    let growing: Vec<(usize, u32)> = (growth_points(&st.planted).into_iter())
        .map(|(r, depth)| {
            let room = (MAX_NESTING + 1).saturating_sub(depth) as u32;
            let rule = &st.rules[r];
            let unit = rule.unit.filter(|_| rule.resemblance.is_some());
            let levels = rule.resemblance.unwrap_or(c.levels).min(room);
            (unit.map_or(r, |u| u.0 as usize), levels)
        })
        .collect();
    let delta = sys.settings.delta;
    let max_level = c.levels.saturating_add(2).max(64);
    let (bw, _) = Structure::per_level(st.stems.broadness.0, st.stems.broadness.1, max_level);
    let (lw, _) = Structure::per_level(st.stems.length.0, st.stems.length.1, max_level);
    let defaults = (st.stems.length.0, st.stems.broadness.0);
    let (stems, points) = growth::walk_seed(&seed_events, &growing, delta, defaults, &bw, &lw);
    let units: Vec<UnitGeom> = (st.rules.iter())
        .map(|r| UnitGeom::new(&r.body.0.iter().filter_map(comp).collect::<Vec<_>>(), delta))
        .collect();
    let params = growth::Params {
        delta,
        depth_first: c.strategy == crate::ir::Growth::DepthFirst,
        broadness: bw,
        length: lw,
        max_stems: growth::MAX_STEMS,
    };
    let bounds = shapes::bounds(&c.outline).unwrap_or([0.0, 0.0, 1.0, 1.0]);
    let out = growth::grow(
        &units,
        &Outline::new(&c.outline),
        bounds,
        &params,
        &stems,
        &points,
    );
    let mut next = 0;
    let mut appeared = Vec::new();
    let seed = (st.planted.iter())
        .map(|item| match item {
            SeedItem::Term(t) => {
                let (t, at) = fill(t, &out.nodes, points.len(), &mut next);
                appeared.push(at);
                SeedItem::Term(t)
            }
            w => w.clone(),
        })
        .collect();
    Ok(Outgrowth {
        seed,
        truncated: out.truncated,
        stems: u32::try_from(out.stems.len()).unwrap_or(u32::MAX),
        appeared,
    })
}

/// `t` with its growth points replaced by the grown nodes, in order, and
/// when its parts appeared.
fn fill(
    t: &BranchTerm,
    nodes: &[growth::Node],
    points: usize,
    next: &mut usize,
) -> (BranchTerm, Appeared) {
    fn node_term(nodes: &[growth::Node], i: usize) -> (BranchTerm, Appeared) {
        let n = &nodes[i];
        let (entries, at) = (n.entries.iter().zip(&n.entries_at))
            .map(|(e, &at)| match *e {
                Grown::Empty => (BranchEntry::Empty, (at, None)),
                Grown::Failed => (BranchEntry::Failed, (at, None)),
                Grown::Node(c) => {
                    let (t, a) = node_term(nodes, c);
                    (BranchEntry::Term(t), (at, Some(a)))
                }
            })
            .unzip();
        let term = BranchTerm {
            rule: crate::ir::StructureRuleId(n.rule as u32),
            entries,
            grows: false,
        };
        let appeared = Appeared {
            trunk: n.trunk_at,
            entries: at,
        };
        (term, appeared)
    }
    if t.grows {
        let k = *next;
        *next += 1;
        return if k < points {
            node_term(nodes, k)
        } else {
            (t.clone(), Appeared::default())
        };
    }
    let (entries, at) = (t.entries.iter())
        .map(|e| match e {
            BranchEntry::Term(c) => {
                let (t, a) = fill(c, nodes, points, next);
                (BranchEntry::Term(t), (0, Some(a)))
            }
            e => (e.clone(), (0, None)),
        })
        .unzip();
    let term = BranchTerm {
        rule: t.rule,
        entries,
        grows: false,
    };
    (
        term,
        Appeared {
            trunk: 0,
            entries: at,
        },
    )
}
