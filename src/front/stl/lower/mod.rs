//! Lowering an STL AST to the IR: the paper's Language Analyzer.
//!
//! * **Rules are macros.** A rule name in a string stands for the rule's
//!   body. Names written together are split into the longest declared rule
//!   names and the components F, L, R (`FR1` is `F R1`). A rule that uses
//!   itself through macros is an error (E0509) with the path.
//! * **`[I n X]`** is what `F` becomes after n parallel rewritings by
//!   `F -> X` (`[I 0 X]` is `F`). A rule whose whole body is `[I n X]` has
//!   the self-resemblance count n: as a macro it is that expansion; in an
//!   outline it grows X for at most n levels.
//! * **Branching terms** `R{e1, …, em}` extend R's top-level branches (of
//!   R's expansion as a macro). A rule name without braces in a seed or an
//!   entry is the term with no entries (`R1{R1, R2, R1}` = `R1{R1{}, R2{},
//!   R1{}}`); a rule without branches is written without braces.
//! * **Levels.** The seed's own stems are level 0; the stems of a term at
//!   level k are level k + 1, and its entries' terms level k + 2, …; a stem
//!   at level k has broadness `B − k·ΔB` and length `L − k·ΔL` (a tenth of
//!   the first value where that would not be positive: W0501). Inside a
//!   rule's body (a macro) there are no levels.
//! * **Outline Descriptions.** A file with a LAYOUT is an OD: in its seed, a
//!   rule name without braces whose rule has branches is a *growth point*
//!   ([`super::growth`]); everything written explicitly (components, terms
//!   with braces) is drawn as written and occupies space before growth
//!   starts. The grown tree replaces each growth point by explicit terms,
//!   so the lowered seed is a BED: written out with its layout
//!   (`translate --to stl`) it reads back to exactly the same stems, since
//!   it has no growth points left.

mod header;
mod names;
mod outline;
mod rules;
mod shapes;
mod terms;
mod word;

use super::ast::{File, Str};
use super::growth;
use super::growth::Comp;
use crate::diagnostics::{codes, nearest, Code, Diagnostic, Diagnostics};
use crate::front::depth::too_deep;
use crate::front::names::LongestNames;
use crate::front::repeats::Repeats;
use crate::front::suggest::Suggester;
use crate::ir::{
    Growth, GrowthConstraint, Shape, Span, SpanTable, Stems, Structure, System, Word, MAX_NESTING,
};
use header::{Header, Settings};
pub use names::rule_uses;
use outline::{grow_outline, no_growth};
use std::collections::HashMap;
use word::{intern_components, ir_seed_item, level_word, warn_clamped};

pub const DEFAULT_ANGLE: f64 = 30.0;
pub const DEFAULT_LEVELS: u32 = 12;
pub const DEFAULT_BROADNESS: f64 = 1.0;
pub const DEFAULT_LENGTH: f64 = 10.0;
/// The most levels an outline grows (`LEVELS`): the one depth limit, since
/// each level of the grown tree is a term nested in the one before.
pub const MAX_LEVELS: u32 = MAX_NESTING as u32;
/// The most drawing components an expansion may have.
const MAX_EXPANSION: usize = Structure::MAX_EXPANSION;

pub use crate::ir::Lowered;

/// A branching term during lowering.
#[derive(Clone, Debug)]
struct Term {
    rule: usize,
    entries: Vec<TermEntry>,
    /// A growth point of an outline (a rule with branches written bare).
    growth: bool,
}

#[derive(Clone, Debug)]
enum TermEntry {
    Empty,
    Failed,
    Term(Term),
}

#[derive(Clone, Debug)]
enum Part {
    Comps(Vec<Comp>),
    Term(Term),
}

/// The expanded seed as the growth walk reads it.
type Ev = growth::SeedEvent;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    New,
    Busy,
    Done,
    Failed,
}

struct RuleSrc {
    name: String,
    name_span: Span,
    span: Span,
    body: Str,
}

struct Ctx<'a> {
    diags: &'a mut Diagnostics,
    rules: Vec<RuleSrc>,
    by_name: HashMap<String, usize>,
    max_name: usize,
    state: Vec<State>,
    full: Vec<Vec<Comp>>,
    unit: Vec<Vec<Comp>>,
    count: Vec<Option<u32>>,
    /// For `[I n Rk]`: k.
    unit_ref: Vec<Option<usize>>,
    stack: Vec<usize>,
    /// Set once an expansion went past [`MAX_EXPANSION`] (reported once).
    too_large: bool,
    /// How deep the expansion under way is: brackets, braces and rules
    /// used through rules, each a level of recursion here.
    level: usize,
    /// Set once the expansion went past [`MAX_NESTING`] (reported once).
    too_deep: bool,
    /// What the rule or seed being read reported: a mistake repeated
    /// through it is reported a few times, then counted.
    repeats: Repeats,
    /// What suggestions for unknown rule names may still cost.
    suggester: Suggester,
    /// The rule names, for splitting runs of them; made when the first
    /// run is split, after every rule is declared.
    name_index: Option<LongestNames>,
    /// The rule each counted rule an outline grew grows by.
    grown_units: HashMap<usize, usize>,
}

impl Ctx<'_> {
    /// Reports what `build` makes, a diagnostic of `code` found in the
    /// rule or seed being read, unless that has reported enough of the
    /// code already ([`Repeats`]).
    fn report(&mut self, code: Code, build: impl FnOnce(&mut Self) -> Diagnostic) {
        if self.repeats.admit(self.diags, code) {
            let d = build(self);
            self.repeats.push(self.diags, d);
        }
    }

    /// `d` (an unknown rule `name`) with the nearest rule name as its fix,
    /// when one is near and the file's budget for suggestions allows, or
    /// `otherwise` as its help.
    fn did_you_mean(&mut self, d: Diagnostic, name: &str, otherwise: String) -> Diagnostic {
        if !self
            .suggester
            .afford(name.len(), self.rules.len(), self.max_name)
        {
            return d.with_help(otherwise);
        }
        let names: Vec<&str> = self.rules.iter().map(|r| r.name.as_str()).collect();
        did_you_mean(d, name, &names, otherwise)
    }

    fn room(&mut self, have: usize, add: usize, span: &Span) -> bool {
        if have.saturating_add(add) <= MAX_EXPANSION {
            return true;
        }
        if !self.too_large {
            self.too_large = true;
            self.diags.push(
                Diagnostic::at(
                    codes::TOO_MANY_SYMBOLS,
                    span.clone(),
                    format!("this expands to more than {MAX_EXPANSION} drawing components"),
                )
                .with_label("expands too far")
                .with_help("use fewer rewritings in `[I n X]` or fewer nested rules"),
            );
        }
        false
    }

    /// `f` one level deeper (a bracket, a brace, a rule used through
    /// another, written at `span`); past [`MAX_NESTING`] levels, `None`
    /// instead, reported once. This bounds the recursion of expanding
    /// nested rules, which the parser's limit on each string does not: a
    /// chain of rules each using the next nests as deep as it is long.
    fn deeper<T>(&mut self, span: &Span, f: impl FnOnce(&mut Self) -> Option<T>) -> Option<T> {
        if self.level >= MAX_NESTING {
            if !std::mem::replace(&mut self.too_deep, true) {
                self.diags.push(too_deep(
                    span.clone(),
                    "use fewer rules through rules here: write some of them out in place",
                ));
            }
            return None;
        }
        self.level += 1;
        let out = f(self);
        self.level -= 1;
        out
    }
}

/// The opening `[` of a bracket written at `span`.
fn opener(span: &Span) -> Span {
    span.start..span.start + 1
}

/// `d` (an unknown `name`) with the nearest of `candidates` as its fix, or
/// `otherwise` as its help when none is near.
fn did_you_mean(
    d: Diagnostic,
    name: &str,
    candidates: &[&str],
    otherwise: impl Into<String>,
) -> Diagnostic {
    match nearest(name, candidates).first() {
        Some(near) => d.suggesting(near),
        None => d.with_help(otherwise.into()),
    }
}

impl<'a> Ctx<'a> {
    fn new(diags: &'a mut Diagnostics) -> Self {
        Ctx {
            diags,
            rules: Vec::new(),
            by_name: HashMap::new(),
            max_name: 0,
            state: Vec::new(),
            full: Vec::new(),
            unit: Vec::new(),
            count: Vec::new(),
            unit_ref: Vec::new(),
            stack: Vec::new(),
            too_large: false,
            level: 0,
            too_deep: false,
            repeats: Repeats::default(),
            suggester: Suggester::default(),
            name_index: None,
            grown_units: HashMap::new(),
        }
    }
}

/// Lowers a parsed STL file.
pub fn lower(file: &File, src_len: usize, diags: &mut Diagnostics) -> Lowered {
    let mut ctx = Ctx::new(diags);
    let hd = Header::read(&mut ctx, file);
    let resolved = ctx.resolve_rules();
    let mut ok = hd.ok && resolved;
    let mut parts = Vec::new();
    match hd.seed {
        Some(body) => {
            ctx.repeats.begin_item();
            ok &= ctx.seed(body, hd.layout_span.is_some(), &mut parts);
            ctx.repeats.end_item(ctx.diags, "in the seed");
        }
        None => {
            ctx.diags.push(
                Diagnostic::at(codes::STL_MISSING_SEED, src_len..src_len, "missing SEED")
                    .with_label("the file ends without a seed")
                    .with_help("add the seed to draw: `SEED`, e.g. `F R1`, then `ENDSEED`"),
            );
            ok = false;
        }
    }
    let st = &hd.st;
    let mut system = System::new();
    system.settings.delta = st.angle.to_radians();
    system.settings.step = st.l.0;
    system.settings.width = st.b.0.min(Structure::MAX_DRAWN_WIDTH);
    let mut structure = new_structure(st, hd.shapes.clone());
    let comp_ids = intern_components(&mut system);
    // Nothing is grown or expanded in a file with errors (a parse error
    // may have dropped part of the seed or the layout).
    if !ok || ctx.too_large || ctx.diags.has_errors() {
        return finish(system, structure);
    }

    // Growth (an outline) or the seed as written (a BED).
    let max_level = st.levels.saturating_add(2).max(64);
    let (bw, _) = Structure::per_level(st.b.0, st.b.1, max_level);
    let (lw, _) = Structure::per_level(st.l.0, st.l.1, max_level);
    if let Some(layout_span) = &hd.layout_span {
        // The seed as planted, before growth replaces its growth points.
        structure.planted = parts.iter().map(|p| ir_seed_item(p, &comp_ids)).collect();
        if !grow_outline(&mut ctx, &mut parts, st, &hd.shapes, &bw, &lw) {
            no_growth(ctx.diags, layout_span);
        }
    }
    let events = ctx.seed_events(&parts);
    if ctx.too_large {
        return finish(system, structure);
    }
    let (word, max_seen) = level_word(&mut system, &events, &comp_ids, st, &bw, &lw);
    warn_clamped(ctx.diags, st, max_seen);
    structure.rules = ctx.ir_rules(&comp_ids);
    structure.seed = parts.iter().map(|p| ir_seed_item(p, &comp_ids)).collect();
    system.axiom = Word::from(word);
    finish(system, structure)
}

/// The structure before the rules and the seed go in.
fn new_structure(st: &Settings, layout: Vec<Shape>) -> Structure {
    Structure {
        rules: Vec::new(),
        seed: Vec::new(),
        planted: Vec::new(),
        constraint: GrowthConstraint {
            outline: layout,
            strategy: if st.depth_first {
                Growth::DepthFirst
            } else {
                Growth::BreadthFirst
            },
            levels: st.levels,
        },
        stems: Stems {
            broadness: st.b,
            length: st.l,
        },
    }
}

/// The lowered system with its structure (an STL file has no span table).
fn finish(mut system: System, structure: Structure) -> Lowered {
    system.structure = Some(structure);
    Lowered {
        system,
        spans: SpanTable::default(),
    }
}
