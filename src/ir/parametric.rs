//! # Parametric systems (cpfg)
//!
//! A cpfg L-system rewrites *modules*: a symbol with zero or more real
//! parameters, `A(1,2.5)`. Its productions bind the predecessor's parameters
//! to formal names, may run C-like statements and test a condition, and
//! compute the successor's parameters from expressions. This part of the IR
//! holds all of that; a [`crate::ir::System`] with `parametric: Some(..)` is
//! derived by [`crate::eval::parametric`] instead of the plain rewriter.
//!
//! ## Data model
//!
//! * Symbols are the system's [`SymbolId`]s. cpfg's symbols are single
//!   characters; its two-character turtle commands (`@O`, `?P`, `~l`, `@Gs`)
//!   are interned as one symbol each.
//! * A parametric word is a [`ModuleWord`]: the symbols, and for each module
//!   the range of its parameters in one flat `f64` array.
//! * Expressions ([`Expr`]) and statements ([`Stmt`]) are trees over three
//!   kinds of storage: a production's *locals* (its formal parameters first,
//!   in predecessor order — left context, strict predecessor, right context —
//!   then the variables its statements assign), the system's *globals*
//!   (assigned in the `Start:`/`StartEach:`/`EndEach:`/`End:` blocks) and its
//!   *arrays* (`define: { array … }`).
//!
//! ## Semantics (cpfg manual §2–§4, and cpfg's own `lsys_input.y`)
//!
//! One derivation step scans the word left to right. At each position, the
//! productions whose strict predecessor starts with that module's symbol are
//! tried in file order: the predecessor's symbols and parameter counts must
//! equal the modules there, the left and right contexts must match (bracket-
//! aware, as in pfg, modulo `ignore:`/`consider:`; around the ends of the word
//! for a ring L-system); then the before-statements run, the condition is
//! evaluated and, if it is non-zero, the after-statements run and the
//! successor's parameters are evaluated. A deterministic system uses the
//! first such production; a stochastic one (`seed:` given) evaluates every
//! applicable production and picks one with probability proportional to its
//! weight. A module no production applies to is copied. After the step, `%`
//! cuts the rest of its branch, then the decomposition productions rewrite
//! each new module again, recursively, up to `maximum depth` times.
//!
//! The homomorphism productions rewrite the word for drawing only: each
//! module is replaced (recursively, up to the homomorphism's maximum depth)
//! and the result goes to the turtle; the next step starts from the word
//! before the homomorphism. Contexts in homomorphism productions are
//! matched in the word before the homomorphism.

use super::{Span, SymbolId};
use serde::Serialize;

/// A parametric word: module `i` is `symbols[i]` with parameters
/// `params[starts[i]..starts[i + 1]]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ModuleWord {
    pub symbols: Vec<SymbolId>,
    pub params: Vec<f64>,
    /// `symbols.len() + 1` offsets into `params`.
    pub starts: Vec<u32>,
}

impl ModuleWord {
    pub fn new() -> Self {
        ModuleWord {
            symbols: Vec::new(),
            params: Vec::new(),
            starts: vec![0],
        }
    }

    pub fn len(&self) -> usize {
        self.symbols.len()
    }

    pub fn is_empty(&self) -> bool {
        self.symbols.is_empty()
    }

    /// The parameters of module `i`.
    pub fn args(&self, i: usize) -> &[f64] {
        &self.params[self.starts[i] as usize..self.starts[i + 1] as usize]
    }

    pub fn push(&mut self, symbol: SymbolId, args: &[f64]) {
        self.symbols.push(symbol);
        self.params.extend_from_slice(args);
        self.starts.push(self.params.len() as u32);
    }

    /// Appends modules `range` of `other`.
    pub fn extend_from(&mut self, other: &ModuleWord, range: std::ops::Range<usize>) {
        for i in range {
            self.push(other.symbols[i], other.args(i));
        }
    }

    pub fn clear(&mut self) {
        self.symbols.clear();
        self.params.clear();
        self.starts.clear();
        self.starts.push(0);
    }
}

/// Where a value lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Var {
    /// A production's formal parameter or local variable (slot index).
    Local(u16),
    /// A global variable (index into [`Parametric::globals`]).
    Global(u16),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum UnOp {
    Neg,
    Not,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum BinOp {
    Or,
    And,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Pow,
}

/// cpfg's predefined functions (manual §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Builtin {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Exp,
    Log,
    Sqrt,
    Fabs,
    Floor,
    Ceil,
    Trunc,
    Sign,
    Srand,
    Ran,
    Nran,
    Bran,
    Biran,
    /// `func(id, x)`: a user function from the view file.
    Func,
    CurveX,
    CurveY,
    CurveZ,
    CurveGal,
    /// `printf`, `fprintf`, `fopen`, `fclose`, `fflush`, `fscanf`: graftal
    /// performs no I/O for a model; these evaluate to 0.
    Io,
    /// `stop(n)`: ends the derivation after the current step.
    Stop,
    /// `vvXmin()` …: the extents of the view volume (0 when not drawn).
    ViewVolume,
    SetDerivationLength,
    GetDerivationLength,
}

/// An expression.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Expr {
    Num(f64),
    /// A string literal (an argument of the I/O functions): its value is 0.
    Str(String),
    Var(Var),
    /// An array element: array index, subscripts.
    Element(u16, Vec<Expr>),
    Unary(UnOp, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `c ? a : b`.
    Cond(Box<Expr>, Box<Expr>, Box<Expr>),
    Call(Builtin, Vec<Expr>),
}

/// Where an assignment stores.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Place {
    Var(Var),
    Element(u16, Vec<Expr>),
}

/// A statement of a block or production.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Stmt {
    Assign(Place, Expr),
    /// An expression evaluated for its effect (`srand(3);`, `printf(…);`).
    Eval(Expr),
    If(Expr, Vec<Stmt>, Vec<Stmt>),
    While(Expr, Vec<Stmt>),
    Do(Vec<Stmt>, Expr),
}

/// A predecessor or context module: a symbol and the local slots its
/// parameters bind (`None` for a slot bound twice — cpfg binds each name once;
/// a repeated name must then equal the first binding… cpfg does not check,
/// and neither does graftal: the later binding wins).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Pattern {
    pub symbol: SymbolId,
    pub params: Vec<u16>,
}

/// A successor (or axiom) module: a symbol and its parameter expressions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModuleCall {
    pub symbol: SymbolId,
    pub args: Vec<Expr>,
}

/// A parametric production.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ParamProduction {
    pub left: Vec<Pattern>,
    pub predecessor: Vec<Pattern>,
    pub right: Vec<Pattern>,
    /// Number of local slots (formal parameters, then assigned locals).
    pub locals: u16,
    pub before: Vec<Stmt>,
    /// `None`: always true (`*` or no condition).
    pub condition: Option<Expr>,
    pub after: Vec<Stmt>,
    pub successor: Vec<ModuleCall>,
    /// The weight of a stochastic production (`: 40`); 1 when absent.
    pub probability: Option<Expr>,
}

/// A set of productions applied after a step (decomposition) or for drawing
/// (homomorphism), with its maximum recursion depth.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ProductionGroup {
    pub productions: Vec<ParamProduction>,
    pub depth: u32,
    /// The homomorphism's own random seed (`seed:` after `homomorphism`).
    pub seed: Option<u64>,
}

/// A `define: { array … }` array.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ArrayDecl {
    pub name: String,
    pub dims: Vec<usize>,
    /// Initial values, row-major; missing ones are 0.
    pub init: Vec<f64>,
}

/// A user-defined function (`func(id, x)`), sampled from the view file's
/// `function:` files: `x` in [0, 1] maps linearly onto the samples.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Function {
    pub name: String,
    pub samples: Vec<f64>,
}

impl Function {
    /// The value at `x` (clamped to [0, 1]), by linear interpolation of the
    /// samples.
    pub fn eval(&self, x: f64) -> f64 {
        let n = self.samples.len();
        if n == 0 {
            return 0.0;
        }
        if n == 1 || x.is_nan() {
            return self.samples[0];
        }
        let t = x.clamp(0.0, 1.0) * (n - 1) as f64;
        let i = (t.floor() as usize).min(n - 2);
        let f = t - i as f64;
        self.samples[i] * (1.0 - f) + self.samples[i + 1] * f
    }
}

/// Everything parametric about a cpfg system.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Parametric {
    pub globals: Vec<String>,
    pub arrays: Vec<ArrayDecl>,
    pub axiom: Vec<ModuleCall>,
    pub start: Vec<Stmt>,
    pub start_each: Vec<Stmt>,
    pub end_each: Vec<Stmt>,
    pub end: Vec<Stmt>,
    pub productions: Vec<ParamProduction>,
    pub decomposition: ProductionGroup,
    pub homomorphism: ProductionGroup,
    /// `ring lsystem`: the word's ends are neighbours for context.
    pub ring: bool,
    /// `seed:`: the system is stochastic, and this seeds its generator
    /// (added to the run's seed).
    pub seed: Option<u64>,
    /// `func(id, x)` tables, id 1 first.
    pub functions: Vec<Function>,
}

/// Spans of a parametric system's parts, for diagnostics at run time.
#[derive(Clone, Debug, Default)]
pub struct ParamSpans {
    /// One span per production (its predecessor), in the order of
    /// [`Parametric::productions`], then decomposition, then homomorphism.
    pub productions: Vec<Span>,
}
