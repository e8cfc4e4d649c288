//! The derivation tree of a context-free deterministic system (a D0L
//! system), with identical subtrees shared.
//!
//! When every production has one predecessor symbol, no context and one
//! successor, the word after `n` steps from a symbol `s` is the
//! concatenation of the words after `n − 1` steps from the symbols of `s`'s
//! successor: `W(s, n) = W(c₁, n−1) W(c₂, n−1) …`. Every node `(s, n)` of
//! the derivation tree with the same symbol and the same remaining depth is
//! the same subtree — the object-instancing view of Bekaert & Willems
//! ("Ray tracing 3D linear graftals"): the tree has at most
//! `symbols × depth` distinct nodes however long the word is.
//!
//! This module uses that three ways:
//!
//! * [`Tree::word_len`]: the exact length of the word before deriving it,
//!   so a derivation that would outgrow the limit says so up front;
//! * [`Tree::walk`]: the word produced left to right in chunks, with the
//!   expansions of small subtrees computed once and copied (to print a word,
//!   or to build it, at memory-copy speed);
//! * [`Tree::symbols`]: the word streamed symbol by symbol in memory that
//!   grows with the depth, not with the word (for interpreting words that
//!   could never be stored).
//!
//! The words are exactly those of step-by-step parallel rewriting
//! ([`super::Deriver`]); the tests check it.

use super::count::Count;
use crate::ir::{D0l, SymbolId, System};

/// The most levels a tree is used for: deeper derivations of systems that
/// do not grow are left to step-by-step rewriting, which skips cycles.
pub const MAX_TREE_DEPTH: u64 = 4096;

/// Bytes of memoised expansions [`Tree::walk`] keeps at most.
const MEMO_BUDGET: usize = 64 << 20;
/// The longest single memoised expansion, in elements.
const MEMO_CHUNK: usize = 4 << 20;
/// The shortest word [`Tree::word_on`] shares among threads.
const PARALLEL_WORD: usize = 1 << 20;
/// The most entries of the table of lengths by symbol and depth that
/// [`Tree::word_on`] builds to cut a word.
const MAX_LENGTHS: usize = 1 << 22;

/// A subtree of the derivation: one symbol (a slice of the axiom or of a
/// successor), the steps it still takes, and the length of its word.
#[derive(Clone, Copy)]
struct Piece<'a> {
    symbol: &'a [SymbolId],
    depth: u64,
    len: usize,
}

/// A D0L system's successors, indexed by symbol.
#[derive(Clone, Debug)]
pub struct Tree<'a> {
    axiom: &'a [SymbolId],
    /// `succ[s]`: the successor of `s`, or `None` when no production
    /// rewrites `s` (it then stays itself at every step).
    succ: Vec<Option<&'a [SymbolId]>>,
}

impl<'a> Tree<'a> {
    /// The tree of `sys`, or `None` when `sys` is not context-free and
    /// deterministic ([`D0l::of`]).
    pub fn new(sys: &'a System) -> Option<Self> {
        let d = D0l::of(sys)?;
        Some(Tree {
            axiom: d.axiom,
            succ: d.successors,
        })
    }

    /// The symbols `s` becomes in one step, `None` when it stays itself.
    pub fn successor(&self, s: SymbolId) -> Option<&'a [SymbolId]> {
        self.succ[s.index()]
    }

    pub fn axiom(&self) -> &'a [SymbolId] {
        self.axiom
    }

    pub fn symbol_count(&self) -> usize {
        self.succ.len()
    }

    /// The length of the word after `steps` steps, or `Err(d)` when the
    /// word after `d ≤ steps` steps is already longer than `max`. Costs
    /// `steps × (symbols + successor lengths)`; the caller keeps `steps` at
    /// most [`MAX_TREE_DEPTH`].
    pub fn word_len(&self, steps: u64, max: u128) -> Result<u128, u64> {
        self.weighed(steps, &vec![1; self.succ.len()], max)
    }

    /// [`Tree::word_len`] with each symbol counted `weight[s]` times
    /// (0 for symbols that are not written), saturating at `u128::MAX`:
    /// for limits, which are far below it.
    pub fn weighed(&self, steps: u64, weight: &[u128], max: u128) -> Result<u128, u64> {
        self.tally(steps, weight, |n, _| *n > max)
    }

    /// The exact number of symbols in the word after `steps` steps, each
    /// symbol counted `weight[s]` times, however large; `None` when the
    /// numbers would take more than [`COUNT_BUDGET`] limb operations to
    /// add up (thousands of steps of a system with many symbols, each
    /// rewritten into many: counts of thousands of digits).
    pub fn count(&self, steps: u64, weight: &[u128]) -> Option<Count> {
        self.count_within(steps, weight, COUNT_BUDGET)
    }

    /// [`Tree::count`] within `budget` limb operations.
    fn count_within(&self, steps: u64, weight: &[u128], budget: u64) -> Option<Count> {
        let weight: Vec<Count> = weight.iter().map(|&w| Count::from(w)).collect();
        self.tally(steps, &weight, |_, work| work > budget).ok()
    }

    /// The weighed length of the word after `steps` steps, level by level
    /// from the leaves up; `Err(d)` when `stop(total, work)` holds after
    /// `d ≤ steps` steps, with the total of the word after `d` steps and
    /// the limb operations spent so far.
    fn tally<N: Tally>(
        &self,
        steps: u64,
        weight: &[N],
        stop: impl Fn(&N, u64) -> bool,
    ) -> Result<N, u64> {
        // Each successor as (child, how many times), so a successor of
        // many copies of a few symbols costs a few products a level.
        let parts: Vec<Option<Vec<(usize, u64)>>> =
            self.succ.iter().map(|w| w.map(multiplicities)).collect();
        let axiom = multiplicities(self.axiom);
        let mut work = 0u64;
        let mut len = weight.to_vec();
        let mut next = weight.to_vec();
        let mut total = N::zero();
        weighed_sum(&axiom, &len, (&mut total, &mut work));
        if stop(&total, work) {
            return Err(0);
        }
        for d in 1..=steps {
            // Into the numbers of two levels ago: their room is reused.
            for (s, out) in next.iter_mut().enumerate() {
                match &parts[s] {
                    None => out.clone_from(&weight[s]),
                    Some(p) => weighed_sum(p, &len, (out, &mut work)),
                }
            }
            std::mem::swap(&mut len, &mut next);
            weighed_sum(&axiom, &len, (&mut total, &mut work));
            if stop(&total, work) {
                return Err(d);
            }
            if len == next {
                // A fixpoint of lengths: no later step changes them.
                break;
            }
        }
        Ok(total)
    }

    /// Produces the word after `steps` steps, left to right, as chunks of
    /// `T` given to `emit`: `leaf(s)` is what one symbol stands for (its
    /// name's bytes when printing, the symbol itself when building a word).
    /// The expansions of subtrees up to a few MB are built once and then
    /// copied whole; the rest of the tree is walked with a stack as deep as
    /// the tree. Stops at the first error `emit` returns.
    pub fn walk<T: Copy + 'a, E>(
        &self,
        steps: u64,
        leaf: impl Fn(SymbolId) -> &'a [T],
        emit: impl FnMut(&[T]) -> Result<(), E>,
    ) -> Result<(), E> {
        let memo = Memo::build(self, steps, &leaf);
        self.walk_from(&memo, self.axiom, steps, &leaf, emit)
    }

    /// [`Tree::walk`] of the word `start` derives in `depth` steps, with
    /// the memoised expansions `memo`.
    fn walk_from<T: Copy + 'a, E>(
        &self,
        memo: &Memo<T>,
        start: &'a [SymbolId],
        depth: u64,
        leaf: &impl Fn(SymbolId) -> &'a [T],
        mut emit: impl FnMut(&[T]) -> Result<(), E>,
    ) -> Result<(), E> {
        // Frames: (symbols still to expand, their remaining depth).
        let mut stack: Vec<(&[SymbolId], u64)> = vec![(start, depth)];
        while let Some(top) = stack.last_mut() {
            let Some((&s, rest)) = top.0.split_first() else {
                stack.pop();
                continue;
            };
            top.0 = rest;
            let d = top.1;
            match self.succ[s.index()] {
                Some(w) if d > 0 => match memo.get(s, d) {
                    Some(chunk) => emit(chunk)?,
                    None => stack.push((w, d - 1)),
                },
                _ => emit(leaf(s))?,
            }
        }
        Ok(())
    }

    /// [`Tree::word`] (`len` symbols) built on `threads` threads (0:
    /// every core): the word is cut into subtrees whose offsets follow
    /// from their known lengths, and each thread fills its own run of
    /// them. The same symbols for every count.
    pub fn word_on(&self, steps: u64, len: usize, threads: usize) -> Vec<SymbolId> {
        self.word_split(steps, len, threads, PARALLEL_WORD)
    }

    /// [`Tree::word_on`], a word shorter than `shortest` built on one
    /// thread.
    fn word_split(&self, steps: u64, len: usize, threads: usize, shortest: usize) -> Vec<SymbolId> {
        let threads = crate::parallel::threads(threads);
        // The table of lengths by depth must stay small.
        let table = (steps as usize + 1).saturating_mul(self.succ.len());
        if threads <= 1 || len < shortest.max(1) || table > MAX_LENGTHS {
            return self.word(steps, len);
        }
        let pieces = self.pieces(steps, len.div_ceil(8 * threads));
        if pieces.iter().map(|p| p.len).sum::<usize>() != len {
            // Not the word's length: nothing to cut by.
            return self.word(steps, len);
        }
        let leaves: Vec<SymbolId> = (0..self.succ.len() as u32).map(SymbolId).collect();
        let leaves = &leaves;
        let leaf = |s: SymbolId| std::slice::from_ref(&leaves[s.index()]);
        let memo = Memo::build(self, steps, &leaf);
        let mut out = vec![SymbolId(0); len];
        // Contiguous runs of pieces of about len / threads symbols each.
        let target = len.div_ceil(threads);
        let mut runs: Vec<(&[Piece<'_>], &mut [SymbolId])> = Vec::new();
        let mut rest: &mut [SymbolId] = &mut out;
        let (mut first, mut run_len) = (0, 0);
        for (k, piece) in pieces.iter().enumerate() {
            run_len += piece.len;
            if run_len >= target || k + 1 == pieces.len() {
                let (mine, others) = std::mem::take(&mut rest).split_at_mut(run_len);
                runs.push((&pieces[first..=k], mine));
                rest = others;
                (first, run_len) = (k + 1, 0);
            }
        }
        std::thread::scope(|scope| {
            for (pieces, slice) in runs {
                let (memo, leaf) = (&memo, &leaf);
                scope.spawn(move || {
                    let mut at = 0;
                    for p in pieces {
                        let _ = self.walk_from(
                            memo,
                            p.symbol,
                            p.depth,
                            leaf,
                            |chunk: &[SymbolId]| {
                                slice[at..at + chunk.len()].copy_from_slice(chunk);
                                at += chunk.len();
                                Ok::<(), ()>(())
                            },
                        );
                    }
                });
            }
        });
        out
    }

    /// The word after `steps` steps as subtrees in order, each at most
    /// `most` symbols long unless it is a single symbol that stays.
    fn pieces(&self, steps: u64, most: usize) -> Vec<Piece<'a>> {
        let lens = self.lengths(steps);
        let piece = |w: &'a [SymbolId], i: usize, depth: u64| Piece {
            symbol: &w[i..i + 1],
            depth,
            len: lens[depth as usize][w[i].index()],
        };
        let mut pieces: Vec<Piece<'a>> = (0..self.axiom.len())
            .map(|i| piece(self.axiom, i, steps))
            .collect();
        loop {
            let mut split = false;
            let mut next = Vec::with_capacity(pieces.len());
            for p in pieces {
                match self.succ[p.symbol[0].index()] {
                    Some(w) if p.depth > 0 && p.len > most => {
                        next.extend((0..w.len()).map(|i| piece(w, i, p.depth - 1)));
                        split = true;
                    }
                    _ => next.push(p),
                }
            }
            pieces = next;
            if !split {
                return pieces;
            }
        }
    }

    /// `lengths[d][s]`: the length of the word `s` derives in `d` steps,
    /// for `d` up to `steps` (saturating: the caller has checked the
    /// word's length).
    fn lengths(&self, steps: u64) -> Vec<Vec<usize>> {
        let n = self.succ.len();
        let mut lengths = vec![vec![1usize; n]];
        for d in 1..=steps as usize {
            let below = &lengths[d - 1];
            let level = (0..n)
                .map(|s| match self.succ[s] {
                    Some(w) => w
                        .iter()
                        .fold(0usize, |sum, c| sum.saturating_add(below[c.index()])),
                    None => 1,
                })
                .collect();
            lengths.push(level);
        }
        lengths
    }

    /// The word after `steps` steps as a vector of symbols.
    pub fn word(&self, steps: u64, capacity: usize) -> Vec<SymbolId> {
        let mut out = Vec::with_capacity(capacity);
        let leaves: Vec<SymbolId> = (0..self.succ.len() as u32).map(SymbolId).collect();
        let leaves = &leaves;
        let _ = self.walk::<SymbolId, ()>(
            steps,
            |s| std::slice::from_ref(&leaves[s.index()]),
            |chunk| {
                out.extend_from_slice(chunk);
                Ok(())
            },
        );
        out
    }

    /// The word after `steps` steps, one symbol at a time, without storing
    /// it: memory grows with `steps`, not with the word.
    pub fn symbols(&self, steps: u64) -> Symbols<'a> {
        Symbols {
            succ: self.succ.clone(),
            stack: vec![(self.axiom, steps)],
        }
    }
}

/// The most limb operations [`Tree::count`] spends: about half a second
/// (2 ns each, optimised). The Koch island at 4096 steps takes about a
/// million; 52 symbols each rewritten into all 52, at 1000 steps, half
/// the budget.
pub const COUNT_BUDGET: u64 = 1 << 28;

/// What [`Tree::tally`] adds up: a saturating `u128` for limits, an exact
/// [`Count`] for what is reported.
trait Tally: Clone + PartialEq {
    fn zero() -> Self;
    /// Sets it to zero, keeping its room.
    fn set_zero(&mut self);
    /// `self += x · k`.
    fn add_times(&mut self, x: &Self, k: u64);
    /// What adding it costs, in limb operations.
    fn cost(&self) -> u64;
}

impl Tally for u128 {
    fn zero() -> Self {
        0
    }
    fn set_zero(&mut self) {
        *self = 0;
    }
    fn add_times(&mut self, x: &Self, k: u64) {
        *self = self.saturating_add(x.saturating_mul(u128::from(k)));
    }
    fn cost(&self) -> u64 {
        1
    }
}

impl Tally for Count {
    fn zero() -> Self {
        Count::zero()
    }
    fn set_zero(&mut self) {
        Count::set_zero(self);
    }
    fn add_times(&mut self, x: &Self, k: u64) {
        Count::add_times(self, x, k);
    }
    fn cost(&self) -> u64 {
        self.limbs() as u64 + 1
    }
}

/// `out = Σ k · len[c]` over the `(c, k)` of `parts`, with its cost added
/// to `work`.
fn weighed_sum<N: Tally>(parts: &[(usize, u64)], len: &[N], (out, work): (&mut N, &mut u64)) {
    out.set_zero();
    for &(c, k) in parts {
        *work = work.saturating_add(len[c].cost());
        out.add_times(&len[c], k);
    }
}

/// The symbols of `w` by index, each with how many times it occurs.
fn multiplicities(w: &[SymbolId]) -> Vec<(usize, u64)> {
    let mut ids: Vec<usize> = w.iter().map(|s| s.index()).collect();
    ids.sort_unstable();
    let mut out: Vec<(usize, u64)> = Vec::new();
    for i in ids {
        match out.last_mut() {
            Some((c, k)) if *c == i => *k += 1,
            _ => out.push((i, 1)),
        }
    }
    out
}

/// The expansions of small subtrees, by symbol and depth.
struct Memo<T> {
    /// `levels[d - 1][s]`: the word after `d` steps from `s` (`d ≥ 1`), when
    /// it was small enough to keep.
    levels: Vec<Vec<Option<Vec<T>>>>,
}

impl<T: Copy> Memo<T> {
    fn build<'a>(tree: &Tree<'a>, steps: u64, leaf: &impl Fn(SymbolId) -> &'a [T]) -> Self
    where
        T: 'a,
    {
        let n = tree.succ.len();
        let mut levels: Vec<Vec<Option<Vec<T>>>> = Vec::new();
        let mut bytes = 0usize;
        let elem = std::mem::size_of::<T>().max(1);
        for d in 1..steps {
            let mut level: Vec<Option<Vec<T>>> = Vec::with_capacity(n);
            let mut any = false;
            for s in 0..n {
                let Some(w) = tree.succ[s] else {
                    level.push(None);
                    continue;
                };
                // The child expansions at depth d − 1, if all are known.
                let child = |c: SymbolId| -> Option<&[T]> {
                    match (d, tree.succ[c.index()]) {
                        (1, _) | (_, None) => Some(leaf(c)),
                        _ => levels[d as usize - 2][c.index()].as_deref(),
                    }
                };
                let mut len = 0usize;
                let mut known = true;
                for &c in w {
                    match child(c) {
                        Some(x) => len += x.len(),
                        None => {
                            known = false;
                            break;
                        }
                    }
                }
                if !known || len > MEMO_CHUNK || bytes + len * elem > MEMO_BUDGET {
                    level.push(None);
                    continue;
                }
                let mut v = Vec::with_capacity(len);
                for &c in w {
                    v.extend_from_slice(child(c).expect("checked above"));
                }
                bytes += len * elem;
                any = true;
                level.push(Some(v));
            }
            levels.push(level);
            if !any {
                break;
            }
        }
        Memo { levels }
    }

    fn get(&self, s: SymbolId, d: u64) -> Option<&[T]> {
        self.levels
            .get(d as usize - 1)
            .and_then(|l| l[s.index()].as_deref())
    }
}

/// The symbols of a derived word in order ([`Tree::symbols`]).
pub struct Symbols<'a> {
    succ: Vec<Option<&'a [SymbolId]>>,
    stack: Vec<(&'a [SymbolId], u64)>,
}

impl Iterator for Symbols<'_> {
    type Item = SymbolId;

    fn next(&mut self) -> Option<SymbolId> {
        loop {
            let top = self.stack.last_mut()?;
            let Some((&s, rest)) = top.0.split_first() else {
                self.stack.pop();
                continue;
            };
            top.0 = rest;
            let d = top.1;
            match self.succ[s.index()] {
                Some(w) if d > 0 => self.stack.push((w, d - 1)),
                _ => return Some(s),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::{DeriveOptions, Deriver};
    use crate::front::pfg::read_ok as sys;

    /// Step-by-step rewriting, the reference.
    fn stepwise(s: &System, n: u64) -> Vec<SymbolId> {
        Deriver::new(s)
            .derive_stepwise(&DeriveOptions::new(n).max_symbols(1 << 26), |_, _| {})
            .unwrap()
            .0
    }

    const SYSTEMS: [&str; 4] = [
        "axiom: F+F+F+F\nF --> F+F-F-FF+F+F-F\n",
        "axiom: a\na --> ab\nb --> a\n",
        // Erasing, identity symbols, brackets, a symbol with two
        // productions (the first wins).
        "axiom: X\nX --> F[+X][-X]FX\nF --> FF\nF --> G\n+ --> *\n",
        "axiom: AB\nA --> B\nB --> *\n",
    ];

    #[test]
    fn walk_word_threads_and_stream_agree_with_stepwise_rewriting() {
        for src in SYSTEMS {
            let s = sys(src);
            let t = Tree::new(&s).expect("context-free");
            for n in 0..8 {
                let want = stepwise(&s, n);
                assert_eq!(t.word(n, 0), want, "{src} n={n}");
                for threads in [2, 3, 7] {
                    // Every word split among the threads, however short.
                    assert_eq!(t.word_split(n, want.len(), threads, 0), want, "{src} n={n}");
                }
                // A length that is not the word's: built on one thread.
                assert_eq!(t.word_split(n, want.len() + 1, 3, 0), want);
                assert_eq!(t.symbols(n).collect::<Vec<_>>(), want, "{src} n={n}");
                assert_eq!(t.word_len(n, u128::MAX), Ok(want.len() as u128));
                let names: Vec<Vec<u8>> = s
                    .symbols
                    .iter()
                    .map(|(_, i)| i.name.clone().into_bytes())
                    .collect();
                let names = &names;
                let mut text = Vec::new();
                t.walk::<u8, ()>(
                    n,
                    |c| &names[c.index()],
                    |b| {
                        text.extend_from_slice(b);
                        Ok(())
                    },
                )
                .unwrap();
                assert_eq!(
                    String::from_utf8(text).unwrap(),
                    Word::from(want).display(&s.symbols)
                );
            }
        }
    }

    #[test]
    fn lengths_are_known_before_deriving() {
        let s = sys(SYSTEMS[0]);
        let t = Tree::new(&s).unwrap();
        // 4 (1 + 13 (8^n - 1) / 7) + 3 symbols.
        let len = |n: u32| 4 * (1 + 13 * (8u128.pow(n) - 1) / 7) + 3;
        assert_eq!(t.word_len(7, u128::MAX), Ok(len(7)));
        assert_eq!(t.word_len(7, u128::MAX), Ok(15_578_843));
        assert_eq!(t.word_len(30, u128::MAX), Ok(len(30)));
        // Over the limit: the first step that outgrows it is named.
        assert_eq!(t.word_len(30, len(9)), Err(10));
    }

    #[test]
    fn counts_are_exact_past_u128_and_stop_at_their_budget() {
        let s = sys(SYSTEMS[0]);
        let t = Tree::new(&s).unwrap();
        let ones = vec![1; t.symbol_count()];
        // Up to u128 the exact count and the saturating one agree.
        let exact = t.count(30, &ones).unwrap();
        assert_eq!(exact, t.word_len(30, u128::MAX).unwrap());
        // 4 (1 + 13 (8^n − 1) / 7) + 3 at n = 50, past u128 (8^50 = 2^150):
        // 8^n = 2^(3n), built by doubling; the rest by small products.
        let mut eight_n = Count::from(1u64);
        for _ in 0..150 {
            let x = eight_n.clone();
            eight_n.add_times(&x, 1);
        }
        // 7 · want = 4 (7 + 13 (8^n − 1)) + 21 = 52 · 8^n − 3.
        let mut want_by_7_plus_3 = Count::zero();
        want_by_7_plus_3.add_times(&eight_n, 52);
        let got = t.count(50, &ones).unwrap();
        let mut got_by_7_plus_3 = Count::from(3u64);
        got_by_7_plus_3.add_times(&got, 7);
        assert_eq!(got_by_7_plus_3, want_by_7_plus_3);
        assert_eq!(t.word_len(50, u128::MAX), Ok(u128::MAX), "saturates");
        // Within a budget too small for it, no count at all.
        assert_eq!(t.count_within(50, &ones, 100), None);
    }

    #[test]
    fn only_d0l_systems_make_trees() {
        for src in [
            "axiom: ab\na < b --> c\n",
            "axiom: a\na --> b : 1\na --> c : 1\n",
            "axiom: ab\nab --> c\n",
        ] {
            assert!(Tree::new(&sys(src)).is_none(), "{src}");
        }
    }

    use crate::ir::Word;
}
