//! The STL abstract syntax tree: what a `.stl` file says, item by item,
//! with spans. Lowering ([`super::lower`]) resolves names and builds the IR.

use crate::ir::Span;

/// A parsed file: its items in order. Items that failed to parse are left
/// out (their diagnostics were reported).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct File {
    pub items: Vec<Item>,
}

/// A number as written, with its span (`negative` when written with `-`).
#[derive(Clone, Debug, PartialEq)]
pub struct Num {
    pub value: f64,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// `ANGLE 30`
    Angle { value: Num, span: Span },
    /// `LEVELS 12`
    Levels { value: Num, span: Span },
    /// `GROWTH BFS` / `GROWTH DFS`
    Growth { depth_first: bool, span: Span },
    /// `B = 8 (1)` (`param` is `'B'`) or `L = 40 (4)` (`'L'`).
    Param {
        param: char,
        value: Num,
        decrement: Option<Num>,
        span: Span,
    },
    /// `R1 = [F][+F][-F]`
    Rule {
        name: String,
        name_span: Span,
        body: Str,
        span: Span,
    },
    /// `SEED … ENDSEED`
    Seed { body: Str, span: Span },
    /// `LAYOUT … ENDLAYOUT`
    Layout { shapes: Vec<ShapeAst>, span: Span },
}

/// A string of drawing components, rule names, branches, self-resemblance
/// counts and branching terms.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Str {
    pub elems: Vec<Elem>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Elem {
    /// An identifier run (`F`, `FLF`, `FR1`, `R2`): components and rule
    /// names written together; `entries` is a `{…}` written right after it,
    /// which belongs to the last name of the run.
    Name {
        text: String,
        span: Span,
        entries: Option<Entries>,
    },
    /// `+` (left) or `-` (right).
    Turn { left: bool, span: Span },
    /// `[ … ]`
    Branch { body: Str, span: Span },
    /// `[I n X]`
    Resemble { count: Num, body: Str, span: Span },
}

/// `{ e1, …, em }`
#[derive(Clone, Debug, PartialEq)]
pub struct Entries {
    pub list: Vec<Entry>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Entry {
    /// Nothing between the commas.
    Empty(Span),
    /// `~`
    Failed(Span),
    /// A rule name with its own optional `{…}`.
    Term {
        name: String,
        name_span: Span,
        entries: Option<Entries>,
    },
}

impl Entry {
    pub fn span(&self) -> Span {
        match self {
            Entry::Empty(s) | Entry::Failed(s) => s.clone(),
            Entry::Term {
                name_span, entries, ..
            } => match entries {
                Some(e) => name_span.start..e.span.end,
                None => name_span.clone(),
            },
        }
    }
}

/// A colour: a Delphi name or `$00BBGGRR`.
#[derive(Clone, Debug, PartialEq)]
pub enum ColourAst {
    Name(String, Span),
    Hex(String, Span),
}

/// One argument of a shape: a number or a point `(x, y)`.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    Num(Num),
    Point(Num, Num, Span),
}

impl Arg {
    pub fn span(&self) -> Span {
        match self {
            Arg::Num(n) => n.span.clone(),
            Arg::Point(_, _, s) => s.clone(),
        }
    }
}

/// `(clGreen) Ellipse (-150,0), 300, 400`
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeAst {
    pub colour: ColourAst,
    pub kind: String,
    pub kind_span: Span,
    pub args: Vec<Arg>,
    pub span: Span,
}
