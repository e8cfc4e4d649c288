//! cpfg's sub-L-systems in the derivation: which L-system rewrites each
//! module of a word, followed along it as cpfg follows it (`generate.c`,
//! `CheckPred`): a call `?(n, s)` makes L-system `n` current for the
//! modules after it, `$` goes back to the caller.

use super::parametric::Group;
use crate::ir::{Phase, SubLsystem, SymbolId, System, TurtleOp, Word};

/// What a module does to the L-system that rewrites the modules after it
/// (cpfg's sub-L-systems).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Switch {
    Stay,
    /// `?(n, s)`: L-system `n` from here.
    Call,
    /// `$`: back to the L-system before the matching call.
    Return,
}

/// The main L-system (index 0) and its sub-L-systems: their labels, and
/// what each symbol does to which of them is current.
pub(super) struct Lsystems {
    labels: Vec<u32>,
    /// By symbol; empty when the system has no sub-L-systems, so a word is
    /// not scanned for calls that cannot change anything.
    switches: Vec<Switch>,
}

impl Lsystems {
    pub(super) fn of(sys: &System) -> Self {
        let labels = std::iter::once(sys.label)
            .chain(sys.sub_lsystems.iter().map(|s| s.label))
            .collect();
        let switches = if sys.sub_lsystems.is_empty() {
            Vec::new()
        } else {
            (0..sys.symbols.len())
                .map(|i| match sys.op(SymbolId(i as u32)) {
                    Some(TurtleOp::SubLsystemCall) => Switch::Call,
                    Some(TurtleOp::SubLsystemReturn) => Switch::Return,
                    _ => Switch::Stay,
                })
                .collect()
        };
        Lsystems { labels, switches }
    }

    /// The productions of `phase` of every L-system, in [`Self::labels`]'
    /// order, each with its depth.
    pub(super) fn phases<'p>(
        sys: &'p System,
        phase: impl Fn(&'p System) -> &'p Phase,
        sub: impl Fn(&'p SubLsystem) -> &'p Phase,
    ) -> Vec<(Group<'p>, u32)> {
        let n = sys.symbols.len();
        std::iter::once(phase(sys))
            .chain(sys.sub_lsystems.iter().map(sub))
            .map(|p| (Group::new(&p.productions, n), p.depth.max(1)))
            .collect()
    }

    pub(super) fn calls(&self) -> Calls<'_> {
        Calls {
            of: self,
            stack: Vec::new(),
        }
    }
}

/// Which L-system rewrites the module at hand, followed along a word as
/// cpfg follows it (`generate.c`, `CheckPred`): after the modules a
/// production consumed (or one copied), each call among them makes the
/// L-system it names current, each `$` goes back to the one before.
pub(super) struct Calls<'s> {
    of: &'s Lsystems,
    stack: Vec<usize>,
}

impl Calls<'_> {
    pub(super) fn current(&self) -> usize {
        self.stack.last().copied().unwrap_or(0)
    }

    /// Follows the modules `from..to` of `word`. A call naming no
    /// L-system keeps the current one (the front ends report the label);
    /// a `$` without its call is ignored, as cpfg ignores it.
    pub(super) fn pass(&mut self, word: &Word, from: usize, to: usize) {
        if self.of.switches.is_empty() {
            return;
        }
        for j in from..to.min(word.len()) {
            match self.of.switches.get(word.0[j].index()) {
                Some(Switch::Call) => {
                    let Some(&label) = word.args(j).first() else {
                        continue;
                    };
                    // cpfg truncates the label to an int.
                    let named = self
                        .of
                        .labels
                        .iter()
                        .position(|&l| f64::from(l) == label.trunc());
                    self.stack.push(named.unwrap_or(self.current()));
                }
                Some(Switch::Return) => {
                    self.stack.pop();
                }
                _ => {}
            }
        }
    }
}
