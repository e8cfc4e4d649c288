//! The LinF abstract syntax tree: the blocks of a `.linf` file as written,
//! with spans. Strings (the axiom and rule bodies) are kept as flat lists of
//! [`Item`]s: how a name splits and whether a sign names an angle depend on
//! the names the whole file declares, which lowering ([`super::lower`])
//! knows.

use super::lexer::BlockKind;
use crate::front::depth::{bounded_operation, Bounded};
use crate::ir::{Span, MAX_NESTING};

/// A parsed file: its blocks in order, and its `#:` directives.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct File {
    pub blocks: Vec<Block>,
    pub directives: Vec<Directive>,
}

/// One block: its keyword and contents.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    pub kind: BlockKind,
    /// The keyword.
    pub keyword: Span,
    pub body: BlockBody,
}

#[derive(Clone, Debug, PartialEq)]
pub enum BlockBody {
    /// `lines` and `blanks`: the names declared.
    Names(Vec<Name>),
    /// `angles`: rotations, named or not.
    Angles(Vec<RotationDecl>),
    /// `axiom`: a string.
    Axiom(Vec<Item>),
    /// `rules`: productions.
    Rules(Vec<Rule>),
    /// `colors`: the colour list.
    Colors(Vec<ColourDecl>),
}

/// A name with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Name {
    pub text: String,
    pub span: Span,
}

/// `t = (torsion, curvature)` or, for the default rotation, `(…, …)`.
#[derive(Clone, Debug, PartialEq)]
pub struct RotationDecl {
    pub name: Option<Name>,
    /// The components as written (a rotation needs exactly two).
    pub components: Vec<Component>,
    /// The parser could not read the components (and said why).
    pub recovered: bool,
    /// From `(` to `)`.
    pub span: Span,
}

/// A rotation component: a value or an interval `[lo hi]`.
#[derive(Clone, Debug, PartialEq)]
pub enum Component {
    Value(Expr),
    Interval { lo: Expr, hi: Expr, span: Span },
}

impl Component {
    pub fn span(&self) -> Span {
        match self {
            Component::Value(e) => e.span.clone(),
            Component::Interval { span, .. } => span.clone(),
        }
    }
}

/// An arithmetic expression over numbers and `pi`.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
    /// How deep the tree is: 1 for a number or a name, one more than the
    /// deepest operand for an operation. Past [`MAX_NESTING`] the
    /// expression is *cut* (see [`Expr::operation`]).
    pub depth: usize,
}

impl Expr {
    /// A number or a name.
    pub fn leaf(kind: ExprKind, span: Span) -> Self {
        Expr {
            kind,
            span,
            depth: 1,
        }
    }

    /// An operation whose operands are in `kind`, written at `span`; `at`
    /// is the operator. The tree is kept within [`MAX_NESTING`] as it is
    /// built ([`bounded_operation`]): an operation that would go deeper
    /// becomes a *cut*, a leaf at `at`, and an operation on a cut is that
    /// cut.
    pub fn operation(kind: ExprKind, span: Span, at: Span) -> Self {
        bounded_operation(kind, ExprKind::operands, at, |kind, depth| Expr {
            kind,
            span,
            depth,
        })
    }

    /// A cut at `at`: where an expression went past [`MAX_NESTING`]. It
    /// stands for what was left out (as a value it is NaN; the parser
    /// reports it and replaces it before anything evaluates it).
    pub fn cut(at: Span) -> Self {
        Expr {
            kind: ExprKind::Number(f64::NAN),
            span: at,
            depth: MAX_NESTING + 1,
        }
    }

    /// Whether this is where an expression went past [`MAX_NESTING`].
    pub fn is_cut(&self) -> bool {
        self.depth > MAX_NESTING
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Number(f64),
    /// A name: `pi`, or an error.
    Name(String),
    Neg(Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
}

impl Bounded for Expr {
    fn depth(&self) -> usize {
        self.depth
    }
    fn cut(at: Span) -> Self {
        Expr::cut(at)
    }
    fn written_at(self, span: Span) -> Self {
        Expr { span, ..self }
    }
}

impl ExprKind {
    /// The expressions this one is made of.
    fn operands(&self) -> Vec<&Expr> {
        match self {
            ExprKind::Number(_) | ExprKind::Name(_) => Vec::new(),
            ExprKind::Neg(a) => vec![a],
            ExprKind::Binary(_, a, b) => vec![a, b],
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
}

/// One element of a string, as written.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A run of name characters (split into declared names when lowered).
    Name(Name),
    /// `+` (`minus == false`) or `-`.
    Sign {
        minus: bool,
        span: Span,
    },
    /// A number (before `?` or `@`).
    Number {
        value: f64,
        text: String,
        span: Span,
    },
    Question(Span),
    At(Span),
    Open(Span),
    Close(Span),
    NextColour(Span),
    PreviousColour(Span),
    Swap(Span),
}

impl Item {
    pub fn span(&self) -> Span {
        match self {
            Item::Name(n) => n.span.clone(),
            Item::Sign { span, .. } | Item::Number { span, .. } => span.clone(),
            Item::Question(s)
            | Item::At(s)
            | Item::Open(s)
            | Item::Close(s)
            | Item::NextColour(s)
            | Item::PreviousColour(s)
            | Item::Swap(s) => s.clone(),
        }
    }
}

/// `head = body`.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    pub head: Name,
    pub body: Vec<Item>,
    /// From the head to the end of the body.
    pub span: Span,
}

/// `(r, g, b)`, optionally labelled `N:` as in the paper's Fig. 7.
#[derive(Clone, Debug, PartialEq)]
pub struct ColourDecl {
    pub label: Option<(f64, Span)>,
    pub components: Vec<Expr>,
    /// From `(` to `)`.
    pub span: Span,
}

/// A `#: key value` directive.
#[derive(Clone, Debug, PartialEq)]
pub struct Directive {
    pub text: String,
    pub span: Span,
}
