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
//! A step of a big word (from 64 Ki symbols) is shared among the threads
//! asked for, one piece of the word a thread ([`parallel`]): each piece's
//! context at its borders is found from short summaries of the others, so
//! the word is the one-thread word for any number of threads. Measured on
//! the 2-core test machine (best and median of interleaved runs while
//! nothing else ran): `graftal derive std:hogeweg-hesper-a -n 60` (9.2
//! million symbols) took 226 ms (median 228) on one thread and 130 ms
//! (134) on two, 1.7 times faster; what stays on one thread whatever the
//! count (writing the word out, about 15 ms, starting up and the steps
//! below the threshold, about 8) keeps it from 2. Shorter words and one
//! thread take the one-thread path. Stochastic productions are cut too:
//! their choices are keyed by place in the word ([`super::Draws`]).
//!
//! Words are exactly those of the general matcher ([`super::Deriver`]); the
//! tests compare them.

use super::{Draws, Stepper, Sym};
use crate::ir::{SymbolId, System};
use std::sync::atomic::{AtomicUsize, Ordering};

mod parallel;

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
    /// decides (all ones: a block of `(n + 1) · k` cells indexed by
    /// `l · k + right[r]`, `n` meaning "no visible symbol") or not (zero:
    /// one cell).
    entry: Vec<(u32, usize)>,
    /// The rule for each cell.
    cells: Vec<u32>,
    /// `n + 1`: the symbols and "none".
    side: usize,
    class: Vec<u8>,
    /// Per symbol and "none", its class as a right context: 1.. for each
    /// symbol some production names as its right context, 0 for all the
    /// others (no production tells them apart). Few classes, so that a
    /// right neighbour fits in a symbol's spare bits.
    right: Vec<u8>,
    /// `k`: how many right-context classes, the stride of `l` in a block.
    rights: usize,
}

/// Scratch space kept from step to step: the right-context class of the
/// nearest visible symbol right of every position when the word's
/// symbols have no spare bits to hold it, and how much the last step grew
/// the word (to size the next output in one allocation).
pub(super) struct Neighbours<T> {
    right: Vec<T>,
    growth: f64,
}

impl<T> Default for Neighbours<T> {
    fn default() -> Self {
        Neighbours {
            right: Vec::new(),
            growth: 1.0,
        }
    }
}

/// When a step is cut into pieces for several threads: from a word of
/// `from` symbols, into pieces of at least `piece` symbols (fewer pieces
/// than threads when the word is short). The tests lower both to cut small
/// words into many pieces, and set `place` to give every piece that many
/// symbols of the new word to be rewritten into (instead of the room the
/// last step's growth says it needs), so that pieces outgrow their places.
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    pub(super) from: usize,
    pub(super) piece: usize,
    pub(super) place: Option<usize>,
}

impl Default for Split {
    /// Measured on two cores (Fig. 3.11a's steps, medians of 6 runs): a
    /// word of 76 K symbols took 0.42 ms on one thread and 0.61 ms in two
    /// pieces (starting the second thread is most of a step that short),
    /// 96 K 0.56 and 0.51 ms, 122 K 0.73 and 0.53 ms.
    fn default() -> Self {
        Split {
            from: 1 << 17,
            piece: 1 << 15,
            place: None,
        }
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
        let mut right = vec![0u8; side];
        let mut rights = 1;
        for p in &sys.productions {
            if let Some(c) = p.right.first() {
                if right[c.index()] == 0 {
                    if rights > u8::MAX as usize {
                        return None;
                    }
                    right[c.index()] = rights as u8;
                    rights += 1;
                }
            }
        }
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
            if cells.len() + side * rights > MAX_CELLS {
                return None;
            }
            let at = cells.len();
            cells.resize(at + side * rights, identity);
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
                    Some(c) => vec![right[c.index()] as usize],
                    None => (0..rights).collect(),
                };
                for &l in &ls {
                    for &r in &rs {
                        block[l * rights + r] = pi as u32;
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
            right,
            rights,
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
            packed_shift: {
                let bits = |max: usize| usize::BITS - max.leading_zeros();
                let (symbol, class) = (bits(self.side - 2), bits(self.rights - 1));
                (symbol + class <= T::BITS).then_some(symbol)
            },
            threads: 1,
            split: Split::default(),
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
    /// When a symbol index and a right-context class fit in a `T` together
    /// (in bytes: 32 symbols and 3 classes, 64 and 1, 16 and 7…), each
    /// position's right neighbour's class is kept in the high bits of the
    /// word's own symbols, shifted by this, instead of in an array as long
    /// as the word: a step then holds just the word and its rewriting.
    packed_shift: Option<u32>,
    /// Threads a step of a big word is shared among ([`parallel`]).
    threads: usize,
    split: Split,
}

impl<T: Sym> Stepper for TableStepper<'_, '_, T> {
    type Sym = T;
    type Scratch = Neighbours<T>;

    fn step(
        &self,
        cur: &mut [T],
        nb: &mut Neighbours<T>,
        out: &mut Vec<T>,
        draws: Draws,
        max: usize,
    ) -> Result<(), ()> {
        out.clear();
        let pieces = self.pieces(cur.len());
        if pieces > 1 {
            return self.step_in_pieces(cur, nb, out, (draws, max), pieces);
        }
        // One allocation of about the output's size (growing by a sixteenth
        // when the guess falls short), not a doubling Vec: the output is
        // most of what a step holds.
        out.reserve_exact(self.room(cur.len(), nb.growth, max));
        let done = match self.packed_shift {
            Some(shift) => {
                self.pack_right_neighbours(cur, shift);
                let dst = (&mut [][..], &mut *out);
                let done = self.rewrite::<true>(cur, &[], dst, draws, max, &mut self.left(), None);
                let low = (1 << shift) - 1;
                for s in cur.iter_mut() {
                    *s = T::from_index(s.index() & low);
                }
                done
            }
            None => {
                self.right_neighbours(cur, &mut nb.right);
                let (left, right) = (&mut self.left(), &nb.right[1..]);
                let dst = (&mut [][..], &mut *out);
                self.rewrite::<false>(cur, right, dst, draws, max, left, None)
            }
        };
        if !cur.is_empty() {
            nb.growth = out.len() as f64 / cur.len() as f64;
        }
        out.shrink_to_fit();
        done.map(|_| ())
    }
}

impl<T: Sym> TableStepper<'_, '_, T> {
    /// The stepper sharing a step of a big word among `threads` threads.
    pub(super) fn on(self, threads: usize) -> Self {
        TableStepper { threads, ..self }
    }

    /// The stepper cutting steps as `split` says (the tests cut small
    /// words into many pieces).
    #[cfg(test)]
    pub(super) fn split(self, split: Split) -> Self {
        TableStepper { split, ..self }
    }

    /// How many pieces a step of a word of `len` symbols is cut into: 1
    /// (the one-thread path) for one thread or a short word.
    fn pieces(&self, len: usize) -> usize {
        if self.threads <= 1 || len < self.split.from {
            return 1;
        }
        self.threads.min(len / self.split.piece.max(1)).max(1)
    }

    /// Room for the rewriting of `len` symbols when the last step grew the
    /// word by `growth`: that growth and a little more (up to `max`), and
    /// what one chunk of [`Self::rewrite`] may write past it.
    fn room(&self, len: usize, growth: f64, max: usize) -> usize {
        let slack = self.chunk_len() * self.longest.max(COPY) + COPY;
        let guess = (len as f64 * growth * 1.02) as usize;
        guess.min(max).saturating_add(slack)
    }

    /// The left-context state at the start of the word.
    fn left(&self) -> Left<T> {
        Left::new(self.none)
    }

    /// Moves the right-context state (`next`: the nearest visible symbol
    /// so far, `stack`: its value outside each branch entered) leftwards
    /// past symbol `s`, of class `class[s]`. The table's slices are passed
    /// in so that a loop can hold them as locals: writes into a word could
    /// otherwise alias their lengths and force a reload every symbol.
    #[inline]
    fn pass_leftwards(class: &[u8], none: T, s: T, next: &mut T, stack: &mut Vec<T>) {
        let class = class[s.index()];
        *next = if class == VISIBLE { s } else { *next };
        if class >= OPEN {
            if class == CLOSE {
                stack.push(*next);
                *next = none;
            } else {
                *next = stack.pop().unwrap_or(none);
            }
        }
    }

    /// `right[i]`: the right-context class of the nearest visible symbol
    /// at or after `i`, a whole branch skipped, `]` ending the search (the
    /// listing's `rcondiff`).
    fn right_neighbours(&self, w: &[T], right: &mut Vec<T>) {
        let (class, rclass, none) = (&self.table.class[..], &self.table.right[..], self.none);
        right.clear();
        right.resize(w.len() + 1, T::from_index(rclass[none.index()] as usize));
        let mut next = none;
        let mut stack: Vec<T> = Vec::new();
        for (r, &s) in right.iter_mut().zip(w).rev() {
            Self::pass_leftwards(class, none, s, &mut next, &mut stack);
            *r = T::from_index(rclass[next.index()] as usize);
        }
    }

    /// [`Self::right_neighbours`] of `i + 1` put in the high bits of
    /// `w[i]`, shifted by `shift`.
    fn pack_right_neighbours(&self, w: &mut [T], shift: u32) {
        let (class, rclass, none) = (&self.table.class[..], &self.table.right[..], self.none);
        let mut next = none;
        let mut stack: Vec<T> = Vec::new();
        for x in w.iter_mut().rev() {
            let s = *x;
            let after = rclass[next.index()] as usize;
            Self::pass_leftwards(class, none, s, &mut next, &mut stack);
            *x = T::from_index(s.index() | after << shift);
        }
    }

    /// Symbols rewritten between checks of the limit: a chunk may grow the
    /// output by at most `RESERVE` symbols before the limit is checked, so
    /// a very long successor shortens the chunk instead of sizing one
    /// allocation from the input.
    fn chunk_len(&self) -> usize {
        (RESERVE / self.longest.max(COPY)).clamp(1, CHUNK)
    }

    /// Rewrites `cur` into `region` and, from the first chunk that might
    /// not fit there, onto the end of `out`, from the left-context state
    /// `state` (left as it is after `cur`); how many symbols went into
    /// `region`. `PACKED`: each symbol of `cur` holds its right neighbour
    /// in its high bits ([`Self::pack_right_neighbours`]); else `right[i]`
    /// holds that of `cur[i]`. `total`: the symbols every piece of a step
    /// cut into pieces has written so far, kept under `max` as well.
    #[allow(clippy::too_many_arguments)]
    fn rewrite<const PACKED: bool>(
        &self,
        cur: &[T],
        right: &[T],
        (region, out): (&mut [T], &mut Vec<T>),
        draws: Draws,
        max: usize,
        state: &mut Left<T>,
        total: Option<&AtomicUsize>,
    ) -> Result<usize, ()> {
        let longest = self.longest.max(COPY);
        let spilled_from = out.len();
        // Written by index into `region`, or into `out` grown ahead a chunk
        // at a time, so the length stays in a register (pushing reloads it
        // every symbol).
        let (mut w, mut in_region, mut used) = (0, true, 0);
        // What is in `total` already.
        let mut counted = 0;
        let mut at = 0;
        for chunk in cur.chunks(self.chunk_len()) {
            let room = chunk.len() * longest + COPY;
            if in_region && w + room > region.len() {
                (in_region, used, w) = (false, w, spilled_from);
            }
            let dst = if in_region {
                &mut region[..]
            } else {
                if out.len() < w + room {
                    if out.capacity() < w + room {
                        let more = (w + room).max(out.capacity() + out.capacity() / 16);
                        out.reserve_exact(more - out.len());
                    }
                    out.resize(w + room, self.none);
                }
                &mut out[..]
            };
            w = self.rewrite_chunk::<PACKED>(chunk, right, at, dst, w, state, draws);
            at += chunk.len();
            let written = match in_region {
                true => w,
                false => used + w - spilled_from,
            };
            if written > max || total.is_some_and(|t| over(t, written - counted, max)) {
                out.truncate(if in_region { spilled_from } else { w });
                return Err(());
            }
            counted = written;
        }
        match in_region {
            true => used = w,
            false => out.truncate(w),
        }
        Ok(used)
    }

    /// The loop of [`Self::rewrite`] over one chunk of `cur`, starting at
    /// `at`, written into `dst` from `w` (with room for the chunk's longest
    /// rewriting and [`COPY`] more); where its rewriting ends.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn rewrite_chunk<const PACKED: bool>(
        &self,
        chunk: &[T],
        right: &[T],
        mut at: usize,
        dst: &mut [T],
        mut w: usize,
        state: &mut Left<T>,
        draws: Draws,
    ) -> usize {
        let t = self.table;
        let none = self.none;
        // A local the loop keeps in registers, put back at the end.
        let mut left = std::mem::replace(state, Left::new(none));
        let shift = self.packed_shift.unwrap_or(0);
        let low = (1 << shift) - 1;
        // Everything the loop reads, as local slices: the output's writes
        // could otherwise alias their lengths and force reloads.
        let (entry, class, cells, rights) = (&t.entry[..], &t.class[..], &t.cells[..], t.rights);
        let (arena, spans) = (&self.arena[..], &self.spans[..]);
        for &s in chunk {
            let (s, si, r) = if PACKED {
                let si = s.index() & low;
                (T::from_index(si), si, s.index() >> shift)
            } else {
                (s, s.index(), right[at].index())
            };
            // Context-free symbols have one cell: the mask is zero.
            let (base, mask) = entry[si];
            let cell = (left.last.index() * rights + r) & mask;
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
                    &alts[super::choose(alts.iter().map(|a| a.0), draws.at(at - 1, 1))].1
                };
                dst[w..w + succ.len()].copy_from_slice(succ);
                w += succ.len();
            }
        }
        *state = left;
        w
    }
}

/// Adds `grown` symbols to `total`; whether that passes `max`.
fn over(total: &AtomicUsize, grown: usize, max: usize) -> bool {
    total.fetch_add(grown, Ordering::Relaxed) + grown > max
}

#[cfg(test)]
mod tests {
    use super::super::{DeriveOptions, Deriver, Symbols};
    use crate::front::pfg::read_ok as sys;

    /// Right neighbours kept in the symbols' spare bits and in an array of
    /// their own give the same words, in bytes and in wider symbols.
    #[test]
    fn packed_and_separate_right_neighbours_give_the_same_words() {
        for (name, n) in [("hogeweg-hesper-a", 45), ("hogeweg-hesper-b", 40)] {
            let s = sys(crate::stdlib::get(name).unwrap().text);
            let d = Deriver::new(&s);
            let t = d.table.as_ref().unwrap();
            let opts = DeriveOptions::new(n);
            let packed = t.stepper::<u8>();
            assert!(packed.packed_shift.is_some(), "{name}");
            let separate = super::TableStepper {
                packed_shift: None,
                ..t.stepper::<u8>()
            };
            let want = d.steps(&packed, &opts, |_, _| {}).unwrap().0;
            assert!(want.len() > 200_000, "{name}: {}", want.len());
            assert_eq!(d.steps(&separate, &opts, |_, _| {}).unwrap().0, want);
            let wide = d.steps(&t.stepper::<crate::ir::SymbolId>(), &opts, |_, _| {});
            let wide: Vec<u8> = Symbols::Wide(wide.unwrap().0)
                .iter()
                .map(|s| s.0 as u8)
                .collect();
            assert_eq!(wide, want, "{name}");
        }
    }
}
