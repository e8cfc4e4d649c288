//! The shortest word a derivation can make, known before deriving.
//!
//! For every symbol, the set of words it may become in one step is read off
//! the productions: the successors of every alternative of every production
//! that may apply to it, and the symbol itself when none need apply (all of
//! its productions have contexts or conditions, or it is guarded). Taking at
//! every symbol the choice that leads to the shortest word after `k` more
//! steps gives a lower bound on the length of step `k`'s word, whatever the
//! random draws, contexts and conditions turn out to be. When that bound
//! already passes `--max-symbols`, the derivation is refused before any of
//! it is done (a stochastic bush at 60 steps, a module system whose every
//! production grows), instead of after building a word of the limit's size.
//!
//! The bound is exact for context-free deterministic systems (which the
//! shared tree already sizes) and can be 1 per symbol for systems whose
//! growth depends on context (a signal travelling through a word): those
//! are stopped by the check inside each step, as soon as the word being
//! built passes the limit.

use crate::ir::{Production, RulePolicy, SymbolId, System};

/// The most symbol visits spent on the bound: the recurrence stops (and
/// refuses nothing) past this, so a slowly growing system over very many
/// steps costs at most a few milliseconds here.
const BUDGET: u64 = 1 << 24;

/// The first step (1-based, at most `steps`) whose word is longer than
/// `max` whatever choices the derivation makes, or `None` when no step is
/// known to be (or the system has a shape the bound does not cover:
/// predecessors of several symbols, decomposition rules or a cut, which
/// can shorten the word in ways the productions alone do not tell).
pub(super) fn first_step_over(sys: &System, steps: u64, max: usize) -> Option<u64> {
    let cap = max as u128 + 1;
    let mut step = 0;
    for shortest in shortest_words(sys, steps, |_| 1, cap)? {
        step += 1;
        if shortest > max as u128 {
            return Some(step);
        }
    }
    None
}

/// The fewest symbols counted by `weight` (1 for every symbol: the
/// length; 1 for the symbols that move the turtle: the moves) that the word
/// of step `steps` can have, or `None` when that is not known.
pub fn fewest_at(
    sys: &System,
    steps: u64,
    weight: impl Fn(SymbolId) -> u128,
    cap: u128,
) -> Option<u128> {
    let mut bounds = shortest_words(sys, steps, weight, cap)?;
    let last = bounds.by_ref().last();
    // The recurrence stops early at a fixed point (the same from then on)
    // or when its budget is spent (nothing is known then).
    bounds.fixed().then_some(last).flatten()
}

/// For steps 1, 2, … up to `steps`: the weighted length (capped at `cap`)
/// below which no derivation of `sys` can make that step's word, each
/// symbol counting `weight(symbol)`. It ends early at a fixed point of the
/// recurrence (no later step is known to be longer) or when [`BUDGET`] is
/// spent.
fn shortest_words(
    sys: &System,
    steps: u64,
    weight: impl Fn(SymbolId) -> u128,
    cap: u128,
) -> Option<Shortest<'_>> {
    let outcomes = Outcomes::of(sys)?;
    let cost = outcomes.size() + sys.axiom.len() as u64;
    let shortest: Vec<u128> = (0..sys.symbols.len())
        .map(|s| weight(SymbolId(s as u32)).min(cap))
        .collect();
    Some(Shortest {
        next: vec![0; shortest.len()],
        shortest,
        outcomes,
        axiom: &sys.axiom.0,
        steps_left: steps.min(BUDGET / cost.max(1)),
        complete: steps <= BUDGET / cost.max(1),
        fixed: false,
        cap,
    })
}

/// The iterator of [`shortest_words`].
struct Shortest<'a> {
    outcomes: Outcomes<'a>,
    axiom: &'a [SymbolId],
    /// Per symbol: its fewest weighted symbols after the steps so far.
    shortest: Vec<u128>,
    next: Vec<u128>,
    steps_left: u64,
    /// Whether the budget covers every step asked for.
    complete: bool,
    fixed: bool,
    cap: u128,
}

impl Shortest<'_> {
    /// Whether the steps not yielded are known: every step was yielded
    /// within the budget, or a fixed point makes them all the same.
    fn fixed(&self) -> bool {
        self.fixed || (self.complete && self.steps_left == 0)
    }
}

impl Iterator for Shortest<'_> {
    type Item = u128;

    fn next(&mut self) -> Option<u128> {
        if self.fixed || self.steps_left == 0 {
            return None;
        }
        self.steps_left -= 1;
        let (shortest, cap) = (&self.shortest, self.cap);
        for (s, slot) in self.next.iter_mut().enumerate() {
            let stays = self.outcomes.may_stay[s].then_some(shortest[s]);
            *slot = self.outcomes.words[s]
                .iter()
                .map(|w| w.iter().map(|t| shortest[t.index()]).sum::<u128>().min(cap))
                .chain(stays)
                .min()
                .unwrap_or(shortest[s]);
        }
        self.fixed = self.next == self.shortest;
        std::mem::swap(&mut self.shortest, &mut self.next);
        let total = self
            .axiom
            .iter()
            .map(|s| self.shortest[s.index()])
            .sum::<u128>();
        Some(total.min(cap))
    }
}

/// What each symbol may become in one step.
struct Outcomes<'a> {
    /// `words[s]`: the successors symbol `s` may be replaced by…
    words: Vec<Vec<&'a [SymbolId]>>,
    /// …and whether it may also stay itself.
    may_stay: Vec<bool>,
}

impl<'a> Outcomes<'a> {
    fn of(sys: &'a System) -> Option<Self> {
        if !sys.decomposition.productions.is_empty() || sys.cut.is_some() {
            return None;
        }
        let n = sys.symbols.len();
        let mut words: Vec<Vec<&[SymbolId]>> = vec![Vec::new(); n];
        // A symbol stays itself unless a production always applies to it.
        let mut may_stay = vec![true; n];
        // Under first match, productions after one that always applies
        // are never reached.
        let mut settled = vec![false; n];
        for p in &sys.productions {
            let &[s] = p.predecessor.as_slice() else {
                return None;
            };
            if settled[s.index()] {
                continue;
            }
            words[s.index()].extend(p.alternatives.iter().map(|a| a.successor.0.as_slice()));
            if always_applies(p) {
                may_stay[s.index()] = false;
                settled[s.index()] = sys.policy == RulePolicy::FirstMatch;
            }
        }
        // A guarded symbol is rewritten as its base, or stays as it is.
        for (id, info) in sys.symbols.iter() {
            if let Some(g) = info.guard {
                words[id.index()] = words[g.base.index()].clone();
                may_stay[id.index()] = true;
            }
        }
        Some(Outcomes { words, may_stay })
    }

    /// The symbol visits of one step of the recurrence.
    fn size(&self) -> u64 {
        self.words
            .iter()
            .flatten()
            .map(|w| w.len() as u64 + 1)
            .sum::<u64>()
            + self.words.len() as u64
    }
}

fn always_applies(p: &Production) -> bool {
    !p.is_context_sensitive() && p.condition.is_none()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::{derive, DeriveOptions};
    use crate::front::pfg::read_ok as pfg;

    /// The bound at each step of `steps`, uncapped for these small words.
    fn bounds(sys: &System, steps: u64) -> Vec<u128> {
        shortest_words(sys, steps, |_| 1, u128::MAX)
            .map(|b| b.collect())
            .unwrap_or_default()
    }

    #[test]
    fn no_derivation_is_shorter_than_the_bound() {
        // Every pfg and LinF system of the stdlib, several seeds: the bound
        // is a lower bound of every word actually derived.
        let mut checked = 0;
        for e in crate::stdlib::ENTRIES {
            let sys = match e.file.rsplit('.').next() {
                Some("l") => pfg(e.text),
                Some("linf") => crate::front::linf::read_ok(e.text),
                _ => continue,
            };
            for (k, bound) in bounds(&sys, 6).into_iter().enumerate() {
                for seed in 0..3 {
                    let opts = DeriveOptions::new(k as u64 + 1)
                        .seed(seed)
                        .max_symbols(1 << 20);
                    let Ok(word) = derive(&sys, &opts) else {
                        continue;
                    };
                    assert!(
                        word.len() as u128 >= bound,
                        "{} step {}: {} < {bound}",
                        e.name,
                        k + 1,
                        word.len()
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 100, "only {checked} derivations compared");
    }

    #[test]
    fn every_choice_growing_is_refused_at_the_first_step_over() {
        // Fig. 3.16's bush: each alternative of F has at least three Fs and
        // three other symbols, so step k has at least 3·(step k-1) + 3.
        let sys =
            pfg("axiom: F\nF --> F[+F]F[-F]F : 0.33\nF --> F[+F]F : 0.33\nF --> F[-F]F : 0.34\n");
        assert_eq!(bounds(&sys, 4), vec![6, 21, 66, 201]);
        assert_eq!(first_step_over(&sys, 100, 65), Some(3));
        assert_eq!(first_step_over(&sys, 100, 66), Some(4));
        assert_eq!(first_step_over(&sys, 3, 66), None);
        let err = derive(&sys, &DeriveOptions::new(1000).max_symbols(10_000)).unwrap_err();
        assert!(
            err.notes
                .iter()
                .any(|n| n.contains("known before deriving")),
            "{err:?}"
        );
    }

    #[test]
    fn growth_that_context_decides_is_left_to_the_step() {
        // A symbol whose only production has a context may stay itself.
        let sys = pfg("axiom: AB\nA > B --> AAAA\n");
        assert_eq!(bounds(&sys, 3), vec![2]);
        assert_eq!(first_step_over(&sys, 1000, 2), None);
        // hh-a: a signal decides where it grows.
        let hh = crate::stdlib::get("hogeweg-hesper-a").unwrap();
        assert_eq!(first_step_over(&pfg(hh.text), 1000, 100), None);
    }

    #[test]
    fn a_guarded_symbol_may_stay() {
        let sys = crate::front::linf::read_ok("lines f\naxiom 0.5?f\nrules f = fff\n");
        assert_eq!(first_step_over(&sys, 50, 10), None);
    }

    #[test]
    fn conditions_and_weighted_choice_in_module_systems() {
        let cpfg = crate::front::cpfg::read_ok;
        let grows = cpfg("Lsystem: 1\nAxiom: A(0)\nA(x) --> A(x+1)A(x)\nendlsystem\n");
        assert_eq!(first_step_over(&grows, 40, 1000), Some(10));
        let conditional =
            cpfg("Lsystem: 1\nAxiom: A(0)\nA(x) : x < 5 --> A(x+1)A(x)\nendlsystem\n");
        assert_eq!(first_step_over(&conditional, 40, 1000), None);
    }

    #[test]
    fn fewest_counts_only_the_weighted_symbols_and_knows_fixed_points() {
        let sys = pfg("axiom: A\nA --> AB\nB --> B\n");
        let b = sys.symbols.get("B").unwrap();
        let is_b = |s: SymbolId| u128::from(s == b);
        // A grows one B per step, forever: step k has k Bs.
        assert_eq!(fewest_at(&sys, 5, is_b, u128::MAX), Some(5));
        // Past the budget nothing is known…
        assert_eq!(fewest_at(&sys, u64::MAX, is_b, u128::MAX), None);
        // …but a fixed point is known for every step.
        let still = pfg("axiom: AB\nA --> A\n");
        assert_eq!(fewest_at(&still, u64::MAX, |_| 1, u128::MAX), Some(2));
    }
}
