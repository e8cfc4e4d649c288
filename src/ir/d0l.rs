//! A context-free deterministic system (a D0L system) seen as one
//! successor per symbol: the shape in which derivation ([`crate::eval`])
//! and the turtle share identical subtrees of the derivation tree.

use super::{SymbolId, System};

/// The axiom and, for each symbol, what it becomes in one step.
#[derive(Clone, Debug)]
pub struct D0l<'a> {
    pub axiom: &'a [SymbolId],
    /// `successors[s]`: the successor of `s`, or `None` when no production
    /// rewrites `s` (it then stays itself at every step).
    pub successors: Vec<Option<&'a [SymbolId]>>,
}

impl<'a> D0l<'a> {
    /// `sys` as a D0L system, or `None` when it is not context-free and
    /// deterministic (contexts, several predecessor symbols, stochastic
    /// alternatives, guarded symbols, parameters).
    pub fn of(sys: &'a System) -> Option<Self> {
        if sys.rewrites_modules() || sys.symbols.iter().any(|(_, i)| i.guard.is_some()) {
            return None;
        }
        let mut successors: Vec<Option<&[SymbolId]>> = vec![None; sys.symbols.len()];
        for p in &sys.productions {
            if p.is_context_sensitive() || p.predecessor.len() != 1 || p.is_stochastic() {
                return None;
            }
            let alt = p.alternatives.first()?;
            let s = p.predecessor[0].index();
            // The first production in file order wins.
            if successors[s].is_none() {
                successors[s] = Some(&alt.successor.0);
            }
        }
        Some(D0l {
            axiom: &sys.axiom.0,
            successors,
        })
    }

    /// The symbols `s` becomes in one step, `None` when it stays itself.
    pub fn successor(&self, s: SymbolId) -> Option<&'a [SymbolId]> {
        self.successors[s.index()]
    }

    pub fn axiom(&self) -> &'a [SymbolId] {
        self.axiom
    }

    pub fn symbol_count(&self) -> usize {
        self.successors.len()
    }
}
