//! Evaluation: parallel rewriting of an IR [`System`], step by step, exactly
//! as the IR module documents (first match in file order, bracket-aware
//! contexts modulo the ignore set, weighted alternatives, guarded symbols).
//!
//! Randomness comes from one [`Rng`] (ChaCha8, a portable generator): the same
//! system, steps and seed give the same word on every machine. It is drawn
//! only where a choice is made, in word order.
//!
//! Growth is bounded: a step that would make the word longer than
//! [`DeriveOptions::max_symbols`] stops with [`codes::TOO_MANY_SYMBOLS`], and
//! a derivation that would rewrite more than [`DeriveOptions::max_work`]
//! symbols in all stops with [`codes::TOO_MUCH_WORK`], so no input can exhaust
//! memory or run without end.

mod rng;

pub use rng::Rng;

use crate::diagnostics::{codes, Diagnostic};
use crate::ir::{Guard, SymbolId, System, Word};

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
}

impl DeriveOptions {
    pub fn new(steps: u64) -> Self {
        DeriveOptions {
            steps,
            seed: 0,
            max_symbols: DEFAULT_MAX_SYMBOLS,
            max_work: 20 * DEFAULT_MAX_SYMBOLS as u64,
        }
    }
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
    /// Sets the symbol limit and a work limit proportional to it.
    pub fn max_symbols(mut self, max: usize) -> Self {
        self.max_symbols = max;
        self.max_work = 20 * max as u64;
        self
    }
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
        let ignored = (0..n).map(|i| sys.is_ignored(SymbolId(i as u32))).collect();
        let guards: Vec<Option<Guard>> = sys.symbols.iter().map(|(_, info)| info.guard).collect();
        let contexts = sys.productions.iter().any(|p| p.is_context_sensitive());
        let stochastic =
            sys.productions.iter().any(|p| p.is_stochastic()) || guards.iter().any(Option::is_some);
        Deriver {
            sys,
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

    /// Derives `opts.steps` steps from the axiom. `progress` is called after
    /// each step with the step number and the word's length.
    pub fn derive(
        &self,
        opts: &DeriveOptions,
        mut progress: impl FnMut(u64, usize),
    ) -> Result<Word, Diagnostic> {
        let mut rng = Rng::new(opts.seed);
        let mut cur = self.sys.axiom.0.clone();
        let mut next = Vec::with_capacity(cur.len() * 2);
        let mut matching = Vec::new();
        let mut work: u64 = 0;
        for step in 1..=opts.steps {
            work += cur.len() as u64;
            if work > opts.max_work {
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
            if self.contexts {
                bracket_matches(&cur, &mut matching);
            }
            next.clear();
            self.step(&cur, &matching, &mut next, &mut rng, opts.max_symbols)
                .map_err(|_| too_many(step, opts))?;
            progress(step, next.len());
            if !self.stochastic && next == cur {
                // A fixpoint: every further step gives the same word.
                break;
            }
            std::mem::swap(&mut cur, &mut next);
        }
        Ok(Word(cur))
    }

    fn step(
        &self,
        cur: &[SymbolId],
        matching: &[usize],
        out: &mut Vec<SymbolId>,
        rng: &mut Rng,
        max: usize,
    ) -> Result<(), ()> {
        let mut around = Around::default();
        let mut i = 0;
        while i < cur.len() {
            let mut sym = cur[i];
            if let Some(g) = self.guards[sym.index()] {
                if rng.next_f64() >= g.probability {
                    out.push(sym);
                    i += 1;
                    continue;
                }
                sym = g.base;
            }
            match self.find(cur, i, sym, matching, &mut around) {
                Some(pi) => {
                    let p = &self.sys.productions[pi as usize];
                    let alt = if p.alternatives.len() == 1 {
                        &p.alternatives[0]
                    } else {
                        let r = rng.next_f64();
                        let mut acc = 0.0;
                        let mut chosen = p.alternatives.last().expect("non-empty");
                        for a in &p.alternatives {
                            acc += a.weight;
                            if r < acc {
                                chosen = a;
                                break;
                            }
                        }
                        chosen
                    };
                    if out.len() + alt.successor.len() > max {
                        return Err(());
                    }
                    out.extend_from_slice(&alt.successor.0);
                    i += p.predecessor.len();
                }
                None => {
                    if out.len() >= max {
                        return Err(());
                    }
                    out.push(cur[i]);
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
        matching: &[usize],
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
                    self.walk_left(w, i, matching, &mut around.left);
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
                    self.walk_right(w, i + n, matching, &mut around.right);
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

    /// The visible symbols left of `i`, nearest first, up to the longest
    /// left context (the listing's `lcondiff`): ignored symbols and `[` are
    /// skipped (the parent branch is the left context of a child), and a
    /// whole branch `[...]` met from its right is skipped.
    fn walk_left(&self, w: &[SymbolId], i: usize, matching: &[usize], out: &mut Vec<SymbolId>) {
        out.clear();
        let mut j = i;
        while out.len() < self.max_left && j > 0 {
            let s = w[j - 1];
            if s == SymbolId::OPEN || self.ignored[s.index()] {
                j -= 1;
            } else if s == SymbolId::CLOSE {
                j = match matching.get(j - 1) {
                    Some(&open) if open < j - 1 => open,
                    _ => 0,
                };
            } else {
                out.push(s);
                j -= 1;
            }
        }
    }

    /// The visible symbols from `i` on, up to the longest right context (the
    /// listing's `rcondiff`): ignored symbols and whole branches `[...]` are
    /// skipped, and a `]` ends the search (nothing to the right inside this
    /// branch).
    fn walk_right(&self, w: &[SymbolId], i: usize, matching: &[usize], out: &mut Vec<SymbolId>) {
        out.clear();
        let mut j = i;
        while out.len() < self.max_right && j < w.len() {
            let s = w[j];
            if s == SymbolId::OPEN {
                j = match matching.get(j) {
                    Some(&close) if close > j && close != usize::MAX => close + 1,
                    _ => w.len(),
                };
            } else if s == SymbolId::CLOSE {
                break;
            } else if self.ignored[s.index()] {
                j += 1;
            } else {
                out.push(s);
                j += 1;
            }
        }
    }
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

/// `matching[i]` is the index of the bracket matching the one at `i` (for
/// unmatched ones: `usize::MAX`); other entries are unspecified.
fn bracket_matches(w: &[SymbolId], matching: &mut Vec<usize>) {
    matching.clear();
    matching.resize(w.len(), usize::MAX);
    let mut stack = Vec::new();
    for (i, &s) in w.iter().enumerate() {
        if s == SymbolId::OPEN {
            stack.push(i);
        } else if s == SymbolId::CLOSE {
            if let Some(open) = stack.pop() {
                matching[open] = i;
                matching[i] = open;
            }
        }
    }
}

/// Derives `opts.steps` steps of `sys`.
pub fn derive(sys: &System, opts: &DeriveOptions) -> Result<Word, Diagnostic> {
    Deriver::new(sys).derive(opts, |_, _| {})
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pfg::read_ok as sys;

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
    fn endless_steps_are_bounded() {
        // A cycle of period 2 never reaches a fixpoint.
        let s = sys("axiom: a\na --> b\nb --> a\n");
        let err = derive(&s, &DeriveOptions::new(u64::MAX).max_symbols(1000)).unwrap_err();
        assert_eq!(err.code, codes::TOO_MUCH_WORK);
        // A fixpoint ends early with the right word.
        let s = sys("axiom: a\na --> b\n");
        let w = derive(&s, &DeriveOptions::new(u64::MAX)).unwrap();
        assert_eq!(w.display(&s.symbols), "b");
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
}
