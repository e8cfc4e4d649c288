//! One step of a big word on several threads: the word is cut into pieces,
//! one a thread, and each piece is rewritten straight into a place of its
//! own in the new word, as long as the last step's growth says its
//! rewriting will be. The pieces' rewritings are then moved up against
//! each other (a piece that outgrows its place goes on in a word of its
//! own, copied in after it). So each thread writes its share of the new
//! word once, into pages asked of the system zeroed that no other thread
//! touched first, and the new word is one allocation as on one thread;
//! moving the later pieces up is a `memmove` on the calling thread.
//!
//! What a position rewrites to depends on context that may lie in other
//! pieces: its left-context state (the nearest visible symbol on its left
//! and the stack of those before each open branch) and its right-context
//! state (the mirror image, met scanning leftwards). Each is a prefix (or
//! suffix) computation over the word, so it is done in three stages:
//!
//! 1. every piece, on its own thread, runs the leftwards pass that finds
//!    right neighbours as if the state right of it were unknown: values
//!    that come from outside the piece are kept as references to it
//!    ([`Val`]), and the few positions whose right neighbour is such a
//!    reference are listed. The same pass sums up the piece's effect on
//!    either state ([`Summary`]): the brackets it leaves unmatched and the
//!    values it pushes, the nearest visible symbol it leaves;
//! 2. one short scan of the summaries, rightwards for the left context and
//!    leftwards for the right context, finds the exact state at each
//!    piece's borders (its cost is the number of unmatched brackets, not
//!    the word's length);
//! 3. every piece, on the thread that scanned it, fills in the listed
//!    right neighbours from the state at its right border and rewrites
//!    itself from the state at its left border, exactly as the one-thread
//!    pass would.
//!
//! So the word is the one-thread word whatever the number of pieces. The
//! symbol limit is kept over all pieces together (a shared count checked
//! as often as the one-thread pass checks its own), so a step fails
//! exactly when its whole output is longer than the limit, and the pieces'
//! places together are no larger than it (and a chunk's room a piece). A
//! step holds what the one-thread step holds, its input and its output.

use super::{Left, Neighbours, TableStepper, CLOSE, OPEN, VISIBLE};
use crate::eval::{Draws, Sym};
use std::sync::atomic::AtomicUsize;
use std::sync::mpsc;

/// A value of the context state while a piece is scanned on its own: a
/// symbol index below `side` (`side - 1` being "none"), or from `side` on a
/// value from outside the piece: `side` the nearest visible symbol the
/// state held at the piece's border, `side + j` the `j`-th value popped
/// from its stack there (the top first; "none" where it held fewer).
type Val = usize;

/// The most listed positions whose right neighbour lies outside their
/// piece; a piece with more (a long run without a visible symbol, say) is
/// scanned again once its right border is known.
const FIXES: usize = 1 << 12;

/// A piece's effect on the context states, from its leftwards pass.
struct Summary {
    /// `[`s with no `]` after them in the piece: each pops a value of the
    /// right-context stack from outside it.
    opens: usize,
    /// The nearest visible symbol at or after the piece's start.
    next: Val,
    /// The values the right-context pass pushes at the `]`s with no `[`
    /// before them in the piece, the rightmost first (so the last is the
    /// top of the stack at the piece's start).
    rights: Vec<Val>,
    /// The left-context state's nearest visible symbol at the piece's end,
    /// then its value at each `[` with no `]` after it, the innermost
    /// (rightmost) first.
    lefts: Vec<Val>,
    /// The positions whose right neighbour is a value from outside, with
    /// that value; `None` when there were more than [`FIXES`].
    fixes: Option<Vec<(usize, Val)>>,
}

/// What a piece's leftwards scan notes on the few occasions it meets a
/// value from outside the piece.
struct Rare {
    side: usize,
    /// The `[`s met so far with no `]` after them.
    opens: usize,
    /// [`Summary::lefts`] so far, the last `waiting` of them not yet
    /// known: each is the first visible symbol met leftwards outside every
    /// branch (one symbol for all of them), or, if none is, a value from
    /// outside.
    lefts: Vec<Val>,
    waiting: usize,
    fixes: Option<Vec<(usize, Val)>>,
}

impl Rare {
    /// Position `i` has the right neighbour `v` from outside; `visible`:
    /// its symbol, when it is visible and outside every branch.
    ///
    /// Outside every branch, a left-context value is waiting exactly when
    /// the right neighbour comes from outside (both start at the piece's
    /// end and at each unmatched `[`, and both end at the first visible
    /// symbol outside every branch), so the waiting values are settled
    /// here too.
    #[cold]
    #[inline(never)]
    fn outside(&mut self, i: usize, v: Val, visible: Option<usize>) {
        self.fixes = self.fixes.take().filter(|f| f.len() < FIXES).map(|mut f| {
            f.push((i, v));
            f
        });
        if let Some(s) = visible {
            let at = self.lefts.len() - self.waiting;
            self.lefts[at..].fill(s);
            self.waiting = 0;
        }
    }

    /// A `[` whose branch goes on past the piece: it pops a value from
    /// outside, and its left context is the one met further left.
    #[cold]
    #[inline(never)]
    fn open(&mut self) -> Val {
        self.opens += 1;
        self.lefts.push(0);
        self.waiting += 1;
        self.side + self.opens
    }
}

/// A piece of a step as [`TableStepper::on_threads`] takes it: its part of
/// the word and of the right neighbours, its place in the new word, and
/// its draws.
type Piece<'w, T> = ((&'w mut [T], &'w mut [T]), (&'w mut [T], Draws));

/// The exact context states at a piece's borders.
struct Borders<T> {
    /// The left-context state at its start, with just the top of the stack
    /// that the piece's unmatched `]`s pop.
    left: Left<T>,
    /// The values its [`Val`]s from outside stand for, at its end: the
    /// nearest visible symbol, then the values popped from the stack.
    outside: Vec<T>,
}

/// The symbol `v` stands for, given the state at the border it refers to:
/// `near` its nearest visible symbol, `stack` its stack (top last).
fn resolve<T: Sym>(v: Val, side: usize, near: T, stack: &[T]) -> T {
    match v.checked_sub(side) {
        None => T::from_index(v),
        Some(0) => near,
        Some(j) => match stack.len().checked_sub(j) {
            Some(i) => stack[i],
            None => T::from_index(side - 1),
        },
    }
}

impl<T: Sym> TableStepper<'_, '_, T> {
    /// [`super::Stepper::step`] of a word cut into `pieces` pieces, one a
    /// thread, for a system without stochastic productions.
    pub(super) fn step_in_pieces(
        &self,
        cur: &mut [T],
        nb: &mut Neighbours<T>,
        out: &mut Vec<T>,
        (draws, max): (Draws, usize),
        pieces: usize,
    ) -> Result<(), ()> {
        let n = cur.len();
        let packed = self.packed_shift.is_some();
        if !packed {
            // Every piece writes all of its positions: only growth is
            // filled here.
            nb.right.resize(n, self.none);
        }
        let bounds: Vec<usize> = (0..=pieces).map(|k| k * n / pieces).collect();
        let words = cut(cur, &bounds);
        let rights: Vec<&mut [T]> = if packed {
            (0..pieces).map(|_| &mut [][..]).collect()
        } else {
            cut(&mut nb.right[..n], &bounds)
        };
        let places = self.places(&bounds, nb.growth, max);
        // The old buffer freed first, so that the step holds its input and
        // its output only (the scale test's bound).
        *out = Vec::new();
        *out = T::zeroed(places[pieces]);
        let regions = cut(&mut out[..], &places);
        // Each piece draws its random choices by their places in the word.
        let starts = bounds.iter().map(|&start| draws.from(start));
        let pieces = (words.into_iter().zip(rights)).zip(regions.into_iter().zip(starts));
        let done = self.on_threads(pieces.collect(), max);
        let parts = done.into_iter().collect::<Result<Vec<_>, ()>>()?;
        lay_out(out, &places, &parts);
        if out.len() > max {
            return Err(());
        }
        if n > 0 {
            nb.growth = out.len() as f64 / n as f64;
        }
        out.shrink_to_fit();
        Ok(())
    }

    /// Stages 1 to 3 of each piece (its part of the word, of the right
    /// neighbours, of the new word, and its draws), one a thread, the first
    /// on this thread: each thread scans its piece and sends its summary
    /// here; this thread finds the borders from them all and sends each
    /// piece its own; each thread then rewrites its piece. One thread a
    /// piece for the whole step, not a round of threads for each stage.
    /// Each piece's symbols in its place and its spill, or `Err` when the
    /// limit was passed.
    fn on_threads(
        &self,
        pieces: Vec<Piece<'_, T>>,
        max: usize,
    ) -> Vec<Result<(usize, Vec<T>), ()>> {
        let total = &AtomicUsize::new(0);
        let scan = |w: &mut [T], r: &mut [T]| match self.packed_shift.is_some() {
            true => self.scan::<true>(w, r),
            false => self.scan::<false>(w, r),
        };
        let finish = |(w, r): (&mut [T], &mut [T]), s: &Summary, b, region, d| {
            let mut spill = Vec::new();
            let used = self.finish(w, r, s, b, (region, &mut spill), d, (max, total));
            used.map(|used| (used, spill))
        };
        let count = pieces.len();
        std::thread::scope(|scope| {
            let mut pieces = pieces.into_iter();
            let ((w, r), (region, d)) = pieces.next().expect("one piece at least");
            let (summaries, scanned) = mpsc::channel();
            let (handles, others): (Vec<_>, Vec<_>) = (pieces.enumerate())
                .map(|(k, ((w, r), (region, d)))| {
                    let (send, bordered) = mpsc::channel::<(Summary, Borders<T>)>();
                    let summaries = summaries.clone();
                    let (scan, finish) = (&scan, &finish);
                    let other = scope.spawn(move || {
                        // A closed channel: a thread panicked, and this
                        // one stops so that the panic is not waited on.
                        summaries.send((k + 1, scan(w, r))).map_err(drop)?;
                        drop(summaries);
                        let (s, b) = bordered.recv().map_err(drop)?;
                        finish((w, r), &s, b, region, d)
                    });
                    (send, other)
                })
                .unzip();
            drop(summaries);
            let mut all: Vec<Option<Summary>> = (0..count).map(|_| None).collect();
            all[0] = Some(scan(w, r));
            for (k, s) in scanned {
                all[k] = Some(s);
            }
            let mine = match all.into_iter().collect::<Option<Vec<Summary>>>() {
                Some(all) => {
                    let borders = self.borders(&all);
                    let mut each = all.into_iter().zip(borders);
                    let (s, b) = each.next().expect("one piece at least");
                    for (send, sb) in handles.iter().zip(each) {
                        let _ = send.send(sb);
                    }
                    drop(handles);
                    finish((w, r), &s, b, region, d)
                }
                // A thread panicked before its summary: the others are
                // let go, and the join below passes the panic on.
                None => {
                    drop(handles);
                    Err(())
                }
            };
            let others = (others.into_iter()).map(|t| t.join().expect("a piece panicked"));
            std::iter::once(mine).chain(others).collect()
        })
    }

    /// Where in the new word each piece (the word cut at `bounds`) is
    /// rewritten: room for its rewriting at the last step's `growth`, the
    /// guesses together kept to `max` (each with a chunk's slack).
    fn places(&self, bounds: &[usize], growth: f64, max: usize) -> Vec<usize> {
        let mut places = vec![0];
        let mut guessed = 0;
        for pair in bounds.windows(2) {
            let room = (self.split.place)
                .unwrap_or_else(|| self.room(pair[1] - pair[0], growth, max - guessed));
            guessed = (guessed + room).min(max);
            places.push(places[places.len() - 1] + room);
        }
        places
    }

    /// Stage 1 for one piece `w`: the leftwards pass of
    /// [`Self::pack_right_neighbours`] (`PACKED`) or
    /// [`Self::right_neighbours`] (into `right`, one a position), the state
    /// right of the piece unknown, and the piece's [`Summary`].
    fn scan<const PACKED: bool>(&self, w: &mut [T], right: &mut [T]) -> Summary {
        let t = self.table;
        let side = t.side;
        let none = side - 1;
        let shift = self.packed_shift.unwrap_or(0);
        let (class, rclass) = (&t.class[..], &t.right[..]);
        let mut next: Val = side;
        let mut stack: Vec<Val> = Vec::new();
        let mut rare = Rare {
            side,
            opens: 0,
            lefts: vec![0],
            waiting: 1,
            fixes: Some(Vec::new()),
        };
        // As `pack_right_neighbours`, what happens rarely kept out of the
        // loop (a value from outside is read only near the piece's ends
        // and its unmatched `[`s), so that the loop's state stays in
        // registers.
        for (i, x) in w.iter_mut().enumerate().rev() {
            let s = x.index();
            let c = class[s];
            let after = if next < side {
                rclass[next] as usize
            } else {
                rare.outside(i, next, (c == VISIBLE && stack.is_empty()).then_some(s));
                0
            };
            if PACKED {
                *x = T::from_index(s | after << shift);
            } else {
                right[i] = T::from_index(after);
            }
            next = if c == VISIBLE { s } else { next };
            if c >= OPEN {
                if c == CLOSE {
                    stack.push(next);
                    next = none;
                } else {
                    next = stack.pop().unwrap_or_else(|| rare.open());
                }
            }
        }
        // Still unknown: the left context comes from outside, either the
        // nearest visible symbol at the start or, when the piece pops the
        // stack, the value its last unmatched `]` pops.
        let at = rare.lefts.len() - rare.waiting;
        rare.lefts[at..].fill(side + stack.len());
        Summary {
            opens: rare.opens,
            next,
            rights: stack,
            lefts: rare.lefts,
            fixes: rare.fixes,
        }
    }

    /// Stage 2: the states at every piece's borders, from the summaries.
    fn borders(&self, summaries: &[Summary]) -> Vec<Borders<T>> {
        let side = self.table.side;
        let mut outside = Vec::with_capacity(summaries.len());
        // The right-context state, from the word's end leftwards.
        let (mut next, mut stack) = (self.none, Vec::<T>::new());
        for s in summaries.iter().rev() {
            outside.push(
                (0..=s.opens)
                    .map(|j| resolve(side + j, side, next, &stack))
                    .collect::<Vec<T>>(),
            );
            let pushed: Vec<T> = s
                .rights
                .iter()
                .map(|&v| resolve(v, side, next, &stack))
                .collect();
            next = resolve(s.next, side, next, &stack);
            stack.truncate(stack.len().saturating_sub(s.opens));
            stack.extend(pushed);
        }
        outside.reverse();
        // The left-context state, from the word's start rightwards.
        let mut left = self.left();
        let mut borders = Vec::with_capacity(summaries.len());
        for (s, outside) in summaries.iter().zip(outside) {
            let keep = left.stack.len().saturating_sub(s.rights.len());
            let at = |v: Val| resolve(v, side, left.last, &left.stack);
            let last = at(s.lefts[0]);
            let pushed: Vec<T> = s.lefts[1..].iter().rev().map(|&v| at(v)).collect();
            borders.push(Borders {
                left: Left {
                    last: left.last,
                    stack: left.stack[keep..].to_vec(),
                },
                outside,
            });
            left.last = last;
            left.stack.truncate(keep);
            left.stack.extend(pushed);
        }
        borders
    }

    /// Stage 3 for one piece: its right neighbours from outside filled in,
    /// then its rewriting into `region` and, past it, `spill`; how many
    /// symbols went into `region`.
    #[allow(clippy::too_many_arguments)]
    fn finish(
        &self,
        w: &mut [T],
        right: &mut [T],
        summary: &Summary,
        borders: Borders<T>,
        dest: (&mut [T], &mut Vec<T>),
        draws: Draws,
        (max, total): (usize, &AtomicUsize),
    ) -> Result<usize, ()> {
        let rclass = &self.table.right;
        let shift = self.packed_shift.unwrap_or(0);
        let side = self.table.side;
        let packed = self.packed_shift.is_some();
        match &summary.fixes {
            Some(fixes) => {
                for &(i, v) in fixes {
                    let after = rclass[borders.outside[v - side].index()] as usize;
                    if packed {
                        w[i] = T::from_index(w[i].index() | after << shift);
                    } else {
                        right[i] = T::from_index(after);
                    }
                }
            }
            None => self.rescan(w, right, &borders.outside),
        }
        let (left, total) = (&mut { borders.left }, Some(total));
        let done = match packed {
            true => self.rewrite::<true>(w, right, dest, draws, max, left, total),
            false => self.rewrite::<false>(w, right, dest, draws, max, left, total),
        };
        if packed {
            let low = (1 << shift) - 1;
            for s in w.iter_mut() {
                *s = T::from_index(s.index() & low);
            }
        }
        done
    }

    /// The leftwards pass over piece `w` again, from the exact state at its
    /// end (`outside`: the nearest visible symbol, then the values its
    /// unmatched `[`s pop), for a piece with too many positions to list.
    fn rescan(&self, w: &mut [T], right: &mut [T], outside: &[T]) {
        let (class, rclass, none) = (&self.table.class[..], &self.table.right[..], self.none);
        let shift = self.packed_shift.unwrap_or(0);
        let low = (1 << shift) - 1;
        let packed = self.packed_shift.is_some();
        let mut next = outside[0];
        let mut stack: Vec<T> = outside[1..].iter().rev().copied().collect();
        for i in (0..w.len()).rev() {
            let s = if packed {
                T::from_index(w[i].index() & low)
            } else {
                w[i]
            };
            let after = rclass[next.index()] as usize;
            if packed {
                w[i] = T::from_index(s.index() | after << shift);
            } else {
                right[i] = T::from_index(after);
            }
            Self::pass_leftwards(class, none, s, &mut next, &mut stack);
        }
    }
}

/// Moves each piece's rewriting up against the one before it: piece `k`'s
/// `parts[k].0` symbols at `places[k]` in `out`, then its spill
/// `parts[k].1`; `out` cut to them all.
///
/// A piece moves left (towards the word's start) unless earlier pieces
/// spilled. The pieces moving left are moved first, from the word's start
/// on, and those moving right then, from its end back, each a `memmove`:
/// no piece is written over before it is moved, as its place starts past
/// the end of every earlier piece's new place and its new place lies past
/// the end of every earlier piece's place. The spills go last, into what
/// is left between the pieces.
fn lay_out<T: Copy>(out: &mut Vec<T>, places: &[usize], parts: &[(usize, Vec<T>)]) {
    let mut len = 0;
    let starts: Vec<usize> = (parts.iter())
        .map(|(used, spill)| {
            len += used + spill.len();
            len - used - spill.len()
        })
        .collect();
    if let Some(&fill) = parts.iter().find_map(|(_, spill)| spill.first()) {
        out.resize(out.len().max(len), fill);
    }
    let moves = || (0..parts.len()).map(|k| (places[k], parts[k].0, starts[k]));
    for (from, used, to) in moves().filter(|&(from, _, to)| to <= from) {
        out.copy_within(from..from + used, to);
    }
    for (from, used, to) in moves().rev().filter(|&(from, _, to)| to > from) {
        out.copy_within(from..from + used, to);
    }
    for ((used, spill), to) in parts.iter().zip(&starts) {
        out[to + used..][..spill.len()].copy_from_slice(spill);
    }
    out.truncate(len);
}

/// `w` cut at `bounds` (its first 0, its last `w.len()`).
fn cut<'w, T>(mut w: &'w mut [T], bounds: &[usize]) -> Vec<&'w mut [T]> {
    let mut pieces = Vec::with_capacity(bounds.len() - 1);
    for pair in bounds.windows(2) {
        let (piece, rest) = std::mem::take(&mut w).split_at_mut(pair[1] - pair[0]);
        pieces.push(piece);
        w = rest;
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::super::Split;
    use crate::diagnostics::Diagnostic;
    use crate::eval::{DeriveOptions, Deriver};
    use crate::front::pfg::read_ok as sys;
    use crate::ir::{SymbolId, System, Word};

    /// Splits every word of at least `from` symbols into pieces of at
    /// least `piece`.
    fn split(from: usize, piece: usize) -> Split {
        Split {
            from,
            piece,
            place: None,
        }
    }

    /// The words of `s` in bytes on `threads` threads, with right
    /// neighbours `packed` in the symbols or not.
    fn bytes(
        s: &System,
        opts: &DeriveOptions,
        threads: usize,
        split: Split,
        packed: bool,
    ) -> Result<Vec<u8>, Diagnostic> {
        let d = Deriver::new(s);
        let t = d.table.as_ref().expect("a table system");
        let mut stepper = t.stepper::<u8>().on(threads);
        stepper.split = split;
        if !packed {
            stepper.packed_shift = None;
        }
        d.steps(&stepper, opts, |_, _| {}).map(|(w, _)| w)
    }

    fn general(s: &System, opts: &DeriveOptions) -> Vec<u8> {
        let d = Deriver {
            table: None,
            ..Deriver::new(s)
        };
        let w = d.derive_stepwise(opts, |_, _| {}).unwrap();
        w.0.iter().map(|s| s.0 as u8).collect()
    }

    #[test]
    fn pieces_give_the_one_thread_words_of_the_stdlib() {
        for (name, n) in [("a", 45), ("b", 40), ("c", 42), ("d", 38), ("e", 43)] {
            let s = sys(crate::stdlib::get(&format!("hogeweg-hesper-{name}"))
                .unwrap()
                .text);
            let opts = DeriveOptions::new(n);
            let one = bytes(&s, &opts, 1, Split::default(), true).unwrap();
            assert!(one.len() > 200_000, "{name}: {}", one.len());
            assert_eq!(one, general(&s, &opts), "{name}");
            for threads in [2, 3, 7] {
                for packed in [true, false] {
                    let many = bytes(&s, &opts, threads, split(1 << 12, 1 << 8), packed);
                    assert!(many.unwrap() == one, "{name}, {threads} threads, {packed}");
                }
            }
        }
        // Past the threshold as it is: the last steps cut in two.
        let s = sys(crate::stdlib::get("hogeweg-hesper-a").unwrap().text);
        let opts = DeriveOptions::new(50);
        let two = bytes(&s, &opts, 2, Split::default(), true).unwrap();
        assert!(two.len() > 2 * Split::default().from, "{}", two.len());
        assert!(two == bytes(&s, &opts, 1, Split::default(), true).unwrap());
        // Symbols four bytes wide, cut into pieces as well.
        let d = Deriver::new(&s);
        let wide = d.table.as_ref().unwrap().stepper::<SymbolId>().on(3);
        let wide = wide.split(split(1 << 12, 1 << 8));
        let wide = d
            .steps(&wide, &DeriveOptions::new(45), |_, _| {})
            .unwrap()
            .0;
        let want = bytes(&s, &DeriveOptions::new(45), 1, Split::default(), true).unwrap();
        assert!(wide.iter().map(|s| s.0 as u8).eq(want));
    }

    #[test]
    fn the_symbol_limit_fails_the_same_step_on_any_threads() {
        let s = sys(crate::stdlib::get("hogeweg-hesper-c").unwrap().text);
        let lens: Vec<usize> = (30..36)
            .map(|n| {
                let opts = DeriveOptions::new(n);
                bytes(&s, &opts, 1, Split::default(), true).unwrap().len()
            })
            .collect();
        let at = |threads, max: usize| {
            let opts = DeriveOptions::new(40).max_symbols(max);
            let e = bytes(&s, &opts, threads, split(1, 1), true).unwrap_err();
            (e.message, e.notes)
        };
        for (k, &len) in lens.iter().enumerate() {
            let step = 30 + k as u64;
            // A word of exactly the limit is allowed; one more symbol is
            // not.
            let ok = DeriveOptions::new(step).max_symbols(len);
            let over = DeriveOptions::new(step).max_symbols(len - 1);
            for threads in [2, 3, 7] {
                assert_eq!(
                    bytes(&s, &ok, threads, split(1, 1), true).unwrap().len(),
                    len
                );
                let e = bytes(&s, &over, threads, split(1, 1), false).unwrap_err();
                assert_eq!(e.code, crate::diagnostics::codes::TOO_MANY_SYMBOLS);
                assert_eq!(at(threads, len - 1), at(1, len - 1), "{threads} threads");
            }
        }
    }

    /// Stochastic productions, one with a context: their choices are keyed
    /// by place in the word, so pieces of any size choose as one thread
    /// does and as the general matcher does, and each seed gives its own
    /// word.
    #[test]
    fn stochastic_choices_in_pieces_are_those_of_one_thread() {
        let bush = crate::stdlib::get("stochastic-bush").unwrap().text;
        let with_context = "axiom: F\nignore: +-\nF < F --> F[+F]F : 0.5\nF < F --> F[-F] : 0.5\n\
                            F --> FF[+F] : 0.6\nF --> F[-F]F : 0.4\n";
        for src in [bush, with_context] {
            let s = sys(src);
            let words: Vec<Vec<u8>> = (0..3)
                .map(|seed| {
                    let opts = DeriveOptions::new(6).seed(seed);
                    let one = bytes(&s, &opts, 1, Split::default(), true).unwrap();
                    assert!(one.len() > 500, "{}", one.len());
                    assert_eq!(one, general(&s, &opts), "{src}");
                    for threads in [2, 3, 7] {
                        for packed in [true, false] {
                            let many =
                                bytes(&s, &opts, threads, split(1, 1 + seed as usize), packed);
                            assert!(many.unwrap() == one, "{src}: {threads} threads, {packed}");
                        }
                    }
                    one
                })
                .collect();
            assert!(words[0] != words[1] && words[1] != words[2], "{src}");
        }
    }

    /// A little generator of test cases (xorshift), so that the loop below
    /// needs no crate.
    struct Xorshift(u64);

    impl Xorshift {
        fn below(&mut self, n: usize) -> usize {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 % n as u64) as usize
        }
    }

    /// Random systems with one-symbol contexts, brackets and an ignored
    /// symbol, from random words with unmatched brackets too, cut into
    /// pieces of one symbol and more: the words of one thread.
    #[test]
    fn random_bracketed_words_in_many_pieces_give_the_one_thread_words() {
        let mut rng = Xorshift(0x9e37_79b9_7f4a_7c15);
        let pick = |rng: &mut Xorshift, from: &str| {
            let b = from.as_bytes();
            b[rng.below(b.len())] as char
        };
        for case in 0..300 {
            let mut src = String::from("axiom: a\nignore: +\n");
            for _ in 0..1 + rng.below(5) {
                let succ: String = ["a[", "b]", "+", "a", "[b]", "[+a]"][..]
                    .iter()
                    .filter(|_| rng.below(2) == 0)
                    .copied()
                    .collect();
                let (l, p, r) = (
                    pick(&mut rng, "ab+*"),
                    pick(&mut rng, "ab+"),
                    pick(&mut rng, "ab+*"),
                );
                let succ = if succ.is_empty() {
                    "*".into()
                } else {
                    crate::eval::tests::balanced(&succ)
                };
                src.push_str(&format!("{l} < {p} > {r} --> {succ}\n"));
            }
            let mut d = crate::diagnostics::Diagnostics::default();
            let mut s = crate::front::pfg::read(&src, &mut d).system;
            assert!(!d.has_errors(), "{src}");
            let a = s.symbols.get("a").unwrap();
            let ids: Vec<SymbolId> = ["a", "b", "+"]
                .iter()
                .map(|c| s.symbols.get(c).unwrap_or(a))
                .chain([SymbolId::OPEN, SymbolId::CLOSE])
                .collect();
            let axiom: Vec<SymbolId> = (0..1 + rng.below(40)).map(|_| ids[rng.below(5)]).collect();
            s.axiom = Word::from(axiom);
            let opts = DeriveOptions::new(1 + rng.below(5) as u64).max_symbols(20_000);
            let one = bytes(&s, &opts, 1, Split::default(), true);
            for threads in [2, 3, 7] {
                for packed in [true, false] {
                    // Places that hold some pieces' rewritings and not
                    // others' (which then spill), every other case.
                    let place = (case % 2 == 1).then(|| rng.below(200));
                    let piece = 1 + rng.below(4);
                    let cut = Split {
                        place,
                        ..split(1, piece)
                    };
                    let many = bytes(&s, &opts, threads, cut, packed);
                    assert!(
                        many.as_ref().ok() == one.as_ref().ok(),
                        "case {case}: {src}"
                    );
                }
            }
        }
    }

    /// A piece with more positions whose right neighbour lies past it than
    /// are listed is scanned again: the same words.
    #[test]
    fn long_runs_without_a_visible_symbol_are_scanned_again() {
        let plus = "+".repeat(3 * super::FIXES);
        // The second: a piece ending in the run inside two branches, whose
        // `a`s see past the inner branch (`b`) and past the outer (`a`).
        for (axiom, steps) in [
            (format!("a{plus}b[{plus}a{plus}]{plus}"), 6),
            (format!("a[a[{plus}]b]a"), 2),
        ] {
            let src = format!("axiom: {axiom}\nignore: +\na > b --> ab\nb < a --> b\n");
            let s = sys(&src);
            let opts = DeriveOptions::new(steps);
            let one = bytes(&s, &opts, 1, Split::default(), true).unwrap();
            for threads in [2, 3, 7] {
                for packed in [true, false] {
                    let many = bytes(&s, &opts, threads, split(1, 1), packed).unwrap();
                    assert!(many == one, "{threads} threads, {packed}");
                }
            }
            assert!(one == general(&s, &opts));
        }
    }

    /// Pieces laid out from places of any size, some moving left and some
    /// right, some spilling: their rewritings one after another.
    #[test]
    fn pieces_laid_out_follow_each_other_whichever_way_they_move() {
        let mut rng = Xorshift(0x2545_f491_4f6c_dd1d);
        let (mut lefts, mut rights) = (0, 0);
        for _ in 0..2000 {
            let pieces = 1 + rng.below(6);
            let mut places = vec![0];
            let mut out = Vec::new();
            let mut parts = Vec::new();
            let mut want = Vec::new();
            for k in 0..pieces {
                let size = rng.below(12);
                let used = rng.below(size + 1);
                let spill: Vec<u32> = (0..[0, 0, rng.below(9)][rng.below(3)])
                    .map(|i| (k * 1000 + 500 + i) as u32)
                    .collect();
                let region: Vec<u32> = (0..size).map(|i| (k * 1000 + i) as u32).collect();
                want.extend_from_slice(&region[..used]);
                want.extend_from_slice(&spill);
                out.extend_from_slice(&region);
                places.push(out.len());
                let to = want.len() - used - spill.len();
                (lefts, rights) = match to <= places[k] {
                    true => (lefts + 1, rights),
                    false => (lefts, rights + 1),
                };
                parts.push((used, spill));
            }
            super::lay_out(&mut out, &places, &parts);
            assert_eq!(out, want, "{places:?}");
        }
        assert!(lefts > 1000 && rights > 1000, "{lefts} {rights}");
    }
}
