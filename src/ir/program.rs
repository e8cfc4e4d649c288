//! # Expressions, statements and the program around a derivation
//!
//! What parametric modules compute with: expressions ([`Expr`]) and
//! statements ([`Stmt`]) over three kinds of storage: a production's
//! *locals* (its formal parameters first, in predecessor order — left
//! context, strict predecessor, right context — then the variables its
//! statements assign), the system's *globals* and its *arrays*
//! ([`Program`]). The [`Program`] also holds the statements run before and
//! after the derivation and each of its steps, and the user functions
//! (`func(id, x)`) sampled from curve files. cpfg writes all of this; any
//! front end may.

use serde::Serialize;

/// Where a value lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Var {
    /// A production's formal parameter or local variable (slot index).
    Local(u16),
    /// A global variable (index into [`Program::globals`]).
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
    /// `curveX(id, t)`, `curveY`, `curveZ`: a coordinate of the point at
    /// `t` of the length of curve `id` ([`super::look::ContourRole::Curve`]).
    CurveX,
    CurveY,
    CurveZ,
    /// `curveGAL(id)`: the length of curve `id`.
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

/// An expression. Its tree is at most [`MAX_NESTING`](super::MAX_NESTING)
/// deep, and blocks of statements nest no deeper: the front ends refuse
/// deeper input (E0013) and lowering maps one source node to one node here.
/// So the code that walks them by recursion ([`Expr::constant`], the
/// evaluator, the emitters, dropping them) stays within the stack.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Expr {
    Num(f64),
    /// A string literal (a label's format, an argument of the I/O
    /// functions): its value is its index among the system's literals
    /// ([`super::System::strings`]).
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

/// The predefined functions: name, builtin, accepted argument counts.
pub const BUILTINS: &[(&str, Builtin, &[usize])] = &[
    ("sin", Builtin::Sin, &[1]),
    ("cos", Builtin::Cos, &[1]),
    ("tan", Builtin::Tan, &[1]),
    ("asin", Builtin::Asin, &[1]),
    ("acos", Builtin::Acos, &[1]),
    ("atan", Builtin::Atan, &[1, 2]),
    ("atan2", Builtin::Atan2, &[2]),
    ("exp", Builtin::Exp, &[1]),
    ("log", Builtin::Log, &[1]),
    ("sqrt", Builtin::Sqrt, &[1]),
    ("fabs", Builtin::Fabs, &[1]),
    ("floor", Builtin::Floor, &[1]),
    ("ceil", Builtin::Ceil, &[1]),
    ("trunc", Builtin::Trunc, &[1]),
    ("sign", Builtin::Sign, &[1]),
    ("srand", Builtin::Srand, &[1]),
    ("ran", Builtin::Ran, &[1]),
    ("nran", Builtin::Nran, &[2]),
    ("bran", Builtin::Bran, &[2]),
    ("biran", Builtin::Biran, &[2]),
    ("func", Builtin::Func, &[2]),
    ("curveX", Builtin::CurveX, &[2]),
    ("curveY", Builtin::CurveY, &[2]),
    ("curveZ", Builtin::CurveZ, &[2]),
    ("curveGAL", Builtin::CurveGal, &[1]),
    ("printf", Builtin::Io, &[]),
    ("fprintf", Builtin::Io, &[]),
    ("fopen", Builtin::Io, &[2]),
    ("fclose", Builtin::Io, &[1]),
    ("fflush", Builtin::Io, &[1]),
    ("fscanf", Builtin::Io, &[]),
    ("stop", Builtin::Stop, &[0, 1]),
    ("vvXmin", Builtin::ViewVolume, &[0]),
    ("vvXmax", Builtin::ViewVolume, &[0]),
    ("vvYmin", Builtin::ViewVolume, &[0]),
    ("vvYmax", Builtin::ViewVolume, &[0]),
    ("vvZmin", Builtin::ViewVolume, &[0]),
    ("vvZmax", Builtin::ViewVolume, &[0]),
    ("SetDerivationLength", Builtin::SetDerivationLength, &[1]),
    ("GetDerivationLength", Builtin::GetDerivationLength, &[0]),
];

/// cpfg's truth: any value but 0.
pub fn truth(v: f64) -> bool {
    v != 0.0
}

fn bool_value(v: bool) -> f64 {
    if v {
        1.0
    } else {
        0.0
    }
}

impl UnOp {
    pub fn apply(self, x: f64) -> f64 {
        match self {
            UnOp::Neg => -x,
            UnOp::Not => bool_value(!truth(x)),
        }
    }
}

impl BinOp {
    /// The operator on two values (`&&` and `||` on values already
    /// evaluated; an evaluator that short-circuits tests them first).
    pub fn apply(self, x: f64, y: f64) -> f64 {
        match self {
            BinOp::Or => bool_value(truth(x) || truth(y)),
            BinOp::And => bool_value(truth(x) && truth(y)),
            BinOp::Eq => bool_value(x == y),
            BinOp::Ne => bool_value(x != y),
            BinOp::Lt => bool_value(x < y),
            BinOp::Le => bool_value(x <= y),
            BinOp::Gt => bool_value(x > y),
            BinOp::Ge => bool_value(x >= y),
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
        }
    }
}

impl Builtin {
    /// The value of a function that depends on its arguments alone (angles
    /// in degrees, as cpfg's are), `None` for the functions that draw random
    /// numbers, read tables or act on the derivation.
    pub fn pure(self, x: f64, y: f64) -> Option<f64> {
        let deg = std::f64::consts::PI / 180.0;
        Some(match self {
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
            _ => return None,
        })
    }

    /// Whether the function's value is a random draw or a table look-up,
    /// so an expression calling it is never a constant.
    pub fn varies(self) -> bool {
        matches!(
            self,
            Builtin::Ran
                | Builtin::Nran
                | Builtin::Bran
                | Builtin::Biran
                | Builtin::Func
                | Builtin::CurveX
                | Builtin::CurveY
                | Builtin::CurveZ
                | Builtin::CurveGal
        )
    }

    /// Whether calling the function changes what comes after it: it draws
    /// from the random stream (or reseeds it), or acts on the derivation
    /// (`stop`, `SetDerivationLength`). Reading a table or the derivation
    /// length changes nothing; I/O is 0 in graftal.
    pub fn acts(self) -> bool {
        matches!(
            self,
            Builtin::Srand
                | Builtin::Ran
                | Builtin::Nran
                | Builtin::Bran
                | Builtin::Biran
                | Builtin::Stop
                | Builtin::SetDerivationLength
        )
    }
}

impl Expr {
    /// Whether evaluating the expression changes nothing but its own value
    /// (it calls no function that [`Builtin::acts`]), so that it gives the
    /// same value wherever and in whatever order it is evaluated.
    pub fn is_quiet(&self) -> bool {
        match self {
            Expr::Num(_) | Expr::Str(_) | Expr::Var(_) => true,
            Expr::Element(_, subs) => subs.iter().all(Expr::is_quiet),
            Expr::Unary(_, a) => a.is_quiet(),
            Expr::Binary(_, x, y) => x.is_quiet() && y.is_quiet(),
            Expr::Cond(c, x, y) => c.is_quiet() && x.is_quiet() && y.is_quiet(),
            Expr::Call(f, args) => !f.acts() && args.iter().all(Expr::is_quiet),
        }
    }
    /// The value of an expression that reads no variable, array or table
    /// and draws no random number, or `None`. Functions that act on the
    /// derivation (`stop`, `srand`, I/O …) are 0 here, as they evaluate to
    /// 0 in a derivation.
    pub fn constant(&self) -> Option<f64> {
        Some(match self {
            Expr::Num(v) => *v,
            // Its value is its place among the system's literals.
            Expr::Str(_) | Expr::Var(_) | Expr::Element(..) => return None,
            Expr::Unary(op, a) => op.apply(a.constant()?),
            Expr::Binary(op, x, y) => op.apply(x.constant()?, y.constant()?),
            Expr::Cond(c, x, y) => {
                let (c, x, y) = (c.constant()?, x.constant()?, y.constant()?);
                if truth(c) {
                    x
                } else {
                    y
                }
            }
            Expr::Call(f, args) => {
                if f.varies() {
                    return None;
                }
                let values: Vec<f64> = args.iter().map(Expr::constant).collect::<Option<_>>()?;
                let x = values.first().copied().unwrap_or(0.0);
                let y = values.get(1).copied().unwrap_or(0.0);
                f.pure(x, y).unwrap_or(0.0)
            }
        })
    }
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

impl Stmt {
    /// Whether running the statements changes nothing outside the
    /// production that runs them: they assign only its local variables and
    /// evaluate only [`Expr::is_quiet`] expressions.
    pub fn are_quiet(stmts: &[Stmt]) -> bool {
        stmts.iter().all(|s| match s {
            Stmt::Assign(Place::Var(Var::Local(_)), e) | Stmt::Eval(e) => e.is_quiet(),
            Stmt::Assign(..) => false,
            Stmt::If(c, t, e) => c.is_quiet() && Stmt::are_quiet(t) && Stmt::are_quiet(e),
            Stmt::While(c, body) | Stmt::Do(body, c) => c.is_quiet() && Stmt::are_quiet(body),
        })
    }
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

/// Variables, arrays, user functions, and the statements run around the
/// derivation (cpfg's `Start:`, `StartEach:`, `EndEach:`, `End:` blocks).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Program {
    pub globals: Vec<String>,
    pub arrays: Vec<ArrayDecl>,
    /// Before the first step.
    pub start: Vec<Stmt>,
    /// Before each step.
    pub start_each: Vec<Stmt>,
    /// After each step.
    pub end_each: Vec<Stmt>,
    /// After the last step.
    pub end: Vec<Stmt>,
    /// `func(id, x)` tables, id 1 first.
    pub functions: Vec<Function>,
}

impl Program {
    /// Whether there is anything to run or store.
    pub fn is_empty(&self) -> bool {
        *self == Program::default()
    }
}
