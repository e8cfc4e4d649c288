//! A step (a decomposition, a homomorphism) of a big word on several
//! threads, for the systems whose modules are each rewritten on their own:
//! the word is cut into pieces, each rewritten on a thread by a copy of the
//! machine (the same values, its own count of work), and the pieces'
//! rewritings joined in order.
//!
//! A module's rewriting reads the whole word (its contexts may lie in other
//! pieces) and the values the step started with, and nothing that another
//! module's rewriting changes, so the word is the one-thread word whatever
//! the number of pieces. The limits hold over the pieces together: the
//! work they did, added to what was done before, and the length of the
//! word they make.

use super::{Engine, Halt, Machine};
use crate::ir::program::{Expr, Stmt};
use crate::ir::{Production, RulePolicy, System, Word};
use std::ops::Range;

/// Modules from which a word is cut into pieces, and the fewest a piece
/// holds: shorter words are rewritten on one thread, whose start costs more
/// than they take. The unit tests cut words of two modules and more, so
/// that every derivation they run on several threads is cut.
const PIECES_FROM: usize = if cfg!(test) { 2 } else { 1 << 12 };

/// What a piece of a word is rewritten into: its modules, and (when asked)
/// the index in the word of the module each came from.
pub(super) type Onto<'o> = (&'o mut Word, Option<&'o mut Vec<u32>>);

/// Whether every module of a word rewritten by `phases` of `sys` may be
/// rewritten on its own, in any order, to the word rewriting them in order
/// gives: the system has one L-system (no calls to follow along the word),
/// takes the first production that applies (no draw for each module), and
/// every production rewrites one module into one successor by statements
/// and expressions that change nothing outside it (no random draw, no
/// global or array written).
pub(super) fn module_by_module<'s>(
    sys: &System,
    phases: impl IntoIterator<Item = &'s [Production]>,
) -> bool {
    sys.sub_lsystems.is_empty()
        && sys.policy == RulePolicy::FirstMatch
        && phases.into_iter().flatten().all(rewrites_alone)
}

/// Whether production `p` reads one module and changes nothing outside
/// its own rewriting.
fn rewrites_alone(p: &Production) -> bool {
    let quiet = |e: &Option<Expr>| e.as_ref().is_none_or(Expr::is_quiet);
    p.predecessor.len() == 1
        && p.alternatives.len() <= 1
        && Stmt::are_quiet(&p.before)
        && Stmt::are_quiet(&p.after)
        && quiet(&p.condition)
        && p.alternatives
            .iter()
            .all(|a| quiet(&a.computed_weight) && a.args.iter().flatten().all(Expr::is_quiet))
}

impl<'p> Machine<'p> {
    /// A copy of the machine to rewrite a piece of a word on another
    /// thread: the same values, and the work left to do counted from 0.
    fn fork(&self) -> Self {
        Machine {
            par: self.par,
            contours: self.contours,
            strings: self.strings.clone(),
            globals: self.globals.clone(),
            arrays: self.arrays.clone(),
            rng: self.rng.clone(),
            choice: None,
            drawn: None,
            spare: self.spare,
            run_seed: self.run_seed,
            work: 0,
            max_work: self.max_work.saturating_sub(self.work),
            stop: false,
            steps: self.steps,
        }
    }
}

impl<'a> Engine<'a> {
    /// `rewrite` of every module of `word`: in pieces on up to `threads`
    /// threads when the word is long enough (`threads` is 1 for a system
    /// whose modules are not rewritten [`module_by_module`]), else whole.
    /// The word made, and the origins of its modules when `origins`.
    pub(super) fn in_pieces<F>(
        &mut self,
        word: &Word,
        threads: usize,
        origins: bool,
        rewrite: F,
    ) -> Result<(Word, Vec<u32>), Halt>
    where
        F: Fn(&mut Engine<'a>, Range<usize>, Onto<'_>) -> Result<(), Halt> + Sync,
    {
        let n = word.len();
        let pieces = match threads > 1 && n >= PIECES_FROM {
            true => threads.min(n / PIECES_FROM).max(1),
            false => 1,
        };
        let run = |e: &mut Engine<'a>, range: Range<usize>| {
            let (mut out, mut from) = (Word::new(), Vec::new());
            rewrite(e, range, (&mut out, origins.then_some(&mut from))).map(|()| (out, from))
        };
        if pieces == 1 {
            return run(self, 0..n);
        }
        let bounds: Vec<usize> = (0..=pieces).map(|k| k * n / pieces).collect();
        let mut forks: Vec<Engine<'a>> = (1..pieces).map(|_| self.fork()).collect();
        let engines = std::iter::once(&mut *self).chain(forks.iter_mut());
        let ranges = bounds.windows(2).map(|b| b[0]..b[1]);
        let mut done =
            crate::parallel::on_own_threads(engines.zip(ranges), |(e, r)| run(e, r)).into_iter();
        let (mut out, mut from) = done.next().expect("one piece at least")?;
        for (fork, piece) in forks.iter().zip(done) {
            self.m.charge(fork.m.work)?;
            let (w, f) = piece?;
            out.append(&w);
            from.extend(f);
            if out.len() > self.max_symbols {
                return Err(Halt::Work);
            }
        }
        Ok((out, from))
    }

    /// A copy of the engine for a piece of a word on another thread.
    fn fork(&self) -> Self {
        Engine {
            m: self.m.fork(),
            matchers: self.matchers.clone(),
            current: 0,
            max_symbols: self.max_symbols,
            locals: Vec::new(),
            args: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{derive, homomorphism, Globals};
    use super::module_by_module;
    use crate::diagnostics::Diagnostic;
    use crate::eval::DeriveOptions;
    use crate::front::cpfg::read_ok;
    use crate::ir::{System, Word};

    /// Contexts across brackets, conditions, a production's own variables,
    /// a global set in `Start:` and read in productions, a decomposition
    /// and a homomorphism that multiply modules.
    const PLANT: &str = "Lsystem: 1
Start: {g = 2;}
derivation length: 9
ignore: + -
Axiom: A(1) B(0) [ A(2) ] B(1) A(3)
A(x) < B(y) > A(z) : y < 50 --> B(y+x+z)
A(x) : x < 5000 {k = x*g;} --> A(k) [+B(x)] -B(x+1)
B(y) > [ A(z) ] : 1 --> B(y*0.5+z)
decomposition
maximum depth: 3
B(y) : y > 10 --> B(y/2) B(y/2)
homomorphism
maximum depth: 2
A(x) --> F(x) [ +F(x/2) ]
B(y) --> f(y)
endlsystem
";

    fn derived(s: &System, opts: DeriveOptions) -> Result<(Word, Globals), Diagnostic> {
        derive(s, &opts, |_, _| {}, &mut |_, _, _| {})
    }

    #[test]
    fn words_in_pieces_are_the_words_of_one_thread() {
        let s = read_ok(PLANT);
        let phases = [&s.productions, &s.decomposition.productions];
        assert!(module_by_module(&s, phases.map(Vec::as_slice)));
        for steps in [0, 1, 4, 9] {
            let (one, values) = derived(&s, DeriveOptions::new(steps).threads(1)).unwrap();
            let drawn = homomorphism(&s, &one, &values, &DeriveOptions::new(0).threads(1));
            let drawn = drawn.unwrap();
            assert!(steps < 9 || (one.len() > 500 && drawn.0.len() > one.len()));
            for threads in [2, 3, 7] {
                let opts = DeriveOptions::new(steps).threads(threads);
                let (many, v) = derived(&s, opts).unwrap();
                assert_eq!(
                    (&many, &v),
                    (&one, &values),
                    "{steps} steps, {threads} threads"
                );
                let opts = DeriveOptions::new(0).threads(threads);
                assert_eq!(homomorphism(&s, &one, &values, &opts).unwrap(), drawn);
            }
        }
    }

    #[test]
    fn limits_stop_the_same_step_on_any_threads() {
        let s = read_ok(PLANT);
        let at = |max_symbols, max_work| {
            let opts = DeriveOptions::new(9).max_symbols(max_symbols);
            DeriveOptions { max_work, ..opts }
        };
        let len = derived(&s, at(usize::MAX, u64::MAX).threads(1))
            .unwrap()
            .0
            .len();
        // The least work the derivation needs, on one thread.
        let (mut lo, mut hi) = (0u64, 1 << 40);
        while lo + 1 < hi {
            let mid = lo + (hi - lo) / 2;
            match derived(&s, at(usize::MAX, mid).threads(1)) {
                Ok(_) => hi = mid,
                Err(_) => lo = mid,
            }
        }
        let fail = |opts: DeriveOptions| {
            let e = derived(&s, opts).unwrap_err();
            (e.code, e.message, e.notes)
        };
        for threads in [2, 3, 7] {
            for (symbols, work) in [(len - 1, u64::MAX), (len / 3, u64::MAX), (len, hi - 1)] {
                let one = fail(at(symbols, work).threads(1));
                assert_eq!(fail(at(symbols, work).threads(threads)), one);
            }
            let fits = derived(&s, at(len, hi).threads(threads)).unwrap();
            assert_eq!(fits.0.len(), len);
        }
    }

    #[test]
    fn rewritings_that_change_what_follows_stay_in_order() {
        let plant = |extra: &str| PLANT.replace("A(x) : x < 5000 {k = x*g;}", extra);
        let cut = |src: &str| {
            let s = read_ok(src);
            let phases = [&s.productions, &s.decomposition.productions];
            module_by_module(&s, phases.map(Vec::as_slice))
        };
        assert!(cut(&plant("A(x) : x < 5000 {k = x*g;}")));
        // A draw from the random stream, a global written, the derivation
        // stopped, a predecessor of two modules, a choice drawn for every
        // module.
        for changed in [
            plant("A(x) : x < ran(5000) {k = x*g;}"),
            plant("A(x) : x < 5000 {k = x*g; g = g + 1;}"),
            plant("A(x) : x < 5000 {k = x*g; stop(2);}"),
            PLANT.replace("B(y) > [ A(z) ] : 1", "B(y) A(z) : 1"),
            PLANT.replace("Lsystem: 1", "Lsystem: 1\nseed: 3"),
        ] {
            assert!(!cut(&changed), "{changed}");
        }
    }
}
