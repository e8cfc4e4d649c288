//! Where each symbol of a derived word was written: the axiom position,
//! or the successor symbol of the production that last rewrote it. What
//! lets a picture point back at its source (the live page links a drawn
//! segment to the symbol that drew it).
//!
//! The word is derived by the general matcher with the same random draws
//! as [`Deriver::derive`], so the traced word is the word every other path
//! gives for the same seed.

use super::{ContextIndex, DeriveOptions, Deriver, Draws, Stepper};
use crate::diagnostics::Diagnostic;
use crate::ir::{SymbolId, System, Word};

/// Where a symbol of a derived word was written in the source.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// The axiom's symbol at this position.
    Axiom(usize),
    /// Symbol `symbol` of alternative `alternative` of production
    /// `production`'s successor.
    Successor {
        production: usize,
        alternative: usize,
        symbol: usize,
    },
}

/// What a rewriting step tells about the symbols it writes.
pub(super) trait Notes {
    /// The symbol at position `i` of the word was copied unchanged.
    fn kept(&mut self, i: usize);
    /// Alternative `alternative` of production `production` wrote its
    /// successor, `len` symbols.
    fn wrote(&mut self, production: u32, alternative: usize, len: usize);
}

/// Rewriting that keeps no notes.
impl Notes for () {
    #[inline(always)]
    fn kept(&mut self, _: usize) {}
    #[inline(always)]
    fn wrote(&mut self, _: u32, _: usize, _: usize) {}
}

/// Origins as numbers: the axiom's positions first, then every successor
/// symbol of every production and alternative in file order.
struct Codes {
    axiom: u32,
    /// `first[p][a]`: the code of alternative a of production p's first
    /// successor symbol.
    first: Vec<Vec<u32>>,
}

impl Codes {
    fn of(sys: &System) -> Self {
        let mut next = sys.axiom.len() as u32;
        let first = (sys.productions.iter())
            .map(|p| {
                (p.alternatives.iter())
                    .map(|a| {
                        let at = next;
                        next = next.saturating_add(a.successor.len() as u32);
                        at
                    })
                    .collect()
            })
            .collect();
        Codes {
            axiom: sys.axiom.len() as u32,
            first,
        }
    }

    fn origin(&self, code: u32) -> Origin {
        if code < self.axiom {
            return Origin::Axiom(code as usize);
        }
        // The last alternative whose first code is at or before `code`.
        let mut found = Origin::Axiom(0);
        for (p, alts) in self.first.iter().enumerate() {
            for (a, &at) in alts.iter().enumerate() {
                if at <= code {
                    found = Origin::Successor {
                        production: p,
                        alternative: a,
                        symbol: (code - at) as usize,
                    };
                }
            }
        }
        found
    }
}

/// The origins of the word being rewritten and of the one being written.
struct Noting<'c> {
    codes: &'c Codes,
    cur: &'c [u32],
    next: &'c mut Vec<u32>,
}

impl Notes for Noting<'_> {
    fn kept(&mut self, i: usize) {
        self.next.push(self.cur[i]);
    }
    fn wrote(&mut self, production: u32, alternative: usize, len: usize) {
        let at = self.codes.first[production as usize][alternative];
        self.next
            .extend((0..len as u32).map(|k| at.saturating_add(k)));
    }
}

/// What the traced stepper keeps between steps.
#[derive(Default)]
struct Traced {
    index: ContextIndex,
    /// The origin code of each symbol of the current word; empty before
    /// the first step (the axiom's own positions).
    origins: Vec<u32>,
    next: Vec<u32>,
}

/// The general matcher, noting the origin of every symbol it writes.
struct TracedStepper<'d, 'a> {
    deriver: &'d Deriver<'a>,
    codes: Codes,
}

impl Stepper for TracedStepper<'_, '_> {
    type Sym = SymbolId;
    type Scratch = Traced;

    fn step(
        &self,
        cur: &mut [SymbolId],
        t: &mut Traced,
        out: &mut Vec<SymbolId>,
        draws: Draws,
        max: usize,
    ) -> Result<(), ()> {
        let d = self.deriver;
        if d.contexts {
            t.index.build(cur, &d.ignored);
        }
        if t.origins.len() != cur.len() {
            t.origins = (0..cur.len() as u32).collect();
        }
        t.next.clear();
        let mut notes = Noting {
            codes: &self.codes,
            cur: &t.origins,
            next: &mut t.next,
        };
        d.step(cur, &t.index, out, draws, max, &mut notes)?;
        std::mem::swap(&mut t.origins, &mut t.next);
        Ok(())
    }
}

impl Deriver<'_> {
    /// [`Deriver::derive`]'s word with the origin of each of its symbols.
    pub fn derive_traced(&self, opts: &DeriveOptions) -> Result<(Word, Vec<Origin>), Diagnostic> {
        if self.sys.axiom.len() > opts.max_symbols {
            return Err(super::too_many(0, opts));
        }
        super::refuse_early(self.sys, opts)?;
        let stepper = TracedStepper {
            deriver: self,
            codes: Codes::of(self.sys),
        };
        let (word, traced) = self.steps(&stepper, opts, |_, _| {})?;
        let origins = if traced.origins.len() == word.len() {
            traced
                .origins
                .iter()
                .map(|&c| stepper.codes.origin(c))
                .collect()
        } else {
            // No step was taken: the axiom itself.
            (0..word.len()).map(Origin::Axiom).collect()
        };
        Ok((Word::from(word), origins))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::pfg::read_ok as sys;

    fn succ(production: usize, symbol: usize) -> Origin {
        Origin::Successor {
            production,
            alternative: 0,
            symbol,
        }
    }

    #[test]
    fn each_symbol_points_at_the_successor_symbol_that_wrote_it() {
        let s = sys("axiom: AB\nA --> AB\nB --> A\n");
        let (w, o) = Deriver::new(&s)
            .derive_traced(&DeriveOptions::new(1))
            .unwrap();
        assert_eq!(w.display(&s.symbols), "ABA");
        assert_eq!(o, vec![succ(0, 0), succ(0, 1), succ(1, 0)]);
    }

    #[test]
    fn unrewritten_symbols_keep_their_axiom_position() {
        let s = sys("axiom: xAy\nA --> AA\n");
        let d = Deriver::new(&s);
        let (_, o) = d.derive_traced(&DeriveOptions::new(3)).unwrap();
        assert_eq!(o.len(), 10);
        assert_eq!(
            (o[0], o[1], o[9]),
            (Origin::Axiom(0), succ(0, 0), Origin::Axiom(2))
        );
        let (_, o) = d.derive_traced(&DeriveOptions::new(0)).unwrap();
        assert_eq!(o, (0..3).map(Origin::Axiom).collect::<Vec<_>>());
    }

    #[test]
    fn the_traced_word_is_the_derived_word_with_contexts_and_chance() {
        for src in [
            "axiom: F\nF --> F[+F]F : 1\nF --> F[-F]F : 1\nF --> FF : 1\n",
            "axiom: baaaaaaa\nb < a --> b\nb --> a\n",
        ] {
            let s = sys(src);
            let d = Deriver::new(&s);
            for seed in 0..5 {
                let opts = DeriveOptions::new(6).seed(seed);
                let (w, o) = d.derive_traced(&opts).unwrap();
                assert_eq!(w, super::super::derive(&s, &opts).unwrap(), "{src}");
                assert_eq!(o.len(), w.len());
            }
        }
    }
}
