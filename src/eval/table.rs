//! One rewriting step by table look-up, for the common shape of pfg and
//! Fractint systems: one-symbol predecessors, left and right contexts of at
//! most one symbol, no guarded symbols.
//!
//! The production that applies at a position depends only on its symbol
//! `s`, the nearest visible symbol on its left `l` and the nearest visible
//! symbol on its right `r` (each possibly "none"), as the IR defines
//! visibility (the listing's `lcondiff`/`rcondiff`: ignored symbols and
//! brackets skipped, whole branches skipped, a branch's left context in its
//! parent, a right context ending with its branch). So the first matching
//! production in file order is worked out once per `(s, l, r)` when the
//! table is built, and a step is two linear passes that find `l` and `r`
//! for every position, then one pass that looks the production up and
//! copies its successor.
//!
//! One thread: splitting a step into halves for two threads was measured
//! slower on the 2-core machines graftal is tested on (the second half
//! must first scan the first for its left-context state, and two threads
//! there run at about 1.3 times one thread's throughput).
//!
//! Words are exactly those of the general matcher ([`super::Deriver`]); the
//! tests compare them.

use super::{Rng, Stepper, Sym};
use crate::ir::{SymbolId, System};

/// The most table cells built (4 bytes each).
const MAX_CELLS: usize = 1 << 22;

/// Symbols rewritten between checks of the output's room and length.
const CHUNK: usize = 4096;
/// The most one chunk of [`TableStepper::rewrite`] reserves ahead of the
/// `max` check: 1 Mi symbols.
const RESERVE: usize = 1 << 20;

/// A system's productions as a look-up table. Rules are the productions,
/// then one identity rule per symbol (`s` stays `s`) for symbols nothing
/// rewrites, so every position looks up exactly one rule.
pub(super) struct Table<'a> {
    sys: &'a System,
    /// Per symbol: where its cells start, and a mask saying whether context
    /// decides (all ones: a block of `(n + 1)²` cells indexed by
    /// `l · (n + 1) + r`, `n` meaning "no visible symbol") or not (zero: one
    /// cell).
    entry: Vec<(u32, usize)>,
    /// The rule for each cell.
    cells: Vec<u32>,
    /// `n + 1`: the stride of `l` in a block.
    side: usize,
    class: Vec<u8>,
}

/// Scratch space kept from step to step: the nearest visible symbol right
/// of every position (a symbol index, `n` for none).
pub(super) struct Neighbours<T> {
    right: Vec<T>,
}

impl<T> Default for Neighbours<T> {
    fn default() -> Self {
        Neighbours { right: Vec::new() }
    }
}

/// How a symbol takes part in context: seen, skipped, or a bracket.
const SKIPPED: u8 = 0;
const VISIBLE: u8 = 1;
const OPEN: u8 = 2;
const CLOSE: u8 = 3;

/// The left-context state at a position: the nearest visible symbol so far
/// and, for each enclosing open branch, the nearest visible symbol before
/// it (a branch's left context is in its parent; a closed branch is
/// skipped).
struct Left<T> {
    last: T,
    stack: Vec<T>,
}

impl<T: Sym> Left<T> {
    fn new(none: T) -> Self {
        Left {
            last: none,
            stack: Vec::new(),
        }
    }

    /// Moves past symbol `s` of class `class`.
    #[inline]
    fn pass(&mut self, s: T, class: u8, none: T) {
        // A select, not a branch, for the common classes: which of them
        // comes next is unpredictable.
        self.last = if class == VISIBLE { s } else { self.last };
        if class >= OPEN {
            if class == OPEN {
                self.stack.push(self.last);
            } else {
                self.last = self.stack.pop().unwrap_or(none);
            }
        }
    }
}

impl<'a> Table<'a> {
    /// The table of `sys`, or `None` when it does not have the shape this
    /// module handles or the table would be too big.
    pub(super) fn new(sys: &'a System, ignored: &[bool]) -> Option<Self> {
        let n = sys.symbols.len();
        if sys.rewrites_modules() || sys.symbols.iter().any(|(_, i)| i.guard.is_some()) {
            return None;
        }
        if sys
            .productions
            .iter()
            .any(|p| p.predecessor.len() != 1 || p.left.len() > 1 || p.right.len() > 1)
        {
            return None;
        }
        let side = n + 1;
        let rules = sys.productions.len();
        let mut entry = Vec::with_capacity(n);
        let mut cells: Vec<u32> = Vec::new();
        for s in 0..n {
            let identity = (rules + s) as u32;
            let mine = || {
                sys.productions
                    .iter()
                    .enumerate()
                    .filter(move |(_, p)| p.predecessor[0].index() == s)
            };
            let contextual = mine().next().is_some_and(|(_, p)| p.is_context_sensitive());
            entry.push((cells.len() as u32, if contextual { usize::MAX } else { 0 }));
            if !contextual {
                cells.push(mine().next().map_or(identity, |(pi, _)| pi as u32));
                continue;
            }
            if cells.len() + side * side > MAX_CELLS {
                return None;
            }
            let at = cells.len();
            cells.resize(at + side * side, identity);
            let block = &mut cells[at..];
            // Later productions first, so the first in file order wins.
            let mut list: Vec<_> = mine().collect();
            list.reverse();
            for (pi, p) in list {
                let ls: Vec<usize> = match p.left.first() {
                    Some(c) => vec![c.index()],
                    None => (0..side).collect(),
                };
                let rs: Vec<usize> = match p.right.first() {
                    Some(c) => vec![c.index()],
                    None => (0..side).collect(),
                };
                for &l in &ls {
                    for &r in &rs {
                        block[l * side + r] = pi as u32;
                    }
                }
            }
        }
        let class = (0..n)
            .map(|i| match SymbolId(i as u32) {
                SymbolId::OPEN => OPEN,
                SymbolId::CLOSE => CLOSE,
                _ if ignored[i] => SKIPPED,
                _ => VISIBLE,
            })
            .collect();
        Some(Table {
            sys,
            entry,
            cells,
            side,
            class,
        })
    }

    /// The table's rewriting step over words of `T` (whose values must
    /// hold every symbol index and one more, for "none").
    pub(super) fn stepper<T: Sym>(&self) -> TableStepper<'_, 'a, T> {
        let conv = |w: &[SymbolId]| -> Vec<T> { w.iter().map(|&s| T::from_id(s)).collect() };
        let mut arena = Vec::new();
        let mut spans = Vec::new();
        for p in &self.sys.productions {
            match p.alternatives.as_slice() {
                [one] => {
                    spans.push((arena.len() as u32, one.successor.len() as u32));
                    arena.extend(conv(&one.successor.0));
                }
                _ => spans.push((0, STOCHASTIC)),
            }
        }
        for s in 0..self.entry.len() {
            spans.push((arena.len() as u32, 1));
            arena.push(T::from_id(SymbolId(s as u32)));
        }
        // Every successor is copied as [`COPY`] symbols (the rest is
        // overwritten or cut off), so the arena has that many more.
        arena.resize(arena.len() + COPY, T::from_id(SymbolId(0)));
        TableStepper {
            table: self,
            arena,
            spans,
            alternatives: self
                .sys
                .productions
                .iter()
                .map(|p| {
                    p.alternatives
                        .iter()
                        .map(|a| (a.weight, conv(&a.successor.0)))
                        .collect()
                })
                .collect(),
            longest: self
                .sys
                .productions
                .iter()
                .flat_map(|p| &p.alternatives)
                .map(|a| a.successor.len())
                .max()
                .unwrap_or(0),
            none: T::from_id(SymbolId((self.side - 1) as u32)),
        }
    }
}

/// Successors up to this long are copied as a block of this many symbols,
/// a fixed-size copy the compiler turns into a few vector moves.
const COPY: usize = 16;

/// A span length marking a stochastic production.
const STOCHASTIC: u32 = u32::MAX;

/// [`Table`] applied to words of `T`.
pub(super) struct TableStepper<'t, 'a, T> {
    table: &'t Table<'a>,
    /// The successors of deterministic productions, one after another…
    arena: Vec<T>,
    /// …and each production's `(start, length)` in it ([`STOCHASTIC`] as
    /// the length of a stochastic production).
    spans: Vec<(u32, u32)>,
    /// Per production, its alternatives: weight and successor.
    alternatives: Vec<Vec<(f64, Vec<T>)>>,
    /// The longest successor.
    longest: usize,
    none: T,
}

impl<T: Sym> Stepper for TableStepper<'_, '_, T> {
    type Sym = T;
    type Scratch = Neighbours<T>;

    fn step(
        &self,
        cur: &[T],
        nb: &mut Neighbours<T>,
        out: &mut Vec<T>,
        rng: &mut Rng,
        max: usize,
    ) -> Result<(), ()> {
        out.clear();
        self.right_neighbours(cur, &mut nb.right);
        self.rewrite(cur, Left::new(self.none), &nb.right, out, rng, max)
    }
}

impl<T: Sym> TableStepper<'_, '_, T> {
    /// `right[i]`: the nearest visible symbol at or after `i`, a whole
    /// branch skipped, `]` ending the search (the listing's `rcondiff`).
    fn right_neighbours(&self, w: &[T], right: &mut Vec<T>) {
        let none = self.none;
        right.clear();
        right.resize(w.len() + 1, none);
        let mut next = none;
        let mut stack: Vec<T> = Vec::new();
        for (r, &s) in right.iter_mut().zip(w).rev() {
            let class = self.table.class[s.index()];
            next = if class == VISIBLE { s } else { next };
            if class >= OPEN {
                if class == CLOSE {
                    stack.push(next);
                    next = none;
                } else {
                    next = stack.pop().unwrap_or(none);
                }
            }
            *r = next;
        }
    }

    /// Rewrites `cur` onto the end of `out`; `left` is the left-context
    /// state at its start.
    fn rewrite(
        &self,
        cur: &[T],
        mut left: Left<T>,
        right: &[T],
        out: &mut Vec<T>,
        rng: &mut Rng,
        max: usize,
    ) -> Result<(), ()> {
        let t = self.table;
        let none = self.none;
        let longest = self.longest.max(COPY);
        // Everything the loop reads, as local slices: the output's writes
        // could otherwise alias their lengths and force reloads.
        let (entry, class, cells, side) = (&t.entry[..], &t.class[..], &t.cells[..], t.side);
        let (arena, spans) = (&self.arena[..], &self.spans[..]);
        // Written by index into `out` grown ahead a chunk at a time, so the
        // length stays in a register (pushing reloads it every symbol).
        let mut w = out.len();
        let mut at = 0;
        // A chunk may grow the output by at most `RESERVE` symbols before the
        // limit is checked, so a very long successor shortens the chunk
        // instead of sizing one allocation from the input.
        let chunk_len = (RESERVE / longest).clamp(1, CHUNK);
        for chunk in cur.chunks(chunk_len) {
            let need = w + chunk.len() * longest + COPY;
            if out.len() < need {
                out.resize(need, none);
            }
            let dst = &mut out[..];
            for &s in chunk {
                let si = s.index();
                // Context-free symbols have one cell: the mask is zero.
                let (base, mask) = entry[si];
                let cell = (left.last.index() * side + right[at + 1].index()) & mask;
                let rule = cells[base as usize + cell] as usize;
                at += 1;
                left.pass(s, class[si], none);
                let (start, len) = spans[rule];
                let (start, len) = (start as usize, len as usize);
                if len <= COPY {
                    dst[w..w + COPY].copy_from_slice(&arena[start..start + COPY]);
                    w += len;
                } else {
                    let succ = if len as u32 != STOCHASTIC {
                        &arena[start..start + len]
                    } else {
                        let alts = &self.alternatives[rule];
                        &alts[super::choose(alts.iter().map(|a| a.0), rng)].1
                    };
                    dst[w..w + succ.len()].copy_from_slice(succ);
                    w += succ.len();
                }
            }
            if w > max {
                out.truncate(w);
                return Err(());
            }
        }
        out.truncate(w);
        Ok(())
    }
}
