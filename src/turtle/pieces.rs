//! A word interpreted in pieces, the pieces on every thread.
//!
//! Interpretation is a prefix computation: where the turtle stands at a
//! symbol follows from the symbols before it. Most of those do not
//! matter, though: a branch `[ … ]` closed before the symbol gives the
//! turtle back as it found it (its frame, width, colour, tropisms and the
//! count of rotations since the frame was last re-orthonormalised all
//! belong to the state a branch keeps, and interval angles are drawn by
//! position, not from a running stream). So each piece of the word is
//! summarised, on every thread at once, by its *spine*: its symbols less
//! the branches that open and close within it (plus what it does to the
//! count of open polygons). A short pass then walks the spines alone, in
//! order, and notes where the turtle stands at the start of each piece;
//! from there every piece is interpreted on its own, on any thread, and
//! draws exactly what it draws when the word is interpreted whole.
//!
//! The pieces are cut by the work they hold (a module drawing a surface
//! of a thousand triangles weighs a thousand symbols), the same pieces
//! whatever the number of threads, and never inside a polygon (`{ … }`
//! collects its vertices across branches). A system with sub-L-system
//! calls (whose scales are a stack of their own) is one piece.

use super::cost::Costs;
use super::interpret::{first_arg, ops_of, Snapshot, Turtle};
use super::run::Record;
use super::{Disc, Geometry, Polygon, Segment, Sink};
use crate::ir::{SymbolId, System, TurtleOp, Word};
use std::ops::Range;

/// A word's symbols, read a range at a time: a stored word's, or a
/// derived word's kept a byte a symbol.
pub trait Letters: Sync {
    type Range<'s>: Iterator<Item = SymbolId>
    where
        Self: 's;
    fn count(&self) -> usize;
    fn range(&self, r: Range<usize>) -> Self::Range<'_>;
}

impl Letters for [SymbolId] {
    type Range<'s> = std::iter::Copied<std::slice::Iter<'s, SymbolId>>;
    fn count(&self) -> usize {
        self.len()
    }
    fn range(&self, r: Range<usize>) -> Self::Range<'_> {
        self[r].iter().copied()
    }
}

/// How a word is cut.
#[derive(Clone, Copy, Debug)]
struct Cut {
    /// Symbols per block when the work of a word is weighed (pieces start
    /// at blocks).
    block: usize,
    /// The work (symbols, and primitives drawn) a piece is cut to hold.
    work: u64,
    /// The most pieces.
    most: u64,
}

/// Pieces of 32 Ki symbols and primitives, at most 128 of them: the
/// walk of the spines and a snapshot per piece are a few thousandths of
/// the work, and there are pieces enough to keep 16 threads busy.
const CUT: Cut = Cut {
    block: 1 << 14,
    work: 1 << 15,
    most: 128,
};

/// A word cut into pieces, each with where the turtle starts it.
pub struct Pieces<'a, L: Letters + ?Sized> {
    sys: &'a System,
    letters: &'a L,
    params: Option<&'a Word>,
    seed: u64,
    ops: Vec<Option<TurtleOp>>,
    /// Each piece's first index and the turtle there.
    starts: Vec<(usize, Snapshot<'a>)>,
}

/// A word in pieces, as those who draw it see it: how many, and each
/// interpreted into a sink of the caller's.
pub trait Pieced: Sync {
    /// How many pieces.
    fn count(&self) -> usize;
    /// Interprets piece `k` into `sink`; the deepest nesting it reaches
    /// (counting the branches it starts inside).
    fn run(&self, k: usize, sink: &mut dyn Sink) -> usize;
}

impl<L: Letters + ?Sized> Pieced for Pieces<'_, L> {
    fn count(&self) -> usize {
        self.starts.len()
    }

    fn run(&self, k: usize, sink: &mut dyn Sink) -> usize {
        let (start, snapshot) = &self.starts[k];
        let end = self.starts.get(k + 1).map_or(self.letters.count(), |s| s.0);
        let mut turtle = Turtle::resumed(self.sys, self.seed, snapshot, sink);
        let symbols = self.letters.range(*start..end);
        turtle.walk(symbols, *start, self.params, &self.ops, None);
        turtle.finish().max_depth
    }
}

/// Every piece of `word` interpreted into a sink of its own (`sink()`),
/// on `threads` threads: the sinks in the order of the pieces, and the
/// deepest nesting of all.
pub fn each<S: Sink + Send>(
    word: &dyn Pieced,
    threads: usize,
    sink: impl Fn() -> S + Sync,
) -> (Vec<S>, usize) {
    let runs = crate::parallel::map_in_order(
        word.count(),
        threads,
        |k| {
            let mut s = sink();
            let depth = word.run(k, &mut s);
            (s, depth)
        },
        |_| {},
    );
    let depth = runs.iter().map(|r| r.1).max().unwrap_or(0);
    (runs.into_iter().map(|r| r.0).collect(), depth)
}

/// Pieces `range` of `word` interpreted on `threads` threads, each into a
/// stored drawing of its own (its deepest nesting in `max_depth`), in the
/// order of the pieces.
pub fn stored(word: &dyn Pieced, range: Range<usize>, threads: usize) -> Vec<Geometry> {
    let first = range.start;
    crate::parallel::map_in_order(
        range.len(),
        threads,
        |j| {
            let mut g = Geometry::default();
            g.max_depth = word.run(first + j, &mut g);
            g
        },
        |_| {},
    )
}

/// Every piece of `word` interpreted on `threads` threads into one stored
/// drawing, in order: a round of pieces at a time, so that no more than a
/// round's drawing is held twice.
pub fn geometry(word: &dyn Pieced, threads: usize) -> Geometry {
    let round = 2 * crate::parallel::threads(threads);
    let mut g = Geometry::default();
    for first in (0..word.count()).step_by(round) {
        for part in stored(word, first..word.count().min(first + round), threads) {
            g.append(part);
        }
    }
    g
}

/// A sink that keeps nothing (the spines' walk draws nothing).
struct Nowhere;

impl Sink for Nowhere {
    fn segment(&mut self, _: Segment) {}
    fn polygon(&mut self, _: Polygon) {}
    fn disc(&mut self, _: Disc) {}
}

/// What a piece does to the count of open polygons: `d` becomes
/// `max(d + add, floor)` (a `}` with none open closes none).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Polygons {
    add: i64,
    floor: i64,
}

impl Polygons {
    const NONE: Polygons = Polygons { add: 0, floor: 0 };
    fn open(self) -> Self {
        Polygons {
            add: self.add + 1,
            floor: self.floor + 1,
        }
    }
    fn close(self) -> Self {
        Polygons {
            add: self.add - 1,
            floor: (self.floor - 1).max(0),
        }
    }
    fn after(self, open: i64) -> i64 {
        (open + self.add).max(self.floor)
    }
}

/// A piece summarised: its spine (the indices of its commands outside
/// the branches that close within it) and what it does to polygons.
struct Summary {
    spine: Vec<usize>,
    polygons: Polygons,
}

impl<'a, L: Letters + ?Sized> Pieces<'a, L> {
    /// The pieces of `letters` (the word's parameters `params`, if it has
    /// any) for the turtle of `sys` with `seed`, weighed and summarised on
    /// `threads` threads (0: every core); the same pieces for any number.
    pub fn plan(
        sys: &'a System,
        letters: &'a L,
        params: Option<&'a Word>,
        seed: u64,
        threads: usize,
    ) -> Self {
        Self::plan_cut(sys, letters, params, seed, threads, CUT)
    }

    fn plan_cut(
        sys: &'a System,
        letters: &'a L,
        params: Option<&'a Word>,
        seed: u64,
        threads: usize,
        cut: Cut,
    ) -> Self {
        let ops = ops_of(sys);
        let mut pieces = Pieces {
            sys,
            letters,
            params,
            seed,
            ops,
            starts: Vec::new(),
        };
        let cuts = pieces.cuts(threads, cut);
        let summaries = crate::parallel::map_in_order(
            cuts.len(),
            threads,
            |k| pieces.summary(&cuts, k),
            |_| {},
        );
        pieces.starts = pieces.starts_from(&cuts, &summaries);
        pieces
    }

    /// Where the pieces start: block boundaries where the work done so far
    /// passes each piece's share of the whole.
    fn cuts(&self, threads: usize, cut: Cut) -> Vec<usize> {
        let Cut { block, work, most } = cut;
        let n = self.letters.count();
        let sub_lsystems = self.ops.iter().any(|op| {
            matches!(
                op,
                Some(TurtleOp::SubLsystemCall | TurtleOp::SubLsystemReturn)
            )
        });
        // Blocks small enough that a short word of heavy modules (a
        // surface each) is still cut evenly.
        let block = block.min(n.div_ceil(8 * most as usize)).max(64);
        if n < 2 * block || sub_lsystems {
            return vec![0];
        }
        let blocks = n.div_ceil(block);
        let costs = Costs::of(self.sys);
        let piece_work = work;
        let work = crate::parallel::map_in_order(
            blocks,
            threads,
            |b| {
                let r = b * block..n.min((b + 1) * block);
                let first = r.start;
                (self.letters.range(r).enumerate())
                    .map(|(k, s)| {
                        let op = self.ops.get(s.index()).copied().flatten();
                        1 + costs.drawn(op, || first_arg(self.params, first + k))
                    })
                    .sum::<u64>()
            },
            |_| {},
        );
        let total: u64 = work.iter().sum();
        let count = (total / piece_work).clamp(1, most);
        let mut cuts = vec![0];
        let mut done = 0u64;
        for (b, w) in work.iter().enumerate().take(blocks - 1) {
            done += w;
            if u128::from(done) * u128::from(count) >= cuts.len() as u128 * u128::from(total) {
                cuts.push((b + 1) * block);
            }
        }
        cuts
    }

    /// Piece `k`'s spine and what it does to polygons.
    fn summary(&self, cuts: &[usize], k: usize) -> Summary {
        let start = cuts[k];
        let end = cuts.get(k + 1).copied().unwrap_or(self.letters.count());
        let mut spine = Vec::new();
        // The spine's length at each branch opened in the piece and still
        // open: where it is cut back to when the branch closes.
        let mut open = Vec::new();
        let mut polygons = Polygons::NONE;
        for (i, s) in (start..end).zip(self.letters.range(start..end)) {
            let Some(op) = self.ops.get(s.index()).copied().flatten() else {
                continue;
            };
            match op {
                TurtleOp::Push => {
                    open.push(spine.len());
                    spine.push(i);
                    continue;
                }
                TurtleOp::Pop => {
                    match open.pop() {
                        Some(at) => spine.truncate(at),
                        None => spine.push(i),
                    }
                    continue;
                }
                TurtleOp::PolygonBegin if first_arg(self.params, i).is_none() => {
                    polygons = polygons.open();
                }
                TurtleOp::PolygonEnd if first_arg(self.params, i).is_none() => {
                    polygons = polygons.close();
                }
                _ => {}
            }
            spine.push(i);
        }
        Summary { spine, polygons }
    }

    /// The turtle at the start of each piece, found by walking the spines
    /// in order; a cut inside a polygon is dropped (the piece before it
    /// runs on).
    fn starts_from(&self, cuts: &[usize], summaries: &[Summary]) -> Vec<(usize, Snapshot<'a>)> {
        // A sink of no size, leaked at no cost, so that the walk's
        // turtle and its snapshots share the system's lifetime.
        let nowhere: &'a mut Nowhere = Box::leak(Box::new(Nowhere));
        let record = Record {
            paths: false,
            queries: false,
        };
        let mut turtle = Turtle::new(self.sys, self.seed, record, nowhere);
        let mut starts = Vec::with_capacity(cuts.len());
        let mut polygons = 0;
        for (&cut, summary) in cuts.iter().zip(summaries) {
            if polygons == 0 {
                starts.push((cut, turtle.snapshot()));
            }
            for &i in &summary.spine {
                turtle.walk(
                    self.letters.range(i..i + 1),
                    i,
                    self.params,
                    &self.ops,
                    None,
                );
            }
            polygons = summary.polygons.after(polygons);
        }
        starts
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::pfg::read_ok;
    use crate::turtle::Run;

    fn word(src: &str, steps: u64) -> (System, Word) {
        derived(read_ok(src), steps)
    }

    fn std_word(name: &str, steps: u64) -> (System, Word) {
        let file = crate::driver::load(name).unwrap();
        derived(crate::driver::compile(file).system.unwrap(), steps)
    }

    fn derived(sys: System, steps: u64) -> (System, Word) {
        let opts = crate::driver::RunOptions {
            steps: Some(steps),
            ..crate::driver::RunOptions::default()
        };
        let w = crate::driver::derive(&sys, &opts).unwrap();
        (sys, w)
    }

    /// The word drawn whole, and drawn in pieces on `threads` threads and
    /// put together in order.
    fn whole_and_pieced(sys: &System, w: &Word, threads: usize) -> (Geometry, Geometry, usize) {
        let whole = Run::word(sys, w, 3).geometry();
        let params = w.has_params().then_some(w);
        let cut = Cut {
            block: 16,
            work: 64,
            most: 1000,
        };
        let pieces = Pieces::plan_cut(sys, &w.0[..], params, 3, threads, cut);
        let mut joined = Geometry::default();
        for g in stored(&pieces, 0..pieces.count(), threads) {
            g.replay(&mut joined);
            joined.max_depth = joined.max_depth.max(g.max_depth);
        }
        (whole, joined, pieces.count())
    }

    fn same(a: &Geometry, b: &Geometry) {
        assert_eq!(a.segments, b.segments);
        assert_eq!(a.polygons, b.polygons);
        assert_eq!(a.discs, b.discs);
        assert_eq!(a.order, b.order);
        assert_eq!(a.max_depth, b.max_depth);
    }

    #[test]
    fn a_branching_plant_drawn_in_pieces_draws_what_it_draws_whole() {
        // A bush with leaves: polygons whose vertices come from inside
        // branches (as ABOP's cordate leaf's do).
        let (sys, w) = word(
            "angle factor: 16\naxiom: X\nX --> F[+X][-X]FX[{+F[-F+F]F-F}]\nF --> FF\n",
            7,
        );
        for threads in [1, 2, 3, 7] {
            let (whole, joined, n) = whole_and_pieced(&sys, &w, threads);
            assert!(n > 4, "{n} pieces");
            same(&whole, &joined);
            assert!(!whole.polygons.is_empty());
        }
    }

    #[test]
    fn random_turns_and_widths_in_branches_are_the_same_in_pieces() {
        // LinF's interval rotations in branches, parameters, widths.
        let (sys, w) = std_word("std:gft/stochastic-tree", 12);
        let (whole, joined, n) = whole_and_pieced(&sys, &w, 3);
        assert!(n > 1, "{n} pieces of {}", w.len());
        same(&whole, &joined);
        // A random walk: one long spine of interval turns.
        let (sys, w) = std_word("std:linf/fig10-brownian-motion", 16);
        let (whole, joined, n) = whole_and_pieced(&sys, &w, 2);
        assert!(n > 1, "{n} pieces");
        same(&whole, &joined);
    }

    #[test]
    fn a_word_without_branches_is_one_long_spine_and_still_exact() {
        let (sys, w) = word("angle factor: 4\naxiom: F\nF --> F+F-F-FF+F+F-F\n", 6);
        let (whole, joined, n) = whole_and_pieced(&sys, &w, 2);
        assert!(n > 1, "{n} pieces");
        same(&whole, &joined);
    }

    #[test]
    fn cuts_never_fall_inside_a_polygon() {
        // Every symbol is inside one polygon that never closes: one piece.
        let (sys, w) = word("angle factor: 4\naxiom: {X\nX --> XF+F\n", 16);
        let (whole, joined, n) = whole_and_pieced(&sys, &w, 2);
        assert_eq!(n, 1);
        same(&whole, &joined);
    }

    #[test]
    fn polygon_counts_compose_as_the_turtle_counts_them() {
        let p = Polygons::NONE.close().close().open();
        assert_eq!(p.after(0), 1);
        assert_eq!(p.after(5), 4);
        assert_eq!(Polygons::NONE.open().close().after(0), 0);
    }
}
