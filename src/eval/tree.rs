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

use crate::ir::{D0l, SymbolId, System};

/// The most levels a tree is used for: deeper derivations of systems that
/// do not grow are left to step-by-step rewriting, which skips cycles.
pub const MAX_TREE_DEPTH: u64 = 4096;

/// Bytes of memoised expansions [`Tree::walk`] keeps at most.
const MEMO_BUDGET: usize = 64 << 20;
/// The longest single memoised expansion, in elements.
const MEMO_CHUNK: usize = 4 << 20;

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
    /// (0 for symbols that are not written).
    pub fn weighed(&self, steps: u64, weight: &[u128], max: u128) -> Result<u128, u64> {
        let n = self.succ.len();
        let mut len = weight.to_vec();
        let mut next = vec![0u128; n];
        let axiom_len = |len: &[u128]| -> u128 {
            self.axiom
                .iter()
                .fold(0u128, |acc, s| acc.saturating_add(len[s.index()]))
        };
        if axiom_len(&len) > max {
            return Err(0);
        }
        for d in 1..=steps {
            for (s, out) in next.iter_mut().enumerate() {
                *out = match self.succ[s] {
                    None => weight[s],
                    Some(w) => w
                        .iter()
                        .fold(0u128, |acc, c| acc.saturating_add(len[c.index()])),
                };
            }
            std::mem::swap(&mut len, &mut next);
            if axiom_len(&len) > max {
                return Err(d);
            }
            if len == next {
                // A fixpoint of lengths: no later step changes them.
                break;
            }
        }
        Ok(axiom_len(&len))
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
        mut emit: impl FnMut(&[T]) -> Result<(), E>,
    ) -> Result<(), E> {
        let memo = Memo::build(self, steps, &leaf);
        // Frames: (symbols still to expand, their remaining depth).
        let mut stack: Vec<(&[SymbolId], u64)> = vec![(self.axiom, steps)];
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
    fn walk_word_and_stream_agree_with_stepwise_rewriting() {
        for src in SYSTEMS {
            let s = sys(src);
            let t = Tree::new(&s).expect("context-free");
            for n in 0..8 {
                let want = stepwise(&s, n);
                assert_eq!(t.word(n, 0), want, "{src} n={n}");
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
