//! The `.gft` syntax tree: items as written, words not yet split into
//! symbols (that needs the file's declarations, see `lower`).

use crate::ir::graph::{Affine, Shape};
use crate::ir::Span;

/// A file: its items in order.
#[derive(Clone, Debug, Default)]
pub struct File {
    pub items: Vec<Item>,
}

#[derive(Clone, Debug)]
pub enum Item {
    /// `KEYWORD ARGS… [{ BLOCK }]`: a setting or declaration.
    Keyword(Keyword),
    /// `NAME = OPERATION`.
    Define {
        name: String,
        span: Span,
        op: Vec<Arg>,
        op_span: Span,
    },
    Production(Production),
}

#[derive(Clone, Debug)]
pub struct Keyword {
    pub name: String,
    pub span: Span,
    pub args: Vec<Arg>,
    /// The productions or statements of a block item.
    pub block: Option<Block>,
    /// The value of a keyword that takes an expression.
    pub value: Option<Expr>,
    /// The word of `axiom`, `ignore`, `consider`, `cut`.
    pub word: Option<Word>,
    /// The whole line.
    pub line: Span,
}

#[derive(Clone, Debug)]
pub enum Block {
    Productions(Vec<Production>),
    /// `sub-lsystem N { … }`: its productions, and its `ignore` or
    /// `consider` line (the keyword and the word) when it has one.
    Lsystem {
        productions: Vec<Production>,
        context: Option<(String, Word)>,
    },
    Statements(Vec<Stmt>),
    /// The lines of `outline`, `surface` and `contour`, as written.
    Lines(Vec<Vec<Arg>>),
    /// The lines of `graph { … }`, each read (docs/gft.md §13).
    Graph(Vec<GraphLine>),
}

impl Keyword {
    /// The values of a block of lines, all lines together (none for any
    /// other item).
    pub fn lines(&self) -> Vec<Arg> {
        match &self.block {
            Some(Block::Lines(lines)) => lines.concat(),
            _ => Vec::new(),
        }
    }
}

/// One argument of a keyword line, as written.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    Word(String, Span),
    Number(f64, String, Span),
    Colour(String, Span),
    Quoted(String, Span),
    Punct(String, Span),
}

impl Arg {
    pub fn span(&self) -> &Span {
        match self {
            Arg::Word(_, s)
            | Arg::Number(_, _, s)
            | Arg::Colour(_, s)
            | Arg::Quoted(_, s)
            | Arg::Punct(_, s) => s,
        }
    }
    pub fn text(&self) -> &str {
        match self {
            Arg::Word(t, _) | Arg::Number(_, t, _) | Arg::Colour(t, _) | Arg::Quoted(t, _) => t,
            Arg::Punct(t, _) => t,
        }
    }
}

/// A word before splitting: pieces of symbol text, quoted names, guards
/// and parameter lists.
#[derive(Clone, Debug, Default)]
pub struct Word {
    pub pieces: Vec<Piece>,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub enum Piece {
    /// Symbol characters, split by the longest declared name.
    Text(String, Span),
    /// `` `name` ``.
    Quoted(String, Span),
    /// `p?` before a module.
    Guard(f64, Span),
    /// `( e, … )` after a module.
    Args(Vec<Expr>, Span),
}

#[derive(Clone, Debug)]
pub struct Production {
    pub left: Option<Word>,
    pub predecessor: Word,
    pub right: Option<Word>,
    pub before: Vec<Stmt>,
    pub condition: Option<Expr>,
    pub after: Vec<Stmt>,
    pub alternatives: Vec<Alternative>,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub struct Alternative {
    pub successor: Word,
    pub weight: Option<Expr>,
}

#[derive(Clone, Debug)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub enum ExprKind {
    Num(f64),
    Str(String),
    Name(String),
    /// `a[i][j]`.
    Element(String, Vec<Expr>),
    Call(String, Vec<Expr>),
    Unary(&'static str, Box<Expr>),
    Binary(String, Box<Expr>, Box<Expr>),
    Cond(Box<Expr>, Box<Expr>, Box<Expr>),
}

#[derive(Clone, Debug)]
pub enum Stmt {
    Assign {
        name: String,
        index: Vec<Expr>,
        value: Expr,
        span: Span,
    },
    Expr(Expr),
    If(Expr, Vec<Stmt>, Vec<Stmt>),
    While(Expr, Vec<Stmt>),
    Do(Vec<Stmt>, Expr),
}

/// A name as written in a `graph` block (a symbol's or a transform's).
#[derive(Clone, Debug, PartialEq)]
pub struct Name {
    pub text: String,
    pub span: Span,
}

/// One line of a `graph { … }` block.
#[derive(Clone, Debug)]
pub enum GraphLine {
    /// `transform NAME = STEPS`.
    Transform {
        name: Name,
        steps: Vec<Step>,
        span: Span,
    },
    /// `axiom COUPLES`.
    Axiom { couples: Vec<Couple>, span: Span },
    /// `symbol NAMES`: symbols with no rule and no geometry.
    Symbol { names: Vec<Name>, span: Span },
    /// `NAME -> COUPLES`.
    Rule {
        symbol: Name,
        couples: Vec<Couple>,
        span: Span,
    },
    /// `geometry NAME = SHAPE`.
    Geometry {
        symbol: Name,
        shape: Shape,
        span: Span,
    },
    /// `alternative NAME [below N] = SHAPE`.
    Alternative {
        symbol: Name,
        below: Option<(f64, Span)>,
        shape: Shape,
        span: Span,
    },
    /// A line that did not read (its error reported), with what it
    /// would have introduced, so that the rest of the block does not
    /// report its names again.
    Unread {
        /// The symbols it introduces (a rule's, a geometry's, `symbol`'s).
        symbols: Vec<Name>,
        /// The transform it declares.
        transform: Option<Name>,
        /// Whether it is a `geometry` or `alternative` line.
        geometry: bool,
        span: Span,
    },
}

impl GraphLine {
    /// The whole line.
    pub fn span(&self) -> &Span {
        match self {
            GraphLine::Transform { span, .. }
            | GraphLine::Axiom { span, .. }
            | GraphLine::Symbol { span, .. }
            | GraphLine::Rule { span, .. }
            | GraphLine::Geometry { span, .. }
            | GraphLine::Alternative { span, .. }
            | GraphLine::Unread { span, .. } => span,
        }
    }
}

/// One step of a transform written in steps.
#[derive(Clone, Debug)]
pub enum Step {
    /// `translate …`, `scale …`, `rotate …`, `shear …`, `matrix …`.
    Affine(Affine, Span),
    /// A transform declared with `transform NAME = …`.
    Name(Name),
}

/// How a couple places its symbol.
#[derive(Clone, Debug)]
pub enum Placement {
    /// `B`: the identity.
    Identity,
    /// `NAME(B)`.
    Named(Name),
    /// `[STEPS](B)`, with the span of the brackets.
    Steps(Vec<Step>, Span),
}

/// A couple `w(B)` of an axiom or a rule.
#[derive(Clone, Debug)]
pub struct Couple {
    pub placement: Placement,
    pub symbol: Name,
    pub span: Span,
}
