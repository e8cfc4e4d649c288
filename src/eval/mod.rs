//! Evaluation: parallel rewriting of an IR [`System`], step by step, exactly
//! as the IR module documents (first match in file order, bracket-aware
//! contexts modulo the ignore set, weighted alternatives, guarded symbols).
//!
//! Randomness is keyed: each choice is drawn from the seed, the step and the
//! place in the word of the symbol it is made for ([`Draws`]), so the same
//! system, steps and seed give the same word on every machine and on any
//! number of threads. (Parametric systems draw in word order from the
//! machine's stream, as cpfg does: [`parametric`].)
//!
//! Growth is bounded: a step that would make the word longer than
//! [`DeriveOptions::max_symbols`] stops with [`codes::TOO_MANY_SYMBOLS`], and
//! a derivation that would rewrite more than [`DeriveOptions::max_work`]
//! symbols in all stops with [`codes::TOO_MUCH_WORK`], so no input can exhaust
//! memory or run without end.

mod bound;
pub mod count;
pub use bound::fewest_at;
pub mod parametric;
pub mod provenance;
mod sub_lsystems;

mod table;
pub mod tree;

use crate::random::Stream;

use crate::diagnostics::{codes, Diagnostic};
use crate::ir::{Guard, SymbolId, System, Word};
use provenance::Notes;
use std::collections::HashMap;

/// Default for [`DeriveOptions::max_symbols`]: 200 million symbols (800 MB
/// per word buffer).
pub const DEFAULT_MAX_SYMBOLS: usize = 200_000_000;

/// How far and how to derive.
#[derive(Clone, Debug)]
pub struct DeriveOptions {
    pub steps: u64,
    pub seed: u64,
    /// The longest word allowed.
    pub max_symbols: usize,
    /// The most symbols rewritten over all steps.
    pub max_work: u64,
    /// Threads that derive; 0 for every core. The word is the same for
    /// every count.
    pub threads: usize,
}

impl DeriveOptions {
    pub fn new(steps: u64) -> Self {
        DeriveOptions {
            steps,
            seed: 0,
            max_symbols: DEFAULT_MAX_SYMBOLS,
            max_work: (DEFAULT_MAX_SYMBOLS as u64).saturating_mul(20),
            threads: 0,
        }
    }
    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = threads;
        self
    }
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
    /// Sets the symbol limit and a work limit proportional to it.
    pub fn max_symbols(mut self, max: usize) -> Self {
        self.max_symbols = max;
        self.max_work = (max as u64).saturating_mul(20);
        self
    }
}

/// How a system is derived. The method follows from the system's
/// properties alone, never from the notation it was read from: the same
/// system read from pfg, LinF or Fractint is derived the same way.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Method {
    /// Context-free and deterministic, without parameters (a D0L system):
    /// the word is built from the shared derivation tree ([`tree`]), its
    /// length known before it is derived.
    SharedTree,
    /// Contexts of at most one symbol on each side, one-symbol
    /// predecessors, without parameters or guards (stochastic alternatives
    /// allowed): each step looks up the production of every (left, symbol,
    /// right) in a table, on words of bytes when the alphabet has fewer
    /// than 256 symbols, a step of a big word on every thread
    /// ([`DeriveOptions::threads`]).
    Table,
    /// Any other system without parameters (longer predecessors and
    /// contexts, guards): the general matcher.
    General,
    /// Parameters, conditions, statements, phases, a ring or a cut
    /// ([`System::rewrites_modules`]): module rewriting ([`parametric`]).
    Modules,
}

impl Method {
    /// The method's name as `stats` reports it.
    pub fn name(self) -> &'static str {
        match self {
            Method::SharedTree => "shared tree",
            Method::Table => "table",
            Method::General => "general",
            Method::Modules => "modules",
        }
    }
}

/// The method [`derive()`] uses for `steps` steps of `sys`.
pub fn plan(sys: &System, steps: u64) -> Method {
    if sys.rewrites_modules() {
        return Method::Modules;
    }
    Deriver::new(sys).method(steps)
}

/// A system prepared for rewriting: productions indexed by their first
/// predecessor symbol, the ignore set as a table.
pub struct Deriver<'a> {
    sys: &'a System,
    /// `by_first[s]`: productions whose predecessor starts with `s`, in file
    /// order.
    by_first: Vec<Vec<u32>>,
    /// `guards[s]`: the guard of a guarded symbol (LinF `p?s`).
    guards: Vec<Option<Guard>>,
    ignored: Vec<bool>,
    contexts: bool,
    stochastic: bool,
    /// The longest left and right contexts of any production.
    max_left: usize,
    max_right: usize,
    /// The look-up table of systems with one-symbol contexts.
    table: Option<table::Table<'a>>,
}

/// The visible neighbours of the position being rewritten, found once and
/// shared by all productions tried there.
#[derive(Default)]
struct Around {
    /// Up to `max_left` symbols to the left, nearest first.
    left: Vec<SymbolId>,
    left_ready: bool,
    /// Up to `max_right` symbols from `right_at` on.
    right: Vec<SymbolId>,
    right_at: usize,
}

impl<'a> Deriver<'a> {
    pub fn new(sys: &'a System) -> Self {
        let n = sys.symbols.len();
        let mut by_first = vec![Vec::new(); n];
        for (i, p) in sys.productions.iter().enumerate() {
            if let Some(&first) = p.predecessor.first() {
                by_first[first.index()].push(i as u32);
            }
        }
        let ignored: Vec<bool> = (0..n).map(|i| sys.is_ignored(SymbolId(i as u32))).collect();
        let guards: Vec<Option<Guard>> = sys.symbols.iter().map(|(_, info)| info.guard).collect();
        let contexts = sys.productions.iter().any(|p| p.is_context_sensitive());
        let stochastic =
            sys.productions.iter().any(|p| p.is_stochastic()) || guards.iter().any(Option::is_some);
        Deriver {
            sys,
            table: table::Table::new(sys, &ignored),
            by_first,
            guards,
            ignored,
            contexts,
            stochastic,
            max_left: sys
                .productions
                .iter()
                .map(|p| p.left.len())
                .max()
                .unwrap_or(0),
            max_right: sys
                .productions
                .iter()
                .map(|p| p.right.len())
                .max()
                .unwrap_or(0),
        }
    }

    /// The method [`Deriver::derive`] takes for `steps` steps.
    pub fn method(&self, steps: u64) -> Method {
        if steps <= tree::MAX_TREE_DEPTH && crate::ir::D0l::of(self.sys).is_some() {
            Method::SharedTree
        } else if self.table.is_some() {
            Method::Table
        } else {
            Method::General
        }
    }

    /// Derives `opts.steps` steps from the axiom. `progress` is called after
    /// each step with the step number and the word's length.
    ///
    /// A deterministic system whose word comes back to an earlier word is in
    /// a cycle: once the cycle is confirmed (by deriving one more period and
    /// comparing words, so a hash collision cannot mislead), the remaining
    /// steps are skipped modulo the period. The result is exactly the word
    /// of step `opts.steps`, at a cost bounded by the cycle's length.
    pub fn derive(
        &self,
        opts: &DeriveOptions,
        progress: impl FnMut(u64, usize),
    ) -> Result<Word, Diagnostic> {
        self.derive_symbols(opts, progress).map(Symbols::into_word)
    }

    /// [`Deriver::derive`], the word's symbols kept as narrow as the
    /// derivation held them ([`Symbols`]): what streams to a pipe or the
    /// turtle needs no wider copy.
    pub fn derive_symbols(
        &self,
        opts: &DeriveOptions,
        mut progress: impl FnMut(u64, usize),
    ) -> Result<Symbols, Diagnostic> {
        if self.sys.axiom.len() > opts.max_symbols {
            return Err(too_many(0, opts));
        }
        // A context-free deterministic system: its length is known before
        // deriving, and its word is built from shared subtrees.
        if opts.steps <= tree::MAX_TREE_DEPTH {
            if let Some(t) = tree::Tree::new(self.sys) {
                let len = self.tree_len(&t, opts)?;
                let word = t.word_on(opts.steps, len, opts.threads);
                progress(opts.steps, word.len());
                return Ok(Symbols::Wide(word));
            }
        }
        refuse_early(self.sys, opts)?;
        self.stepwise_symbols(opts, progress)
    }

    /// The length of the word `t` derives in `opts.steps` steps, or
    /// [`codes::TOO_MANY_SYMBOLS`] (naming the step that outgrows the limit)
    /// before any of it is derived.
    pub fn tree_len(&self, t: &tree::Tree, opts: &DeriveOptions) -> Result<usize, Diagnostic> {
        t.word_len(opts.steps, opts.max_symbols as u128)
            .map(|len| len as usize)
            .map_err(|step| too_many(step, opts))
    }

    /// [`Deriver::derive`] by rewriting the whole word at every step, for
    /// every kind of system (the reference the shared-subtree path of
    /// context-free systems is tested against). Systems with one-symbol
    /// contexts are rewritten through their look-up table, in words of
    /// bytes when they have fewer than 256 symbols.
    pub fn derive_stepwise(
        &self,
        opts: &DeriveOptions,
        progress: impl FnMut(u64, usize),
    ) -> Result<Word, Diagnostic> {
        self.stepwise_symbols(opts, progress)
            .map(Symbols::into_word)
    }

    /// [`Deriver::derive_stepwise`] in the words it rewrote.
    fn stepwise_symbols(
        &self,
        opts: &DeriveOptions,
        progress: impl FnMut(u64, usize),
    ) -> Result<Symbols, Diagnostic> {
        let n = self.sys.symbols.len();
        // A table step of a big word is shared among the threads.
        let threads = crate::parallel::threads(opts.threads);
        Ok(match &self.table {
            Some(t) if n < 256 => {
                let stepper = t.stepper::<u8>().on(threads);
                Symbols::Bytes(self.steps(&stepper, opts, progress)?.0)
            }
            Some(t) if n < 65536 => {
                let stepper = t.stepper::<u16>().on(threads);
                Symbols::Shorts(self.steps(&stepper, opts, progress)?.0)
            }
            Some(t) => {
                let stepper = t.stepper::<SymbolId>().on(threads);
                Symbols::Wide(self.steps(&stepper, opts, progress)?.0)
            }
            None => Symbols::Wide(self.steps(&General(self), opts, progress)?.0),
        })
    }

    /// Rewrites `opts.steps` steps with `stepper`, stopping early at a fixed
    /// point and skipping confirmed cycles: the word, and what the stepper
    /// kept beside it.
    fn steps<S: Stepper>(
        &self,
        stepper: &S,
        opts: &DeriveOptions,
        mut progress: impl FnMut(u64, usize),
    ) -> Result<(Vec<S::Sym>, S::Scratch), Diagnostic> {
        let mut run = Run {
            seed: opts.seed,
            cur: self
                .sys
                .axiom
                .0
                .iter()
                .map(|&s| S::Sym::from_id(s))
                .collect(),
            next: Vec::with_capacity(self.sys.axiom.len() * 2),
            scratch: S::Scratch::default(),
            work: 0,
        };
        if run.cur.len() > opts.max_symbols {
            return Err(too_many(0, opts));
        }
        // Hashes of the small words seen so far (deterministic systems only).
        let mut seen: HashMap<u64, u64> = HashMap::new();
        let mut step = 0;
        while step < opts.steps {
            step += 1;
            advance(stepper, &mut run, opts, step)?;
            progress(step, run.cur.len());
            if run.cur.is_empty() {
                // The empty word rewrites to itself.
                break;
            }
            if self.stochastic {
                continue;
            }
            if run.cur == run.next {
                // A fixpoint: every further step gives the same word.
                break;
            }
            if run.cur.len() > CYCLE_WORD_LIMIT || seen.len() >= CYCLE_TABLE_LIMIT {
                continue;
            }
            let h = word_hash(&run.cur);
            match seen.insert(h, step) {
                Some(earlier) if step < opts.steps => {
                    let period = step - earlier;
                    if confirm_cycle(stepper, &mut run, opts, step, period)? {
                        let remaining = (opts.steps - step) % period;
                        for k in 1..=remaining {
                            advance(stepper, &mut run, opts, step + k)?;
                        }
                        progress(opts.steps, run.cur.len());
                        break;
                    }
                }
                _ => {}
            }
        }
        Ok((run.cur, run.scratch))
    }

    /// One step of the general matcher: `out` becomes the rewriting of
    /// `cur`, and `notes` hears where each symbol of it came from.
    fn step(
        &self,
        cur: &[SymbolId],
        index: &ContextIndex,
        out: &mut Vec<SymbolId>,
        draws: Draws,
        max: usize,
        notes: &mut impl Notes,
    ) -> Result<(), ()> {
        let mut around = Around::default();
        let mut i = 0;
        while i < cur.len() {
            let mut sym = cur[i];
            if let Some(g) = self.guards[sym.index()] {
                if draws.at(i, 0) >= g.probability {
                    out.push(sym);
                    notes.kept(i);
                    i += 1;
                    continue;
                }
                sym = g.base;
            }
            match self.find(cur, i, sym, index, &mut around) {
                Some(pi) => {
                    let p = &self.sys.productions[pi as usize];
                    let a = if p.alternatives.len() == 1 {
                        0
                    } else {
                        choose(p.alternatives.iter().map(|a| a.weight), draws.at(i, 1))
                    };
                    let alt = &p.alternatives[a];
                    if out.len() + alt.successor.len() > max {
                        return Err(());
                    }
                    out.extend_from_slice(&alt.successor.0);
                    notes.wrote(pi, a, alt.successor.len());
                    i += p.predecessor.len();
                }
                None => {
                    if out.len() >= max {
                        return Err(());
                    }
                    out.push(cur[i]);
                    notes.kept(i);
                    i += 1;
                }
            }
        }
        Ok(())
    }

    /// The first production (file order) that applies at position `i`, where
    /// the symbol is `sym` (the base of a guarded symbol).
    fn find(
        &self,
        w: &[SymbolId],
        i: usize,
        sym: SymbolId,
        index: &ContextIndex,
        around: &mut Around,
    ) -> Option<u32> {
        around.left_ready = false;
        around.right_at = usize::MAX;
        'productions: for &pi in &self.by_first[sym.index()] {
            let p = &self.sys.productions[pi as usize];
            let n = p.predecessor.len();
            if n > 1 && (i + n > w.len() || w[i + 1..i + n] != p.predecessor[1..]) {
                continue;
            }
            if !p.left.is_empty() {
                if !around.left_ready {
                    index.left_of(i, self.max_left, w, &mut around.left);
                    around.left_ready = true;
                }
                // `left` is nearest first; the context is written left to right.
                if around.left.len() < p.left.len()
                    || p.left.iter().rev().zip(&around.left).any(|(a, b)| a != b)
                {
                    continue 'productions;
                }
            }
            if !p.right.is_empty() {
                if around.right_at != i + n {
                    index.right_from(i + n, self.max_right, w, &mut around.right);
                    around.right_at = i + n;
                }
                if around.right.len() < p.right.len()
                    || p.right.iter().zip(&around.right).any(|(a, b)| a != b)
                {
                    continue 'productions;
                }
            }
            return Some(pi);
        }
        None
    }
}

/// A symbol as words hold it while they are rewritten: a [`SymbolId`], or
/// a narrower integer when the alphabet is small (less memory to move).
pub(crate) trait Sym: Copy + Eq + Send + Sync {
    /// How many bits a value holds.
    const BITS: u32;
    fn from_id(s: SymbolId) -> Self;
    fn index(self) -> usize;
    /// The value `i` (which must fit in [`Sym::BITS`]).
    fn from_index(i: usize) -> Self;
    /// `len` zeros. Of integers, in memory asked of the system zeroed, so
    /// that nothing writes it before its users do: threads that each fill
    /// a part of it touch their own pages first, at the same time.
    fn zeroed(len: usize) -> Vec<Self> {
        vec![Self::from_index(0); len]
    }
}

impl Sym for SymbolId {
    const BITS: u32 = 32;
    fn from_index(i: usize) -> Self {
        SymbolId(i as u32)
    }
    fn from_id(s: SymbolId) -> Self {
        s
    }
    fn index(self) -> usize {
        self.0 as usize
    }
}

impl Sym for u8 {
    const BITS: u32 = 8;
    fn zeroed(len: usize) -> Vec<Self> {
        vec![0; len]
    }
    fn from_index(i: usize) -> Self {
        i as u8
    }
    fn from_id(s: SymbolId) -> Self {
        s.0 as u8
    }
    fn index(self) -> usize {
        self as usize
    }
}

impl Sym for u16 {
    const BITS: u32 = 16;
    fn zeroed(len: usize) -> Vec<Self> {
        vec![0; len]
    }
    fn from_index(i: usize) -> Self {
        i as u16
    }
    fn from_id(s: SymbolId) -> Self {
        s.0 as u16
    }
    fn index(self) -> usize {
        self as usize
    }
}

/// A derived word of plain symbols, each held in a byte or two when the
/// alphabet allows (1 or 2 bytes a symbol instead of 4): what a word of
/// tens of millions of symbols costs while it is written or drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum Symbols {
    Bytes(Vec<u8>),
    Shorts(Vec<u16>),
    Wide(Vec<SymbolId>),
}

impl Symbols {
    pub fn len(&self) -> usize {
        match self {
            Symbols::Bytes(w) => w.len(),
            Symbols::Shorts(w) => w.len(),
            Symbols::Wide(w) => w.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The symbols in word order.
    pub fn iter(&self) -> impl Iterator<Item = SymbolId> + '_ {
        let (bytes, shorts, wide): (&[u8], &[u16], &[SymbolId]) = match self {
            Symbols::Bytes(w) => (w, &[], &[]),
            Symbols::Shorts(w) => (&[], w, &[]),
            Symbols::Wide(w) => (&[], &[], w),
        };
        // Two of the three are empty: chaining them costs nothing per symbol
        // but the check of an exhausted iterator.
        bytes
            .iter()
            .map(|&s| SymbolId(u32::from(s)))
            .chain(shorts.iter().map(|&s| SymbolId(u32::from(s))))
            .chain(wide.iter().copied())
    }

    /// The word, a [`SymbolId`] a symbol.
    pub fn into_word(self) -> Word {
        match self {
            Symbols::Wide(w) => Word::from(w),
            narrow => Word::from(narrow.iter().collect::<Vec<_>>()),
        }
    }
}

/// Where a step's random choices come from: each is drawn from the run's
/// seed, the step, and the place in the word of the symbol it is drawn for
/// ([`crate::random::keyed`]), never from a running stream. So a word
/// rewritten in pieces on any number of threads makes the same choices.
#[derive(Clone, Copy, Debug)]
struct Draws {
    seed: u64,
    step: u64,
    /// Where the piece of the word being rewritten starts in it.
    offset: usize,
}

impl Draws {
    fn new(seed: u64, step: u64) -> Self {
        Draws {
            seed,
            step,
            offset: 0,
        }
    }

    /// The draws of the piece of the word from `offset` (its places counted
    /// from there).
    fn from(self, offset: usize) -> Self {
        Draws {
            offset: self.offset + offset,
            ..self
        }
    }

    /// Draw `k` for the symbol at place `i` of the piece: 0 is a guard's,
    /// 1 a choice among a production's alternatives.
    fn at(self, i: usize, k: u64) -> f64 {
        let place = (self.offset + i) as u64;
        crate::random::keyed(self.seed, Stream::Derivation, place, 2 * self.step + k)
    }
}

/// One parallel rewriting step over words of `Sym`.
trait Stepper {
    type Sym: Sym;
    /// What a step keeps from one step to the next.
    type Scratch: Default;
    /// `out` becomes the rewriting of `cur`; `Err(())` when it would grow
    /// past `max` symbols. `cur` is mutable so that a step may keep its
    /// scratch in the word's spare bits; it holds the same word after.
    fn step(
        &self,
        cur: &mut [Self::Sym],
        scratch: &mut Self::Scratch,
        out: &mut Vec<Self::Sym>,
        draws: Draws,
        max: usize,
    ) -> Result<(), ()>;
}

/// The general matcher: any predecessor and context lengths, guards.
struct General<'d, 'a>(&'d Deriver<'a>);

impl Stepper for General<'_, '_> {
    type Sym = SymbolId;
    type Scratch = ContextIndex;

    fn step(
        &self,
        cur: &mut [SymbolId],
        index: &mut ContextIndex,
        out: &mut Vec<SymbolId>,
        draws: Draws,
        max: usize,
    ) -> Result<(), ()> {
        if self.0.contexts {
            index.build(cur, &self.0.ignored);
        }
        self.0.step(cur, index, out, draws, max, &mut ())
    }
}

/// One derivation step: `run.cur` becomes the next word, `run.next` the
/// previous one.
fn advance<S: Stepper>(
    stepper: &S,
    run: &mut Run<S>,
    opts: &DeriveOptions,
    step: u64,
) -> Result<(), Diagnostic> {
    // Every step costs its word plus a constant, so that even steps on an
    // empty or tiny word add up to the work limit.
    run.work += run.cur.len() as u64 + STEP_COST;
    if run.work > opts.max_work {
        return Err(Diagnostic::global(
            codes::TOO_MUCH_WORK,
            format!(
                "the derivation would rewrite more than {} symbols in all",
                opts.max_work
            ),
        )
        .with_note(format!("stopped at step {step} of {}", opts.steps))
        .with_help("derive fewer steps with `-n`, or raise `--max-symbols`"));
    }
    run.next.clear();
    stepper
        .step(
            &mut run.cur,
            &mut run.scratch,
            &mut run.next,
            Draws::new(run.seed, step),
            opts.max_symbols,
        )
        .map_err(|_| too_many(step, opts))?;
    std::mem::swap(&mut run.cur, &mut run.next);
    Ok(())
}

/// Derives `period` steps from a copy of the current word; whether it comes
/// back to the current word.
fn confirm_cycle<S: Stepper>(
    stepper: &S,
    run: &mut Run<S>,
    opts: &DeriveOptions,
    step: u64,
    period: u64,
) -> Result<bool, Diagnostic> {
    let mut probe = Run {
        seed: run.seed,
        cur: run.cur.clone(),
        next: Vec::new(),
        scratch: S::Scratch::default(),
        work: run.work,
    };
    for k in 1..=period {
        advance(stepper, &mut probe, opts, step + k)?;
    }
    run.work = probe.work;
    Ok(probe.cur == run.cur)
}

/// A stochastic production's alternative, given the weights in file
/// order: one draw, scaled to the weights' sum and compared with the
/// cumulative weights (the last one when rounding leaves the draw past them
/// all). Weights are relative (`: 3` and `: 1` is three to one), as the IR
/// says; a sum of exactly 1 leaves the draw untouched.
fn choose(weights: impl ExactSizeIterator<Item = f64> + Clone, u: f64) -> usize {
    let n = weights.len();
    let total: f64 = weights.clone().sum();
    let r = u * total;
    let mut acc = 0.0;
    for (i, w) in weights.enumerate() {
        acc += w;
        if r < acc {
            return i;
        }
    }
    n - 1
}

fn too_many(step: u64, opts: &DeriveOptions) -> Diagnostic {
    Diagnostic::global(
        codes::TOO_MANY_SYMBOLS,
        format!("the derived word would exceed {} symbols", opts.max_symbols),
    )
    .with_note(format!(
        "step {step} of {} outgrew the limit (`--max-symbols {}`)",
        opts.steps, opts.max_symbols
    ))
    .with_help("derive fewer steps with `-n`, or raise the limit with `--max-symbols`")
}

/// [`codes::TOO_MANY_SYMBOLS`] before deriving, when even the shortest
/// choices at every step make a word longer than the limit ([`bound`]).
pub(crate) fn refuse_early(sys: &System, opts: &DeriveOptions) -> Result<(), Diagnostic> {
    match bound::first_step_over(sys, opts.steps, opts.max_symbols) {
        Some(step) => Err(too_many(step, opts).with_note(
            "known before deriving: whatever the contexts, conditions and random choices, \
             every production that can apply makes the word at least this long",
        )),
        None => Ok(()),
    }
}

/// Per-step cost added to the word's length in the work count: a step
/// costs at least this much whatever the word, so that a derivation of a
/// word that does not grow (with a block run every step, or random
/// choices that rule out skipping a cycle) ends at the work limit after
/// max_work / STEP_COST steps: 3.9 million at the default limit, about a
/// second of tiny steps.
pub(crate) const STEP_COST: u64 = 1024;
/// Cycle detection looks at words up to this length…
const CYCLE_WORD_LIMIT: usize = 1 << 16;
/// …and remembers at most this many of them.
const CYCLE_TABLE_LIMIT: usize = 1 << 16;

/// The state of a derivation in progress.
struct Run<S: Stepper> {
    /// The run's seed, from which each step's [`Draws`] come.
    seed: u64,
    cur: Vec<S::Sym>,
    next: Vec<S::Sym>,
    scratch: S::Scratch,
    work: u64,
}

/// FNV-1a over the symbol ids: a fast hash to spot a word seen before.
fn word_hash<T: Sym>(w: &[T]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for s in w {
        h ^= s.index() as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h ^ w.len() as u64
}

const NONE: u32 = u32::MAX;

/// For context matching in one word, built in linear time per step:
/// `prev[i]` is the position of the nearest *visible* symbol left of `i` (the
/// listing's `lcondiff` walk: ignored symbols and `[` are skipped, so the
/// parent branch is the left context of a child, and a whole branch `[...]`
/// met from its right is skipped); `next[i]` is the nearest visible symbol
/// at or after `i` (`rcondiff`: ignored symbols and whole branches are
/// skipped, and a `]` ends the search). Following these links, a context of
/// length k is matched in k steps however many symbols are skipped.
#[derive(Default)]
struct ContextIndex {
    prev: Vec<u32>,
    next: Vec<u32>,
    open: Vec<u32>,
}

impl ContextIndex {
    fn build(&mut self, w: &[SymbolId], ignored: &[bool]) {
        let n = w.len();
        // Matching brackets: partner[i] for brackets, NONE if unmatched.
        let mut partner = std::mem::take(&mut self.open);
        partner.clear();
        partner.resize(n, NONE);
        let mut stack: Vec<u32> = Vec::new();
        for (i, &s) in w.iter().enumerate() {
            if s == SymbolId::OPEN {
                stack.push(i as u32);
            } else if s == SymbolId::CLOSE {
                if let Some(o) = stack.pop() {
                    partner[o as usize] = i as u32;
                    partner[i] = o;
                }
            }
        }
        let visible =
            |s: SymbolId| s != SymbolId::OPEN && s != SymbolId::CLOSE && !ignored[s.index()];
        self.prev.clear();
        self.prev.resize(n + 1, NONE);
        for i in 1..=n {
            let s = w[i - 1];
            self.prev[i] = if visible(s) {
                (i - 1) as u32
            } else if s == SymbolId::CLOSE {
                match partner[i - 1] {
                    NONE => NONE,
                    o => self.prev[o as usize],
                }
            } else {
                self.prev[i - 1]
            };
        }
        self.next.clear();
        self.next.resize(n + 1, NONE);
        for i in (0..n).rev() {
            let s = w[i];
            self.next[i] = if visible(s) {
                i as u32
            } else if s == SymbolId::OPEN {
                match partner[i] {
                    NONE => NONE,
                    c => self.next[c as usize + 1],
                }
            } else if s == SymbolId::CLOSE {
                NONE
            } else {
                self.next[i + 1]
            };
        }
        self.open = partner;
    }

    /// Up to `k` visible symbols left of `i`, nearest first.
    fn left_of(&self, i: usize, k: usize, w: &[SymbolId], out: &mut Vec<SymbolId>) {
        out.clear();
        let mut j = self.prev[i];
        while out.len() < k && j != NONE {
            out.push(w[j as usize]);
            j = self.prev[j as usize];
        }
    }

    /// Up to `k` visible symbols from `i` on.
    fn right_from(&self, i: usize, k: usize, w: &[SymbolId], out: &mut Vec<SymbolId>) {
        out.clear();
        let mut j = self.next[i];
        while out.len() < k && j != NONE {
            out.push(w[j as usize]);
            j = self.next[j as usize + 1];
        }
    }
}

/// Derives `opts.steps` steps of `sys` by the method [`plan`] chooses.
/// (Query modules, `?P` and the like, are answered by the turtle: the
/// driver derives systems that have them.)
pub fn derive(sys: &System, opts: &DeriveOptions) -> Result<Word, Diagnostic> {
    // As `plan` decides, without building the Deriver twice.
    if sys.rewrites_modules() {
        return parametric::derive(sys, opts, |_, _| {}, &mut |_, _, _| {}).map(|(w, _)| w);
    }
    Deriver::new(sys).derive(opts, |_, _| {})
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::pfg::read_ok as sys;

    /// `w` with the `]`s that close nothing dropped and what stays open
    /// closed (pfg wants balanced successors).
    pub(super) fn balanced(w: &str) -> String {
        let mut depth = 0usize;
        let mut out = String::new();
        for c in w.chars() {
            match c {
                '[' => depth += 1,
                ']' if depth == 0 => continue,
                ']' => depth -= 1,
                _ => {}
            }
            out.push(c);
        }
        out + &"]".repeat(depth)
    }

    fn run(src: &str, n: u64) -> String {
        let s = sys(src);
        derive(&s, &DeriveOptions::new(n))
            .unwrap()
            .display(&s.symbols)
    }

    #[test]
    fn context_free_and_identity() {
        assert_eq!(run("axiom: b\na --> ab\nb --> a\n", 5), "abaababa");
        assert_eq!(run("axiom: XY\nX --> XX\n", 2), "XXXXY");
    }

    #[test]
    fn left_context_skips_branches_and_enters_parents() {
        // ABOP p.32 / the book §3.4: D is the left context of G, N its right.
        let src = "axiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nD < G --> x\n";
        assert_eq!(run(src, 1), "ABCD[EF][x[HI[JKL]M]NOPQ]");
        let src = "axiom: ABCD[EF][G[HI[JKL]M]NOPQ]\nG > N --> x\n";
        assert_eq!(run(src, 1), "ABCD[EF][x[HI[JKL]M]NOPQ]");
        // A right context stops at the end of a branch.
        assert_eq!(run("axiom: A[B]C\nB > C --> x\n", 1), "A[B]C");
    }

    #[test]
    fn multi_symbol_predecessors_consume_their_symbols() {
        assert_eq!(run("axiom: XABCDY\nAB < CD > Y --> z\n", 1), "XABzY");
        assert_eq!(run("axiom: FlFl\nFl --> Fl+rF+\n", 1), "Fl+rF+Fl+rF+");
    }

    #[test]
    fn limit_is_an_error_not_a_crash() {
        let s = sys("axiom: F\nF --> FF\n");
        let err = derive(&s, &DeriveOptions::new(40).max_symbols(1000)).unwrap_err();
        assert_eq!(err.code, codes::TOO_MANY_SYMBOLS);
        let ok = derive(&s, &DeriveOptions::new(9).max_symbols(512)).unwrap();
        assert_eq!(ok.len(), 512);
    }

    #[test]
    fn cycles_are_skipped_exactly() {
        // Period 3: the word at step n is the word at step n mod 3.
        let s = sys("axiom: a\na --> b\nb --> c\nc --> a\n");
        for (n, want) in [
            (0, "a"),
            (1, "b"),
            (2, "c"),
            (3, "a"),
            (10, "b"),
            (1_000_000_000_001, "c"),
        ] {
            let w = derive(&s, &DeriveOptions::new(n)).unwrap();
            assert_eq!(w.display(&s.symbols), want, "n = {n}");
        }
        // A cycle that starts late (after a transient) and involves context:
        // the signal runs down a filament and wraps around in two phases.
        let src =
            "axiom: xbaaa\nb < a --> b\nb > a --> a\nx < b --> c\nc --> x\nx > c --> y\ny --> x\n";
        let s = sys(src);
        let brute = |n: u64| {
            let mut w = derive(&s, &DeriveOptions::new(0)).unwrap();
            for _ in 0..n {
                let one = System {
                    axiom: w.clone(),
                    ..s.clone()
                };
                w = derive(&one, &DeriveOptions::new(1)).unwrap();
            }
            w
        };
        for n in [5u64, 17, 40, 41, 42, 97] {
            assert_eq!(
                derive(&s, &DeriveOptions::new(n)).unwrap(),
                brute(n),
                "n = {n}"
            );
        }
        let huge = derive(&s, &DeriveOptions::new(10u64.pow(15))).unwrap();
        assert_eq!(huge.len(), 5);
    }

    #[test]
    fn empty_words_and_tiny_stochastic_loops_end() {
        let s = sys("axiom: F\nF --> * : 1\nF --> * : 1\n");
        let w = derive(&s, &DeriveOptions::new(99_999_999_999)).unwrap();
        assert!(w.is_empty());
        // A stochastic word that never grows: bounded by the work limit.
        let s = sys("axiom: F\nF --> G : 1\nF --> F : 1\nG --> F\n");
        let err = derive(&s, &DeriveOptions::new(u64::MAX).max_symbols(1000)).unwrap_err();
        assert_eq!(err.code, codes::TOO_MUCH_WORK);
    }

    #[test]
    fn context_matching_is_linear_in_skipped_symbols() {
        // 2^14 ignored G's; every one checks a left context that walks over
        // all the others in a naive matcher.
        let src = "axiom: a\nignore: GH\na --> bb\nb --> cc\nc --> dd\nd --> ee\ne --> ff\nf --> gg\ng --> hh\nh --> ii\ni --> jj\nj --> kk\nk --> ll\nl --> mm\nm --> nn\nn --> GG\nA < G --> X\nG --> H\nA < H --> X\nH --> G\n";
        let s = sys(src);
        let t = std::time::Instant::now();
        let w = derive(&s, &DeriveOptions::new(200).max_symbols(20_000)).unwrap();
        assert_eq!(w.len(), 1 << 14);
        assert!(t.elapsed().as_secs_f64() < 1.0, "{:?}", t.elapsed());
    }

    #[test]
    fn endless_steps_are_bounded() {
        // A stochastic cycle cannot be skipped: the work limit ends it.
        let s = sys("axiom: a\na --> b : 1\na --> b : 1\nb --> a\n");
        let err = derive(&s, &DeriveOptions::new(u64::MAX).max_symbols(1000)).unwrap_err();
        assert_eq!(err.code, codes::TOO_MUCH_WORK);
        // A fixpoint ends early with the right word.
        let s = sys("axiom: a\na --> b\n");
        let w = derive(&s, &DeriveOptions::new(u64::MAX)).unwrap();
        assert_eq!(w.display(&s.symbols), "b");
    }

    /// Derives with the general matcher only (no table, no tree).
    fn general(s: &System, opts: &DeriveOptions) -> Result<Word, Diagnostic> {
        let d = Deriver {
            table: None,
            ..Deriver::new(s)
        };
        d.derive_stepwise(opts, |_, _| {})
    }

    #[test]
    fn table_rewriting_matches_the_general_matcher_on_the_stdlib() {
        let mut tabled = 0;
        for e in crate::stdlib::ENTRIES
            .iter()
            .filter(|e| e.file.ends_with(".l"))
        {
            let s = sys(e.text);
            if Deriver::new(&s).table.is_none() {
                continue;
            }
            tabled += 1;
            for seed in [0, 1] {
                let opts = DeriveOptions::new(s.settings.steps.unwrap_or(4).min(40))
                    .seed(seed)
                    .max_symbols(400_000);
                let fast = Deriver::new(&s).derive_stepwise(&opts, |_, _| {});
                assert_eq!(fast.ok(), general(&s, &opts).ok(), "{}", e.name);
            }
        }
        assert!(tabled >= 30, "{tabled} stdlib systems use the table");
    }

    #[test]
    fn table_rewriting_of_big_words_is_exact() {
        // Fig. 3.11a at 50 steps: many output chunks per step.
        let s = sys(crate::stdlib::get("hogeweg-hesper-a").unwrap().text);
        let opts = DeriveOptions::new(50);
        let fast = Deriver::new(&s).derive_stepwise(&opts, |_, _| {}).unwrap();
        assert!(fast.len() > 1 << 19, "{}", fast.len());
        assert_eq!(fast, general(&s, &opts).unwrap());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
        /// Random bracketed systems with one-symbol contexts and an ignore
        /// set: the table gives the general matcher's words.
        #[test]
        fn table_rewriting_matches_the_general_matcher(
            axiom in "[ab+\\[\\]]{1,12}",
            rules in proptest::collection::vec(
                ("[ab+*]", "[ab+]", "[ab+*]", "[ab+\\[\\]]{0,5}"), 1..6),
            ignore_plus in proptest::bool::ANY,
            seed in 0u64..4,
            threads in 1usize..8,
        ) {
            let axiom = balanced(&axiom);
            let rules: Vec<_> = rules.iter().map(|(l, p, r, w)| (l, p, r, balanced(w))).collect();
            let mut src = format!("axiom: {axiom}\n");
            if ignore_plus {
                src.push_str("ignore: +\n");
            }
            for (l, p, r, succ) in &rules {
                let succ = if succ.is_empty() { "*" } else { succ.as_str() };
                src.push_str(&format!("{l} < {p} > {r} --> {succ}\n"));
            }
            let mut d = crate::diagnostics::Diagnostics::default();
            let s = crate::front::pfg::read(&src, &mut d).system;
            proptest::prop_assume!(!d.has_errors());
            proptest::prop_assert!(Deriver::new(&s).table.is_some());
            let opts = DeriveOptions::new(6).seed(seed).max_symbols(100_000);
            let fast = Deriver::new(&s).derive_stepwise(&opts, |_, _| {});
            // Every step cut into pieces of one symbol and more, one a
            // thread.
            let d = Deriver::new(&s);
            let split = table::Split { from: 1, piece: 1 + seed as usize, place: None };
            let stepper = d.table.as_ref().unwrap().stepper::<u8>().on(threads).split(split);
            let pieces = d.steps(&stepper, &opts, |_, _| {}).map(|(w, _)| w);
            let bytes = fast.as_ref().map(|w| w.0.iter().map(|s| s.0 as u8).collect::<Vec<_>>());
            proptest::prop_assert_eq!(pieces.ok(), bytes.ok(), "{} on {} threads", src, threads);
            proptest::prop_assert_eq!(fast.ok(), general(&s, &opts).ok(), "{}", src);
        }
    }

    #[test]
    fn stochastic_choice_is_seeded_and_follows_weights() {
        let s = sys("axiom: AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA\nA --> x : 1\nA --> y : 3\n");
        let a = derive(&s, &DeriveOptions::new(1).seed(7)).unwrap();
        let b = derive(&s, &DeriveOptions::new(1).seed(7)).unwrap();
        let c = derive(&s, &DeriveOptions::new(1).seed(8)).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
        let ys = a.display(&s.symbols).matches('y').count();
        assert!((60..=90).contains(&ys), "{ys} of 100 should be near 75");
    }

    #[test]
    fn weights_are_relative_whatever_their_sum() {
        let mut s = sys("axiom: AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA\nA --> x : 0.5\nA --> y : 0.5\n");
        // As a reader that keeps weights as written would give them.
        for (alt, w) in s.productions[0].alternatives.iter_mut().zip([1.0, 3.0]) {
            alt.weight = w;
        }
        let a = derive(&s, &DeriveOptions::new(1).seed(7)).unwrap();
        let ys = a.display(&s.symbols).matches('y').count();
        assert!((60..=90).contains(&ys), "{ys} of 100 should be near 75");
    }
}
