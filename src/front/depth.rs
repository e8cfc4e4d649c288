//! The one depth limit, [`MAX_NESTING`], as the front ends apply it.
//!
//! A parser that descends into brackets by recursion (chumsky's
//! `recursive`, or recursive descent) must not be handed deeper nesting
//! than the limit. Before parsing, a chumsky front end passes its tokens
//! through [`cut_too_deep`], which replaces what lies past the limit with a
//! marker token (the parser reads it as a *cut*, reported once with
//! [`too_deep`]) so that the parser never descends further and the rest of
//! the item still reads. Expressions built by iteration (a chain
//! `1+1+…+1`, a run of signs `---x`) are cut by the parser itself where
//! their tree gets too deep, since no bracket shows that depth.

use crate::diagnostics::{codes, Diagnostic};
use crate::ir::{Span, MAX_NESTING};

/// E0013 at `span`, the first place past the limit; `help` says how to
/// avoid the nesting where it happens.
pub fn too_deep(span: Span, help: impl Into<String>) -> Diagnostic {
    Diagnostic::at(
        codes::NESTED_TOO_DEEPLY,
        span,
        format!("nested more than {MAX_NESTING} deep"),
    )
    .with_label(format!("level {} starts here", MAX_NESTING + 1))
    .with_help(help)
}

/// What a token does to the nesting a parser descends into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Nest {
    /// `(`, `[` or `{`: opens a level that its closer ends.
    Open,
    /// `)`, `]` or `}`: ends the innermost open level, whichever bracket
    /// opened it (a mismatch is the parser's to report). A closer with
    /// nothing open is ignored.
    Close,
    /// C's `?`: the branches of `c ? a : b` are parsed one level deeper,
    /// up to the end of the expression.
    Question,
    /// The `:` of `c ? a : b`, between the branches (no deeper).
    Else,
    /// `,`, `;` or an arrow: ends the expression of the innermost group,
    /// and with it the levels its `?`s opened.
    Separator,
    /// Ends every open level: the start of a new block.
    Reset,
    /// Anything else.
    Other,
}

/// The nesting met so far in a scan of tokens.
#[derive(Clone, Debug)]
pub struct Nesting {
    /// The levels opened by `?` in each open group, the top level first.
    questions: Vec<usize>,
    depth: usize,
}

impl Default for Nesting {
    fn default() -> Self {
        Nesting {
            questions: vec![0],
            depth: 0,
        }
    }
}

impl Nesting {
    /// How many levels are open.
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// Takes the next token; true when it would open a level past
    /// [`MAX_NESTING`]. That level is not counted, so a caller that skips
    /// what follows can go on scanning.
    pub fn step(&mut self, nest: Nest) -> bool {
        match nest {
            Nest::Open | Nest::Question if self.depth >= MAX_NESTING => return true,
            Nest::Open => {
                self.depth += 1;
                self.questions.push(0);
            }
            Nest::Question => {
                self.depth += 1;
                if let Some(q) = self.questions.last_mut() {
                    *q += 1;
                }
            }
            Nest::Close => {
                if self.questions.len() > 1 {
                    let q = self.questions.pop().unwrap_or(0);
                    self.depth -= q + 1;
                }
            }
            Nest::Separator => {
                if let Some(q) = self.questions.last_mut() {
                    self.depth -= *q;
                    *q = 0;
                }
            }
            Nest::Reset => *self = Nesting::default(),
            Nest::Else | Nest::Other => {}
        }
        false
    }
}

/// `tokens` with each part nested past [`MAX_NESTING`] replaced, or `None`
/// when nothing is that deep. Where an opener `(` `[` `{` goes past the
/// limit, what it holds becomes `filler(opener)` (the opener and its
/// closer stay); where a `?` does, its branches `a : b` become
/// `filler(?)`. A part never closed runs to the next reset (or the end),
/// and the groups still open there get a `closer(opener)` each, so the
/// parser reads the item as if it were balanced (its first problem, the
/// depth, is reported; the imbalance is not). The scan goes on after each
/// cut, so the result holds nothing past the limit.
pub fn cut_too_deep<T: Clone>(
    tokens: &[T],
    nest: impl Fn(&T) -> Nest,
    filler: impl Fn(&T) -> Vec<T>,
    closer: impl Fn(&T) -> T,
) -> Option<Vec<T>> {
    let mut n = Nesting::default();
    // The openers of the open groups.
    let mut open: Vec<usize> = Vec::new();
    let mut out: Option<Vec<T>> = None;
    let mut i = 0;
    while i < tokens.len() {
        let kind = nest(&tokens[i]);
        if !n.step(kind) {
            match kind {
                Nest::Open => open.push(i),
                Nest::Close => {
                    open.pop();
                }
                Nest::Reset => open.clear(),
                _ => {}
            }
            if let Some(out) = &mut out {
                out.push(tokens[i].clone());
            }
            i += 1;
            continue;
        }
        let out = out.get_or_insert_with(|| tokens[..i].to_vec());
        out.push(tokens[i].clone());
        out.extend(filler(&tokens[i]));
        match end_of_level(tokens, i, kind, &nest) {
            // The opener's own closer is kept; the level it closes was not
            // counted.
            Ok(e) if kind == Nest::Open => {
                out.push(tokens[e].clone());
                i = e + 1;
            }
            // What ends a `?` level (a separator, the group's closer) is
            // read as usual.
            Ok(e) => i = e,
            Err(e) => {
                if kind == Nest::Open {
                    out.push(closer(&tokens[i]));
                }
                out.extend(open.iter().rev().map(|&k| closer(&tokens[k])));
                open.clear();
                n = Nesting::default();
                i = e;
            }
        }
    }
    out
}

/// Where the level that `tokens[at]` (of kind `kind`) opens ends: `Ok` with
/// the index of the token that ends it (an opener's closer; for a `?`, what
/// ends its else-branch: a separator, the closer of the group, or the `:`
/// of an enclosing `?`), or `Err` with the index of the reset (or the end)
/// it runs to unclosed.
fn end_of_level<T>(
    tokens: &[T],
    at: usize,
    kind: Nest,
    nest: &impl Fn(&T) -> Nest,
) -> Result<usize, usize> {
    // Groups opened since `at` (for an opener, its own group counts).
    let mut inner = usize::from(kind == Nest::Open);
    // The `?`s since `at` (itself included) still waiting for their `:`.
    let mut questions = 1;
    for (k, t) in tokens.iter().enumerate().skip(at + 1) {
        match nest(t) {
            Nest::Open => inner += 1,
            Nest::Close if kind == Nest::Open && inner == 1 => return Ok(k),
            Nest::Close | Nest::Separator if inner == 0 => return Ok(k),
            Nest::Close => inner -= 1,
            Nest::Question if inner == 0 => questions += 1,
            Nest::Else if inner == 0 && kind == Nest::Question => {
                if questions == 0 {
                    return Ok(k);
                }
                questions -= 1;
            }
            Nest::Reset => return Err(k),
            Nest::Question | Nest::Else | Nest::Separator | Nest::Other => {}
        }
    }
    Err(tokens.len())
}

/// How an expression node over operands of depths `operands` is built
/// (the rule both cpfg's and LinF's expression trees follow): an operand
/// that is already a cut (deeper than [`MAX_NESTING`]) makes the node that
/// cut, `Err(Some(i))`; a node that would itself pass the limit becomes a
/// new cut, `Err(None)`; otherwise `Ok(depth)`.
pub fn node_depth(operands: impl IntoIterator<Item = usize>) -> Result<usize, Option<usize>> {
    let mut deepest = 0;
    for (i, d) in operands.into_iter().enumerate() {
        if d > MAX_NESTING {
            return Err(Some(i));
        }
        deepest = deepest.max(d);
    }
    if deepest + 1 > MAX_NESTING {
        Err(None)
    } else {
        Ok(deepest + 1)
    }
}

/// An expression tree kept within [`MAX_NESTING`] as the parser builds it
/// (cpfg's and LinF's): each node knows how deep it is, and a node that
/// would pass the limit becomes a *cut*, a leaf standing for what was left
/// out, for the parser to report.
pub trait Bounded: Clone {
    /// How deep the tree is: 1 for a leaf, one more than the deepest
    /// operand for an operation, past [`MAX_NESTING`] for a cut.
    fn depth(&self) -> usize;
    /// A cut at `at`, where an expression went past [`MAX_NESTING`].
    fn cut(at: Span) -> Self;
    /// The same tree, written at `span`.
    fn written_at(self, span: Span) -> Self;
}

/// The operation `make(kind, depth)` over the operands `operands(&kind)`,
/// `at` its operator, kept within [`MAX_NESTING`] as [`node_depth`] says:
/// an operation on a cut is that cut, and one that would go deeper than
/// the limit is a new cut at `at`. So no tree a parser builds is deeper
/// than the limit (chains like `1+1+…+1` are built by iteration; the code
/// that walks trees, dropping them included, recurses), and the first
/// place past the limit is kept for the parser to report.
pub fn bounded_operation<K, E: Bounded>(
    kind: K,
    operands: impl Fn(&K) -> Vec<&E>,
    at: Span,
    make: impl FnOnce(K, usize) -> E,
) -> E {
    let depth = {
        let operands = operands(&kind);
        match node_depth(operands.iter().map(|e| e.depth())) {
            Ok(depth) => depth,
            Err(Some(cut)) => return operands[cut].clone(),
            Err(None) => return E::cut(at),
        }
    };
    make(kind, depth)
}

/// `inner` read between parentheses written at `span`: the whole span is
/// the expression's, unless it is a cut, which stays where it went too
/// deep rather than at the parentheses around.
pub fn parenthesized<E: Bounded>(inner: E, span: Span) -> E {
    if inner.depth() > MAX_NESTING {
        inner
    } else {
        inner.written_at(span)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn classify(c: &char) -> Nest {
        match c {
            '(' | '[' | '{' => Nest::Open,
            ')' | ']' | '}' => Nest::Close,
            '?' => Nest::Question,
            ':' => Nest::Else,
            ',' | ';' => Nest::Separator,
            'K' => Nest::Reset,
            _ => Nest::Other,
        }
    }

    /// `text` cut at the limit: `#` for what was left out, `:#` after a
    /// `?`, `)` for each closer added.
    fn cut(text: &str) -> Option<String> {
        let chars: Vec<char> = text.chars().collect();
        let filler = |c: &char| match c {
            '?' => vec!['#', ':', '#'],
            _ => vec!['#'],
        };
        cut_too_deep(&chars, classify, filler, |_| ')').map(|v| v.into_iter().collect())
    }

    fn parens(n: usize, inner: &str) -> String {
        format!("{}{inner}{}", "(".repeat(n), ")".repeat(n))
    }

    #[test]
    fn what_an_opener_past_the_limit_holds_is_cut() {
        let m = MAX_NESTING;
        assert_eq!(cut(&parens(m, "1")), None);
        // The 257th opener stays, with the marker for what it held and
        // its closer; the levels around it are read as they are.
        assert_eq!(cut(&parens(m + 40, "1")), Some(parens(m + 1, "#")));
        // Brackets of every kind count alike.
        let mixed = format!("f{}1{}", "([{".repeat(m), "}])".repeat(m));
        let kept: String = "([{".repeat(m).chars().take(m + 1).collect();
        let closers: String = "}])".repeat(m).chars().skip(2 * m - 1).collect();
        assert_eq!(cut(&mixed), Some(format!("f{kept}#{closers}")));
        // Closed levels do not add up, and a stray closer closes nothing.
        assert_eq!(cut(&"()".repeat(10 * m)), None);
        assert_eq!(cut(&")".repeat(5)), None);
    }

    #[test]
    fn a_part_never_closed_is_closed_at_the_next_reset() {
        let m = MAX_NESTING;
        let unclosed = format!("{}K(1)", "(".repeat(m + 500));
        assert_eq!(cut(&unclosed), Some(format!("{}K(1)", parens(m + 1, "#"))));
        assert_eq!(cut(&"(".repeat(3 * m)), Some(parens(m + 1, "#")));
    }

    #[test]
    fn the_scan_goes_on_after_a_cut() {
        let m = MAX_NESTING;
        let two = format!("{},{}", parens(m + 1, "1"), parens(m + 2, "2"));
        let both = format!("{},{}", parens(m + 1, "#"), parens(m + 1, "#"));
        assert_eq!(cut(&two), Some(both));
    }

    #[test]
    fn question_marks_nest_until_the_expression_ends() {
        let m = MAX_NESTING;
        // `1?1?…`: the 257th `?` keeps its condition; its branches are cut,
        // and the `:`s of the `?`s around it stay.
        let then_chain = format!("{}1{}", "1?".repeat(m + 10), ":2".repeat(m + 10));
        let kept = format!("{}#:#{}", "1?".repeat(m + 1), ":2".repeat(m));
        assert_eq!(cut(&then_chain), Some(kept));
        let else_chain = format!("{}1", "1?2:".repeat(m + 10));
        assert_eq!(
            cut(&else_chain),
            Some(format!("{}#:#", "1?2:".repeat(m).to_string() + "1?"))
        );
        // Separated expressions each start again, and so does a group's
        // end.
        assert_eq!(cut(&"1?1:1,".repeat(3 * m)), None);
        assert_eq!(cut(&"(1?1:1)".repeat(3 * m)), None);
        // A `?` inside parentheses adds to the parentheses around it; the
        // cut ends at the closer of its group, which stays.
        let inside = parens(m, "1?1:2");
        let expected = format!("{}1?#:#{}", "(".repeat(m), ")".repeat(m));
        assert_eq!(cut(&inside), Some(expected));
    }
}
