//! # The graftal IR: one representation for every notation
//!
//! This module is the specification of graftal's semantics. Every front end
//! ([`crate::front`]: pfg, LinF, STL, cpfg, Fractint, Smith, `.gft`, IFS) *lowers*
//! its AST into a [`System`]; everything downstream — derivation ([`crate::eval`]), turtle
//! interpretation ([`crate::turtle`]), rendering and the emitters
//! ([`crate::back`]) — reads only this type. No field says which notation a
//! system came from: each construct is named for what it means and any
//! front end may fill it. Spans live in a side table ([`SpanTable`]) that
//! takes no part in equality or output. Every angle is in radians.
//!
//! ## Data model
//!
//! * **Symbols** are interned names ([`SymbolId`] into [`SymbolTable`]). A
//!   name may be several characters long (`+t` in LinF, `R1` in STL, `@O` in
//!   cpfg). Ids 0 and 1 are always `[` and `]`, the branch delimiters that
//!   context matching and the turtle both understand.
//! * **Words** ([`Word`]) are sequences of *modules*: a symbol with zero or
//!   more real parameters. The symbols are one array; the parameters a side
//!   array that is empty, and allocates nothing, while no module has any, so
//!   a word of plain symbols costs what a symbol array costs.
//! * **What a symbol does** is a separate table ([`System::interpretation`]):
//!   for each symbol an optional [`TurtleOp`]. pfg `+`, LinF `+t` and STL `L`
//!   lower to the same kind of operation (a rotation of the turtle frame),
//!   so one turtle draws every notation.
//! * **Productions** ([`Production`]): a strict predecessor (one or more
//!   symbols), left and right contexts, the [`Formals`] its modules bind, an
//!   optional condition with statements before and after it, and one or more
//!   weighted [`Alternative`] successors whose modules carry parameter
//!   expressions. A production of plain symbols is the case with no formals,
//!   no condition, no statements and constant weights.
//! * **Around the productions**: the [`RulePolicy`] (first match, or weighted
//!   choice among all that match), the [`ContextFilter`] (ignored or
//!   considered symbols), the decomposition and homomorphism [`Phase`]s, the
//!   [`Program`] (variables, arrays, user functions, statements run around
//!   the derivation), a ring (the word's ends are neighbours), a cut symbol
//!   (removes the rest of its branch after each step).
//! * **Per-occurrence probability** ([`Guard`]): a symbol `p?s` is an
//!   occurrence of `s` expanded with probability `p` at each step.
//! * **Named rotations** ([`Rotation`]): (torsion, curvature) pairs of
//!   [`Angle`]s, fixed or drawn uniformly from an interval each time.
//! * **Colours and widths**: [`System::colours`] (a list stepped through or an
//!   indexed palette), [`Settings::colour`], widths with decrements.
//! * **Structure** ([`Structure`]): named rules (a table of rules with
//!   self-resemblance counts), a seed of branching terms, a
//!   [`GrowthConstraint`] — layout [`Shape`]s with colours, the growth
//!   strategy and level limit — and [`Stems`]: broadness and length per
//!   level. The geometry of the shapes, the growth inside them and the
//!   seed's expansion are computations over this data, in
//!   [`crate::layout`], so a front end that states a growth constraint
//!   draws nothing itself.
//! * **Settings** ([`Settings`]): derivation length, angle increment δ,
//!   step length, scale, widths, the view, the file's own seed.
//!
//! ## Rewriting semantics ([`crate::eval`])
//!
//! One derivation step rewrites the whole word in parallel, scanning left
//! to right. At each position the productions whose predecessor starts with
//! the symbol there are tried in file order: a production applies when its
//! predecessor's symbols equal the modules at this position (with as many
//! parameters as its formals bind), both contexts match, and its condition
//! holds after its before-statements ran. Under [`RulePolicy::FirstMatch`]
//! the first that applies is used and one of its alternatives is chosen by
//! weight with the seeded generator when there are several (the Appendix A
//! listing's `FindProd`); under [`RulePolicy::Weighted`] every production
//! that applies is a candidate, chosen by its (possibly computed) weight.
//! The predecessor's modules are consumed, the after-statements run and the
//! successor's parameter expressions are evaluated. When none applies, the
//! module is copied. Branch delimiters are never rewritten unless a
//! production names them. Before the step, a cut removes the rest of its
//! branch (so what follows a cut made in one step is still drawn after
//! it); after the step the decomposition phase rewrites each new module
//! again, recursively, up to its depth. The homomorphism rewrites the word for
//! drawing only.
//!
//! Context matching in bracketed words (the listing's `lcondiff` and
//! `rcondiff`): symbols the filter does not see are skipped. Going left,
//! `[` is skipped (the parent branch is the left context of a child) and a
//! whole branch `[...]` met from its right is skipped. Going right, a whole
//! branch `[...]` in the way is skipped and a `]` ends the search (nothing
//! to the right inside this branch). The start and end of the word match
//! only an empty context, unless the word is a ring.
//!
//! How a system is derived follows from these properties alone
//! ([`crate::eval::plan`]): a shared derivation tree for context-free
//! deterministic systems of plain symbols ([`D0l`]), a look-up table for
//! one-symbol contexts, the general matcher for other plain systems, module
//! rewriting when [`System::rewrites_modules`].
//!
//! ## How each notation lands here
//!
//! Each example below is a test (`cargo test` runs it).
//!
//! **pfg context-sensitive production** `0 < 1 > 1 --> 1[+F1F1]` with
//! `ignore: +-F`: one [`Production`] with `left = [0]`, `predecessor = [1]`,
//! `right = [1]`, one alternative of weight 1; the filter ignores `+ - F`.
//! Stochastic productions with the same predecessor and contexts are one
//! production with several alternatives.
//!
//! ```
//! use graftal::ir::{ContextFilter, SymbolId};
//! let sys = graftal::front::pfg::read_ok("axiom: 0\nignore: +-F\n0 < 1 > 1 --> 1[+F1F1]\n");
//! let name = |ids: &[SymbolId]| -> String { ids.iter().map(|&s| sys.symbols.name(s)).collect() };
//! let p = &sys.productions[0];
//! assert_eq!((name(&p.left), name(&p.predecessor), name(&p.right)), ("0".into(), "1".into(), "1".into()));
//! assert_eq!(p.alternatives[0].successor.display(&sys.symbols), "1[+F1F1]");
//! assert!(!p.uses_modules() && !sys.rewrites_modules());
//! let ContextFilter::Ignore(ignored) = &sys.context else { panic!() };
//! assert!(["+", "-", "F"].iter().all(|s| ignored.contains(&sys.symbols.get(s).unwrap())));
//!
//! let bush = graftal::front::pfg::read_ok(
//!     "axiom: F\nF --> F[+F]F : 0.33\nF --> F[-F]F : 0.33\nF --> F : 0.34\n",
//! );
//! let weights: Vec<f64> = bush.productions[0].alternatives.iter().map(|a| a.weight).collect();
//! assert_eq!((bush.productions.len(), weights), (1, vec![0.33, 0.33, 0.34]));
//! ```
//!
//! **LinF rotation pair with an interval**, `w = (0, [0 2*pi])`: the `angles`
//! block becomes [`System::rotations`]; `+w` in a successor is the symbol
//! `+w` interpreted as [`TurtleOp::Frenet`], `--w` two symbols `-w -w` (one
//! rotation per sign). The LinF frame {t, n, b} is the turtle frame
//! {H, L, U}. **LinF `0.5?f`** is the symbol `0.5?f` carrying a [`Guard`]:
//! rewritten by `f`'s production with probability 0.5 at each step,
//! otherwise left as it is for the next step; the turtle draws it as `f`.
//!
//! ```
//! use graftal::ir::{Angle, Guard, TurtleOp};
//! let sys = graftal::front::linf::read_ok(
//!     "lines f\nangles (0, pi/3) w = (0, [0 2*pi])\naxiom f\nrules\n  f = f+w--w[0.5?f]\n",
//! );
//! let w = &sys.rotations[1];
//! assert_eq!(w.name, "w");
//! assert_eq!(w.curvature, Angle::Uniform { lo: 0.0, hi: std::f64::consts::TAU });
//! let succ = &sys.productions[0].alternatives[0].successor;
//! assert_eq!(succ.display(&sys.symbols), "f+w-w-w[0.5?f]");
//! let minus_w = sys.symbols.get("-w").unwrap();
//! assert!(matches!(sys.op(minus_w), Some(TurtleOp::Frenet { negate: true, .. })));
//! let guarded = sys.symbols.get("0.5?f").unwrap();
//! let f = sys.symbols.get("f").unwrap();
//! assert_eq!(sys.symbols.info(guarded).guard, Some(Guard { probability: 0.5, base: f }));
//! assert_eq!(sys.op(guarded), sys.op(f));
//! ```
//!
//! **STL branching term** `R1{R1, , R2}`: the rules are a [`Structure`]'s
//! [`StructureRule`]s, the seed a list of [`SeedItem`]s where the term is a
//! [`BranchTerm`] whose entries extend the rule's top-level branches (an
//! empty entry keeps the branch as it is). A file with explicit branching
//! (a Branch-Expansion Description) is expanded into the axiom word; a
//! file with a layout is grown inside its shapes into one. Drawing
//! components `F`, `L`/`+`, `R`/`-` are symbols interpreted as `Forward`
//! and rotations about [`Axis::Up`]; silent symbols (empty names) set each
//! stem level's width and length ([`TurtleOp::Stem`]).
//!
//! ```
//! use graftal::ir::{BranchEntry, SeedItem};
//! let sys = graftal::front::stl::read_ok(
//!     "ANGLE 30\nB = 8 (1)\nL = 40 (4)\nR1 = [F][+F][-F]\nR2 = [++F][-F]\nSEED\nF R1{R1, , R2}\nENDSEED\n",
//! );
//! let st = sys.structure.as_ref().unwrap();
//! let rules: Vec<&str> = st.rules.iter().map(|r| r.name.as_str()).collect();
//! assert_eq!(rules, ["R1", "R2"]);
//! let SeedItem::Term(term) = &st.seed[1] else { panic!() };
//! assert!(matches!(term.entries[..], [BranchEntry::Term(_), BranchEntry::Empty, BranchEntry::Term(_)]));
//! assert_eq!(sys.axiom.display(&sys.symbols), "F[F[F][+F][-F]][+F][-F[++F][-F]]");
//! assert_eq!((st.stems.broadness, st.stems.length), ((8.0, 1.0), (40.0, 4.0)));
//! assert!(st.constraint.outline.is_empty());
//! assert!((sys.settings.delta - 30f64.to_radians()).abs() < 1e-15);
//! ```
//!
//! **Fractint entry** `Dragon { Angle 8  Axiom FX  F=  y=+FX--FY+ … }`:
//! `Angle 8` is δ = 2π/8; the derivation length is Fractint's default order
//! 2; rules for the same character are one production (`F=` has the empty
//! successor); commands are lowercased symbols. Fractint's second, *real*
//! heading is turned by [`TurtleOp::RotateReal`] and used by
//! [`TurtleOp::ForwardReal`]; `|` is [`TurtleOp::TurnUnswapped`]; colour
//! commands index a 256-colour palette starting at colour 15.
//!
//! ```
//! let sys = graftal::front::fractint::read_ok(
//!     "Dragon {\n  Angle 8\n  Axiom FX\n  F=\n  y=+FX--FY+\n  x=-FX++FY-\n}\n",
//! );
//! assert!((sys.settings.delta - std::f64::consts::TAU / 8.0).abs() < 1e-15);
//! assert_eq!((sys.settings.steps, sys.settings.colour, sys.colours.len()), (Some(2), 15, 256));
//! let rules: Vec<String> = sys
//!     .productions
//!     .iter()
//!     .map(|p| format!("{}={}", sys.symbols.name(p.predecessor[0]), p.alternatives[0].successor.display(&sys.symbols)))
//!     .collect();
//! assert_eq!(rules, ["f=", "y=+fx--fy+", "x=-fx++fy-"]);
//! ```
//!
//! **cpfg parametric production** `A(x) : x < 3 --> F(x) A(x+1)`: the
//! predecessor binds `x` to local slot 0 ([`Formals`]), the condition and
//! the successor's parameters are [`program::Expr`]essions over it, and the
//! axiom's parameters are expressions too ([`System::axiom_args`]). Such a
//! system is derived by module rewriting.
//!
//! ```
//! use graftal::ir::program::Expr;
//! let sys = graftal::front::cpfg::read_ok(
//!     "lsystem: 1\nderivation length: 3\naxiom: A(1)\nA(x) : x < 3 --> F(x) A(x+1)\nendlsystem\n",
//! );
//! let p = &sys.productions[0];
//! assert_eq!(p.formals.predecessor, [vec![0]]);
//! assert!(p.condition.is_some() && p.uses_modules());
//! assert_eq!(p.alternatives[0].args.len(), 2);
//! assert_eq!(sys.axiom_args, [vec![Expr::Num(1.0)]]);
//! assert_eq!(graftal::eval::plan(&sys, 3), graftal::eval::Method::Modules);
//! let word = graftal::driver::derive(&sys, &graftal::driver::RunOptions::default()).unwrap();
//! assert_eq!(word.display(&sys.symbols), "F(1)F(2)A(3)");
//! ```

pub mod colours;
pub mod d0l;
pub mod environment;
pub mod graph;
pub mod look;
pub mod program;
mod same;
pub mod texture;

pub use d0l::D0l;
use program::{Expr, Program, Stmt};

use serde::Serialize;
use std::collections::HashMap;
use std::ops::Range;

/// How deep nesting may go, in every notation: parentheses and operations
/// in expressions, brackets and braces a parser descends into, rules
/// written through rules, the levels of a derivation an emitter writes out
/// one by one. The front ends refuse deeper input with one
/// [`NESTED_TOO_DEEPLY`](crate::diagnostics::codes::NESTED_TOO_DEEPLY)
/// (E0013) at the first place past it, so that the code that follows
/// nesting by recursion (parsers, lowering, the walks over
/// [`program::Expr`] trees, emitters) stays well within a 2 MiB stack, a
/// test thread's in an unoptimised build included. Branches `[ ]` in a
/// *word* are not limited: everything that walks a word does so with an
/// explicit stack.
pub const MAX_NESTING: usize = 256;

/// An interned symbol: an index into [`SymbolTable`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct SymbolId(pub u32);

impl SymbolId {
    /// `[`: push the turtle state; opens a branch for context matching.
    pub const OPEN: SymbolId = SymbolId(0);
    /// `]`: pop the turtle state; closes a branch.
    pub const CLOSE: SymbolId = SymbolId(1);

    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What the table knows about one symbol besides its name.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SymbolInfo {
    pub name: String,
    /// LinF `p?s`: this symbol is an occurrence of `base` expanded with
    /// `probability` at each step.
    pub guard: Option<Guard>,
}

/// Per-occurrence expansion probability (LinF `p?s`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Guard {
    pub probability: f64,
    pub base: SymbolId,
}

/// Interned symbol names.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SymbolTable {
    symbols: Vec<SymbolInfo>,
    #[serde(skip)]
    index: HashMap<String, SymbolId>,
}

impl SymbolTable {
    /// A table that already holds `[` and `]` as ids 0 and 1.
    pub fn new() -> Self {
        let mut t = SymbolTable::default();
        t.intern("[");
        t.intern("]");
        t
    }

    pub fn intern(&mut self, name: &str) -> SymbolId {
        if let Some(&id) = self.index.get(name) {
            return id;
        }
        let id = SymbolId(self.symbols.len() as u32);
        self.symbols.push(SymbolInfo {
            name: name.to_string(),
            guard: None,
        });
        self.index.insert(name.to_string(), id);
        id
    }

    /// Interns a *silent* symbol under `key`: its name is empty, so words
    /// print without it; `get(key)` finds it again. Used for markers that
    /// only the turtle sees (STL stem levels).
    pub fn intern_silent(&mut self, key: &str) -> SymbolId {
        if let Some(&id) = self.index.get(key) {
            return id;
        }
        let id = SymbolId(self.symbols.len() as u32);
        self.symbols.push(SymbolInfo {
            name: String::new(),
            guard: None,
        });
        self.index.insert(key.to_string(), id);
        id
    }

    /// The key a silent symbol was interned under (its name is empty);
    /// `None` for any other symbol.
    pub fn silent_key(&self, id: SymbolId) -> Option<&str> {
        if !self.name(id).is_empty() {
            return None;
        }
        (self.index.iter())
            .find(|(_, &v)| v == id)
            .map(|(k, _)| k.as_str())
    }

    /// Interns a guarded occurrence (`p?base`) of `base`.
    pub fn intern_guarded(&mut self, probability: f64, base: SymbolId) -> SymbolId {
        let name = format!("{probability}?{}", self.name(base));
        let id = self.intern(&name);
        self.symbols[id.index()].guard = Some(Guard { probability, base });
        id
    }

    pub fn get(&self, name: &str) -> Option<SymbolId> {
        self.index.get(name).copied()
    }

    pub fn name(&self, id: SymbolId) -> &str {
        &self.symbols[id.index()].name
    }

    pub fn info(&self, id: SymbolId) -> &SymbolInfo {
        &self.symbols[id.index()]
    }

    pub fn len(&self) -> usize {
        self.symbols.len()
    }

    pub fn is_empty(&self) -> bool {
        self.symbols.is_empty()
    }

    pub fn iter(&self) -> impl Iterator<Item = (SymbolId, &SymbolInfo)> {
        self.symbols
            .iter()
            .enumerate()
            .map(|(i, s)| (SymbolId(i as u32), s))
    }
}

/// A word: a sequence of modules, each a symbol with zero or more real
/// parameters (`A(1,2.5)`). The symbols are `self.0`, one [`SymbolId`]
/// each; the parameters live in a side array that is empty, and allocates
/// nothing, while no module has any. So a word of plain symbols is as
/// compact as a symbol array, and rewriting it moves nothing else.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Word(pub Vec<SymbolId>, Params);

/// The parameters of a word's modules: module `i` has
/// `values[starts[i]..starts[i + 1]]`; `starts` is empty while no module
/// has parameters.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
struct Params {
    values: Vec<f64>,
    starts: Vec<u32>,
}

impl From<Vec<SymbolId>> for Word {
    fn from(symbols: Vec<SymbolId>) -> Self {
        Word(symbols, Params::default())
    }
}

impl Word {
    pub fn new() -> Self {
        Word::default()
    }
    /// Modules in the word.
    pub fn len(&self) -> usize {
        self.0.len()
    }
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    pub fn symbols(&self) -> &[SymbolId] {
        &self.0
    }
    /// Whether some module has parameters.
    pub fn has_params(&self) -> bool {
        !self.1.starts.is_empty()
    }
    /// The parameters of module `i`.
    pub fn args(&self, i: usize) -> &[f64] {
        match self.1.starts.get(i..i + 2) {
            Some(&[a, b]) => &self.1.values[a as usize..b as usize],
            _ => &[],
        }
    }
    /// Appends the module `symbol(args)`.
    pub fn push(&mut self, symbol: SymbolId, args: &[f64]) {
        if !args.is_empty() && self.1.starts.is_empty() {
            // The first module with parameters: every earlier one has none.
            self.1.starts = vec![0; self.0.len() + 1];
        }
        self.0.push(symbol);
        if !self.1.starts.is_empty() {
            self.1.values.extend_from_slice(args);
            self.1.starts.push(self.1.values.len() as u32);
        }
    }
    /// Appends modules `range` of `other`.
    pub fn extend_from(&mut self, other: &Word, range: Range<usize>) {
        if !other.has_params() && !self.has_params() {
            self.0.extend_from_slice(&other.0[range]);
            return;
        }
        for i in range {
            self.push(other.0[i], other.args(i));
        }
    }
    /// Appends every module of `other`, its parameters copied in bulk.
    pub fn append(&mut self, other: &Word) {
        if other.has_params() {
            if !self.has_params() {
                self.1.starts = vec![0; self.0.len() + 1];
            }
            let base = self.1.values.len() as u32;
            self.1.values.extend_from_slice(&other.1.values);
            let starts = other.1.starts[1..].iter().map(|&s| s + base);
            self.1.starts.extend(starts);
        } else if let Some(&end) = self.1.starts.last() {
            let none = std::iter::repeat_n(end, other.0.len());
            self.1.starts.extend(none);
        }
        self.0.extend_from_slice(&other.0);
    }
    /// Empties the word, keeping its buffers (rewriting reuses words as
    /// scratch space).
    pub fn clear(&mut self) {
        self.0.clear();
        self.1.values.clear();
        self.1.starts.clear();
    }
    /// Sets the parameters of module `i`, which has as many already.
    pub fn set_args(&mut self, i: usize, args: &[f64]) {
        if let Some(&[a, b]) = self.1.starts.get(i..i + 2) {
            for (slot, x) in self.1.values[a as usize..b as usize].iter_mut().zip(args) {
                *slot = *x;
            }
        }
    }
    /// The word written with the symbols' names, nothing between them (the
    /// way pfg and the goldens print derived strings), and each module's
    /// parameters in parentheses as cpfg writes them (`F(1.5)A(2,3)`).
    pub fn display(&self, table: &SymbolTable) -> String {
        let mut s = String::with_capacity(self.0.len());
        for (i, &id) in self.0.iter().enumerate() {
            s.push_str(table.name(id));
            let args = self.args(i);
            if !args.is_empty() {
                s.push('(');
                for (k, a) in args.iter().enumerate() {
                    if k > 0 {
                        s.push(',');
                    }
                    s.push_str(&crate::number::readable(*a));
                }
                s.push(')');
            }
        }
        s
    }
}

/// An angle as written in the source; in radians, or a multiple of the increment δ, or an interval.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Angle {
    /// `factor` times the system's angle increment δ ([`Settings::delta`]).
    Delta(f64),
    /// A fixed angle in radians.
    Radians(f64),
    /// Drawn uniformly from `[lo, hi]` (radians) each time it is applied.
    Uniform { lo: f64, hi: f64 },
}

/// The axes of the turtle frame {H, L, U} (heading, left, up), which is the
/// LinF Frenet frame {t, n, b}.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Axis {
    Heading,
    Left,
    Up,
}

/// A named LinF rotation: a (torsion, curvature) pair.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Rotation {
    pub name: String,
    pub torsion: Angle,
    pub curvature: Angle,
}

/// Index into [`System::rotations`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct RotationId(pub u32);

/// An RGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Rgb(pub u8, pub u8, pub u8);

/// What the turtle does for one symbol.
///
/// Rotations follow the book's matrices (Prusinkiewicz & Hanan §2.3, Fig.
/// 2.12): `[H' L' U'] = [H L U] R(α)`, so for an angle α
///
/// * about U: `H' = H cos α − L sin α`, `L' = H sin α + L cos α` — positive
///   α turns the heading away from L, i.e. to the right (clockwise seen
///   from +z, the default view);
/// * about L: `H' = H cos α + U sin α`, `U' = −H sin α + U cos α`;
/// * about H: `L' = L cos α + U sin α`, `U' = −L sin α + U cos α`.
///
/// pfg `+` is `Rotate { Up, Delta(1) }` and `-` is `Delta(−1)`; `&`/`^` are
/// about L, `\`/`/` about H. A LinF curvature θ is a rotation about U by −θ
/// (it turns t towards n, counter-clockwise) and a torsion θ about H by −θ.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum TurtleOp {
    /// Move one step (times the current length); draw a segment if `draw`.
    Forward { draw: bool },
    /// Rotate the frame about `axis` by `angle` (negated when turns are
    /// swapped, see [`TurtleOp::SwapTurns`]).
    Rotate { axis: Axis, angle: Angle },
    /// Apply a named LinF rotation: torsion first, then curvature; `negate`
    /// for `-`.
    Frenet { rotation: RotationId, negate: bool },
    /// Turn around: rotate about U by 180°.
    TurnAround,
    /// `[`: push the turtle state.
    Push,
    /// `]`: pop the turtle state.
    Pop,
    /// `{` in pfg: start a filled polygon.
    PolygonBegin,
    /// `}` in pfg: close and fill the polygon.
    PolygonEnd,
    /// `!` in pfg: decrement the line width.
    DecrementWidth,
    /// `'` in pfg, `{` in LinF: the next colour.
    NextColour,
    /// `}` in LinF: back to the previous colour.
    PreviousColour,
    /// `!` in LinF: exchange the meaning of positive and negative turns.
    SwapTurns,
    /// LinF `x@`: multiply the step length by `x`.
    ScaleLength(f64),
    /// STL stem level: set the line width and the step length (absolute,
    /// turtle units) for what follows.
    Stem { width: f64, length: f64 },
    /// cpfg `;` (`up`) and `,`: step the colour index by the view file's
    /// colour increment, or set it to the module's parameter.
    ColourIndex { up: bool },
    /// cpfg `#` (`up`) and `!`: step the line width by the view file's
    /// width increment, or set it to the module's parameter.
    LineWidth { up: bool },
    /// cpfg `.`: a polygon vertex at the turtle's position (with a
    /// parameter, a generalized-cylinder control point, as `@Gc`).
    PolygonVertex,
    /// cpfg `@O(d)`: a sphere of diameter `d` (default: the line width),
    /// drawn as a filled disc facing the viewer.
    Sphere,
    /// cpfg `@o(d)`: a filled circle facing the viewer (in the screen plane).
    ScreenDisc,
    /// cpfg `@c(d)`: a filled circle in the turtle's HL plane.
    Circle,
    /// cpfg `@M(x,y,z)`: move the turtle to a point without drawing.
    MoveTo,
    /// cpfg `@R(hx,hy,hz[,ux,uy,uz])`: set the heading (and cpfg's up
    /// vector, the turtle's −U: cpfg's frame is left-handed).
    SetHeading,
    /// cpfg `@v`: roll about H so that U is as close to +y as it can be.
    RollToVertical,
    /// cpfg `~id`: draw surface `id` (an index into the system's surfaces)
    /// at the turtle, scaled by the module's parameters; its z goes along
    /// cpfg's up, the turtle's −U.
    Surface(u16),
    /// cpfg `@Gs`: start a generalized cylinder at the turtle's position.
    CylinderStart,
    /// cpfg `@Gc(n)` / `@Ge(n)`: a control point of the cylinder's axis;
    /// `end` finishes the cylinder.
    CylinderPoint { end: bool },
    /// cpfg `@Gt(a[,b])`: the tangent factors of the control points that
    /// follow: `a` for the Hermite piece arriving at a point, `b` (default
    /// `a`) for the one leaving it.
    CylinderTangents,
    /// cpfg `@Gr(a1,l1[,a2,l2])`: the radius tangents of the control points
    /// that follow, for the piece of cylinder arriving at a point (angle
    /// `a1` in degrees from the axis parameter, length `l1`) and the one
    /// leaving it (`a2`, `l2`; without them as arriving); `@Gr(s)`: whether
    /// their radius parts are scaled by the distance between control
    /// points (non-zero `s`).
    RadiusTangents,
    /// cpfg `?P`, `?H`, `?L`, `?U`: the turtle writes its position or frame
    /// vector into the module's parameters (see [`crate::eval::parametric`]);
    /// `?U` gets cpfg's up, the turtle's −U.
    Query(QueryKind),
    /// Fractint `|`: rotate about U by `angle` like [`TurtleOp::Rotate`],
    /// but *not* negated when turns are swapped (Fractint's `!` leaves `|`
    /// alone).
    TurnUnswapped(Angle),
    /// Fractint `\n` / `/n`: turn the turtle's second, *real* heading (an
    /// angle in the plane of the initial H and L, independent of the frame)
    /// by `angle`, positive to the right as for [`TurtleOp::Rotate`] about
    /// U; negated when turns are swapped.
    RotateReal(Angle),
    /// Fractint `D` / `M`: move one step (times the current length) along
    /// the real heading; draw a segment if `draw`.
    ForwardReal { draw: bool },
    /// Fractint `Cn`: set the colour index to `n` modulo the palette's
    /// length.
    SetColour(u32),
    /// Fractint `<n` (`up`) / `>n`: shift the colour index by `by`, modulo
    /// the palette's length; landing on 0 gives 1 going up and the last
    /// colour going down (Fractint never reaches the background colour 0
    /// this way).
    ShiftColour { by: u32, up: bool },
    /// cpfg `@Ts`, `@Ti`, `@Td`, `_`: changes the turtle's elasticity for
    /// one of [`Settings::tropisms`]: `tropism` (0-based), or, when `None`,
    /// the one the module's first parameter names (1-based; then the value
    /// is the second parameter). Without an id nothing changes.
    Elasticity {
        tropism: Option<u16>,
        change: ElasticityChange,
    },
    /// cpfg `@Tp`: U and L follow the turn of H since the last drawn step
    /// without twisting about H.
    Untwist,
    /// cpfg `@Tf`: the frame as it is now is the one later untwisting
    /// starts from (a roll made since the last step is kept).
    KeepTwist,
    /// cpfg `@#(id)`: the cross-section of the generalized cylinders that
    /// follow is contour `id` of [`System::contours`]; 0 or no parameter:
    /// the default circle.
    SetContour,
    /// cpfg `@Tx(n)`: what the turtle draws next wears texture `n` of
    /// [`look::Look::textures`] (counted from 1); 0 or no parameter: no
    /// texture.
    SetTexture,
    /// cpfg `?(n, s)`: the modules that follow, up to the matching
    /// [`TurtleOp::SubLsystemReturn`], belong to sub-L-system `n`
    /// ([`System::sub_lsystems`]); the turtle's scale (step lengths,
    /// sizes) and its line width are multiplied by `s` (1 without).
    /// Without parameters it does nothing.
    SubLsystemCall,
    /// cpfg `$`: back to the L-system and the scale before the matching
    /// call.
    SubLsystemReturn,
    /// cpfg `@L("format", p1, …)`: the text printf makes of the format (a
    /// string literal, [`System::strings`]) and the values, written at the
    /// turtle's place in the current colour (`@L("label")`: the label).
    Label,
}

/// How [`TurtleOp::Elasticity`] changes an elasticity by its value `v`,
/// or, when the module gives none, by the tropism's step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ElasticityChange {
    /// To `v` (to 0 without one).
    Set,
    /// Up by `v` (by the step).
    Increase,
    /// Down by `v` (by the step).
    Decrease,
    /// To `v` with one, up by the step without (cpfg's `_`).
    SetOrIncrease,
}

/// What a cpfg query module reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum QueryKind {
    Position,
    Heading,
    Left,
    Up,
    /// cpfg `?E`: the environment ([`System::environment`]) is told the
    /// module's parameters and the turtle's position, and its answer is
    /// written into the parameters.
    Environment,
}

/// A successor with its weight.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Alternative {
    /// Relative weight (normalised over the production's alternatives).
    pub weight: f64,
    /// A weight computed each time the production applies (cpfg's `: e`),
    /// in place of `weight`.
    pub computed_weight: Option<Expr>,
    pub successor: Word,
    /// The parameter expressions of each successor module, evaluated with
    /// the production's locals; empty when no module has parameters.
    pub args: Vec<Vec<Expr>>,
}

impl Alternative {
    /// A successor of plain symbols with a fixed weight.
    pub fn new(weight: f64, successor: Word) -> Self {
        Alternative {
            weight,
            computed_weight: None,
            successor,
            args: Vec::new(),
        }
    }
}

/// The formal parameters of a production's modules: for each module of the
/// left context, the strict predecessor and the right context, the local
/// slots its parameters bind (a module matches only a module with as many
/// parameters). All empty for a production of plain symbols.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Formals {
    pub left: Vec<Vec<u16>>,
    pub predecessor: Vec<Vec<u16>>,
    pub right: Vec<Vec<u16>>,
    /// Local slots: the formal parameters, then the variables the
    /// production's statements assign.
    pub locals: u16,
    /// The author's names of the local slots (slot i's is `names[i]`;
    /// empty where a notation has none, an unnamed slot is ""). Spelling
    /// only, as spans are: `System::same_as` ignores them, and the `.gft`
    /// emitter writes them where they read back as the same slots.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub names: Vec<String>,
}

impl Formals {
    /// The one form of a side whose modules bind nothing: no entries (the
    /// matcher reads a missing entry as no parameters, so both forms match
    /// the same modules; the IR keeps one so that equal systems are equal).
    pub fn tidy(&mut self) {
        for side in [&mut self.left, &mut self.predecessor, &mut self.right] {
            if side.iter().all(Vec::is_empty) {
                side.clear();
            }
        }
    }

    /// The slots module `k` of `side` binds (none for a plain production).
    pub fn of(side: &[Vec<u16>], k: usize) -> &[u16] {
        side.get(k).map_or(&[], |v| v.as_slice())
    }
}

/// A rewriting rule: `left < predecessor > right : condition -->
/// alternatives`, with the statements run around the condition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Production {
    pub left: Vec<SymbolId>,
    pub predecessor: Vec<SymbolId>,
    pub right: Vec<SymbolId>,
    pub formals: Formals,
    /// Run before the condition is tested (cpfg's `{ … }` before `?`).
    pub before: Vec<Stmt>,
    /// The production applies only where this is non-zero; `None`: always.
    pub condition: Option<Expr>,
    /// Run after the condition held, before the successor is computed.
    pub after: Vec<Stmt>,
    pub alternatives: Vec<Alternative>,
}

impl Production {
    /// A production of plain symbols, without condition or statements.
    pub fn new(
        left: Vec<SymbolId>,
        predecessor: Vec<SymbolId>,
        right: Vec<SymbolId>,
        alternatives: Vec<Alternative>,
    ) -> Self {
        Production {
            left,
            predecessor,
            right,
            formals: Formals::default(),
            before: Vec::new(),
            condition: None,
            after: Vec::new(),
            alternatives,
        }
    }
    /// The one form of what binds or passes no parameters (see
    /// [`Formals::tidy`]): sides and successors whose modules have no
    /// expressions hold none, as the fields' documentation says.
    pub fn tidy(&mut self) {
        self.formals.tidy();
        for alt in &mut self.alternatives {
            if alt.args.iter().all(Vec::is_empty) {
                alt.args.clear();
            }
        }
    }

    pub fn is_context_sensitive(&self) -> bool {
        !self.left.is_empty() || !self.right.is_empty()
    }
    pub fn is_stochastic(&self) -> bool {
        self.alternatives.len() > 1
    }
    /// Whether the production binds or computes parameters, tests a
    /// condition, runs statements or computes its weights.
    pub fn uses_modules(&self) -> bool {
        // Brackets in a context (cpfg's `[B]C`, `=]`) are matched over
        // branches by module rewriting only.
        let brackets = |side: &[SymbolId]| {
            side.iter()
                .any(|&s| s == SymbolId::OPEN || s == SymbolId::CLOSE)
        };
        brackets(&self.left)
            || brackets(&self.right)
            || self.formals != Formals::default()
            || !self.before.is_empty()
            || self.condition.is_some()
            || !self.after.is_empty()
            || self
                .alternatives
                .iter()
                .any(|a| !a.args.is_empty() || a.computed_weight.is_some())
    }
}

/// Index into [`System::productions`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct ProductionId(pub u32);

/// How a production is chosen at a position.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum RulePolicy {
    /// The first production in file order that matches (pfg, LinF,
    /// Fractint, STL, a cpfg system without `seed:`); a production's
    /// alternatives are chosen among by weight.
    FirstMatch,
    /// Every production that matches is a candidate, chosen by its weight
    /// (a cpfg system with `seed:`).
    Weighted,
}

/// Productions applied again to what a step produced (decomposition) or
/// to the word for drawing only (homomorphism), recursively up to `depth`
/// times.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Phase {
    pub productions: Vec<Production>,
    pub depth: u32,
    /// The phase's own random seed (cpfg's `seed:` after `homomorphism`).
    pub seed: Option<u64>,
}

/// A cpfg sub-L-system (an `lsystem: n` block after the file's first):
/// the productions, decomposition, homomorphism and context filter that
/// rewrite and draw the modules between a [`TurtleOp::SubLsystemCall`]
/// naming it and the matching [`TurtleOp::SubLsystemReturn`] (cpfg's
/// `?(n, s)` … `$`). cpfg ignores a called L-system's axiom and
/// derivation length; its blocks run with the system's own
/// ([`System::program`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SubLsystem {
    /// The number a call names it by.
    pub label: u32,
    pub productions: Vec<Production>,
    pub decomposition: Phase,
    pub homomorphism: Phase,
    pub context: ContextFilter,
}

/// Which symbols context matching sees. The brackets keep their meaning
/// in a left context always, and in a right context unless the filter
/// skips them: cpfg's `consider:` skips every symbol it does not list,
/// brackets included, so a right context read past `]` leaves the branch
/// and reads on along the word (cpfg's `RconDiff` tests the ignore table
/// before any bracket; `LconDiff` handles the brackets first).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum ContextFilter {
    /// Skip these symbols (pfg `ignore:`, cpfg `#ignore`).
    Ignore(Vec<SymbolId>),
    /// See only these symbols (cpfg `#consider`).
    Consider(Vec<SymbolId>),
}

impl ContextFilter {
    /// Whether context matching skips `id` (brackets aside: they open and
    /// close branches, never skipped).
    pub fn skips(&self, id: SymbolId) -> bool {
        match self {
            ContextFilter::Ignore(set) => set.contains(&id),
            ContextFilter::Consider(set) => {
                id != SymbolId::OPEN && id != SymbolId::CLOSE && !set.contains(&id)
            }
        }
    }

    /// Whether a right context reads past `id`: as [`Self::skips`], and
    /// the brackets too when a `Consider` filter does not list them.
    pub fn skips_on_the_right(&self, id: SymbolId) -> bool {
        match self {
            ContextFilter::Ignore(set) => set.contains(&id),
            ContextFilter::Consider(set) => !set.contains(&id),
        }
    }
}

impl Default for ContextFilter {
    /// Nothing skipped.
    fn default() -> Self {
        ContextFilter::Ignore(Vec::new())
    }
}

/// Derivation and drawing settings.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Derivation length from the file (`derivation length:`), if given.
    pub steps: Option<u64>,
    /// Angle increment δ in radians (every angle in the IR is in
    /// radians; degrees and `360/n` are the front ends' affair).
    pub delta: f64,
    /// Initial step length, in turtle units.
    pub step: f64,
    /// Share of the picture the figure fills, 0..=100 (pfg `scale factor`).
    pub scale: f64,
    /// Initial line width (turtle units scaled to the picture's stroke).
    pub width: f64,
    /// Factor applied to the width by [`TurtleOp::DecrementWidth`].
    pub width_factor: f64,
    /// The view the file asks for, `(azimuth, elevation)` in radians (a
    /// LinF `#: view` directive, a cpfg view file); `--view` overrides it.
    pub view: Option<(f64, f64)>,
    /// The initial colour index (cpfg `initial color`, Fractint 15; 0 elsewhere).
    pub colour: usize,
    /// What cpfg's `;` and `,` add to the colour index (`color increment`).
    pub colour_step: f64,
    /// What cpfg's `#` and `!` add to the line width (`line width
    /// increment`).
    pub width_step: f64,
    /// Whether line widths are in turtle units (cpfg `line style: polygon`
    /// or `cylinder`) rather than pixels.
    pub world_widths: bool,
    /// Whether polygons (`{` … `}`) are made as cpfg makes them: a drawn
    /// step inside one draws its segment as well as adding a vertex
    /// (`interpret.c` passes every `F` to the renderer), and the vertices
    /// are only those the steps and `.` add, not the turtle's place at `{`.
    pub cpfg_polygons: bool,
    /// The file's own seed, added to the run's (cpfg `seed:`).
    pub seed: Option<u64>,
    /// The generator the system's random numbers come from.
    pub randomness: Randomness,
    /// Tropisms bending every step (cpfg `tropism:`; none elsewhere).
    pub tropisms: Vec<look::Tropism>,
}

/// Where a system's random numbers come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub enum Randomness {
    /// graftal's portable streams (ChaCha8), one per purpose.
    #[default]
    Graftal,
    /// cpfg's: `drand48` for choosing among productions, seeded from
    /// `seed:`, and a second 48-bit stream for `ran`, `nran`, `bran`,
    /// `biran` and `srand`, drawn in cpfg's order with cpfg's formulas, so a
    /// seeded cpfg model grows the plant cpfg grows.
    Cpfg,
}

impl Settings {
    /// The n for which δ is 2π/n, when δ divides the turn whole (n at
    /// most 3600, within 1e-9).
    pub fn whole_divisions(&self) -> Option<u64> {
        let n = std::f64::consts::TAU / self.delta;
        let whole = n.round();
        (n.is_finite() && (1.0..=3600.0).contains(&whole) && (n - whole).abs() < 1e-9)
            .then_some(whole as u64)
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            steps: None,
            delta: std::f64::consts::FRAC_PI_2,
            step: 1.0,
            scale: 100.0,
            width: 1.0,
            width_factor: 0.8,
            view: None,
            colour: 0,
            colour_step: 1.0,
            width_step: 1.0,
            world_widths: false,
            cpfg_polygons: false,
            seed: None,
            randomness: Randomness::Graftal,
            tropisms: Vec::new(),
        }
    }
}

/// A system stated as structure rather than productions (see the module
/// docs): named rules, a seed of branching terms over them, stems, and for
/// an outline where and how the seed grows. STL states systems so, and
/// `.gft` writes them out.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Structure {
    /// Named rules (a table of rules, each with its self-resemblance count).
    pub rules: Vec<StructureRule>,
    /// The seed: strings and branching terms over the rules (for an
    /// outline, the grown seed: its growth points replaced by what grew).
    pub seed: Vec<SeedItem>,
    /// For an outline, the seed as the file plants it, with its growth
    /// points ([`BranchTerm::grows`]): what a notation writes, so that
    /// reading it grows `seed` again. Empty without an outline.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub planted: Vec<SeedItem>,
    /// Where and how the seed grows, for an outline.
    pub constraint: GrowthConstraint,
    /// Stem broadness and length per level.
    pub stems: Stems,
}

/// A growth constraint: the seed grows inside the union of the `outline`'s
/// shapes (with the stems keeping clear of each other) by the `strategy`,
/// each rule for at most its self-resemblance count of levels, `levels`
/// for rules without one. An empty outline constrains nothing.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct GrowthConstraint {
    pub outline: Vec<Shape>,
    pub strategy: Growth,
    pub levels: u32,
}

/// Stem broadness and length, each with its decrement per level (`B = 8
/// (1)`, `L = 40 (4)`): a stem at level k has `B − k·ΔB` and `L − k·ΔL`.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Stems {
    pub broadness: (f64, f64),
    pub length: (f64, f64),
}

impl Structure {
    /// The most drawing components an expansion may have.
    pub const MAX_EXPANSION: usize = 8_000_000;
    /// The widest stroke drawn (turtle width units: pixels per 600 pixels
    /// of picture). Growth uses the broadness as given; only the picture is
    /// capped.
    pub const MAX_DRAWN_WIDTH: f64 = 200.0;

    /// Broadness or length per level, clamped to a tenth of the first value
    /// where it would not be positive; the first clamped level, if any.
    pub fn per_level(base: f64, dec: f64, levels: u32) -> (Vec<f64>, Option<u32>) {
        let mut first = None;
        let v = (0..=levels)
            .map(|k| {
                let x = base - dec * k as f64;
                if x <= 0.0 && base > 0.0 {
                    first.get_or_insert(k);
                    base * 0.1
                } else {
                    x.max(0.0)
                }
            })
            .collect();
        (v, first)
    }
}

/// A named rule of a [`Structure`]: a body whose top-level branches a
/// [`BranchTerm`] extends, with how many levels it may grow.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StructureRule {
    pub name: String,
    pub body: Word,
    /// `[I n X]`: the self-resemblance count, if given.
    pub resemblance: Option<u32>,
    /// For a rule with a count that an outline grows: the rule whose body
    /// one level of growth adds (`Rk` of `[I n Rk]`, or a rule made to
    /// hold the `X` of `[I n X]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<StructureRuleId>,
}

/// Index into [`Structure::rules`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct StructureRuleId(pub u32);

/// One item of a structure's seed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum SeedItem {
    Word(Word),
    Term(BranchTerm),
}

/// `R{e1, …, em}`: entry k extends the k-th top-level branch of R.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchTerm {
    pub rule: StructureRuleId,
    pub entries: Vec<BranchEntry>,
    /// A growth point of an outline (only in [`Structure::planted`]): the
    /// rule grows here, and `entries` is empty.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub grows: bool,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum BranchEntry {
    /// Keep the branch, append nothing.
    Empty,
    /// `~`: the branch failed and is not drawn.
    Failed,
    /// Apply this term at the end of the branch.
    Term(BranchTerm),
}

/// The growth strategy of an outline.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub enum Growth {
    #[default]
    BreadthFirst,
    DepthFirst,
}

/// A layout shape of an outline (stem units, origin at the root, y up).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Shape {
    Rectangle {
        colour: Rgb,
        x: f64,
        y: f64,
        w: f64,
        h: f64,
    },
    RoundRect {
        colour: Rgb,
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        corner: f64,
    },
    Ellipse {
        colour: Rgb,
        x: f64,
        y: f64,
        w: f64,
        h: f64,
    },
    Polygon {
        colour: Rgb,
        points: Vec<(f64, f64)>,
    },
}

/// A byte range in one source file.
pub type Span = Range<usize>;

/// Where the parts of a [`System`] came from. A side table: it never takes
/// part in equality or serialised output.
#[derive(Clone, Debug, Default)]
pub struct SpanTable {
    /// One span per production (the whole line).
    pub productions: Vec<Span>,
    /// Spans of each successor symbol, per production and alternative.
    pub successors: Vec<Vec<Vec<Span>>>,
    /// Span of each axiom symbol.
    pub axiom: Vec<Span>,
    /// First place each symbol is written.
    pub symbols: HashMap<SymbolId, Span>,
}

/// An L-system in graftal's IR: what every front end produces.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct System {
    pub symbols: SymbolTable,
    /// `interpretation[s]` is what the turtle does for symbol `s`.
    pub interpretation: Vec<Option<TurtleOp>>,
    pub axiom: Word,
    /// The parameter expressions of each axiom module, evaluated after
    /// [`Program::start`]; empty when none has parameters.
    pub axiom_args: Vec<Vec<Expr>>,
    pub productions: Vec<Production>,
    /// Applied after each step to what it produced.
    pub decomposition: Phase,
    /// Applied to the word for drawing only.
    pub homomorphism: Phase,
    /// Variables and the statements run around the derivation.
    pub program: Program,
    /// The word's ends are neighbours for context (a ring).
    pub ring: bool,
    /// The symbol that, after each step, removes itself and the rest of
    /// its branch (cpfg's `%`).
    pub cut: Option<SymbolId>,
    pub policy: RulePolicy,
    pub context: ContextFilter,
    pub settings: Settings,
    pub rotations: Vec<Rotation>,
    pub colours: Vec<Rgb>,
    pub structure: Option<Structure>,
    /// An object-instancing graph (Bekaert & Willems' IFS codes with
    /// restrictions): a model made of transformed instances of itself,
    /// drawn without being expanded ([`graph`]).
    pub graph: Option<graph::InstancingGraph>,
    /// Surfaces drawn by [`TurtleOp::Surface`]: triangles in the surface's
    /// own frame (x along the turtle's L, y along H, z along cpfg's up,
    /// −U), with the contact point at the origin.
    pub surfaces: Vec<SurfaceMesh>,
    /// Contours for generalized cylinders and `curveX` (cpfg `.con`).
    pub contours: Vec<look::Contour>,
    /// Background, light, materials and camera of its pictures.
    pub look: look::Look,
    /// The number sub-L-system calls name this system by (cpfg's
    /// `lsystem: n` of the file's first L-system; 1 by default).
    pub label: u32,
    /// The L-systems that rewrite and draw the parts of the word the calls
    /// hand them ([`SubLsystem`]).
    pub sub_lsystems: Vec<SubLsystem>,
    /// What answers the [`QueryKind::Environment`] modules (an open
    /// L-system); `None`: nothing does, and they keep their parameters.
    pub environment: Option<environment::Environment>,
}

/// What a front end makes of a source: the system and where its parts
/// came from. The system is usable only when reading gave no error.
#[derive(Clone, Debug)]
pub struct Lowered {
    pub system: System,
    pub spans: SpanTable,
}

/// A surface the turtle can place (a cpfg `~id`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SurfaceMesh {
    pub name: String,
    pub triangles: Vec<[[f64; 3]; 3]>,
    /// Per triangle, its corners' texture coordinates as a texture laid
    /// once on each patch takes them (the patch's own parameters); empty
    /// when the surface has none (it is then drawn untextured).
    pub patch_uvs: Vec<[[f64; 2]; 3]>,
    /// The same for a texture laid once across the whole surface (cpfg's
    /// `S:`): the surface's x and y across its extent.
    pub surface_uvs: Vec<[[f64; 2]; 3]>,
    /// The texture the surface always wears (a cpfg `surface:` line's
    /// texture file), an index of [`look::Look::textures`]; it takes
    /// precedence over the turtle's.
    pub texture: Option<u16>,
}

impl SurfaceMesh {
    /// The texture coordinates of a texture laid once across a surface of
    /// `triangles` (cpfg's `set_texture_coordinates` lays it in the plane
    /// z = 0): each corner's x and y over the surface's extent in them. A
    /// surface flat along x or y spreads the texture's edge texel over
    /// it. The `.gft` reader derives [`SurfaceMesh::surface_uvs`] so, as
    /// the cpfg front end computes them.
    pub fn extent_uvs(triangles: &[[[f64; 3]; 3]]) -> Vec<[[f64; 2]; 3]> {
        let mut low = [f64::INFINITY; 2];
        let mut high = [f64::NEG_INFINITY; 2];
        for p in triangles.iter().flatten() {
            for k in 0..2 {
                low[k] = low[k].min(p[k]);
                high[k] = high[k].max(p[k]);
            }
        }
        let across = |p: &[f64; 3], k: usize| {
            let span = high[k] - low[k];
            if span > 0.0 {
                (p[k] - low[k]) / span
            } else {
                0.0
            }
        };
        triangles
            .iter()
            .map(|t| t.map(|p| [across(&p, 0), across(&p, 1)]))
            .collect()
    }
}

impl Default for System {
    fn default() -> Self {
        System::new()
    }
}

impl System {
    /// An empty system with `[` and `]` already interpreted.
    pub fn new() -> Self {
        let mut sys = System {
            symbols: SymbolTable::new(),
            interpretation: Vec::new(),
            axiom: Word::default(),
            axiom_args: Vec::new(),
            environment: None,
            productions: Vec::new(),
            decomposition: Phase::default(),
            homomorphism: Phase::default(),
            program: Program::default(),
            ring: false,
            cut: None,
            policy: RulePolicy::FirstMatch,
            context: ContextFilter::Ignore(Vec::new()),
            settings: Settings::default(),
            rotations: Vec::new(),
            colours: Vec::new(),
            structure: None,
            graph: None,
            surfaces: Vec::new(),
            contours: Vec::new(),
            look: look::Look::default(),
            label: 1,
            sub_lsystems: Vec::new(),
        };
        sys.set_interpretation(SymbolId::OPEN, TurtleOp::Push);
        sys.set_interpretation(SymbolId::CLOSE, TurtleOp::Pop);
        sys
    }

    /// Interns `name`, growing the interpretation table to match.
    pub fn intern(&mut self, name: &str) -> SymbolId {
        let id = self.symbols.intern(name);
        if self.interpretation.len() < self.symbols.len() {
            self.interpretation.resize(self.symbols.len(), None);
        }
        id
    }

    /// Interns a silent symbol (see [`SymbolTable::intern_silent`]),
    /// growing the interpretation table to match.
    pub fn intern_silent(&mut self, key: &str) -> SymbolId {
        let id = self.symbols.intern_silent(key);
        if self.interpretation.len() < self.symbols.len() {
            self.interpretation.resize(self.symbols.len(), None);
        }
        id
    }

    pub fn set_interpretation(&mut self, id: SymbolId, op: TurtleOp) {
        if self.interpretation.len() <= id.index() {
            self.interpretation.resize(id.index() + 1, None);
        }
        self.interpretation[id.index()] = Some(op);
    }

    /// What the turtle does for `id` (a guarded symbol acts as its base).
    pub fn op(&self, id: SymbolId) -> Option<TurtleOp> {
        let id = match self.symbols.info(id).guard {
            Some(g) => g.base,
            None => id,
        };
        self.interpretation.get(id.index()).copied().flatten()
    }

    /// Whether rewriting needs modules: parameters, conditions,
    /// statements, a program, decomposition or homomorphism phases, a
    /// ring, a cut, or weighted choice among productions. Such a system is
    /// derived by module rewriting ([`crate::eval`] says how it chooses).
    pub fn rewrites_modules(&self) -> bool {
        self.productions.iter().any(Production::uses_modules)
            || !self.axiom_args.is_empty()
            || self.decomposition != Phase::default()
            || self.homomorphism != Phase::default()
            || !self.program.is_empty()
            || self.ring
            || self.cut.is_some()
            || self.policy == RulePolicy::Weighted
            || !self.sub_lsystems.is_empty()
    }

    /// Every production of the system: its own, its phases', then each
    /// sub-L-system's and its phases'.
    pub fn every_production(&self) -> impl Iterator<Item = &Production> {
        let phases = [&self.decomposition, &self.homomorphism];
        let subs = self.sub_lsystems.iter().flat_map(|s| {
            (s.productions.iter())
                .chain(&s.decomposition.productions)
                .chain(&s.homomorphism.productions)
        });
        (self.productions.iter())
            .chain(phases.into_iter().flat_map(|p| &p.productions))
            .chain(subs)
    }

    /// Whether any symbol writes a label ([`TurtleOp::Label`]).
    pub fn writes_labels(&self) -> bool {
        self.interpretation.contains(&Some(TurtleOp::Label))
    }

    /// The string literals of the system's successors and axiom, each once,
    /// in the order first met (the axiom, then the productions, the
    /// phases and the sub-L-systems' in order). A literal's value in an
    /// expression is its index here: what a [`TurtleOp::Label`] formats.
    pub fn strings(&self) -> Vec<&str> {
        fn walk<'s>(e: &'s Expr, out: &mut Vec<&'s str>) {
            match e {
                Expr::Str(s) if !out.contains(&s.as_str()) => out.push(s),
                Expr::Element(_, xs) | Expr::Call(_, xs) => xs.iter().for_each(|x| walk(x, out)),
                Expr::Unary(_, a) => walk(a, out),
                Expr::Binary(_, a, b) => {
                    walk(a, out);
                    walk(b, out)
                }
                Expr::Cond(c, a, b) => [c, a, b].into_iter().for_each(|x| walk(x, out)),
                _ => {}
            }
        }
        let mut out = Vec::new();
        let successors =
            (self.every_production()).flat_map(|p| p.alternatives.iter().flat_map(|a| &a.args));
        for e in self.axiom_args.iter().chain(successors).flatten() {
            walk(e, &mut out);
        }
        out
    }

    /// Whether a right context reads past `id` ([`ContextFilter`]):
    /// as [`System::is_ignored`], and the brackets too when a
    /// `Consider` filter does not list them.
    pub fn is_ignored_on_the_right(&self, id: SymbolId) -> bool {
        self.context.skips_on_the_right(id)
    }

    /// Whether context matching skips `id` (brackets aside: they open and
    /// close branches, never skipped).
    pub fn is_ignored(&self, id: SymbolId) -> bool {
        self.context.skips(id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_word_of_plain_symbols_keeps_no_parameter_array() {
        let mut w = Word::from(vec![SymbolId(2); 1000]);
        for _ in 0..1000 {
            w.push(SymbolId(3), &[]);
        }
        assert!(!w.has_params());
        assert_eq!((w.1.values.capacity(), w.1.starts.capacity()), (0, 0));
        assert_eq!(w.args(1500), &[] as &[f64]);
    }

    #[test]
    fn parameters_appear_with_the_first_module_that_has_them() {
        let mut table = SymbolTable::new();
        let (a, f) = (table.intern("A"), table.intern("F"));
        let mut w = Word::from(vec![a, f]);
        w.push(f, &[1.5]);
        w.push(a, &[]);
        w.push(a, &[2.0, 3.0]);
        assert!(w.has_params());
        assert_eq!(w.args(0), &[] as &[f64]);
        assert_eq!(w.args(2), &[1.5]);
        assert_eq!(w.args(4), &[2.0, 3.0]);
        assert_eq!(w.display(&table), "AFF(1.5)AA(2,3)");
        let mut copy = Word::new();
        copy.extend_from(&w, 2..5);
        assert_eq!(copy.display(&table), "F(1.5)AA(2,3)");
        copy.set_args(0, &[7.0]);
        assert_eq!(copy.args(0), &[7.0]);
        copy.clear();
        assert!(!copy.has_params() && copy.is_empty());
    }

    #[test]
    fn which_systems_rewrite_modules_follows_from_their_parts() {
        let mut sys = System::new();
        let a = sys.intern("A");
        sys.axiom = Word::from(vec![a]);
        let plain = Production::new(
            vec![],
            vec![a],
            vec![],
            vec![Alternative::new(1.0, Word::from(vec![a, a]))],
        );
        sys.productions.push(plain.clone());
        assert!(!sys.rewrites_modules());
        let mut conditional = plain.clone();
        conditional.condition = Some(program::Expr::Num(1.0));
        let changes: [&dyn Fn(&mut System); 6] = [
            &|s| s.ring = true,
            &|s| s.cut = Some(a),
            &|s| s.policy = RulePolicy::Weighted,
            &|s| s.axiom_args = vec![vec![program::Expr::Num(1.0)]],
            &|s| s.homomorphism.productions.push(s.productions[0].clone()),
            &|s| s.productions[0] = conditional.clone(),
        ];
        for change in changes {
            let mut s = sys.clone();
            change(&mut s);
            assert!(s.rewrites_modules());
        }
    }
}
