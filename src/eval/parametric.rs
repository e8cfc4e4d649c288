//! Derivation of parametric (cpfg) systems, as [`crate::ir::parametric`]
//! specifies: productions with formal parameters, contexts, statements and
//! conditions; stochastic choice; `%` cuts; decomposition after each step;
//! the homomorphism for drawing; Start/StartEach/EndEach/End blocks.
//!
//! Bounds: the word is limited by [`DeriveOptions::max_symbols`], and all
//! work (modules rewritten, loop iterations, recursion) by
//! [`DeriveOptions::max_work`], so no model runs without end.

use super::DeriveOptions;
use crate::diagnostics::{codes, Diagnostic};
use crate::ir::parametric::{
    BinOp, Builtin, Expr, ModuleWord, ParamProduction, Parametric, Pattern, Place, Stmt, UnOp, Var,
};
use crate::ir::{SymbolId, System};
use crate::random::{Rng, Stream};

/// The value of an expression that uses no variables, or `None`.
pub fn constant(e: &Expr) -> Option<f64> {
    let par = Parametric::default();
    let mut m = Machine::new(&par, 0, u64::MAX);
    if uses_variables(e) {
        return None;
    }
    m.eval(e, &mut []).ok()
}

fn uses_variables(e: &Expr) -> bool {
    match e {
        Expr::Num(_) | Expr::Str(_) => false,
        Expr::Var(_) | Expr::Element(..) => true,
        Expr::Unary(_, a) => uses_variables(a),
        Expr::Binary(_, a, b) => uses_variables(a) || uses_variables(b),
        Expr::Cond(a, b, c) => uses_variables(a) || uses_variables(b) || uses_variables(c),
        Expr::Call(f, args) => {
            matches!(
                f,
                Builtin::Ran | Builtin::Nran | Builtin::Bran | Builtin::Biran | Builtin::Func
            ) || args.iter().any(uses_variables)
        }
    }
}

/// Why evaluation stopped early.
#[derive(Debug)]
enum Halt {
    /// The work budget ran out.
    Work,
}

/// Variables, arrays, the random stream and the work budget.
struct Machine<'p> {
    par: &'p Parametric,
    globals: Vec<f64>,
    arrays: Vec<Vec<f64>>,
    rng: Rng,
    run_seed: u64,
    work: u64,
    max_work: u64,
    stop: bool,
    steps: u64,
}

/// The most iterations of one loop statement.
const MAX_LOOP: u64 = 10_000_000;

fn truth(v: f64) -> bool {
    v != 0.0
}

fn b(v: bool) -> f64 {
    if v {
        1.0
    } else {
        0.0
    }
}

impl<'p> Machine<'p> {
    fn new(par: &'p Parametric, seed: u64, max_work: u64) -> Self {
        Machine {
            par,
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
            rng: Rng::new(seed.wrapping_add(par.seed.unwrap_or(0)), Stream::Derivation),
            run_seed: seed,
            work: 0,
            max_work,
            stop: false,
            steps: 0,
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
            Expr::Str(_) => 0.0,
            Expr::Var(Var::Local(i)) => locals.get(*i as usize).copied().unwrap_or(0.0),
            Expr::Var(Var::Global(i)) => self.globals.get(*i as usize).copied().unwrap_or(0.0),
            Expr::Element(a, subs) => match self.element(*a, subs, locals)? {
                Some(i) => self.arrays[*a as usize][i],
                None => 0.0,
            },
            Expr::Unary(UnOp::Neg, a) => -self.eval(a, locals)?,
            Expr::Unary(UnOp::Not, a) => b(!truth(self.eval(a, locals)?)),
            Expr::Binary(BinOp::And, x, y) => {
                b(truth(self.eval(x, locals)?) && truth(self.eval(y, locals)?))
            }
            Expr::Binary(BinOp::Or, x, y) => {
                b(truth(self.eval(x, locals)?) || truth(self.eval(y, locals)?))
            }
            Expr::Binary(op, x, y) => {
                let (x, y) = (self.eval(x, locals)?, self.eval(y, locals)?);
                match op {
                    BinOp::Eq => b(x == y),
                    BinOp::Ne => b(x != y),
                    BinOp::Lt => b(x < y),
                    BinOp::Le => b(x <= y),
                    BinOp::Gt => b(x > y),
                    BinOp::Ge => b(x >= y),
                    BinOp::Add => x + y,
                    BinOp::Sub => x - y,
                    BinOp::Mul => x * y,
                    BinOp::Div => x / y,
                    // cpfg computes `%` on integers.
                    BinOp::Rem => {
                        let (a, m) = (x as i64, y as i64);
                        if m == 0 {
                            0.0
                        } else {
                            a.wrapping_rem(m) as f64
                        }
                    }
                    BinOp::Pow => x.powf(y),
                    BinOp::And | BinOp::Or => unreachable!("handled above"),
                }
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
        let deg = std::f64::consts::PI / 180.0;
        match f {
            Builtin::Sin => (x * deg).sin(),
            Builtin::Cos => (x * deg).cos(),
            Builtin::Tan => (x * deg).tan(),
            Builtin::Asin => x.asin() / deg,
            Builtin::Acos => x.acos() / deg,
            Builtin::Atan => x.atan() / deg,
            Builtin::Atan2 => x.atan2(y) / deg,
            Builtin::Exp => x.exp(),
            Builtin::Log => x.ln(),
            Builtin::Sqrt => x.sqrt(),
            Builtin::Fabs => x.abs(),
            Builtin::Floor => x.floor(),
            Builtin::Ceil => x.ceil(),
            Builtin::Trunc => x.trunc(),
            Builtin::Sign => {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            }
            Builtin::Srand => {
                self.rng = Rng::new(
                    (x as i64 as u64).wrapping_add(self.run_seed),
                    Stream::Derivation,
                );
                0.0
            }
            Builtin::Ran => x * self.rng.next_f64(),
            Builtin::Nran => x + y * self.normal(),
            Builtin::Bran => self.beta(x, y),
            Builtin::Biran => {
                let trials = x.clamp(0.0, 1e6) as u64;
                let _ = self.charge(trials);
                (0..trials).filter(|_| self.rng.next_f64() < y).count() as f64
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
            Builtin::Stop => {
                self.stop = true;
                0.0
            }
            Builtin::SetDerivationLength => {
                if x >= 0.0 && x.is_finite() {
                    self.steps = x as u64;
                }
                0.0
            }
            Builtin::GetDerivationLength => self.steps as f64,
            Builtin::CurveX
            | Builtin::CurveY
            | Builtin::CurveZ
            | Builtin::CurveGal
            | Builtin::Io
            | Builtin::ViewVolume => {
                let _ = n;
                0.0
            }
        }
    }

    /// A standard normal deviate (Box–Muller).
    fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.rng.next_f64();
        let u2 = self.rng.next_f64();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
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

/// Which productions to try for a symbol, and how context is matched.
struct Matcher {
    ignored: Vec<bool>,
    ring: bool,
}

impl Matcher {
    fn is_ignored(&self, s: SymbolId) -> bool {
        self.ignored.get(s.index()).copied().unwrap_or(false)
    }

    /// Binds `pat`'s parameters from module `i` of `word`.
    fn bind(word: &ModuleWord, i: usize, pat: &Pattern, locals: &mut [f64]) -> bool {
        if word.symbols[i] != pat.symbol {
            return false;
        }
        let args = word.args(i);
        if args.len() != pat.params.len() {
            return false;
        }
        for (slot, v) in pat.params.iter().zip(args) {
            if let Some(l) = locals.get_mut(*slot as usize) {
                *l = *v;
            }
        }
        true
    }

    /// Left context ending just before module `i`.
    fn left(&self, word: &ModuleWord, i: usize, pats: &[Pattern], locals: &mut [f64]) -> bool {
        let n = word.len();
        let mut j = i; // next module to look at is j - 1
        let mut steps = 0;
        for pat in pats.iter().rev() {
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
                let s = word.symbols[j];
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
                        if word.symbols[j] == SymbolId::CLOSE {
                            depth += 1;
                        } else if word.symbols[j] == SymbolId::OPEN {
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
            if !Self::bind(word, j, pat, locals) {
                return false;
            }
        }
        true
    }

    /// Right context starting at module `i`.
    fn right(&self, word: &ModuleWord, i: usize, pats: &[Pattern], locals: &mut [f64]) -> bool {
        let n = word.len();
        let mut j = i;
        let mut steps = 0;
        for pat in pats {
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
                    let s = word.symbols[j];
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
                let s = word.symbols[j];
                if s == pat.symbol {
                    break;
                }
                if s == SymbolId::OPEN {
                    let mut depth = 1;
                    j += 1;
                    while depth > 0 {
                        if j >= n {
                            return false;
                        }
                        if word.symbols[j] == SymbolId::OPEN {
                            depth += 1;
                        } else if word.symbols[j] == SymbolId::CLOSE {
                            depth -= 1;
                        }
                        j += 1;
                    }
                    continue;
                }
                if s == SymbolId::CLOSE {
                    return false;
                }
                if self.is_ignored(s) {
                    j += 1;
                    continue;
                }
                return false;
            }
            if !Self::bind(word, j, pat, locals) {
                return false;
            }
            j += 1;
        }
        true
    }
}

/// The productions of a group, indexed by their first predecessor symbol.
struct Group<'p> {
    prods: &'p [ParamProduction],
    by_first: Vec<Vec<u32>>,
}

impl<'p> Group<'p> {
    fn new(prods: &'p [ParamProduction], symbols: usize) -> Self {
        let mut by_first = vec![Vec::new(); symbols];
        for (k, p) in prods.iter().enumerate() {
            if let Some(first) = p.predecessor.first() {
                if let Some(v) = by_first.get_mut(first.symbol.index()) {
                    v.push(k as u32);
                }
            }
        }
        Group { prods, by_first }
    }
}

/// Stochastic, deterministic: how a production is chosen.
#[derive(Clone, Copy, PartialEq)]
enum Choice {
    First,
    Weighted,
}

struct Engine<'a> {
    m: Machine<'a>,
    matcher: Matcher,
    max_symbols: usize,
    locals: Vec<f64>,
}

impl Engine<'_> {
    /// Tries the productions of `group` at module `i` of `word` (contexts
    /// are matched in `ctx.0` around module `ctx.1`). On success appends the
    /// successor to `out` and returns the number of modules consumed.
    fn apply(
        &mut self,
        group: &Group<'_>,
        (word, i): (&ModuleWord, usize),
        (ctx, ctx_i): (&ModuleWord, usize),
        choice: Choice,
        out: &mut ModuleWord,
    ) -> Result<Option<usize>, Halt> {
        let Some(cands) = group.by_first.get(word.symbols[i].index()) else {
            return Ok(None);
        };
        if cands.is_empty() {
            return Ok(None);
        }
        let mut applicable: Vec<(u32, f64, Vec<f64>)> = Vec::new();
        for &k in cands {
            let p = &group.prods[k as usize];
            self.m.charge(1)?;
            let len = p.predecessor.len();
            if i + len > word.len() {
                continue;
            }
            self.locals.clear();
            self.locals.resize(p.locals as usize, 0.0);
            let mut ok = true;
            for (o, pat) in p.predecessor.iter().enumerate() {
                if !Matcher::bind(word, i + o, pat, &mut self.locals) {
                    ok = false;
                    break;
                }
            }
            if !ok {
                continue;
            }
            let ctx_end = if std::ptr::eq(word, ctx) {
                ctx_i + len
            } else {
                ctx_i + 1
            };
            if !p.left.is_empty() && !self.matcher.left(ctx, ctx_i, &p.left, &mut self.locals) {
                continue;
            }
            if !p.right.is_empty() && !self.matcher.right(ctx, ctx_end, &p.right, &mut self.locals)
            {
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
            if choice == Choice::First {
                self.emit(p, &mut locals, out)?;
                self.locals = locals;
                return Ok(Some(len));
            }
            let w = match &p.probability {
                Some(e) => self.m.eval(e, &mut locals)?,
                None => 1.0,
            };
            applicable.push((k, w.max(0.0), locals));
        }
        if applicable.is_empty() {
            return Ok(None);
        }
        let total: f64 = applicable.iter().map(|a| a.1).sum();
        let mut pick = applicable.len() - 1;
        if total > 0.0 && total.is_finite() {
            let r = self.m.rng.next_f64() * total;
            let mut acc = 0.0;
            for (n, a) in applicable.iter().enumerate() {
                acc += a.1;
                if r < acc {
                    pick = n;
                    break;
                }
            }
        }
        let (k, _, mut locals) = applicable.swap_remove(pick);
        let p = &group.prods[k as usize];
        self.emit(p, &mut locals, out)?;
        Ok(Some(p.predecessor.len()))
    }

    fn emit(
        &mut self,
        p: &ParamProduction,
        locals: &mut [f64],
        out: &mut ModuleWord,
    ) -> Result<(), Halt> {
        self.m.run(&p.after, locals)?;
        let mut args: Vec<f64> = Vec::new();
        for call in &p.successor {
            args.clear();
            for a in &call.args {
                args.push(self.m.eval(a, locals)?);
            }
            out.push(call.symbol, &args);
        }
        self.m.charge(p.successor.len() as u64)?;
        Ok(())
    }

    /// One parallel rewriting of `word` with `group`.
    fn step(
        &mut self,
        group: &Group<'_>,
        word: &ModuleWord,
        choice: Choice,
    ) -> Result<ModuleWord, Halt> {
        let mut out = ModuleWord::new();
        let mut i = 0;
        while i < word.len() {
            match self.apply(group, (word, i), (word, i), choice, &mut out)? {
                Some(n) => i += n.max(1),
                None => {
                    out.push(word.symbols[i], word.args(i));
                    i += 1;
                }
            }
            if out.len() > self.max_symbols {
                return Err(Halt::Work);
            }
        }
        Ok(out)
    }

    /// Rewrites each module of `word` with `group` recursively, up to
    /// `depth` times (decomposition, homomorphism). Contexts are matched in
    /// `word`. `origins`, when given, receives for each output module the
    /// index of the module of `word` it came from.
    fn recursive(
        &mut self,
        group: &Group<'_>,
        word: &ModuleWord,
        depth: u32,
        choice: Choice,
        mut origins: Option<&mut Vec<u32>>,
    ) -> Result<ModuleWord, Halt> {
        let mut out = ModuleWord::new();
        let mut i = 0;
        let mut scratch = ModuleWord::new();
        while i < word.len() {
            scratch.clear();
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
                    out.push(word.symbols[i], word.args(i));
                    if let Some(o) = origins.as_deref_mut() {
                        o.push(i as u32);
                    }
                    1
                }
            };
            i += consumed;
            if out.len() > self.max_symbols {
                return Err(Halt::Work);
            }
        }
        Ok(out)
    }

    /// Applies `group` again to the modules `sub` produced from module
    /// `at` of `ctx`, `depth` more times.
    fn deeper(
        &mut self,
        group: &Group<'_>,
        sub: &ModuleWord,
        ctx: &ModuleWord,
        at: usize,
        depth: u32,
        choice: Choice,
    ) -> Result<ModuleWord, Halt> {
        if depth == 0 {
            return Ok(sub.clone());
        }
        let mut out = ModuleWord::new();
        let mut scratch = ModuleWord::new();
        let mut i = 0;
        while i < sub.len() {
            scratch.clear();
            match self.apply(group, (sub, i), (ctx, at), choice, &mut scratch)? {
                Some(n) => {
                    let deeper = self.deeper(group, &scratch, ctx, at, depth - 1, choice)?;
                    out.extend_from(&deeper, 0..deeper.len());
                    i += n.max(1);
                }
                None => {
                    out.push(sub.symbols[i], sub.args(i));
                    i += 1;
                }
            }
            if out.len() > self.max_symbols {
                return Err(Halt::Work);
            }
        }
        Ok(out)
    }
}

/// Removes each `%` and the rest of its branch.
fn cut(word: &mut ModuleWord, cut: SymbolId) {
    if !word.symbols.contains(&cut) {
        return;
    }
    let mut out = ModuleWord::new();
    let mut i = 0;
    while i < word.len() {
        let s = word.symbols[i];
        if s == cut {
            let mut depth = 0usize;
            i += 1;
            while i < word.len() {
                let t = word.symbols[i];
                if t == SymbolId::OPEN {
                    depth += 1;
                } else if t == SymbolId::CLOSE {
                    if depth == 0 {
                        break;
                    }
                    depth -= 1;
                }
                i += 1;
            }
            continue;
        }
        out.push(s, word.args(i));
        i += 1;
    }
    *word = out;
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

fn matcher(sys: &System, par: &Parametric) -> Matcher {
    let ignored = (0..sys.symbols.len())
        .map(|i| sys.is_ignored(SymbolId(i as u32)))
        .collect();
    Matcher {
        ignored,
        ring: par.ring,
    }
}

/// Derives a parametric system: `opts.steps` steps from the axiom, with
/// `progress` called after each step. `query` is called before each step
/// when the system has query modules, to fill their parameters.
pub fn derive(
    sys: &System,
    opts: &DeriveOptions,
    mut progress: impl FnMut(u64, usize),
    query: &mut dyn FnMut(&mut ModuleWord),
) -> Result<ModuleWord, Diagnostic> {
    let par = sys
        .parametric
        .as_deref()
        .expect("derive_parametric is called for parametric systems");
    let n = sys.symbols.len();
    let main = Group::new(&par.productions, n);
    let decomposition = Group::new(&par.decomposition.productions, n);
    let stochastic = if par.seed.is_some() {
        Choice::Weighted
    } else {
        Choice::First
    };
    let mut e = Engine {
        m: Machine::new(par, opts.seed, opts.max_work),
        matcher: matcher(sys, par),
        max_symbols: opts.max_symbols,
        locals: Vec::new(),
    };
    e.m.steps = opts.steps;
    let cut_symbol = sys.symbols.get("%");
    let has_query = sys
        .symbols
        .iter()
        .any(|(id, _)| matches!(sys.op(id), Some(crate::ir::TurtleOp::Query(_))));
    let mut len = 0;
    let result: Result<ModuleWord, Halt> = (|| {
        e.m.run(&par.start, &mut [])?;
        let mut word = ModuleWord::new();
        for call in &par.axiom {
            let mut args = Vec::new();
            for a in &call.args {
                args.push(e.m.eval(a, &mut [])?);
            }
            word.push(call.symbol, &args);
        }
        let mut step = 0;
        while step < e.m.steps {
            if has_query {
                query(&mut word);
            }
            e.m.run(&par.start_each, &mut [])?;
            let mut next = e.step(&main, &word, stochastic)?;
            if let Some(c) = cut_symbol {
                cut(&mut next, c);
            }
            if !par.decomposition.productions.is_empty() {
                next = e.recursive(
                    &decomposition,
                    &next,
                    par.decomposition.depth.max(1),
                    stochastic,
                    None,
                )?;
            }
            word = next;
            len = word.len();
            e.m.run(&par.end_each, &mut [])?;
            step += 1;
            progress(step, word.len());
            if e.m.stop {
                break;
            }
        }
        e.m.run(&par.end, &mut [])?;
        if has_query {
            query(&mut word);
        }
        Ok(word)
    })();
    result.map_err(|h| halt_error(h, opts, len))
}

/// The word the turtle draws: `word` rewritten by the homomorphism, and
/// for each module of the result the index of the module of `word` it
/// came from.
pub fn homomorphism(
    sys: &System,
    word: &ModuleWord,
    opts: &DeriveOptions,
) -> Result<(ModuleWord, Vec<u32>), Diagnostic> {
    let par = sys.parametric.as_deref().expect("a parametric system");
    if par.homomorphism.productions.is_empty() {
        return Ok((word.clone(), (0..word.len() as u32).collect()));
    }
    let group = Group::new(&par.homomorphism.productions, sys.symbols.len());
    let seed = par.homomorphism.seed.unwrap_or(0).wrapping_add(opts.seed);
    let mut m = Machine::new(par, seed, opts.max_work);
    m.rng = Rng::new(seed, Stream::Homomorphism);
    let mut e = Engine {
        m,
        matcher: matcher(sys, par),
        max_symbols: opts.max_symbols,
        locals: Vec::new(),
    };
    let choice = if par.seed.is_some() {
        Choice::Weighted
    } else {
        Choice::First
    };
    let mut origins = Vec::new();
    let out = e
        .recursive(
            &group,
            word,
            par.homomorphism.depth.max(1),
            choice,
            Some(&mut origins),
        )
        .map_err(|h| halt_error(h, opts, word.len()))?;
    Ok((out, origins))
}
