//! Module rewriting: systems whose productions bind parameters, test
//! conditions or run statements ([`crate::ir::System::rewrites_modules`]),
//! as the IR specifies: contexts matched with parameters, weighted choice
//! among applicable productions, `%` cuts, the decomposition phase after
//! each step, the homomorphism for drawing, and the program's statements
//! around the derivation.
//!
//! Bounds: the word is limited by [`DeriveOptions::max_symbols`], and all
//! work (modules rewritten, loop iterations, recursion) by
//! [`DeriveOptions::max_work`], so no model runs without end.

use super::sub_lsystems::Lsystems;
use super::DeriveOptions;
use std::ops::Range;

mod cut;
mod pieces;

use crate::diagnostics::{codes, Diagnostic};
use crate::ir::look::{Contour, ContourRole};
use crate::ir::program::{truth, BinOp, Builtin, Expr, Place, Program, Stmt, Var};
use crate::ir::Randomness;
use crate::ir::{
    Alternative, ContextFilter, Formals, Production, RulePolicy, SymbolId, System, Word,
};
use crate::random::{Lcg48, Rng, Stream};
use cut::cut;
pub use cut::cut_mask;

/// Why evaluation stopped early.
#[derive(Debug)]
enum Halt {
    /// The work budget ran out.
    Work,
}

/// The values of a program's globals and arrays. The derivation leaves
/// them for the homomorphism: in cpfg a global set in `Start:` (or in any
/// block or production) is seen wherever it is read, drawing included.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Globals {
    globals: Vec<f64>,
    arrays: Vec<Vec<f64>>,
}

impl Globals {
    /// The values before anything ran: globals 0, arrays as declared.
    pub fn initial(par: &Program) -> Self {
        Globals {
            globals: vec![0.0; par.globals.len()],
            arrays: par
                .arrays
                .iter()
                .map(|a| {
                    let n: usize = a.dims.iter().product();
                    let mut v = a.init.clone();
                    v.resize(n, 0.0);
                    v
                })
                .collect(),
        }
    }
}

/// The state of cpfg's `nran` between calls.
#[derive(Clone, Copy, Debug)]
enum Spare {
    /// Before any `srand`: cpfg's flag starts neither clear nor set, and
    /// its first call returns the (zero) kept deviate.
    Unstarted,
    /// No deviate kept: the next call draws a pair.
    None,
    Kept(f64),
}

/// Variables, arrays, the random stream and the work budget.
struct Machine<'p> {
    par: &'p Program,
    /// The curves `curveX` and `curveGAL` read.
    contours: &'p [Contour],
    /// The value of each string literal: its index among the system's.
    strings: std::collections::HashMap<&'p str, f64>,
    globals: Vec<f64>,
    arrays: Vec<Vec<f64>>,
    rng: Rng,
    /// cpfg's stream for choosing among productions (`drand48`), apart
    /// from `rng`; graftal's own choices draw from `rng`.
    choice: Option<Lcg48>,
    /// The number a cpfg module's choice uses, drawn before its
    /// productions are tried: cpfg draws one for every module of a
    /// stochastic step, whether a production applies or not.
    drawn: Option<f64>,
    /// cpfg's `nran` keeps the second deviate of each pair; `None` until
    /// `srand` (cpfg's first `nran` before any `srand` returns the mean).
    spare: Spare,
    run_seed: u64,
    work: u64,
    max_work: u64,
    stop: bool,
    steps: u64,
}

/// The most iterations of one loop statement.
const MAX_LOOP: u64 = 10_000_000;

impl<'p> Machine<'p> {
    /// The machine of `sys`'s program; its random stream starts from the
    /// run's seed plus the file's own.
    fn new(sys: &'p System, seed: u64, max_work: u64) -> Self {
        let par = &sys.program;
        let Globals { globals, arrays } = Globals::initial(par);
        let file_seed = seed.wrapping_add(sys.settings.seed.unwrap_or(0));
        // cpfg: `seed:` seeds only the choice of productions; expressions
        // draw from a stream `srand48(0)` started (the run's seed moves both).
        let (rng, choice) = match sys.settings.randomness {
            Randomness::Graftal => (Rng::new(file_seed, Stream::Derivation), None),
            Randomness::Cpfg => (
                Rng::Cpfg(Lcg48::srand48(seed as u32)),
                Some(Lcg48::cpfg_choice(file_seed)),
            ),
        };
        let strings = sys.strings().into_iter().enumerate();
        Machine {
            par,
            contours: &sys.contours,
            strings: strings.map(|(k, s)| (s, k as f64)).collect(),
            globals,
            arrays,
            rng,
            choice,
            drawn: None,
            spare: Spare::Unstarted,
            run_seed: seed,
            work: 0,
            max_work,
            stop: false,
            steps: 0,
        }
    }

    /// The values of the globals and arrays now.
    fn values(&self) -> Globals {
        Globals {
            globals: self.globals.clone(),
            arrays: self.arrays.clone(),
        }
    }

    /// Sets the globals and arrays to `g` (when `g` is of this program).
    fn set_values(&mut self, g: &Globals) {
        let fits = |a: &[Vec<f64>], b: &[Vec<f64>]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.len() == y.len())
        };
        if g.globals.len() == self.globals.len() && fits(&g.arrays, &self.arrays) {
            self.globals.clone_from(&g.globals);
            self.arrays.clone_from(&g.arrays);
        }
    }

    fn charge(&mut self, n: u64) -> Result<(), Halt> {
        self.work = self.work.saturating_add(n);
        if self.work > self.max_work {
            Err(Halt::Work)
        } else {
            Ok(())
        }
    }

    fn element(
        &mut self,
        a: u16,
        subs: &[Expr],
        locals: &mut [f64],
    ) -> Result<Option<usize>, Halt> {
        let dims = &self.par.arrays[a as usize].dims;
        let mut idx = 0usize;
        for (k, s) in subs.iter().enumerate() {
            let v = self.eval(s, locals)?;
            let d = dims.get(k).copied().unwrap_or(0);
            if !(v >= 0.0 && (v as usize) < d) {
                return Ok(None);
            }
            idx = idx * d + v as usize;
        }
        Ok(Some(idx))
    }

    fn eval(&mut self, e: &Expr, locals: &mut [f64]) -> Result<f64, Halt> {
        Ok(match e {
            Expr::Num(v) => *v,
            Expr::Str(s) => self.strings.get(s.as_str()).copied().unwrap_or(0.0),
            Expr::Var(Var::Local(i)) => locals.get(*i as usize).copied().unwrap_or(0.0),
            Expr::Var(Var::Global(i)) => self.globals.get(*i as usize).copied().unwrap_or(0.0),
            Expr::Element(a, subs) => match self.element(*a, subs, locals)? {
                Some(i) => self.arrays[*a as usize][i],
                None => 0.0,
            },
            Expr::Unary(op, a) => op.apply(self.eval(a, locals)?),
            // `&&` and `||` evaluate their right side only when needed.
            Expr::Binary(BinOp::And, x, y) => f64::from(u8::from(
                truth(self.eval(x, locals)?) && truth(self.eval(y, locals)?),
            )),
            Expr::Binary(BinOp::Or, x, y) => f64::from(u8::from(
                truth(self.eval(x, locals)?) || truth(self.eval(y, locals)?),
            )),
            Expr::Binary(op, x, y) => {
                let (x, y) = (self.eval(x, locals)?, self.eval(y, locals)?);
                op.apply(x, y)
            }
            Expr::Cond(c, x, y) => {
                if truth(self.eval(c, locals)?) {
                    self.eval(x, locals)?
                } else {
                    self.eval(y, locals)?
                }
            }
            Expr::Call(f, args) => {
                let mut v = [0.0f64; 2];
                for (k, a) in args.iter().enumerate() {
                    let x = self.eval(a, locals)?;
                    if k < 2 {
                        v[k] = x;
                    }
                }
                self.call(*f, v, args.len())
            }
        })
    }

    fn call(&mut self, f: Builtin, v: [f64; 2], n: usize) -> f64 {
        let [x, y] = v;
        if let Some(value) = f.pure(x, y) {
            return value;
        }
        match f {
            Builtin::Srand => {
                let seed = (x as i64 as u64).wrapping_add(self.run_seed);
                self.rng = match self.rng {
                    Rng::Cpfg(_) => Rng::Cpfg(Lcg48::srand48(seed as u32)),
                    Rng::Portable(_) => Rng::new(seed, Stream::Derivation),
                };
                self.spare = Spare::None;
                0.0
            }
            Builtin::Ran => x * self.rng.next_f64(),
            Builtin::Nran if matches!(self.rng, Rng::Cpfg(_)) => x + y * self.cpfg_normal(),
            Builtin::Nran => x + y * self.normal(),
            Builtin::Bran if matches!(self.rng, Rng::Cpfg(_)) => self.cheng_beta(x, y),
            Builtin::Bran => self.beta(x, y),
            Builtin::Biran => {
                let trials = x.clamp(0.0, 1e6) as u64;
                let _ = self.charge(trials);
                // cpfg counts the draws at or under p; graftal's own, under.
                let cpfg = matches!(self.rng, Rng::Cpfg(_));
                (0..trials)
                    .filter(|_| {
                        let u = self.rng.next_f64();
                        u < y || (cpfg && u == y)
                    })
                    .count() as f64
            }
            Builtin::Func => {
                let id = x as i64;
                match usize::try_from(id - 1)
                    .ok()
                    .and_then(|i| self.par.functions.get(i))
                {
                    Some(func) => func.eval(y),
                    None => 0.0,
                }
            }
            Builtin::CurveX | Builtin::CurveY | Builtin::CurveZ | Builtin::CurveGal => {
                self.curve(f, x, y)
            }
            // A derivation is cpfg's Run, where stop(1) draws and goes on.
            Builtin::Stop => {
                self.stop |= x != 1.0;
                0.0
            }
            Builtin::SetDerivationLength => {
                if x >= 0.0 && x.is_finite() {
                    self.steps = x as u64;
                }
                0.0
            }
            Builtin::GetDerivationLength => self.steps as f64,
            // The pure functions returned above; I/O and the view
            // volume are 0 (graftal performs no I/O for a model).
            _ => {
                let _ = n;
                0.0
            }
        }
    }

    /// `curveX(id, t)` and the like: 0 for a curve the system does not
    /// have (the front end reports the call).
    fn curve(&self, f: Builtin, id: f64, t: f64) -> f64 {
        let Some(c) = self
            .contours
            .iter()
            .find(|c| c.role == ContourRole::Curve && f64::from(c.id) == id)
        else {
            return 0.0;
        };
        match f {
            Builtin::CurveX => c.at(t)[0],
            Builtin::CurveY => c.at(t)[1],
            Builtin::CurveZ => c.at(t)[2],
            _ => c.length,
        }
    }

    /// A standard normal deviate (Box–Muller).
    fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.rng.next_f64();
        let u2 = self.rng.next_f64();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }

    /// cpfg's standard normal deviate (`utility.c`): Marsaglia's polar
    /// method, the second deviate of each pair kept for the next call.
    fn cpfg_normal(&mut self) -> f64 {
        match std::mem::replace(&mut self.spare, Spare::None) {
            Spare::Unstarted => return 0.0,
            Spare::Kept(g) => return g,
            Spare::None => {}
        }
        for _ in 0..1000 {
            let v1 = 2.0 * self.rng.next_f64() - 1.0;
            let v2 = 2.0 * self.rng.next_f64() - 1.0;
            let rsq = v1 * v1 + v2 * v2;
            if rsq < 1.0 && rsq != 0.0 {
                let fac = (-2.0 * rsq.ln() / rsq).sqrt();
                self.spare = Spare::Kept(v1 * fac);
                return v2 * fac;
            }
        }
        0.0
    }

    /// cpfg's Beta(a, b) deviate (`utility.c`): Cheng's algorithm BA.
    fn cheng_beta(&mut self, a: f64, b: f64) -> f64 {
        if !(a > 0.0 && b > 0.0) {
            return self.rng.next_f64();
        }
        let s = a + b;
        let lambda = if a.min(b) <= 1.0 {
            a.min(b)
        } else {
            ((2.0 * a * b - s) / (s - 2.0)).sqrt()
        };
        let u = a + lambda;
        let nonzero = |rng: &mut Rng| loop {
            let x = rng.next_f64();
            if x != 0.0 {
                break x;
            }
        };
        for _ in 0..10_000 {
            let u1 = nonzero(&mut self.rng);
            let u2 = nonzero(&mut self.rng);
            let v = (u1 / (1.0 - u1)).ln() / lambda;
            let y = a * v.exp();
            if s * (s / (b + y)).ln() + u * v - 4f64.ln() >= (u1 * u1 * u2).ln() {
                return y / (b + y);
            }
        }
        a / s
    }

    /// A Beta(a, b) deviate (Jöhnk's method; uniform for bad parameters).
    fn beta(&mut self, a: f64, b: f64) -> f64 {
        if !(a > 0.0 && b > 0.0) {
            return self.rng.next_f64();
        }
        for _ in 0..1000 {
            let x = self.rng.next_f64().powf(1.0 / a);
            let y = self.rng.next_f64().powf(1.0 / b);
            if x + y <= 1.0 && x + y > 0.0 {
                return x / (x + y);
            }
        }
        a / (a + b)
    }

    fn run(&mut self, stmts: &[Stmt], locals: &mut [f64]) -> Result<(), Halt> {
        for s in stmts {
            match s {
                Stmt::Assign(place, e) => {
                    let v = self.eval(e, locals)?;
                    match place {
                        Place::Var(Var::Local(i)) => {
                            if let Some(slot) = locals.get_mut(*i as usize) {
                                *slot = v;
                            }
                        }
                        Place::Var(Var::Global(i)) => {
                            if let Some(slot) = self.globals.get_mut(*i as usize) {
                                *slot = v;
                            }
                        }
                        Place::Element(a, subs) => {
                            if let Some(i) = self.element(*a, subs, locals)? {
                                self.arrays[*a as usize][i] = v;
                            }
                        }
                    }
                }
                Stmt::Eval(e) => {
                    self.eval(e, locals)?;
                }
                Stmt::If(c, t, e) => {
                    if truth(self.eval(c, locals)?) {
                        self.run(t, locals)?;
                    } else {
                        self.run(e, locals)?;
                    }
                }
                Stmt::While(c, body) => {
                    let mut n = 0;
                    while truth(self.eval(c, locals)?) {
                        self.run(body, locals)?;
                        n += 1;
                        self.charge(1)?;
                        if n >= MAX_LOOP {
                            return Err(Halt::Work);
                        }
                    }
                }
                Stmt::Do(body, c) => {
                    let mut n = 0;
                    loop {
                        self.run(body, locals)?;
                        n += 1;
                        self.charge(1)?;
                        if n >= MAX_LOOP {
                            return Err(Halt::Work);
                        }
                        if !truth(self.eval(c, locals)?) {
                            break;
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// A context: its symbols and their formal parameters.
type Patterns<'p> = (&'p [SymbolId], &'p [Vec<u16>]);

/// One module of a context pattern.
struct Pattern<'p> {
    symbol: SymbolId,
    params: &'p [u16],
}

/// Which productions to try for a symbol, and how context is matched.
#[derive(Clone)]
struct Matcher {
    ignored: Vec<bool>,
    /// What a right context reads past: `ignored`, and the brackets when
    /// the filter skips them ([`crate::ir::ContextFilter`]).
    ignored_on_the_right: Vec<bool>,
    ring: bool,
}

impl Matcher {
    fn is_ignored(&self, s: SymbolId) -> bool {
        self.ignored.get(s.index()).copied().unwrap_or(false)
    }

    fn is_ignored_on_the_right(&self, s: SymbolId) -> bool {
        self.ignored_on_the_right
            .get(s.index())
            .copied()
            .unwrap_or(false)
    }

    /// Binds the formal parameters `params` of a pattern module `symbol`
    /// to module `i` of `word`, which must be the same symbol with as many
    /// parameters.
    fn bind(word: &Word, i: usize, symbol: SymbolId, params: &[u16], locals: &mut [f64]) -> bool {
        if word.0[i] != symbol {
            return false;
        }
        let args = word.args(i);
        if args.len() != params.len() {
            return false;
        }
        for (slot, v) in params.iter().zip(args) {
            if let Some(l) = locals.get_mut(*slot as usize) {
                *l = *v;
            }
        }
        true
    }

    /// Left context ending just before module `i`.
    fn left(&self, word: &Word, i: usize, pats: Patterns<'_>, locals: &mut [f64]) -> bool {
        let n = word.len();
        let mut j = i; // next module to look at is j - 1
        let mut steps = 0;
        for (k, &symbol) in pats.0.iter().enumerate().rev() {
            let pat = Pattern {
                symbol,
                params: Formals::of(pats.1, k),
            };
            // A module the context filter does not see is not looked for
            // (cpfg's `consider:` applies to patterns as to words).
            if self.is_ignored(pat.symbol)
                && pat.symbol != SymbolId::OPEN
                && pat.symbol != SymbolId::CLOSE
            {
                continue;
            }
            loop {
                if j == 0 {
                    if self.ring && steps < n {
                        j = n;
                    } else {
                        return false;
                    }
                }
                j -= 1;
                steps += 1;
                if steps > 2 * n + 2 {
                    return false;
                }
                let s = word.0[j];
                if s == pat.symbol {
                    break;
                }
                if s == SymbolId::CLOSE {
                    // Skip the whole branch to its `[`.
                    let mut depth = 1;
                    while depth > 0 {
                        if j == 0 {
                            return false;
                        }
                        j -= 1;
                        if word.0[j] == SymbolId::CLOSE {
                            depth += 1;
                        } else if word.0[j] == SymbolId::OPEN {
                            depth -= 1;
                        }
                    }
                    continue;
                }
                if s == SymbolId::OPEN || self.is_ignored(s) {
                    continue;
                }
                return false;
            }
            if !Self::bind(word, j, pat.symbol, pat.params, locals) {
                return false;
            }
        }
        true
    }

    /// Right context starting at module `i`.
    fn right(&self, word: &Word, i: usize, pats: Patterns<'_>, locals: &mut [f64]) -> bool {
        let n = word.len();
        let mut j = i;
        let mut steps = 0;
        for (k, &symbol) in pats.0.iter().enumerate() {
            let pat = Pattern {
                symbol,
                params: Formals::of(pats.1, k),
            };
            if self.is_ignored(pat.symbol)
                && pat.symbol != SymbolId::OPEN
                && pat.symbol != SymbolId::CLOSE
            {
                continue;
            }
            if pat.symbol == SymbolId::CLOSE {
                // `]` in a right context: the rest of the current branch.
                let mut depth = 0usize;
                loop {
                    if j >= n {
                        return false;
                    }
                    let s = word.0[j];
                    if s == SymbolId::OPEN {
                        depth += 1;
                    } else if s == SymbolId::CLOSE {
                        if depth == 0 {
                            break;
                        }
                        depth -= 1;
                    }
                    j += 1;
                }
                j += 1;
                continue;
            }
            loop {
                if j >= n {
                    if self.ring && steps < n {
                        j = 0;
                    } else {
                        return false;
                    }
                }
                steps += 1;
                if steps > 2 * n + 2 {
                    return false;
                }
                let s = word.0[j];
                if s == pat.symbol {
                    break;
                }
                if self.is_ignored_on_the_right(s) {
                    j += 1;
                    continue;
                }
                if s == SymbolId::OPEN {
                    let mut depth = 1;
                    j += 1;
                    while depth > 0 {
                        if j >= n {
                            return false;
                        }
                        if word.0[j] == SymbolId::OPEN {
                            depth += 1;
                        } else if word.0[j] == SymbolId::CLOSE {
                            depth -= 1;
                        }
                        j += 1;
                    }
                    continue;
                }
                // `]` ends the branch; anything else seen is not the context.
                return false;
            }
            if !Self::bind(word, j, pat.symbol, pat.params, locals) {
                return false;
            }
            j += 1;
        }
        true
    }
}

/// The productions of a group, indexed by their first predecessor symbol.
pub(super) struct Group<'p> {
    pub(super) prods: &'p [Production],
    by_first: Vec<Vec<u32>>,
}

impl<'p> Group<'p> {
    pub(super) fn new(prods: &'p [Production], symbols: usize) -> Self {
        let mut by_first = vec![Vec::new(); symbols];
        for (k, p) in prods.iter().enumerate() {
            if let Some(first) = p.predecessor.first() {
                if let Some(v) = by_first.get_mut(first.index()) {
                    v.push(k as u32);
                }
            }
        }
        Group { prods, by_first }
    }
}

struct Engine<'a> {
    m: Machine<'a>,
    /// Each L-system's context matching ([`Lsystems::labels`]' order).
    matchers: Vec<Matcher>,
    /// The L-system rewriting now.
    current: usize,
    max_symbols: usize,
    locals: Vec<f64>,
    /// The parameters of the successor module being emitted.
    args: Vec<f64>,
}

impl Engine<'_> {
    /// Binds the strict predecessor of `p` at module `i` of `word` and
    /// matches its contexts in `ctx` around module `ctx_i`.
    fn matches(
        &mut self,
        p: &Production,
        (word, i): (&Word, usize),
        (ctx, ctx_i): (&Word, usize),
    ) -> bool {
        let len = p.predecessor.len();
        if i + len > word.len() {
            return false;
        }
        self.locals.clear();
        self.locals.resize(p.formals.locals as usize, 0.0);
        for (o, &symbol) in p.predecessor.iter().enumerate() {
            let params = Formals::of(&p.formals.predecessor, o);
            if !Matcher::bind(word, i + o, symbol, params, &mut self.locals) {
                return false;
            }
        }
        let ctx_end = if std::ptr::eq(word, ctx) {
            ctx_i + len
        } else {
            ctx_i + 1
        };
        let left = (p.left.as_slice(), p.formals.left.as_slice());
        let matcher = &self.matchers[self.current];
        if !p.left.is_empty() && !matcher.left(ctx, ctx_i, left, &mut self.locals) {
            return false;
        }
        let right = (p.right.as_slice(), p.formals.right.as_slice());
        !(!p.right.is_empty() && !matcher.right(ctx, ctx_end, right, &mut self.locals))
    }

    /// Tries the productions of `group` at module `i` of `word` (contexts
    /// are matched in `ctx.0` around module `ctx.1`). On success appends the
    /// successor to `out` and returns the number of modules consumed.
    fn apply(
        &mut self,
        group: &Group<'_>,
        at: (&Word, usize),
        context: (&Word, usize),
        choice: RulePolicy,
        out: &mut Word,
    ) -> Result<Option<usize>, Halt> {
        let Some(cands) = group.by_first.get(at.0 .0[at.1].index()) else {
            return Ok(None);
        };
        // Candidates: (production, alternative, weight, locals).
        let mut applicable: Vec<(u32, usize, f64, Vec<f64>)> = Vec::new();
        for &k in cands {
            let p = &group.prods[k as usize];
            self.m.charge(1)?;
            if !self.matches(p, at, context) {
                continue;
            }
            let mut locals = std::mem::take(&mut self.locals);
            self.m.run(&p.before, &mut locals)?;
            let pass = match &p.condition {
                None => true,
                Some(c) => truth(self.m.eval(c, &mut locals)?),
            };
            if !pass {
                self.locals = locals;
                continue;
            }
            if choice == RulePolicy::FirstMatch {
                let alt = self.alternative(p);
                self.emit(p, alt, &mut locals, out)?;
                self.locals = locals;
                return Ok(Some(p.predecessor.len()));
            }
            let last = p.alternatives.len().saturating_sub(1);
            for (a, alt) in p.alternatives.iter().enumerate() {
                let w = match &alt.computed_weight {
                    Some(e) => self.m.eval(e, &mut locals)?,
                    None => alt.weight,
                };
                // The locals go with the last alternative; earlier ones (a
                // production of several) get a copy.
                let mine = if a == last {
                    std::mem::take(&mut locals)
                } else {
                    locals.clone()
                };
                applicable.push((k, a, w.max(0.0), mine));
            }
        }
        if applicable.is_empty() {
            return Ok(None);
        }
        let weights: Vec<f64> = applicable.iter().map(|a| a.2).collect();
        let pick = self.pick(&weights);
        if pick >= applicable.len() {
            // cpfg: rounding left the draw above every probability; the
            // module stays as it is.
            return Ok(None);
        }
        let (k, a, _, mut locals) = applicable.swap_remove(pick);
        let p = &group.prods[k as usize];
        self.emit(p, &p.alternatives[a], &mut locals, out)?;
        Ok(Some(p.predecessor.len()))
    }

    /// An index drawn with probability proportional to `weights` (the
    /// last when they add up to nothing usable).
    fn pick(&mut self, weights: &[f64]) -> usize {
        if let Some(lcg) = &mut self.m.choice {
            let u = self.m.drawn.take().unwrap_or_else(|| lcg.next_f64());
            return Self::cpfg_pick_of(weights, u).unwrap_or(usize::MAX);
        }
        let total: f64 = weights.iter().sum();
        if total > 0.0 && total.is_finite() {
            let r = self.m.rng.next_f64() * total;
            let mut acc = 0.0;
            for (n, w) in weights.iter().enumerate() {
                acc += w;
                if r < acc {
                    return n;
                }
            }
        }
        weights.len() - 1
    }

    /// cpfg's choice among the applicable productions (`generate.c`'s
    /// `SelectProd`), in single precision as cpfg computes it: `r = total ·
    /// u`, then the first production whose probability, taken from `r`,
    /// leaves `r ≤ 0`; none when rounding leaves `r` above 0.
    fn cpfg_pick_of(weights: &[f64], u: f64) -> Option<usize> {
        let total: f32 = weights.iter().map(|&w| w as f32).sum();
        let mut r = (f64::from(total) * u) as f32;
        for (n, &w) in weights.iter().enumerate() {
            r -= w as f32;
            if r <= 0.0 {
                return Some(n);
            }
        }
        None
    }

    /// The alternative of a production chosen first-match: its only one,
    /// or one drawn by the fixed weights.
    fn alternative<'p>(&mut self, p: &'p Production) -> &'p Alternative {
        if p.alternatives.len() == 1 {
            return &p.alternatives[0];
        }
        let weights: Vec<f64> = p.alternatives.iter().map(|a| a.weight).collect();
        &p.alternatives[self.pick(&weights).min(weights.len() - 1)]
    }

    fn emit(
        &mut self,
        p: &Production,
        alt: &Alternative,
        locals: &mut [f64],
        out: &mut Word,
    ) -> Result<(), Halt> {
        self.m.run(&p.after, locals)?;
        // A buffer kept from module to module: most successors have
        // parameters, and a fresh one each time was a tenth of a step.
        let mut args = std::mem::take(&mut self.args);
        for (k, &symbol) in alt.successor.0.iter().enumerate() {
            args.clear();
            for a in alt.args.get(k).map_or(&[][..], |v| v.as_slice()) {
                args.push(self.m.eval(a, locals)?);
            }
            out.push(symbol, &args);
        }
        self.args = args;
        self.m.charge(alt.successor.len() as u64)?;
        Ok(())
    }

    /// One parallel rewriting of the modules `range` of `word` onto `out`,
    /// each module by the productions of the L-system it belongs to
    /// (`groups`, [`Lsystems`]' order). Contexts are matched in the whole
    /// of `word`.
    fn step(
        &mut self,
        (lsystems, groups): (&Lsystems, &[Group<'_>]),
        word: &Word,
        range: Range<usize>,
        choice: RulePolicy,
        out: &mut Word,
    ) -> Result<(), Halt> {
        let mut i = range.start;
        let draw_each = choice == RulePolicy::Weighted;
        let mut calls = lsystems.calls();
        while i < range.end {
            if let (Some(lcg), true) = (&mut self.m.choice, draw_each) {
                self.m.drawn = Some(lcg.next_f64());
            }
            self.current = calls.current();
            let group = &groups[self.current];
            let applied = self.apply(group, (word, i), (word, i), choice, out)?;
            self.m.drawn = None;
            let consumed = match applied {
                Some(n) => n.max(1),
                None => {
                    out.push(word.0[i], word.args(i));
                    1
                }
            };
            calls.pass(word, i, i + consumed);
            i += consumed;
            if out.len() > self.max_symbols {
                return Err(Halt::Work);
            }
        }
        Ok(())
    }

    /// Rewrites each module of `range` of `word` recursively
    /// (decomposition, homomorphism) onto `out` with the productions of the
    /// L-system it belongs to, up to that phase's depth (`phases`,
    /// [`Lsystems`]' order). Contexts are matched in the whole of `word`.
    /// `origins`, when given, receives for each output module the index of
    /// the module of `word` it came from.
    fn recursive(
        &mut self,
        (lsystems, phases): (&Lsystems, &[(Group<'_>, u32)]),
        word: &Word,
        range: Range<usize>,
        choice: RulePolicy,
        (out, mut origins): (&mut Word, Option<&mut Vec<u32>>),
    ) -> Result<(), Halt> {
        let mut i = range.start;
        let mut scratch = Word::new();
        let mut calls = lsystems.calls();
        while i < range.end {
            scratch.clear();
            self.current = calls.current();
            let (group, depth) = (&phases[self.current].0, phases[self.current].1);
            let consumed = match self.apply(group, (word, i), (word, i), choice, &mut scratch)? {
                Some(n) => {
                    let sub =
                        self.deeper(group, &scratch, word, i, depth.saturating_sub(1), choice)?;
                    out.extend_from(&sub, 0..sub.len());
                    if let Some(o) = origins.as_deref_mut() {
                        o.extend(std::iter::repeat_n(i as u32, sub.len()));
                    }
                    n.max(1)
                }
                None => {
                    out.push(word.0[i], word.args(i));
                    if let Some(o) = origins.as_deref_mut() {
                        o.push(i as u32);
                    }
                    1
                }
            };
            calls.pass(word, i, i + consumed);
            i += consumed;
            if out.len() > self.max_symbols {
                return Err(Halt::Work);
            }
        }
        Ok(())
    }

    /// Applies `group` again to the modules `sub` produced from module
    /// `at` of `ctx`, `depth` more times. Iterative: a `maximum depth:` of
    /// a million costs memory for the words still being expanded, never
    /// stack, and a word done is dropped before the next one is pushed, so
    /// a chain of single rewrites (`A --> A`) keeps one word at a time.
    fn deeper(
        &mut self,
        group: &Group<'_>,
        sub: &Word,
        ctx: &Word,
        at: usize,
        depth: u32,
        choice: RulePolicy,
    ) -> Result<Word, Halt> {
        if depth == 0 {
            return Ok(sub.clone());
        }
        let mut out = Word::new();
        // Words being expanded: each with the next module to rewrite and
        // how many more times its modules are rewritten.
        let mut pending: Vec<(Word, usize, u32)> = vec![(sub.clone(), 0, depth)];
        while let Some((word, i, levels)) = pending.last_mut() {
            if *i >= word.len() {
                pending.pop();
                continue;
            }
            let (i0, levels) = (*i, *levels);
            let mut scratch = Word::new();
            let applied = if levels == 0 {
                None
            } else {
                self.apply(group, (word, i0), (ctx, at), choice, &mut scratch)?
            };
            match applied {
                Some(n) => *i += n.max(1),
                None => {
                    out.push(word.0[i0], word.args(i0));
                    *i += 1;
                }
            }
            if *i >= word.len() {
                pending.pop();
            }
            if applied.is_some() && !scratch.is_empty() {
                pending.push((scratch, 0, levels - 1));
            }
            if out.len() > self.max_symbols {
                return Err(Halt::Work);
            }
        }
        Ok(out)
    }
}

fn halt_error(h: Halt, opts: &DeriveOptions, len: usize) -> Diagnostic {
    match h {
        Halt::Work if len > opts.max_symbols => Diagnostic::global(
            codes::TOO_MANY_SYMBOLS,
            format!(
                "the derived word grows past {} modules",
                opts.max_symbols
            ),
        )
        .with_help("derive fewer steps with `-n`"),
        Halt::Work => Diagnostic::global(
            codes::TOO_MUCH_WORK,
            "the derivation does more work than graftal allows (a loop that does not end, or a word that grows too fast)",
        )
        .with_help("derive fewer steps with `-n`, or check the `while` and `do` loops"),
    }
}

/// The context matching of each L-system of `sys` ([`Lsystems`]' order).
fn matchers(sys: &System) -> Vec<Matcher> {
    let matcher = |filter: &ContextFilter| {
        let table = |skips: &dyn Fn(SymbolId) -> bool| {
            (0..sys.symbols.len())
                .map(|i| skips(SymbolId(i as u32)))
                .collect()
        };
        Matcher {
            ignored: table(&|s| filter.skips(s)),
            ignored_on_the_right: table(&|s| filter.skips_on_the_right(s)),
            ring: sys.ring,
        }
    };
    std::iter::once(&sys.context)
        .chain(sys.sub_lsystems.iter().map(|s| &s.context))
        .map(matcher)
        .collect()
}

/// The axiom with its parameters evaluated (after the start block ran).
fn axiom(sys: &System, m: &mut Machine<'_>) -> Result<Word, Halt> {
    let mut word = Word::new();
    let mut args = Vec::new();
    for (k, &symbol) in sys.axiom.0.iter().enumerate() {
        args.clear();
        for a in sys.axiom_args.get(k).map_or(&[][..], |v| v.as_slice()) {
            args.push(m.eval(a, &mut [])?);
        }
        word.push(symbol, &args);
    }
    Ok(word)
}

/// Derives a system by module rewriting: `opts.steps` steps from the
/// axiom, with `progress` called after each step. `query` is called before
/// each step when the system has query modules, to fill their parameters
/// (with the program's values then, which the homomorphism reads), and
/// once more on the last word (its `bool` then true). The
/// word comes with the values the program left, for [`homomorphism`].
pub fn derive(
    sys: &System,
    opts: &DeriveOptions,
    mut progress: impl FnMut(u64, usize),
    query: &mut dyn FnMut(&mut Word, &Globals, bool),
) -> Result<(Word, Globals), Diagnostic> {
    super::refuse_early(sys, opts)?;
    let n = sys.symbols.len();
    let lsystems = Lsystems::of(sys);
    let productions: Vec<Group> = std::iter::once(&sys.productions)
        .chain(sys.sub_lsystems.iter().map(|s| &s.productions))
        .map(|p| Group::new(p, n))
        .collect();
    let decomposition = Lsystems::phases(sys, |s| &s.decomposition, |s| &s.decomposition);
    let decomposes = decomposition.iter().any(|(g, _)| !g.prods.is_empty());
    let choice = sys.policy;
    let mut e = Engine {
        m: Machine::new(sys, opts.seed, opts.max_work),
        matchers: matchers(sys),
        current: 0,
        max_symbols: opts.max_symbols,
        locals: Vec::new(),
        args: Vec::new(),
    };
    e.m.steps = opts.steps;
    let phases = [&sys.productions, &sys.decomposition.productions];
    let threads = match pieces::module_by_module(sys, phases.map(Vec::as_slice)) {
        true => crate::parallel::threads(opts.threads),
        false => 1,
    };
    let cut_symbol = sys.cut;
    let has_query = sys
        .symbols
        .iter()
        .any(|(id, _)| matches!(sys.op(id), Some(crate::ir::TurtleOp::Query(_))));
    let program = &sys.program;
    let (mut len, mut done) = (0, 0);
    let result: Result<(Word, Globals), Halt> = (|| {
        e.m.run(&program.start, &mut [])?;
        let mut word = axiom(sys, &mut e.m)?;
        let mut step = 0;
        while step < e.m.steps {
            if has_query {
                query(&mut word, &e.m.values(), false);
            }
            e.m.charge(super::STEP_COST)?;
            e.m.run(&program.start_each, &mut [])?;
            // cpfg cuts as it reads the word to rewrite it: what follows a
            // `%` stays in the word that step made, and is drawn
            // (`interpretation past %: on`, the default), until the next
            // step removes it.
            if let Some(c) = cut_symbol {
                cut(&mut word, c);
            }
            let rewrite = |e: &mut Engine, range, (out, _): pieces::Onto<'_>| {
                e.step((&lsystems, &productions), &word, range, choice, out)
            };
            let (mut next, _) = e.in_pieces(&word, threads, false, rewrite)?;
            if decomposes {
                let decompose = |e: &mut Engine, range, into: pieces::Onto<'_>| {
                    e.recursive((&lsystems, &decomposition), &next, range, choice, into)
                };
                next = e.in_pieces(&next, threads, false, decompose)?.0;
            }
            word = next;
            len = word.len();
            e.m.run(&program.end_each, &mut [])?;
            step += 1;
            done = step;
            progress(step, word.len());
            if e.m.stop {
                break;
            }
        }
        e.m.run(&program.end, &mut [])?;
        if has_query {
            query(&mut word, &e.m.values(), true);
        }
        Ok((word, e.m.values()))
    })();
    result.map_err(|h| {
        let mut d = halt_error(h, opts, len);
        if opts.steps > 0 {
            d = d.with_note(format!("stopped in step {} of {}", done + 1, opts.steps));
        }
        d
    })
}

/// The word the turtle draws: `word` rewritten by the homomorphism, and
/// for each module of the result the index of the module of `word` it
/// came from. The homomorphism reads the globals and arrays as `values`
/// holds them (what [`derive`] left).
pub fn homomorphism(
    sys: &System,
    word: &Word,
    values: &Globals,
    opts: &DeriveOptions,
) -> Result<(Word, Vec<u32>), Diagnostic> {
    let phase = &sys.homomorphism;
    let phases = Lsystems::phases(sys, |s| &s.homomorphism, |s| &s.homomorphism);
    if phases.iter().all(|(g, _)| g.prods.is_empty()) {
        return Ok((word.clone(), (0..word.len() as u32).collect()));
    }
    let seed = phase.seed.unwrap_or(0).wrapping_add(opts.seed);
    let mut m = Machine::new(sys, seed, opts.max_work);
    m.set_values(values);
    m.rng = match sys.settings.randomness {
        Randomness::Graftal => Rng::new(seed, Stream::Homomorphism),
        // cpfg seeds a homomorphism's own stream with its `seed:` on every
        // drawing; without one, `ran` there continues the derivation's
        // stream across cpfg's passes over the word (a count of passes no
        // file says), which graftal starts afresh.
        Randomness::Cpfg => Rng::Cpfg(Lcg48::srand48(seed as u32)),
    };
    let mut e = Engine {
        m,
        matchers: matchers(sys),
        current: 0,
        max_symbols: opts.max_symbols,
        locals: Vec::new(),
        args: Vec::new(),
    };
    let threads = match pieces::module_by_module(sys, [phase.productions.as_slice()]) {
        true => crate::parallel::threads(opts.threads),
        false => 1,
    };
    let lsystems = Lsystems::of(sys);
    let rewrite = |e: &mut Engine, range, into: pieces::Onto<'_>| {
        e.recursive((&lsystems, &phases), word, range, sys.policy, into)
    };
    e.in_pieces(word, threads, true, rewrite)
        .map_err(|h| halt_error(h, opts, word.len()))
}
