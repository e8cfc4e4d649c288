//! An STL structure's seed as the word it draws, and an outline's planted
//! seed grown ([`super::growth`]): what a front end that reads a
//! [`Structure`] written out (rules, seed, stems, outline) does to get the
//! axiom, the same way the STL front end does from its own source.
//!
//! The seed's stems are level 0, a term's stems one level below the term
//! that holds it; a silent marker `stl-level-K` (a stem of that level's
//! broadness and length) stands wherever the level changes.

use super::growth::{self, Comp, Grown, SeedEvent, UnitGeom};
use super::layout::{self, Outline};
use super::{
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
}

impl Expander<'_> {
    /// Term `t` at `level`: the rule's body, each top-level branch
    /// extended by its entry (a failed one left out). Recurses as deep as
    /// the term nests: readers keep terms within [`MAX_NESTING`].
    fn term(&mut self, t: &BranchTerm, level: u32) -> Result<(), TooLarge> {
        let Some(rule) = self.st.rules.get(t.rule.0 as usize) else {
            return Ok(());
        };
        self.out.push(Ev::Level(level));
        if t.grows {
            self.out.push(Ev::Growth);
            return Ok(());
        }
        let body = &rule.body.0;
        let mut branches = body_branches(body).into_iter().zip(&t.entries).peekable();
        let mut i = 0;
        while i < body.len() {
            let Some(&((open, close), entry)) = branches.peek().filter(|b| b.0 .0 == i) else {
                self.out.push(Ev::Symbol(body[i]));
                i += 1;
                continue;
            };
            branches.next();
            match entry {
                BranchEntry::Failed => {}
                BranchEntry::Term(child) => {
                    self.out
                        .extend(body[open..close].iter().map(|&s| Ev::Symbol(s)));
                    self.term(child, level + 1)?;
                    self.out.push(Ev::Level(level));
                    self.out.push(Ev::Symbol(SymbolId::CLOSE));
                }
                BranchEntry::Empty => {
                    self.out
                        .extend(body[open..=close].iter().map(|&s| Ev::Symbol(s)));
                }
            }
            i = close + 1;
            if self.out.len() > Structure::MAX_EXPANSION {
                return Err(TooLarge);
            }
        }
        Ok(())
    }
}

/// The events of `seed` expanded over the structure's rules.
fn events(st: &Structure, seed: &[SeedItem]) -> Result<Vec<Ev>, TooLarge> {
    let mut x = Expander {
        st,
        out: vec![Ev::Level(0)],
    };
    for item in seed {
        match item {
            SeedItem::Word(w) => x.out.extend(w.0.iter().map(|&s| Ev::Symbol(s))),
            SeedItem::Term(t) => {
                x.term(t, 1)?;
                x.out.push(Ev::Level(0));
            }
        }
        if x.out.len() > Structure::MAX_EXPANSION {
            return Err(TooLarge);
        }
    }
    Ok(x.out)
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
    let mut word = Vec::new();
    let mut markers: Vec<SymbolId> = Vec::new();
    let mut last = None;
    for e in events(st, seed)? {
        match e {
            Ev::Symbol(s) => word.push(s),
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
                }
                word.push(id);
            }
            Ev::Level(_) | Ev::Growth => {}
        }
    }
    Ok(Word::from(word))
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
    let seed_events: Vec<SeedEvent> = (events(st, &st.planted)?.iter())
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
        depth_first: c.strategy == super::Growth::DepthFirst,
        broadness: bw,
        length: lw,
        max_stems: growth::MAX_STEMS,
    };
    let bounds = layout::bounds(&c.outline).unwrap_or([0.0, 0.0, 1.0, 1.0]);
    let out = growth::grow(
        &units,
        &Outline::new(&c.outline),
        bounds,
        &params,
        &stems,
        &points,
    );
    let mut next = 0;
    let seed = (st.planted.iter())
        .map(|item| match item {
            SeedItem::Term(t) => SeedItem::Term(fill(t, &out.nodes, points.len(), &mut next)),
            w => w.clone(),
        })
        .collect();
    Ok(Outgrowth {
        seed,
        truncated: out.truncated,
    })
}

/// `t` with its growth points replaced by the grown nodes, in order.
fn fill(t: &BranchTerm, nodes: &[growth::Node], points: usize, next: &mut usize) -> BranchTerm {
    fn node_term(nodes: &[growth::Node], i: usize) -> BranchTerm {
        BranchTerm {
            rule: super::StlRuleId(nodes[i].rule as u32),
            entries: (nodes[i].entries.iter())
                .map(|e| match *e {
                    Grown::Empty => BranchEntry::Empty,
                    Grown::Failed => BranchEntry::Failed,
                    Grown::Node(c) => BranchEntry::Term(node_term(nodes, c)),
                })
                .collect(),
            grows: false,
        }
    }
    if t.grows {
        let k = *next;
        *next += 1;
        return if k < points {
            node_term(nodes, k)
        } else {
            t.clone()
        };
    }
    let entries = (t.entries.iter())
        .map(|e| match e {
            BranchEntry::Term(c) => BranchEntry::Term(fill(c, nodes, points, next)),
            e => e.clone(),
        })
        .collect();
    BranchTerm {
        rule: t.rule,
        entries,
        grows: false,
    }
}
